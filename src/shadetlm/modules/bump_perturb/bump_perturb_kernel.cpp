#include "shadetlm/modules/bump_perturb/bump_perturb_kernel.hpp"

namespace shadetlm::modules {

bool BumpPerturbKernel::needed(const core::Scene& scene) {
  for (const auto& o : scene.objects)
    if (scene.materials[size_t(o.material)].path == core::ShadingPath::BumpClassic) return true;
  return false;
}

// The planes' seeds at the packet's first pixel are float32 (setup's), rounded to the
// format as the packet starts; from there every step, product and sum is T's.
template <class T>
void BumpPerturbKernel::perturb(SpanPacket& p) {
  const TriangleSetup& t = *p.tri;
  const int dx = p.x0 - t.x_ref, dy = p.y - t.y_ref;
  T x_w[3], y_w[3], x_step[3], y_step[3];
  for (int c = 0; c < 3; ++c) {
    n_x_pv_range_.add_span(t.n_x_pv[c].at(dx, dy), t.n_x_pv[c].ax, p.count, p.w);
    pu_x_n_range_.add_span(t.pu_x_n[c].at(dx, dy), t.pu_x_n[c].ax, p.count, p.w);
    x_w[c] = plane_seed<T>(t.n_x_pv[c], dx, dy), y_w[c] = plane_seed<T>(t.pu_x_n[c], dx, dy);
    x_step[c] = T(t.n_x_pv[c].ax), y_step[c] = T(t.pu_x_n[c].ax);
  }
  const T c_scale = T(t.bump_c);
  for (int i = 0; i < p.count; ++i) {
    const T w = T(p.w[i]);
    T x[3], y[3];
    for (int c = 0; c < 3; ++c) {
      x[c] = x_w[c] * w, y[c] = y_w[c] * w;
      x_w[c] = x_w[c] + x_step[c], y_w[c] = y_w[c] + y_step[c];
    }
    const T fu = T(p.bump[0][i]), fv = T(p.bump[1][i]);
    for (int c = 0; c < 3; ++c) {
      // The walker carries N/w in perspective mode: the normal itself is that times w.
      const T n = perspective_ ? T(p.n[c][i]) * w : T(p.n[c][i]);
      p.n[c][i] = float(c_scale * n + fu * x[c] + fv * y[c]);
    }
    if (capture_) captured_[0][i] = float(x[0]), captured_[1][i] = float(y[0]);
  }
  for (int c = 0; c < 3; ++c) perturbed_range_.add(p.n[c], p.count);
  ops_ += ops_per_pixel() * uint64_t(p.count);
  if (p.count > 0) ops_ += kOpsPerSpan;
}

void BumpPerturbKernel::process(SpanPacket& p) {
  with_number_type(numbers_, [&](auto zero) { perturb<decltype(zero)>(p); });
  nonfinite_ += count_nonfinite(p.n, p.count);
}

}  // namespace shadetlm::modules
