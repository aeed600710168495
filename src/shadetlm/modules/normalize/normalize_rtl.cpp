#include "shadetlm/modules/normalize/normalize_rtl.hpp"

#include <sstream>
#include <stdexcept>
#include <type_traits>

#include <systemc>

#include "shadetlm/core/input_error.hpp"

#ifdef SHADETLM_HAVE_RTL
#include "shadetlm/rtl/normalize_rtl_build.hpp"
#endif

namespace shadetlm::modules {

namespace {
const std::string kSetting = "pipeline.normalize.impl";
}  // namespace

// What the transactor drives and reads, whatever the model (one class per mode).
class NormalizeRtlPins {
 public:
  struct In {
    bool valid = false, first = false, direct = false;
    uint32_t tag = 0;
    uint64_t n[3] = {}, dh[3] = {}, c = 0;
  };
  struct Out {
    bool in_ready = false, out_valid = false;
    uint32_t tag = 0;
    uint64_t n[3] = {};
  };
  virtual ~NormalizeRtlPins() = default;
  // Sets the inputs for the next rising edge (the outputs read are this cycle's).
  virtual void drive(const In& in, bool out_ready, bool reset) = 0;
  virtual Out sample() const = 0;
  // One clock cycle: the rising edge and the outputs settled, then the falling edge.
  virtual void cycle() = 0;
};

#ifdef SHADETLM_HAVE_RTL

namespace {

// The signals bound to a verilated model's pins. V's ports are uint32_t up to 32 bits,
// uint64_t up to 64 (the word type is read from them).
template <class V>
class VerilatedPins : public NormalizeRtlPins {
  template <class Port> using data_of = typename std::remove_reference_t<Port>::data_type;
  using Word = data_of<decltype(std::declval<V&>().in_nx)>;
  using Tag = data_of<decltype(std::declval<V&>().in_tag)>;

 public:
  VerilatedPins()
      : model_("normalize_rtl"),
        clk_("rtl_clk"), rst_("rtl_rst"), in_valid_("rtl_in_valid"), in_ready_("rtl_in_ready"),
        in_first_("rtl_in_first"), in_direct_("rtl_in_direct"), out_valid_("rtl_out_valid"),
        out_ready_("rtl_out_ready"), in_tag_("rtl_in_tag"), out_tag_("rtl_out_tag") {
    model_.clk(clk_), model_.rst(rst_), model_.in_valid(in_valid_), model_.in_ready(in_ready_);
    model_.in_first(in_first_), model_.in_direct(in_direct_), model_.out_valid(out_valid_);
    model_.out_ready(out_ready_), model_.in_tag(in_tag_), model_.out_tag(out_tag_);
    model_.in_nx(in_n_[0]), model_.in_ny(in_n_[1]), model_.in_nz(in_n_[2]);
    model_.in_dhx(in_dh_[0]), model_.in_dhy(in_dh_[1]), model_.in_dhz(in_dh_[2]), model_.in_c(in_c_);
    model_.out_nx(out_n_[0]), model_.out_ny(out_n_[1]), model_.out_nz(out_n_[2]);
  }
  void drive(const In& in, bool out_ready, bool reset) override {
    rst_.write(reset);
    in_valid_.write(in.valid), in_first_.write(in.first), in_direct_.write(in.direct);
    in_tag_.write(Tag(in.tag));
    for (int k = 0; k < 3; ++k) in_n_[k].write(Word(in.n[k])), in_dh_[k].write(Word(in.dh[k]));
    in_c_.write(Word(in.c));
    out_ready_.write(out_ready);
  }
  Out sample() const override {
    Out o;
    o.in_ready = in_ready_.read(), o.out_valid = out_valid_.read();
    o.tag = uint32_t(out_tag_.read());
    for (int k = 0; k < 3; ++k) o.n[k] = uint64_t(out_n_[k].read());
    return o;
  }
  void cycle() override {
    // Delta cycles: the edge's update, then the model's evaluation and its outputs'.
    clk_.write(true);
    sc_core::wait(sc_core::SC_ZERO_TIME);
    sc_core::wait(sc_core::SC_ZERO_TIME);
    clk_.write(false);
    sc_core::wait(sc_core::SC_ZERO_TIME);
  }

