#include "shadetlm/modules/bump_fetch/bump_fetch_kernel.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "shadetlm/core/bump_map.hpp"

namespace shadetlm::modules {

bool BumpFetchKernel::needed(const core::Scene& scene) {
  for (const auto& o : scene.objects)
    if (core::bump_path(scene.materials[size_t(o.material)].path)) return true;
  return false;
}

namespace {
// Each component as the texture memory holds it in `bits` (core::encode_unorm), and back.
void store_unorm(core::Texture& t, int bits) {
  const float levels = float((1u << bits) - 1);
  for (auto& texel : t.texels)
    for (int k = 0; k < 3; ++k) texel[k] = float(core::encode_unorm(texel[k], bits)) / levels * 2.0f - 1.0f;
}
}  // namespace

BumpFetchKernel::BumpFetchKernel(const core::Scene& scene, const Options& options, core::NumberFormat format)
    : scene_(scene), options_(options), numbers_(format), sampler_(options.filter, options.probes) {
  const auto start = std::chrono::steady_clock::now();
  std::map<std::pair<int, int>, const Map*> made;  // (material, object or −1) → map
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    const core::Object& object = scene.objects[o];
    const core::Material& m = scene.materials[size_t(object.material)];
    const Map* map = nullptr;
    if (core::bump_path(m.path)) {
      // Maps of the height map alone are shared by the material's objects.
      const bool per_object = m.normal_map < 0 && (m.path == core::ShadingPath::BumpTangent ||
                                                   m.path == core::ShadingPath::BumpObject);
      const auto key = std::make_pair(object.material, per_object ? int(o) : -1);
      auto it = made.find(key);
      map = it != made.end() ? it->second : (made[key] = &build(scene, object, m));
    }
    map_of_object_.push_back(map);
  }
  if (options.cache) {  // the maps one after another in the unit's memory
    memory_ = std::make_unique<MemoryClient>(*options.cache);
    for (auto& map : maps_) place(map->mip, *memory_);
    sampler_.set_memory(memory_.get());
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
  if (options_.stored_bits > 0 && m.path != core::ShadingPath::BumpClassic) {
    store_unorm(map->base, options_.stored_bits);
    for (auto& l : map->levels) store_unorm(l, options_.stored_bits);
  }
  map->mip.levels.push_back(&map->base);
  for (const auto& l : map->levels) map->mip.levels.push_back(&l);
  maps_.push_back(std::move(map));
  return *maps_.back();
}

void BumpFetchKernel::fetch(SpanPacket& p) {
  const TriangleSetup& t = *p.tri;
  if (!t.bump_frame) {  // no tangent frame: the unperturbed normal (+z), no derivatives
    for (int i = 0; i < p.count; ++i) p.bump[0][i] = 0, p.bump[1][i] = 0, p.bump[2][i] = 1, work_[i] = 1, lines_[i] = 0;
    if (capture_)
      for (int c = 0; c < 3; ++c)
        for (int i = 0; i < p.count; ++i) captured_[c][i] = 0;
    return;
  }
  const Map& map = *map_of_object_[size_t(t.object)];
  sample_span(t, p, map.mip, sampler_, p.bump, ops_, uv_range_, work_, capture_ ? captured_ : nullptr,
              memory_ ? lines_ : nullptr);
  for (int c = 0; c < 3; ++c) fetched_range_.add(p.bump[c], p.count);
}

}  // namespace shadetlm::modules
