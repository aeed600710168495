#include "shadetlm/modules/texel_project/texel_project_kernel.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "shadetlm/core/bump_map.hpp"
#include "shadetlm/core/coverage.hpp"
#include "shadetlm/sampling/sampler.hpp"

namespace shadetlm::modules {

PolygonRotation::PolygonRotation(const glm::dvec3& n) {
  const double d = std::sqrt(n.y * n.y + n.z * n.z);
  if (d > 1e-12) cos_a = n.z / d, sin_a = n.y / d;  // d = 0: n = ±x, any α; α = 0
  cos_b = d, sin_b = n.x;
}

glm::dvec3 PolygonRotation::apply(const glm::dvec3& p, const glm::dvec3& n) const {
  return {p.x * cos_b - p.z * cos_a * sin_b - p.y * sin_a * sin_b, p.y * cos_a - p.z * sin_a,
          p.x * sin_b + p.y * n.y + p.z * n.z};
}

glm::dvec3 PolygonRotation::inverse(const glm::dvec3& q, const glm::dvec3& n) const {
  return {q.x * cos_b + q.z * sin_b, -q.x * sin_a * sin_b + q.y * cos_a + q.z * n.y,
          -q.x * cos_a * sin_b - q.y * sin_a + q.z * n.z};
}

bool TexelProjectKernel::needed(const core::Scene& scene) {
  for (const auto& o : scene.objects)
    if (scene.materials[size_t(o.material)].path == core::ShadingPath::TextureObject) return true;
  return false;
}

TexelProjectKernel::TexelProjectKernel(const core::Scene& scene, int units, core::NumberFormat format,
                                       std::optional<Memory> memory, Lod lod)
    : scene_(scene),
      units_(std::max(1, units)),
      lod_(lod),
      view_projection_(scene.camera.projection() * scene.camera.view()),
      unit_texels_(size_t(std::max(1, units)), 0),
      unit_round_robin_(size_t(std::max(1, units)), 0),
      numbers_(format) {
  mips_.resize(scene.textures.size());
  for (const auto& o : scene.objects) {
    const core::Material& m = scene.materials[size_t(o.material)];
    if (m.path == core::ShadingPath::TextureObject && mips_[size_t(m.texture)].empty())
      mips_[size_t(m.texture)] = core::mip_levels(scene.textures[size_t(m.texture)], false);
  }
  if (memory) {  // every texture's levels one after another; the accumulators in a memory of their own
    memory_settings_ = memory;
    texel_memory_ = std::make_unique<MemoryClient>(memory->cache);
    accumulators_ = std::make_unique<MemoryClient>(memory->cache);
    for (const auto& o : scene.objects) {  // each texture-object texture once (a 1×1 one has no mips)
      const core::Material& m = scene.materials[size_t(o.material)];
      if (m.path != core::ShadingPath::TextureObject) continue;  // (others may have no texture)
      const core::Texture& base = scene.textures[size_t(m.texture)];
      if (surfaces_.count(&base)) continue;
      surfaces_[&base] = texel_memory_->place(base.width, base.height, 4);
      for (const auto& l : mips_[size_t(m.texture)]) surfaces_[&l] = texel_memory_->place(l.width, l.height, 4);
    }
    // A pixel's four numbers, padded to a power of two bytes as a memory would store them
    // (64-bit ones span two lines of 16 bytes: MemoryClient::access reads both).
    uint32_t bytes = 1;
    while (bytes < uint32_t((4 * memory->accumulator_bits + 7) / 8)) bytes *= 2;
    accumulator_surface_ = accumulators_->place(scene.camera.width, scene.camera.height, bytes);
  }
}

uint64_t TexelProjectKernel::accumulator_bytes() const {
  if (!accumulators_) return 0;
  const Cache& c = accumulators_->cache();
  return (c.counts().misses + c.counts().writebacks + c.dirty_lines()) * c.config().line;
}

void TexelProjectKernel::run(FramebufferKernel& fb) {
  if (!needed(scene_)) return;  // elaborated for all (pipeline.elaborate = all), nothing to do
  const int width = scene_.camera.width, height = scene_.camera.height;
  accumulated_.assign(size_t(width) * size_t(height) * 4, 0.0);
  uint32_t source = 0;
  for (const auto& object : scene_.objects) {
    const core::Material& m = scene_.materials[size_t(object.material)];
    if (m.path != core::ShadingPath::TextureObject) {
      source += uint32_t(object.mesh.triangles.size());
      continue;
    }
    const core::Mesh mesh = core::to_world(object);
    const core::Texture& texture = scene_.textures[size_t(m.texture)];
    std::vector<const core::Texture*> levels = {&texture};
    for (const auto& l : mips_[size_t(m.texture)]) levels.push_back(&l);
    for (const auto& t : mesh.triangles) {
      const glm::dvec3 P[3] = {mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]};
      const glm::dvec2 uv[3] = {mesh.uvs[t.x], mesh.uvs[t.y], mesh.uvs[t.z]};
      splat_triangle(P, uv, texture, levels, source++, fb);
    }
  }
  // Resolve and composite: C = (Σ s·c / Σ s) ⊙ D + S.
  core::Frame& frame = fb.frame();
  float* rgb[3] = {frame.at("R").data(), frame.at("G").data(), frame.at("B").data()};
  const auto& visible = fb.visible_source();
  const auto& specular = fb.specular();
  for (size_t i = 0; i < visible.size(); ++i) {
    if (visible[i] == 0) continue;
    ++covered_;
    const double weight = accumulated_[i * 4 + 3];
    if (!(weight > 0)) ++holes_;
    for (int c = 0; c < 3; ++c) {
      const float tex = weight > 0 ? float(accumulated_[i * 4 + size_t(c)] / weight) : 0.0f;
      rgb[c][i] = tex * rgb[c][i] + specular[i * 3 + size_t(c)];
    }
  }
  ops_ += kOpsPerPixel * covered_;
  uint64_t busiest = 0;
  for (uint64_t u : unit_texels_) busiest = std::max(busiest, u);
  cycles_ = busiest + (covered_ + uint64_t(units_) - 1) / uint64_t(units_);
  if (texel_memory_) {  // the DRAM's bytes at its rate, then its latency
    const Cache& c = texel_memory_->cache();
    const uint64_t bytes = (c.counts().misses + c.dirty_lines()) * c.config().line + accumulator_bytes();
    const DramTiming& d = memory_settings_->dram;
    if (bytes > 0) cycles_ = std::max(cycles_, (bytes + d.bytes_per_cycle - 1) / d.bytes_per_cycle) + d.latency;
  }
}