 private:
  V model_;
  sc_core::sc_signal<bool> clk_, rst_, in_valid_, in_ready_, in_first_, in_direct_, out_valid_, out_ready_;
  sc_core::sc_signal<Tag> in_tag_, out_tag_;
  sc_core::sc_signal<Word> in_n_[3], in_dh_[3], in_c_, out_n_[3];
};

std::unique_ptr<NormalizeRtlPins> make_pins(NormalizeMode mode) {
  switch (mode) {
    case NormalizeMode::Exact: return std::make_unique<VerilatedPins<Vnormalize_exact>>();
    case NormalizeMode::ForwardDifference: return std::make_unique<VerilatedPins<Vnormalize_forward_difference>>();
    case NormalizeMode::Rsqrt0: return std::make_unique<VerilatedPins<Vnormalize_rsqrt0>>();
    case NormalizeMode::Rsqrt1: return std::make_unique<VerilatedPins<Vnormalize_rsqrt1>>();
    default: return std::make_unique<VerilatedPins<Vnormalize_rsqrt2>>();
  }
}

core::NumberFormat built_format() { return core::NumberFormat::fixed(rtl::kIntBits, rtl::kFracBits); }

}  // namespace

bool normalize_rtl_built() { return true; }

std::string normalize_rtl_build() {
  std::ostringstream s;
  s << built_format().name() << ";";
  for (const auto& m : rtl::kNormalizeTiming) s << " " << m.mode << " latency " << m.latency << " II " << m.ii << ";";
  std::string text = s.str();
  text.pop_back();
  return text;
}

NormalizeRtlKernel::NormalizeRtlKernel(NormalizeMode mode, core::NumberFormat format, Timing timing,
                                       const std::string& scene_file)
    : mode_(mode), format_(format), timing_(timing), scene_file_(scene_file), numbers_(format) {
  if (format != built_format())
    throw core::InputError(scene_file, "pipeline.normalize.format",
                           "is " + format.name() + ", but the RTL normalize unit of this build is " +
                               built_format().name() + " (set it, or configure with -DSHADETLM_RTL_FORMAT=" +
                               format.name() + ")");
  const rtl::ModeTiming& built = rtl::kNormalizeTiming[int(mode)];
  if (timing.latency != uint64_t(built.latency) || timing.ii != uint64_t(built.ii))
    throw core::InputError(scene_file, kSetting,
                           "the RTL normalize unit (mode " + std::string(built.mode) + ") has latency " +
                               std::to_string(built.latency) + " and II " + std::to_string(built.ii) +
                               "; the scene's settings give normalize latency " + std::to_string(timing.latency) +
                               " and II " + std::to_string(timing.ii) + " (rtl/CMakeLists.txt builds it)");
  pins_ = make_pins(mode);
}

#else  // no Verilator when this build was configured

bool normalize_rtl_built() { return false; }
std::string normalize_rtl_build() { return "none: built without Verilator, or with SHADETLM_RTL=OFF"; }

NormalizeRtlKernel::NormalizeRtlKernel(NormalizeMode mode, core::NumberFormat format, Timing timing,
                                       const std::string& scene_file)
    : mode_(mode), format_(format), timing_(timing), scene_file_(scene_file), numbers_(format) {
  throw core::InputError(scene_file, kSetting,
                         "rtl: this build has no RTL normalize unit (built without Verilator, which "
                         "scripts/setup.sh installs, or with SHADETLM_RTL=OFF)");
}

#endif

NormalizeRtlKernel::~NormalizeRtlKernel() = default;

Work NormalizeRtlKernel::work(const SpanPacket&) const {
  return Work{nullptr, 1, nullptr, mode_ == NormalizeMode::ForwardDifference ? 1u : 0u};
}

Ops NormalizeRtlKernel::ops() const {
  // (the RTL is fixed point: one rsqrt unit)
  return normalize_ops_per_pixel(mode_, true) * tally_.pixels[0] + normalize_ops_per_span(mode_) * tally_.packets[0] +
         normalize_ops_per_pixel_direct_rsqrt(true) * tally_.pixels[1];
}

nlohmann::json NormalizeRtlKernel::details() const {
  return {{"impl", "rtl"}, {"rtl_cycles", cycles_}};
}

void NormalizeRtlKernel::process(SpanPacket& p) {
  if (p.count == 0) return;
  if (!sc_core::sc_is_running() ||
      sc_core::sc_get_current_process_handle().proc_kind() != sc_core::SC_THREAD_PROC_)
    throw core::InputError(scene_file_, kSetting,
                           "rtl runs in the SystemC pipeline only (not in the plain loop: --engine loop, bench)");
  const TriangleSetup& t = *p.tri;
  const bool direct = mode_ == NormalizeMode::ForwardDifference && core::bump_path(t.material->path);
  NumberScope scope(numbers_);
  // The float32 wires rounded to the format at the pins, as the kernel rounds them.
  auto word = [&](float v) { return uint64_t(Fixed(v).raw()) & word_mask(); };
  NormalizeRtlPins::In first;
  first.first = true, first.direct = direct;
  for (int k = 0; k < 3; ++k) first.dh[k] = word(t.n[k].ax);
  first.c = word(t.c);

  int64_t taken[kSpanMax], out[kSpanMax];
  int next = 0, received = 0;
  int64_t cycle = 0;
  const int64_t bound = int64_t(p.count + 2) * int64_t(timing_.ii * 2 + timing_.latency) + 8;
  if (!reset_) pins_->drive({}, true, true), pins_->cycle(), reset_ = true;
  while (received < p.count) {
    NormalizeRtlPins::In in = next == 0 ? first : NormalizeRtlPins::In{};
    in.valid = next < p.count, in.direct = direct, in.tag = uint32_t(next);
    if (in.valid)
      for (int k = 0; k < 3; ++k) in.n[k] = word(p.n[k][next]);
    pins_->drive(in, true, false);
    const NormalizeRtlPins::Out o = pins_->sample();
    if (in.valid && o.in_ready) taken[next++] = cycle;
    if (o.out_valid) {
      const int i = int(o.tag);
      if (i != received)
        throw std::logic_error("RTL normalize: pixel " + std::to_string(i) + " came out where " +
                               std::to_string(received) + " was due");
      for (int k = 0; k < 3; ++k) p.n[k][i] = float(Fixed::from_raw(sign_extend(o.n[k])));
      out[received++] = cycle;
    }
    pins_->cycle();
    if (++cycle > bound) throw std::logic_error("RTL normalize: no result after " + std::to_string(bound) + " cycles");
  }
  cycles_ += uint64_t(cycle);
  tally_.add(direct ? 1 : 0, p.count);
  check_timing(p, taken, out);
}

// The pins against the block's timing: pixel i taken II · work(i − 1) cycles after pixel
// i − 1 (the first at once: the unit is idle between packets here), and put out
// II · (work(i) − 1) + latency cycles after it was taken.
void NormalizeRtlKernel::check_timing(const SpanPacket& p, const int64_t* taken, const int64_t* out) const {
  const Work w = work(p);
  const int64_t ii = int64_t(timing_.ii), latency = int64_t(timing_.latency);
  for (int i = 0; i < p.count; ++i) {
    const int64_t take_due = i == 0 ? 0 : taken[i - 1] + ii * w.at(i - 1);
    const int64_t out_due = taken[i] + ii * (int64_t(w.at(i)) - 1) + latency;
    if (taken[i] == take_due && out[i] == out_due) continue;
    std::ostringstream s;
    s << "RTL normalize: pixel (" << p.x0 + i << ", " << p.y << ") taken at cycle " << taken[i] << " of its packet, "
      << "put out at " << out[i] << "; the block's timing (latency " << latency << ", II " << ii << ", work "
      << w.at(i) << ") says " << take_due << " and " << out_due;
    throw std::logic_error(s.str());
  }
}

}  // namespace shadetlm::modules
