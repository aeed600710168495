#include "shadetlm/modules/bump_perturb/bump_perturb_kernel.hpp"

namespace shadetlm::modules {

bool BumpPerturbKernel::needed(const core::Scene& scene) {
  for (const auto& o : scene.objects)
    if (scene.materials[size_t(o.material)].path == core::ShadingPath::BumpClassic) return true;
  return false;
}

void BumpPerturbKernel::perturb(SpanPacket& p) {
  const TriangleSetup& t = *p.tri;
  const int dx = p.x0 - t.x_ref, dy = p.y - t.y_ref;
  float x_w[3], y_w[3];
  for (int c = 0; c < 3; ++c) {
    x_w[c] = t.n_x_pv[c].at(dx, dy), y_w[c] = t.pu_x_n[c].at(dx, dy);
    n_x_pv_range_.add_span(x_w[c], t.n_x_pv[c].ax, p.count, p.w);
    pu_x_n_range_.add_span(y_w[c], t.pu_x_n[c].ax, p.count, p.w);
  }
  const float c_scale = t.bump_c;
  for (int i = 0; i < p.count; ++i) {
    const float w = p.w[i];
    // The walker carries N/w in perspective mode: the normal itself is that times w.
    const float scale = perspective_ ? w : 1.0f;
    float x[3], y[3];
    for (int c = 0; c < 3; ++c) {
      x[c] = x_w[c] * w, y[c] = y_w[c] * w;
      x_w[c] += t.n_x_pv[c].ax, y_w[c] += t.pu_x_n[c].ax;
    }
    const float fu = p.bump[0][i], fv = p.bump[1][i];
    for (int c = 0; c < 3; ++c) p.n[c][i] = c_scale * (p.n[c][i] * scale) + fu * x[c] + fv * y[c];
    if (capture_) captured_[0][i] = x[0], captured_[1][i] = y[0];
  }
  for (int c = 0; c < 3; ++c) perturbed_range_.add(p.n[c], p.count);
  ops_ += ops_per_pixel() * uint64_t(p.count);
  if (p.count > 0) ops_ += kOpsPerSpan;
}

}  // namespace shadetlm::modules