// One triangle's splatting once it is set up: the level sampled and the sampling rate
// (the LOD), the samples' bounds (the traversal), the mapping from the rotated plane
// back to clip space (M*), and the texture tiles its texels are read from.
struct TexelProjectKernel::Splat {
  const glm::dvec2* uv = nullptr;   // the triangle's uvs
  glm::dvec2 t1, t2;                // uv edges from vertex A
  double det = 0;                   // their determinant
  uint32_t source = 0;              // the scene triangle (the visibility buffer holds source + 1)
  const std::vector<uint32_t>* visible = nullptr;
  const core::Texture* texture = nullptr;  // level 0
  const core::Texture* tex = nullptr;      // the level sampled
  long mi = 1;                      // samples per texel and axis (magnified), else 1
  double GW = 0, GH = 0;            // samples per unit of u and of v
  long i0 = 0, i1 = 0, j0 = 0, j1 = 0;  // the samples' box
  double margin = 0, altitude[3] = {}, slope[3] = {};
  glm::dvec2 along_u, along_v;      // uv → (x', y') − A
  double z_eye = 0;                 // z' of the rotated plane relative to the eye's: its distance
  glm::dvec4 A_x, A_y, a0;          // M*: clip = A_x·(x' − x'_A) + A_y·(y' − y'_A) + clip(A)
  long tile_row0 = 0;
  std::vector<std::pair<long, long>> tile_span;  // per row of tiles: the tiles read
  Surface texture_surface, tex_surface;          // where level 0 and the level sampled lie (DRAM model)
};

