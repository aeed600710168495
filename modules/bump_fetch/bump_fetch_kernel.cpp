#include "modules/bump_fetch/bump_fetch_kernel.hpp"

#include <chrono>
#include <cmath>

#include "core/bump_map.hpp"

namespace modules {

bool BumpFetchKernel::needed(const core::Scene& scene) {
  for (const auto& o : scene.objects)
    if (scene.materials[size_t(o.material)].path != core::ShadingPath::Phong) return true;
  return false;
}

BumpFetchKernel::BumpFetchKernel(const core::Scene& scene, const Options& options)
    : scene_(scene), options_(options), sampler_(options.filter, options.probes) {
  const auto start = std::chrono::steady_clock::now();
  std::map<std::pair<int, int>, const Map*> made;  // (material, object or −1) → map
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    const core::Object& object = scene.objects[o];
    const core::Material& m = scene.materials[size_t(object.material)];
    const Map* map = nullptr;
    if (m.path != core::ShadingPath::Phong) {
      // Maps of the height map alone are shared by the material's objects.
      const bool per_object = m.normal_map < 0 && (m.path == core::ShadingPath::BumpTangent ||
                                                   m.path == core::ShadingPath::BumpObject);
      const auto key = std::make_pair(object.material, per_object ? int(o) : -1);
      auto it = made.find(key);
      map = it != made.end() ? it->second : (made[key] = &build(scene, object, m));
    }
    map_of_object_.push_back(map);
  }
  precompute_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

const BumpFetchKernel::Map& BumpFetchKernel::build(const core::Scene& scene, const core::Object& object,
                                                   const core::Material& m) {
  auto map = std::make_unique<Map>();
  bool renormalize = options_.renormalize_mips;
  if (m.normal_map >= 0) {
    const core::Texture& stored = scene.textures[size_t(m.normal_map)];
    map->base = stored;
    map->base.mips.clear();
    map->levels = stored.mips;  // as stored, if the file has them
    for (auto& l : map->levels) l.wrap = stored.wrap;
  } else {
    const core::Texture& height = scene.textures[size_t(m.height_map)];
    switch (m.path) {
      case core::ShadingPath::BumpClassic:
        map->base = core::height_derivatives(height, m.height_scale);
        renormalize = false;  // derivatives, not directions
        break;
      case core::ShadingPath::BumpSquare:
        map->base = core::square_normal_map(height, m.height_scale, m.square_k);
        break;
      case core::ShadingPath::BumpTangent:
        map->base = core::surface_normal_map(height, m.height_scale, core::to_world(object),
                                             core::NormalMapForm::Tangent);
        break;
      default:
        map->base = core::surface_normal_map(height, m.height_scale, core::to_world(object),
                                             core::NormalMapForm::Object, glm::transpose(glm::dmat3(object.model)));
    }
  }
  if (map->levels.empty()) map->levels = core::mip_levels(map->base, renormalize);
  map->mip.levels.push_back(&map->base);
  for (const auto& l : map->levels) map->mip.levels.push_back(&l);
  maps_.push_back(std::move(map));
  return *maps_.back();
}

void BumpFetchKernel::process(SpanPacket& p) {
  const TriangleSetup& t = *p.tri;
  if (!t.bump_frame) {  // no tangent frame: the unperturbed normal (+z), no derivatives
    for (int i = 0; i < p.count; ++i) p.bump[0][i] = 0, p.bump[1][i] = 0, p.bump[2][i] = 1;
    if (capture_)
      for (int c = 0; c < 3; ++c)
        for (int i = 0; i < p.count; ++i) captured_[c][i] = 0;
    return;
  }
  const Map& map = *map_of_object_[size_t(t.object)];
  const int dx = p.x0 - t.x_ref, dy = p.y - t.y_ref;
  float u_w = t.uv[0].at(dx, dy), v_w = t.uv[1].at(dx, dy);
  uv_range_.add_span(u_w, t.uv[0].ax, p.count, p.w);
  uv_range_.add_span(v_w, t.uv[1].ax, p.count, p.w);
  for (int i = 0; i < p.count; ++i) {
    // uv = (uv/w)·w; its derivative along x is (∂(u/w)/∂x − u·∂(1/w)/∂x)·w.
    const float w = p.w[i];
    const float u = u_w * w, v = v_w * w;
    const float dudx = (t.uv[0].ax - u * t.inv_w.ax) * w, dvdx = (t.uv[1].ax - v * t.inv_w.ax) * w;
    const float dudy = (t.uv[0].ay - u * t.inv_w.ay) * w, dvdy = (t.uv[1].ay - v * t.inv_w.ay) * w;
    u_w += t.uv[0].ax, v_w += t.uv[1].ax;
    float out[3];
    sampler_.sample(map.mip, u, v, dudx, dvdx, dudy, dvdy, out, ops_);
    for (int c = 0; c < 3; ++c) p.bump[c][i] = out[c];
    if (capture_) captured_[0][i] = u, captured_[1][i] = v, captured_[2][i] = sampler_.last_lod();
  }
  for (int c = 0; c < 3; ++c) fetched_range_.add(p.bump[c], p.count);
  ops_ += kOpsPerPixel * uint64_t(p.count);
  if (p.count > 0) ops_ += kOpsPerSpan;
}

}  // namespace modules
