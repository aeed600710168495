#pragma once
// Precomputation for bump mapping (docs/bump-mapping.md, bump-mapping paper):
//
//  * the height map's derivatives Fu, Fv by central differences, for the classic path;
//  * textures of perturbed normals: the square-patch form (10)–(11), which depends on
//    the height map alone; the general tangent-space form (8)–(9), which needs the
//    surface's Pu and Pv at every texel; the object-space variant;
//  * mip chains of either, by 2×2 box filtering, renormalized or not.
//
// The height is F(u, v) = height_scale · h(u, v), h the first channel of the height map
// and (u, v) the texture coordinates of core/texture.hpp (v = 1 at row 0).
#include <string>
#include <vector>

#include "shadetlm/core/mesh.hpp"
#include "shadetlm/core/texture.hpp"

namespace shadetlm::core {

// Checks a texture for use as a height map (power-of-two sides, finite values) and
// throws InputError naming `file` and `field` if it cannot be one.
void check_height_map(const Texture& height, const std::string& file, const std::string& field);

// (Fu, Fv, 0, 1) per texel. Central differences over two texels,
//   Fu = s·(h[x+1] − h[x−1])·W/2,   Fv = s·(h[y−1] − h[y+1])·H/2   (rows run down, v up);
// at the border a Repeat map wraps, a Clamp map takes the one-sided difference.
Texture height_derivatives(const Texture& height, double height_scale);

// Square patch (10)–(11): normalize(−Fu/k, −Fv/k, 1).
Texture square_normal_map(const Texture& height, double height_scale, double k);

// The perturbed normal of a surface, per texel: N' = c·n + Fu (n × Pv) + Fv (Pu × n),
// c = |Pu × Pv|, n the unit (interpolated vertex) normal, Pu and Pv the triangle's
// position derivatives, found by rasterizing the mesh's triangles in uv space (texels
// that no triangle covers hold the unperturbed normal). Tangent form: N' in the frame
// T = Pu projected on the tangent plane and normalized, B = n × T, n, i.e. the paper's
// [a, b, c] of (9), normalized. Object form: `to_object` · N', normalized — for a mesh in
// world space, to_object is the transpose of the model matrix's linear part, which takes
// world normals back to object space.
enum class NormalMapForm { Square, Tangent, Object };
const char* to_string(NormalMapForm form);
Texture surface_normal_map(const Texture& height, double height_scale, const Mesh& mesh, NormalMapForm form,
                           const glm::dmat3& to_object = glm::dmat3(1.0));

// Levels 1 … 1×1 of `base` (which must have power-of-two sides), each the 2×2 box
// average of the one above; with `renormalize`, the RGB of every texel of levels ≥ 1 is
// made unit length again (the question the paper leaves open for filtered normals).
std::vector<Texture> mip_levels(const Texture& base, bool renormalize);

// ---- The io component (shadetlm::io, linked apart: file formats) from here on.
// A mip chain as one tiled, mip-mapped EXR (float R, G, B; ZIP), with `attributes`
// (string header attributes), written atomically; and read back: level 0 in the
// returned texture, levels 1 … in its `mips`.
void write_mip_chain(const std::string& path, const Texture& base, const std::vector<Texture>& levels,
                     const std::vector<std::pair<std::string, std::string>>& attributes);

}  // namespace shadetlm::core