namespace {
long floor_div(long a, long b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
long bound(double x) { return long(std::clamp(x, -4e9, 4e9)); }
}  // namespace

void TexelProjectKernel::splat_triangle(const glm::dvec3 P[3], const glm::dvec2 uv[3], const core::Texture& texture,
                                        const std::vector<const core::Texture*>& levels, uint32_t source,
                                        const FramebufferKernel& fb) {
  const glm::dvec3 N = glm::cross(P[1] - P[0], P[2] - P[0]);
  const double length = glm::length(N);
  if (!(length > 0) || !std::isfinite(length)) return;  // no plane to rotate (setup skips it too)
  // Only triangles that reach the frame's visible region.
  glm::dvec4 clip[3];
  for (int k = 0; k < 3; ++k) clip[k] = view_projection_ * glm::dvec4(P[k], 1.0);
  const auto visible_part = core::clip_triangle(clip[0], clip[1], clip[2]);
  if (visible_part.size() < 3) return;
  ++polygons_;
  Splat s;
  s.uv = uv, s.source = source, s.visible = &fb.visible_source(), s.texture = &texture;
  s.t1 = uv[1] - uv[0], s.t2 = uv[2] - uv[0];
  s.det = s.t1.x * s.t2.y - s.t2.x * s.t1.y;
  if (!(std::abs(s.det) * texture.width * texture.height > 1e-6) || !std::isfinite(s.det))
    return splat_constant(s, visible_part);
  glm::dvec4 c_u, c_v;
  rotate_into_plane(P, N / length, clip[0], s, c_u, c_v);
  glm::dvec2 uv_lo, uv_hi;
  choose_level(visible_part, levels, c_u, c_v, s, uv_lo, uv_hi);
  bound_samples(uv_lo, uv_hi, s);
  // The projection and the splat weights run in pipeline.texel_project.format (T); the
  // traversal's set-up above stays in double, the accumulation in the frame's buffer.
  with_number_type(numbers_, [&](auto zero) { splat_samples<decltype(zero)>(s); });
  for (const auto& span : s.tile_span)
    if (span.first <= span.second) ops_.line += uint64_t(span.second - span.first + 1);
}

// No texture mapping (the uv triangle covers less than a millionth of a texel): the
// texture is constant over the triangle, its value at the uv. One sample, weight 1, on
// every pixel it is seen at.
void TexelProjectKernel::splat_constant(const Splat& s, const core::ClipPolygon& visible_part) {
  const int width = scene_.camera.width, height = scene_.camera.height;
  const glm::dvec2 centre = (s.uv[0] + s.uv[1] + s.uv[2]) / 3.0;
  const glm::vec4 c = s.texture->bilinear(centre);
  if (texel_memory_) {  // the line of the texel under the centre, for the whole triangle
    const core::Texture& t = *s.texture;
    const double fx = std::floor(centre.x * t.width), fy = std::floor((1 - centre.y) * t.height);
    if (std::isfinite(fx) && std::isfinite(fy)) {
      const bool repeat = t.wrap == core::Wrap::Repeat;
      const double x = repeat ? fx - t.width * std::floor(fx / t.width) : std::clamp(fx, 0.0, double(t.width - 1));
      const double y = repeat ? fy - t.height * std::floor(fy / t.height) : std::clamp(fy, 0.0, double(t.height - 1));
      texel_memory_->access(surfaces_.at(s.texture), std::min(int(x), t.width - 1), std::min(int(y), t.height - 1), false);
    }
  }
  glm::dvec2 lo(width, height), hi(0, 0);
  for (const auto& vertex : visible_part) {
    const glm::dvec3 sp = core::to_screen(vertex.clip, width, height);
    lo = glm::min(lo, glm::dvec2(sp)), hi = glm::max(hi, glm::dvec2(sp));
  }
  ops_.fetch += 4;
  for (int y = std::max(0, int(lo.y) - 1); y <= std::min(height - 1, int(hi.y) + 1); ++y)
    for (int x = std::max(0, int(lo.x) - 1); x <= std::min(width - 1, int(hi.x) + 1); ++x) {
      const size_t at = size_t(y) * size_t(width) + size_t(x);
      if ((*s.visible)[at] != s.source + 1) continue;
      for (int k = 0; k < 3; ++k) accumulated_[at * 4 + size_t(k)] += c[k];
      accumulated_[at * 4 + 3] += 1;
      if (accumulators_) accumulators_->access(accumulator_surface_, x, y, true);
      ++splats_;
    }
}

// (1)–(2), (6), (7): the triangle laid parallel to XY; z' once. Positions in the rotated
// plane are taken relative to vertex A, (x' − x'_A, y' − y'_A), so that float keeps
// their precision far from the origin; M* then adds A's clip position. Also the clip
// coordinates as an affine function of uv, c_u·du + c_v·dv + clip(A), for the LOD.
void TexelProjectKernel::rotate_into_plane(const glm::dvec3 P[3], const glm::dvec3& n, const glm::dvec4& clip_a,
                                           Splat& s, glm::dvec4& c_u, glm::dvec4& c_v) {
  const PolygonRotation R(n);
  glm::dvec3 q[3];
  for (int k = 0; k < 3; ++k) q[k] = R.apply(P[k], n);
  ops_ += Ops{/*add*/ 2 + 9 + 2, /*mul*/ 6 + 2 + 3 * 6 + 2, /*div*/ 3, /*sqrt*/ 2};
  if (lod_ == Lod::ConstantZ) {  // (7) applied to the eye: z' − z'_eye, one product saved as for the vertices
    s.z_eye = std::abs(q[0].z - R.apply(scene_.camera.position, n).z);
    ops_ += Ops{/*add*/ 3, /*mul*/ 3};
  }
  // uv → (x', y') − A: affine over the rotated triangle.
  const glm::dvec2 e1(q[1] - q[0]), e2(q[2] - q[0]);
  s.along_u = (e1 * s.t2.y - e2 * s.t1.y) / s.det, s.along_v = (e2 * s.t1.x - e1 * s.t2.x) / s.det;
  // M* = view-projection · [R]⁻¹: clip = A·(x' − x'_A, y' − y'_A) + clip(A) (z' − z'_A = 0).
  s.A_x = view_projection_ * glm::dvec4(R.inverse({1, 0, 0}, n), 0.0);
  s.A_y = view_projection_ * glm::dvec4(R.inverse({0, 1, 0}, n), 0.0);
  s.a0 = clip_a;
  ops_ += Ops{/*add*/ 6 + 8 + 16, /*mul*/ 12 + 8 + 24, /*div*/ 1};
  c_u = s.A_x * s.along_u.x + s.A_y * s.along_u.y, c_v = s.A_x * s.along_v.x + s.A_y * s.along_v.y;
}

// Pixels per texel step of level 0 at the most magnified point of the visible triangle
// (taken at the vertices of its clipped polygon, where 1/w is largest).
double TexelProjectKernel::most_magnified(const core::ClipPolygon& visible_part, const glm::dvec4& c_u,
                                          const glm::dvec4& c_v, const Splat& s) {
  const int width = scene_.camera.width, height = scene_.camera.height;
  const double W0 = s.texture->width, H0 = s.texture->height;
  double pixels_per_texel = 0;
  for (const auto& vertex : visible_part) {
    const glm::dvec4 c = vertex.clip;
    auto step = [&](const glm::dvec4& d, double texels) {
      const double sx = 0.5 * width * (d.x * c.w - c.x * d.w) / (c.w * c.w);
      const double sy = 0.5 * height * (d.y * c.w - c.y * d.w) / (c.w * c.w);
      return std::sqrt(sx * sx + sy * sy) / texels;
    };
    pixels_per_texel = std::max({pixels_per_texel, step(c_u, W0), step(c_v, H0)});
  }
  ops_ += Ops{/*add*/ 12, /*mul*/ 24, /*div*/ 4, /*sqrt*/ 2, 0, /*lut*/ 1} * uint64_t(visible_part.size());
  return pixels_per_texel;
}

// The paper's rule: the rotated polygon lies parallel to the image plane at distance z'
// from the eye, so a texel step of level 0 (its length in the plane: |along_u| / W0, the
// rotation keeps lengths) spans f / z' pixels per unit, f = ½·height·P[1][1] the focal
// length in pixels. One scale for the whole polygon.
double TexelProjectKernel::constant_z(const Splat& s) {
  const double focal = 0.5 * scene_.camera.height * double(scene_.camera.projection()[1][1]);
  const double texel = std::max(glm::length(s.along_u) / s.texture->width, glm::length(s.along_v) / s.texture->height);
  ops_ += Ops{/*add*/ 2, /*mul*/ 7, /*div*/ 3, /*sqrt*/ 2, 0, /*lut*/ 1};
  return focal * texel / s.z_eye;
}

// The LOD, once per polygon (pipeline.texel_project.lod): pixels per texel step of level
// 0, and the level that makes the spacing at most one pixel. Magnified beyond level 0: m
// samples per texel and axis, read bilinearly. Also the visible part's uv box.
void TexelProjectKernel::choose_level(const core::ClipPolygon& visible_part,
                                      const std::vector<const core::Texture*>& levels, const glm::dvec4& c_u,
                                      const glm::dvec4& c_v, Splat& s, glm::dvec2& uv_lo, glm::dvec2& uv_hi) {
  const int width = scene_.camera.width, height = scene_.camera.height;
  ++lod_computations_;
  const double W0 = s.texture->width, H0 = s.texture->height;
  // A plane through the eye has no z' to scale by: the vertices' rule then.
  const double pixels_per_texel = lod_ == Lod::ConstantZ && s.z_eye > 1e-12 ? constant_z(s)
                                                                            : most_magnified(visible_part, c_u, c_v, s);
  uv_lo = glm::dvec2(1e300), uv_hi = glm::dvec2(-1e300);
  for (const auto& vertex : visible_part) {
    const glm::dvec2 at = vertex.bary.x * s.uv[0] + vertex.bary.y * s.uv[1] + vertex.bary.z * s.uv[2];
    uv_lo = glm::min(uv_lo, at), uv_hi = glm::max(uv_hi, at);
  }
  const int last = int(levels.size()) - 1;
  int level = 0;
  double m = 1;
  if (!(pixels_per_texel > 0) || !std::isfinite(pixels_per_texel)) level = last;
  else if (pixels_per_texel > 1) m = std::ceil(pixels_per_texel), ++oversampled_;
  else level = std::min(last, int(std::floor(-std::log2(pixels_per_texel))));
  // A budget of 64 samples per frame pixel for the visible part's uv box: beyond it the
  // sampling coarsens (fewer samples between texels, then coarser levels), which may
  // leave holes; such polygons are counted.
  const double box = std::max(1e-12, (uv_hi.x - uv_lo.x) * (uv_hi.y - uv_lo.y)) * W0 * H0;
  const double budget = 64.0 * double(width) * double(height);
  auto samples = [&] { return box * m * m / std::pow(4.0, level); };
  if (samples() > budget) {
    ++budget_limited_;
    if (m > 1) m = std::max(1.0, std::floor(std::sqrt(budget / box)));
    while (samples() > budget && level < last) ++level;
  }
  s.tex = levels[size_t(level)];
  s.mi = long(m);
  s.GW = s.tex->width * m, s.GH = s.tex->height * m;
}

// The samples covering the uv triangle, conservatively: within 1.5 sample spacings of it
// (the visibility test drops what lands on other triangles), so that no pixel near an
// edge is left without a sample; only over the visible part's uv box. The traversal
// walks rows of samples; on each row the three edges (moved out by the margin) bound
// the run of samples inside, b_k(u) · altitude_k ≥ −margin with b_k affine in u, like a
// scanline rasterizer's spans.
void TexelProjectKernel::bound_samples(const glm::dvec2& uv_lo, const glm::dvec2& uv_hi, Splat& s) {
  const glm::dvec2* uv = s.uv;
  s.i0 = bound(std::floor(uv_lo.x * s.GW - 0.5)) - 1, s.i1 = bound(std::ceil(uv_hi.x * s.GW - 0.5)) + 1;
  s.j0 = bound(std::floor((1 - uv_hi.y) * s.GH - 0.5)) - 1, s.j1 = bound(std::ceil((1 - uv_lo.y) * s.GH - 0.5)) + 1;
  s.margin = 1.5 * std::max(1.0 / s.GW, 1.0 / s.GH);
  const double area2 = std::abs(s.det);
  s.altitude[0] = area2 / glm::length(uv[2] - uv[1]);
  s.altitude[1] = area2 / glm::length(uv[0] - uv[2]);
  s.altitude[2] = area2 / glm::length(uv[1] - uv[0]);
  s.slope[0] = -(s.t2.y - s.t1.y) / s.det, s.slope[1] = s.t2.y / s.det, s.slope[2] = -s.t1.y / s.det;  // ∂b_k/∂u
  // Memory: the texture is read in 4×4-texel tiles, one line each; a unit streams a
  // triangle's texels row by row with a buffer of one row of tiles, so each tile row
  // costs its span of tiles.
  s.tile_row0 = floor_div(floor_div(s.j0, s.mi), 4);
  s.tile_span.assign(size_t(floor_div(floor_div(s.j1, s.mi), 4) - s.tile_row0 + 1), {1, 0});
}

// The run of samples [first, end] of row j inside the (widened) uv triangle; false if
// the row has none. v and dv: the row's v, and v − v_A.
bool TexelProjectKernel::row_run(const Splat& s, long j, long& first, long& end, double& v, double& dv) {
  const glm::dvec2* uv = s.uv;
  v = 1 - (double(j) + 0.5) / s.GH, dv = v - uv[0].y;
  const double at_u0[3] = {1 - (-dv * s.t2.x + dv * s.t1.x) / s.det, -dv * s.t2.x / s.det,
                           dv * s.t1.x / s.det};  // b_k at u = u0
  double u_min = -1e300, u_max = 1e300;
  for (int k = 0; k < 3; ++k) {
    const double lowest = -s.margin / s.altitude[k];
    if (s.slope[k] > 0) u_min = std::max(u_min, uv[0].x + (lowest - at_u0[k]) / s.slope[k]);
    else if (s.slope[k] < 0) u_max = std::min(u_max, uv[0].x + (lowest - at_u0[k]) / s.slope[k]);
    else if (at_u0[k] < lowest) u_max = -1e300;
  }
  ops_ += kOpsPerRow;
  if (!(u_min <= u_max)) return false;
  first = std::max(s.i0, bound(std::ceil(u_min * s.GW - 0.5))), end = std::min(s.i1, bound(std::floor(u_max * s.GW - 0.5)));
  return true;
}

// Every sample of the triangle: back to the screen through M*; those that land on the
// frame are taken (take_sample).
template <class T>
void TexelProjectKernel::splat_samples(Splat& s) {
  const int width = scene_.camera.width, height = scene_.camera.height;
  const float ax[3] = {float(s.A_x.x), float(s.A_x.y), float(s.A_x.w)};
  const float ay[3] = {float(s.A_y.x), float(s.A_y.y), float(s.A_y.w)};
  const float origin[3] = {float(s.a0.x), float(s.a0.y), float(s.a0.w)};
  const T ax_t[3] = {T(ax[0]), T(ax[1]), T(ax[2])}, ay_t[3] = {T(ay[0]), T(ay[1]), T(ay[2])};
  const T origin_t[3] = {T(origin[0]), T(origin[1]), T(origin[2])};
  const T one = T(1.0f), half = T(0.5f), w_min = T(1e-6f), width_t = T(float(width)), height_t = T(float(height));
  Sampler bilinear(Filter::Bilinear, 1);
  MipMap finest;
  finest.levels.push_back(s.texture);
  if (texel_memory_) {
    s.texture_surface = surfaces_.at(s.texture), s.tex_surface = surfaces_.at(s.tex);
    finest.surfaces.push_back(s.texture_surface);
    bilinear.set_memory(texel_memory_.get());
  }
  uint64_t nonfinite_positions = 0;
  for (long j = s.j0; j <= s.j1; ++j) {
    long first, end;
    double v, dv;
    if (!row_run(s, j, first, end, v, dv)) continue;
    // (x', y') − A at the run's first sample, then a constant step per sample.
    const double du_first = (double(first) + 0.5) / s.GW - s.uv[0].x;
    T xr = T(float(s.along_u.x * du_first + s.along_v.x * dv)), yr = T(float(s.along_u.y * du_first + s.along_v.y * dv));
    const T step_x = T(float(s.along_u.x / s.GW)), step_y = T(float(s.along_u.y / s.GW));
    ops_ += Ops{/*add*/ 3, /*mul*/ 6, /*div*/ 2};
    for (long i = first; i <= end; ++i, xr += step_x, yr += step_y) {
      // Back to the screen: (x', y') − A (stepped along the row: 2 add), then M*; behind
      // the eye: nothing to splat.
      ops_ += kOpsProjection;
      const T cx = ax_t[0] * xr + ay_t[0] * yr + origin_t[0];
      const T cy = ax_t[1] * xr + ay_t[1] * yr + origin_t[1];
      const T cw = ax_t[2] * xr + ay_t[2] * yr + origin_t[2];
      if (!(cw > w_min)) {  // behind the eye (or, in a reduced format, not finite: counted)
        if constexpr (!std::is_same_v<T, float>) nonfinite_positions += !std::isfinite(float(cw));
        continue;
      }
      const T inv_w = one / cw;
      const T x = (cx * inv_w * half + half) * width_t - half;  // pixel centres at +½
      const T y = (half - cy * inv_w * half) * height_t - half;
      if (!(x > -one && y > -one && x < width_t && y < height_t)) {  // off the frame
        // A non-finite position (a reduced format's overflow: in float32, w > 1e-6 keeps
        // it finite) is dropped too, counted.
        if constexpr (!std::is_same_v<T, float>)
          nonfinite_positions += !std::isfinite(float(x)) + !std::isfinite(float(y));
        continue;
      }
      take_sample(s, i, j, v, x, y, bilinear, finest);
    }
  }
  nonfinite_ += nonfinite_positions;
}

// A sample on the frame: its texel counted, its colour, its splat.
template <class T>
void TexelProjectKernel::take_sample(Splat& s, long i, long j, double v, T x, T y, Sampler& bilinear,
                                     const MipMap& finest) {
  count_texel(s, i, j);
  float colour[3];
  const double u = (double(i) + 0.5) / s.GW;
  sample_colour(s, i, j, u, v, bilinear, finest, colour);
  splat(s, x, y, colour);
}

// A texel on the frame: its operations, and the tile it is read from.
void TexelProjectKernel::count_texel(Splat& s, long i, long j) {
  ++texels_;
  ops_ += kOpsPerTexel;
  auto& span = s.tile_span[size_t(floor_div(floor_div(j, s.mi), 4) - s.tile_row0)];
  const long tile = floor_div(floor_div(i, s.mi), 4);
  if (span.first > span.second) span = {tile, tile};
  else span.first = std::min(span.first, tile), span.second = std::max(span.second, tile);
}

// The sample's colour: the texel of the level (or, magnified, bilinear on level 0).
void TexelProjectKernel::sample_colour(const Splat& s, long i, long j, double u, double v, Sampler& bilinear,
                                       const MipMap& finest, float colour[3]) {
  const core::Texture& tex = *s.tex;
  if (s.mi == 1) {
    int tx = int(((i % tex.width) + tex.width) % tex.width), ty = int(((j % tex.height) + tex.height) % tex.height);
    if (tex.wrap == core::Wrap::Clamp)
      tx = int(std::clamp<long>(i, 0, tex.width - 1)), ty = int(std::clamp<long>(j, 0, tex.height - 1));
    const glm::vec4& c = tex.texels[size_t(ty) * size_t(tex.width) + size_t(tx)];
    colour[0] = c.r, colour[1] = c.g, colour[2] = c.b;
    if (texel_memory_) texel_memory_->access(s.tex_surface, tx, ty, false);
    return;
  }
  Ops sampler_ops;
  const bool repeat = s.texture->wrap == core::Wrap::Repeat;  // whole periods off in double
  bilinear.sample(finest, float(repeat ? u - std::floor(u) : u), float(repeat ? v - std::floor(v) : v), 0, 0, 0, 0,
                  colour, sampler_ops);
  sampler_ops.line = 0;  // lines: counted by tile rows
  ops_ += sampler_ops;
  ops_.fetch -= 1;       // counted in kOpsPerTexel
}

// (S1 … S4): the area weights of the four pixels around the sample at (x, y), each
// accumulated where this triangle is the one seen.
template <class T>
void TexelProjectKernel::splat(const Splat& s, T x, T y, const float colour[3]) {
  const int width = scene_.camera.width, height = scene_.camera.height;
  const T one = T(1.0f);
  const T fx0 = floor_op(x), fy0 = floor_op(y);
  const T fx = x - fx0, fy = y - fy0;
  const T weight_t[4] = {(one - fx) * (one - fy), fx * fy, fx * (one - fy), (one - fx) * fy};  // S1 … S4
  const float weight[4] = {float(weight_t[0]), float(weight_t[1]), float(weight_t[2]), float(weight_t[3])};
  const int px0 = int(float(fx0)), py0 = int(float(fy0));
  const int px[4] = {px0, px0 + 1, px0 + 1, px0};
  const int py[4] = {py0, py0 + 1, py0, py0 + 1};
  weight_sum_error_ = std::max(weight_sum_error_, std::abs(double(weight[0] + weight[1] + weight[2] + weight[3]) - 1.0));
  // Splat units own interleaved 4×4 pixel tiles; a texel goes to the unit of its first
  // pixel, and a splat into another unit's tile is a write across units (counted).
  const int owner = (((px[0] + 4) >> 2) + ((py[0] + 4) >> 2)) % units_;
  ++unit_texels_[size_t(owner)];
  ++unit_round_robin_[size_t(texels_ % uint64_t(units_))];
  unsigned taken = 0;  // the splats accumulated, a bit each (their memory, below)
#pragma GCC unroll 4  // (GCC keeps the loop otherwise: 7 % of texel_project's instructions)
  for (int k = 0; k < 4; ++k) {
    if (px[k] < 0 || py[k] < 0 || px[k] >= width || py[k] >= height || weight[k] <= 0) continue;
    const size_t at = size_t(py[k]) * size_t(width) + size_t(px[k]);
    if ((*s.visible)[at] != s.source + 1) continue;  // the depth test: another surface is seen here
    for (int c = 0; c < 3; ++c) accumulated_[at * 4 + size_t(c)] += double(weight[k] * colour[c]);
    accumulated_[at * 4 + 3] += double(weight[k]);
    taken |= 1u << k;
    ++splats_;
    ops_ += kOpsPerAccumulation;
    if ((((px[k] + 4) >> 2) + ((py[k] + 4) >> 2)) % units_ != owner) ++cross_unit_splats_;
  }
  if (accumulators_ && taken) accumulate_in_memory(px0, py0, taken);
}

// The accumulators' read-modify-writes of the splats taken (bit k: pixel k of splat's
// S1 … S4 order around (px0, py0)), through their cache.
void TexelProjectKernel::accumulate_in_memory(int px0, int py0, unsigned taken) {
  const int dx[4] = {0, 1, 1, 0}, dy[4] = {0, 1, 0, 1};
  for (int k = 0; k < 4; ++k)
    if (taken >> k & 1) accumulators_->access(accumulator_surface_, px0 + dx[k], py0 + dy[k], true);
}

nlohmann::json TexelProjectKernel::details() const {
  uint64_t busiest = 0, busiest_rr = 0;
  for (uint64_t u : unit_texels_) busiest = std::max(busiest, u);
  for (uint64_t u : unit_round_robin_) busiest_rr = std::max(busiest_rr, u);
  const double covered = covered_ > 0 ? double(covered_) : 1.0;
  return {{"polygons", polygons_},
          {"lod_rule", lod_ == Lod::ConstantZ ? "constant-z" : "most-magnified"},
          {"lod_computations", lod_computations_},
          {"magnified_polygons", oversampled_},
          {"texels", texels_},
          {"texels_per_covered_pixel", double(texels_) / covered},
          {"splats", splats_},
          {"accumulations_per_covered_pixel", double(splats_) / covered},
          {"covered_pixels", covered_},
          {"holes", holes_},
          {"weight_sum_error", weight_sum_error_},
          {"budget_limited_polygons", budget_limited_},
          {"cross_unit_splats", cross_unit_splats_},
          {"units", units_},
          {"unit_texels", unit_texels_},
          {"busiest_unit_texels", busiest},
          {"busiest_unit_texels_round_robin", busiest_rr},
          {"cycles", cycles_}};
}

}  // namespace shadetlm::modules
