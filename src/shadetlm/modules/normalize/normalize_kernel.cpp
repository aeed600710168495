#include "shadetlm/modules/normalize/normalize_kernel.hpp"

#include <cstring>
#include <stdexcept>
#include <type_traits>

#include "shadetlm/core/input_error.hpp"

namespace shadetlm::modules {

const std::vector<std::string>& normalize_mode_names() {
  static const std::vector<std::string> names = {"exact", "forward-difference", "rsqrt0", "rsqrt1", "rsqrt2"};
  return names;
}

NormalizeMode parse_normalize_mode(const std::string& name) {
  const auto& names = normalize_mode_names();
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return NormalizeMode(i);
  throw std::invalid_argument("unknown normalize mode " + name);
}

const std::vector<std::string>& radicand_seed_names() {
  static const std::vector<std::string> names = {"packet", "line"};
  return names;
}

namespace {
// The inverse square root of forward-difference mode: float32 computes 1 / √r (a
// square root, then a division: the same two units as exact mode); float16 and fixed
// point one correctly rounded 1/√r, one rsqrt unit (numeric/number.hpp).
Ops inverse_root(bool rsqrt_unit) { return rsqrt_unit ? Ops{0, 0, 0, 0, /*rsqrt*/ 1} : Ops{0, 0, /*div*/ 1, /*sqrt*/ 1}; }
}  // namespace

Ops normalize_ops_per_pixel(NormalizeMode mode, bool rsqrt_unit) {
  switch (mode) {
    case NormalizeMode::Exact: return {/*add*/ 2, /*mul*/ 6, /*div*/ 1, /*sqrt*/ 1};
    case NormalizeMode::ForwardDifference: return Ops{2, 3} + inverse_root(rsqrt_unit);
    // The estimate is one integer subtraction; each Newton step 3 mul and 1 add.
    case NormalizeMode::Rsqrt0: return {/*add*/ 3, /*mul*/ 6};
    case NormalizeMode::Rsqrt1: return {4, 10};
    default: return {5, 13};
  }
}

Ops normalize_ops_per_pixel_direct_rsqrt(bool rsqrt_unit) { return Ops{/*add*/ 2, /*mul*/ 6} + inverse_root(rsqrt_unit); }

Ops normalize_ops_per_span(NormalizeMode mode) {
  // R_0 = |N_0|² and δ_0 = 2 N_0·ΔN_H + c/2, once per span.
  if (mode == NormalizeMode::ForwardDifference) return {/*add*/ 5, /*mul*/ 8};
  return {};
}

Ops normalize_ops_per_jump() { return {/*add*/ 3, /*mul*/ 3}; }

NormalizeKernel::Start NormalizeKernel::start_of(const SpanPacket& p, bool direct) const {
  if (mode_ != NormalizeMode::ForwardDifference || direct || seed_ == RadicandSeed::Packet) return Start::Seed;
  const bool same_line = line_.open && p.tri->id == line_.triangle && p.y == line_.y && p.x0 >= line_.next_x;
  return !same_line ? Start::Seed : p.x0 == line_.next_x ? Start::Carry : Start::Jump;
}

void NormalizeKernel::process(SpanPacket& p) {
  const TriangleSetup& t = *p.tri;
  if (capture_)
    for (int i = 0; i < p.count; ++i) {
      const float n[3] = {p.n[0][i], p.n[1][i], p.n[2][i]};
      radicand_[i] = radicand(n);
    }
  // The forward-difference radicand follows a normal that steps by ΔN_H along the span;
  // a bump-mapped normal does not, so bump packets take the radicand directly.
  const bool direct = mode_ == NormalizeMode::ForwardDifference && core::bump_path(t.material->path);
  if (p.count == 0) return;
  start_ = start_of(p, direct);
  reseed_at_ = -1;
  with_number_type(numbers_, [&](auto zero) { normalize_as<decltype(zero)>(p, direct); });  // (may re-seed)
  if (!direct && mode_ == NormalizeMode::ForwardDifference) {
    if (start_ == Start::Seed) ++seeds_;
    if (start_ == Start::Jump) ++jumps_;
  }
  if (reseed_at_ >= 0) {  // the work: a seed's cycle before pixel reseed_at_, and the start's own
    ++seeds_, ++reseeds_;
    for (int i = 0; i < p.count; ++i) reseeded_[i] = i == 0 && start_ != Start::Carry ? 2 : 1;
    ++reseeded_[reseed_at_];
  }
  nonfinite_ += count_nonfinite(p.n, p.count);
  tally_.add(direct ? 1 : 0, p.count);
}

Ops NormalizeKernel::ops() const {
  const bool rsqrt_unit = numbers_.format.kind != core::NumberFormat::Kind::Float32;
  return normalize_ops_per_pixel(mode_, rsqrt_unit) * tally_.pixels[0] + normalize_ops_per_span(mode_) * seeds_ +
         normalize_ops_per_jump() * jumps_ + Ops{/*add*/ 2} * reseeds_ + normalize_ops_per_pixel_direct_rsqrt(rsqrt_unit) * tally_.pixels[1];
}

uint64_t NormalizeKernel::word(float v) const {
  const core::NumberFormat& f = numbers_.format;
  if (f.kind != core::NumberFormat::Kind::Fixed) {
    if (f.kind == core::NumberFormat::Kind::Float16) v = float(Half(v));  // its value, as float32 bits
    uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    return bits;
  }
  NumberContext context(f);  // (its own: the vectors' conversions are not the block's events)
  NumberScope scope(context);
  return uint64_t(Fixed(v).raw()) & (~uint64_t(0) >> (63 - f.int_bits - f.frac_bits));
}

VectorLayout NormalizeKernel::vector_layout() const {
  if (mode_ == NormalizeMode::ForwardDifference && seed_ == RadicandSeed::Line)
    throw core::InputError("--vectors", "pipeline.normalize.seed=line",
                           "the RTL unit seeds its radicand at every packet: write vectors with seed=packet");
  const core::NumberFormat& f = numbers_.format;
  const int w = f.kind == core::NumberFormat::Kind::Fixed ? 1 + f.int_bits + f.frac_bits : 32;
  std::string about = "format " + f.name() + ", mode " + normalize_mode_names()[size_t(mode_)];
  if (f.kind != core::NumberFormat::Kind::Fixed) about += " (words: float32 bits of the format's values)";
  return {about,
          {{"first", 1}, {"direct", 1}, {"nx", w}, {"ny", w}, {"nz", w}, {"dhx", w}, {"dhy", w}, {"dhz", w}, {"c", w}},
          {{"nx", w}, {"ny", w}, {"nz", w}}};
}

void NormalizeKernel::vector_in(const SpanPacket& p, int i, uint64_t* words) const {
  const TriangleSetup& t = *p.tri;
  words[0] = i == 0;
  words[1] = mode_ == NormalizeMode::ForwardDifference && core::bump_path(t.material->path);
  for (int k = 0; k < 3; ++k) words[2 + k] = word(p.n[k][i]), words[5 + k] = word(t.n[k].ax);
  words[8] = word(t.c);
}

void NormalizeKernel::vector_out(const SpanPacket& p, int i, uint64_t* words) const {
  const core::NumberFormat& f = numbers_.format;
  for (int k = 0; k < 3; ++k)
    words[k] = f.kind == core::NumberFormat::Kind::Fixed
                   ? uint64_t(raw_out_[k][i]) & (~uint64_t(0) >> (63 - f.int_bits - f.frac_bits))
                   : word(p.n[k][i]);
}

template <class T>
void NormalizeKernel::normalize_as(SpanPacket& p, bool direct) {
  const TriangleSetup& t = *p.tri;
  const T dh[3] = {T(t.n[0].ax), T(t.n[1].ax), T(t.n[2].ax)};
  // seed=line: the radicand this packet starts from, and after it the one it leaves.
  RadicandState<T> state;
  RadicandState<T>* carried = nullptr;
  if (!direct && mode_ == NormalizeMode::ForwardDifference && seed_ == RadicandSeed::Line) {
    carried = &state;
    const T n0[3] = {T(p.n[0][0]), T(p.n[1][0]), T(p.n[2][0])};
    state = start_ == Start::Seed ? RadicandState<T>::seed(n0, dh, T(t.c)) : RadicandState<T>{T(line_.r), T(line_.delta)};
    if (start_ == Start::Jump) state.jump(p.x0 - line_.next_x, T(t.c));
  }
  // A carried radicand that reaches zero or below is dropped there for a seed.
  int* guard = carried && start_ != Start::Seed ? &reseed_at_ : nullptr;
  if constexpr (std::is_same_v<T, float>) {  // in place, in whole groups of lanes (kLanes) …
    const int count = carried ? p.count : lanes(p.count);  // … but a carried radicand steps to the last pixel only
    normalize_span(p.n[0], p.n[1], p.n[2], count, dh, T(t.c), mode_, direct, carried, guard);
  } else {  // the packet's float32 wires rounded to the format, and back
    T n[3][kSpanMax];
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < p.count; ++i) n[c][i] = T(p.n[c][i]);
    normalize_span(n[0], n[1], n[2], p.count, dh, T(t.c), mode_, direct, carried, guard);
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < p.count; ++i) {
        p.n[c][i] = float(n[c][i]);
        if constexpr (std::is_same_v<T, Fixed>) raw_out_[c][i] = n[c][i].raw();  // (wider than a float's)
      }
  }
  if (carried) line_ = {true, t.id, p.y, p.x0 + p.count, double(state.r), double(state.delta)};
}

}  // namespace shadetlm::modules
