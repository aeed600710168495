// What a run will hold beyond its scene, estimated before anything is built
// (docs/robustness.md): the scene's images and meshes were counted as they were read.
// The figures per pixel were measured with /usr/bin/time on 2048×2048 frames (the
// pipeline about 36 bytes a pixel on Phong, the golden model about 97) and rounded up
// for the layers and buffers other paths add (texel_project's accumulators: 48 bytes).
#include <algorithm>

#include "app/commands.hpp"
#include "shadetlm/core/memory_budget.hpp"

namespace shadetlm::app {

namespace {

constexpr uint64_t kPipelinePerPixel = 96;   // the frame's layers and the blocks' buffers
constexpr uint64_t kGoldenPerPixel = 128;    // the golden model's image and its frame
constexpr uint64_t kGoldenHitPerPixel = 40;  // and its parallax hit (Image::hit, three float layers)
constexpr uint64_t kTracePerPixel = 4096;    // a traced pixel's records at every block
constexpr uint64_t kTexel = 16;              // a float RGBA texel

uint64_t texels(const core::Texture& t) { return uint64_t(t.width) * uint64_t(t.height); }

// The maps the blocks build from a material's textures (docs/memory.md has what each holds).
void material_needs(const core::Scene& s, size_t material, int objects, std::vector<MemoryNeed>& needs) {
  const core::Material& m = s.materials[material];
  const std::string field = "materials." + m.name;
  if (m.path == core::ShadingPath::Parallax && m.height_map >= 0) {
    const uint64_t cells = texels(s.textures[size_t(m.height_map)]);
    const core::ParallaxSettings& p = m.parallax;
    const uint64_t volume = cells * uint64_t(p.slices) * 4;
    const uint64_t maps = p.method == core::ParallaxMethod::Distance ? volume * (p.map == core::DistanceMap::Refined ? 2 : 1)
                          : p.method == core::ParallaxMethod::Cone   ? cells * 16
                                                                     : 0;
    needs.push_back({cells * 4 + maps, field + ".parallax.slices"});
  }
  if (core::bump_path(m.path) && (m.height_map >= 0 || m.normal_map >= 0)) {
    // A normal map and its mip levels (4/3 of it), per object for the forms that follow
    // the surface.
    const int map = m.normal_map >= 0 ? m.normal_map : m.height_map;
    const bool per_object = m.normal_map < 0 && (m.path == core::ShadingPath::BumpTangent ||
                                                  m.path == core::ShadingPath::BumpObject);
    needs.push_back({texels(s.textures[size_t(map)]) * kTexel * 4 / 3 * uint64_t(per_object ? objects : 1),
                     field + (m.normal_map >= 0 ? ".normal_map" : ".height_map")});
  }
  if ((m.path == core::ShadingPath::TextureScreen || m.path == core::ShadingPath::TextureObject) && m.texture >= 0)
    needs.push_back({texels(s.textures[size_t(m.texture)]) * kTexel / 3, field + ".texture"});  // its mip levels
}

}  // namespace

std::vector<MemoryNeed> run_needs(const core::Scene& s, bool pipeline, bool golden, uint64_t traced_pixels) {
  const uint64_t pixels = uint64_t(s.camera.width) * uint64_t(s.camera.height);
  std::vector<MemoryNeed> needs;
  if (pipeline) needs.push_back({pixels * kPipelinePerPixel, "camera.resolution"});
  const bool parallax = std::any_of(s.objects.begin(), s.objects.end(), [&](const core::Object& o) {
    return s.materials[size_t(o.material)].path == core::ShadingPath::Parallax;
  });
  if (golden) needs.push_back({pixels * (kGoldenPerPixel + (parallax ? kGoldenHitPerPixel : 0)), "camera.resolution"});
  if (traced_pixels > 0) needs.push_back({traced_pixels * kTracePerPixel, "--trace-region"});
  if (pipeline)
    for (size_t m = 0; m < s.materials.size(); ++m) {
      const int objects = int(std::count_if(s.objects.begin(), s.objects.end(),
                                            [&](const core::Object& o) { return size_t(o.material) == m; }));
      if (objects > 0) material_needs(s, m, objects, needs);
    }
  return needs;
}

void take_run_memory(const core::Scene& scene, bool pipeline, bool golden, uint64_t traced_pixels) {
  const std::vector<MemoryNeed> needs = run_needs(scene, pipeline, golden, traced_pixels);
  core::MemoryBudget& budget = core::MemoryBudget::process();
  uint64_t total = 0;
  const MemoryNeed* largest = nullptr;
  for (const MemoryNeed& n : needs) {
    total += n.bytes;
    if (!largest || n.bytes > largest->bytes) largest = &n;
  }
  if (largest) budget.take(total, scene.file, largest->field);
}

}  // namespace shadetlm::app
