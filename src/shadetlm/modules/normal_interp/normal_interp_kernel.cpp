#include "shadetlm/modules/normal_interp/normal_interp_kernel.hpp"

namespace shadetlm::modules {

void NormalInterpKernel::process(SpanPacket& p) {
  with_number_type(numbers_, [&](auto zero) { walk<decltype(zero)>(p); });
  if (checks_) nonfinite_ += count_nonfinite(p.n, p.count);
}

template <class T>
void NormalInterpKernel::walk(SpanPacket& p) {
  const TriangleSetup& t = *p.tri;
  const uint64_t steps_before = steps_;
  const T dh[3] = {T(t.n[0].ax), T(t.n[1].ax), T(t.n[2].ax)};
  const T dv[3] = {T(t.n[0].ay), T(t.n[1].ay), T(t.n[2].ay)};
  const T mh[3] = {-dh[0], -dh[1], -dh[2]};
  const T dn_d[3] = {T(t.dn_d[0]), T(t.dn_d[1]), T(t.dn_d[2])};
  const T dn_a[3] = {T(t.dn_a[0]), T(t.dn_a[1]), T(t.dn_a[2])};
  if (t.id != triangle_) {  // a new triangle: start from its seed
    triangle_ = t.id;
    row_y_ = t.y_ref;
    row_x_ = t.x_ref;
    for (int c = 0; c < 3; ++c) row_n_[c] = double(T(t.n[c].a0));
    x_ = row_x_;
    for (int c = 0; c < 3; ++c) n_[c] = row_n_[c];
  }
  // The walker's registers, in the format (exact: they hold values of it).
  T row_n[3] = {T(row_n_[0]), T(row_n_[1]), T(row_n_[2])};
  T n[3] = {T(n_[0]), T(n_[1]), T(n_[2])};
  auto step = [&](T v[3], const T d[3]) {
    v[0] += d[0];
    v[1] += d[1];
    v[2] += d[2];
    ++steps_;
  };
  // Re-seeding (normal_interp.reseed): the row start, and every `tile` pixels along the
  // row, taken straight from the plane instead of by steps — bounding how far rounding
  // errors accumulate. (The plane is setup's, in float32; its value is rounded to the
  // format.)
  auto seed = [&](T v[3], int x, int y) {
    for (int c = 0; c < 3; ++c) v[c] = T(t.n[c].at(x - t.x_ref, y - t.y_ref));
    ops_ += kOpsPerReseed;
    ++steps_;
  };
  if (reseed_ != 0 && row_y_ < p.y) {
    row_y_ = p.y, row_x_ = p.row_start;
    seed(row_n, row_x_, row_y_);
    x_ = row_x_;
    for (int c = 0; c < 3; ++c) n[c] = row_n[c];
  }
  // Down the left edge to this packet's row. Rows with no pixel at all (possible for
  // slivers) are crossed straight down.
  while (row_y_ < p.y) {
    const int next_x = row_y_ + 1 == p.y ? p.row_start : row_x_;
    int dx = next_x - row_x_;
    if (dx > 0) {
      step(row_n, dn_d);
      --dx;
    } else if (dx < 0) {
      step(row_n, dn_a);
      ++dx;
    } else {
      step(row_n, dv);
    }
    for (; dx > 0; --dx) step(row_n, dh);
    for (; dx < 0; ++dx) step(row_n, mh);
    ++row_y_;
    row_x_ = next_x;
    x_ = row_x_;
    for (int c = 0; c < 3; ++c) n[c] = row_n[c];
  }
  // Along the row, through hidden pixels, to the packet's first pixel.
  const int tile = reseed_ > 0 ? reseed_ : 0;
  auto tile_start = [&](int x) { return tile > 0 && x > row_x_ && (x - row_x_) % tile == 0; };
  for (; x_ < p.x0; ++x_) {
    if (tile_start(x_)) seed(n, x_, row_y_);
    step(n, dh);
  }
  if (tile_start(x_)) seed(n, x_, row_y_);
  // Each pixel's steps: its own, and the first pixel's walk to it.
  lead_ = uint32_t(std::min<uint64_t>(steps_ - steps_before + 1, 65535)) - 1;
  tiled_ = tile > 0;
  if (tile > 0) {  // the tiled walk; the plain one below stays a straight loop
    std::fill(work_, work_ + p.count, uint16_t(1));
    if (p.count > 0) work_[0] = uint16_t(1 + lead_);
    for (int i = 0; i < p.count; ++i) {
      if (i > 0 && tile_start(x_ + i)) seed(n, x_ + i, row_y_), ++work_[i];
      for (int c = 0; c < 3; ++c) p.n[c][i] = float(n[c]), n[c] += dh[c];
    }
  } else for (int i = 0; i < p.count; ++i) {
    p.n[0][i] = float(n[0]);
    p.n[1][i] = float(n[1]);
    p.n[2][i] = float(n[2]);
    n[0] += dh[0];
    n[1] += dh[1];
    n[2] += dh[2];
  }
  for (int c = 0; c < 3; ++c) row_n_[c] = double(row_n[c]), n_[c] = double(n[c]);
  // N is affine along the span: its extremes are at the ends.
  if (p.count > 0)
    for (int c = 0; c < 3; ++c) range_.add(p.n[c], 1), range_.add(&p.n[c][p.count - 1], 1);
  x_ += p.count;
  steps_ += uint64_t(p.count);
  last_steps_ = steps_ - steps_before;
  ops_.add += 3 * last_steps_;
}

}  // namespace shadetlm::modules
