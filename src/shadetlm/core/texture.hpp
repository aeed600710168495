#pragma once
// Textures and the texture-addressing convention that the golden model and the
// pipeline share: texel (x, y) has its centre at u = (x + ½)/W, v = 1 − (y + ½)/H;
// row 0 is the top of the image (v = 1), as in image files.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace shadetlm::core {

enum class Wrap { Repeat, Clamp };

struct Texture {
  std::string name;
  int width = 0, height = 0;
  std::vector<glm::vec4> texels;  // row-major, row 0 at the top
  Wrap wrap = Wrap::Repeat;
  bool srgb = false;  // the stored values are sRGB-encoded colours
  bool unorm = false;  // read from an 8- or 16-bit image: values in [0, 1] (a normal map's are (N + 1) / 2)
  std::vector<Texture> mips;  // levels 1 … of a mip-mapped EXR as read (else empty)

  glm::dvec4 texel(int x, int y) const;      // with the wrap mode applied
  glm::dvec4 bilinear(glm::dvec2 uv) const;  // of the stored (finest) level
};

double srgb_to_linear(double c);
double linear_to_srgb(double c);
// The texture with its colour channels decoded to linear (alpha untouched).
Texture decode_srgb(const Texture& t);
// A normal map read from an 8- or 16-bit image: x ↦ 2x − 1 on R, G, B, the stored
// (N + 1) / 2 back to N (docs/scene-format.md).
Texture decode_unorm_normals(const Texture& t);
// How a normal map's stored channels R, G, B hold the model's axes (a material's
// normal_map_channels): channel c holds sign[c] times axis axis[c] (0 x, 1 y, 2 z). The
// default reads R, G, B as x, y, z (OpenGL's and glTF's tangent space); a map whose
// green points down (DirectX's) is x, −y, z.
struct NormalChannels {
  int axis[3] = {0, 1, 2};
  float sign[3] = {1, 1, 1};
  bool identity() const;
  std::string text() const;  // e.g. "x,-y,z"
};
// The normal map read through `channels`: each texel's (and mip level's) normal in the
// model's axes (alpha untouched).
Texture remap_normal_channels(const Texture& t, const NormalChannels& channels);
// A normal's component as such an image stores it in `bits`: (n + 1) / 2 in
// 0 … 2^bits − 1, rounded to nearest (clamped to [−1, 1]).
uint32_t encode_unorm(float n, int bits);

// Procedural textures for tests and demos. All are periodic over [0,1]², so they tile
// seamlessly under Wrap::Repeat. Noise values lie in [0, 1].
struct ProceduralParams {
  glm::ivec2 size{256, 256};
  glm::ivec2 cells{8, 8};   // checks, bricks, tiles, or noise lattice cells
  int octaves = 1;
  int levels = 4;           // steps: number of height levels
  double gap = 0.05;        // bricks, tiles: mortar / grout width as a share of a cell
  uint32_t seed = 1;
  glm::dvec3 color_a{1, 1, 1}, color_b{0, 0, 0};
};
Texture make_checker(const ProceduralParams& p);
Texture make_bricks(const ProceduralParams& p);        // color_a bricks, color_b mortar
Texture make_tiles(const ProceduralParams& p);         // tiles of varying shade of color_a
Texture make_value_noise(const ProceduralParams& p);   // mix(color_b, color_a, noise)
Texture make_gradient_noise(const ProceduralParams& p);
Texture make_ridges(const ProceduralParams& p);        // sharp crests: 1 − |gradient noise|
Texture make_steps(const ProceduralParams& p);         // value noise quantized to `levels`

// ---- The io component (shadetlm::io, linked apart: file formats) from here on.
// Image files: PNG (8 or 16 bit, through stb) and EXR (any of R, G, B, A, Y).
Texture load_texture_file(const std::string& path);

}  // namespace shadetlm::core
