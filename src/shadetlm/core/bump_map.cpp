#include "shadetlm/core/bump_map.hpp"

#include <algorithm>
#include <cmath>


#include "shadetlm/core/frame.hpp"
#include "shadetlm/core/input_error.hpp"

namespace shadetlm::core {

namespace {

bool power_of_two(int n) { return n > 0 && (n & (n - 1)) == 0; }

double h_at(const Texture& t, int x, int y) { return t.texel(x, y).r; }

}  // namespace

void check_height_map(const Texture& height, const std::string& file, const std::string& field) {
  if (height.width <= 0 || height.height <= 0) throw InputError(file, field, "the height map is empty");
  if (!power_of_two(height.width) || !power_of_two(height.height))
    throw InputError(file, field,
                     "the height map is " + std::to_string(height.width) + "×" + std::to_string(height.height) +
                         ": its sides must be powers of two (the texture unit addresses mip levels by shifts); "
                         "resample the image");
  for (const auto& c : height.texels)
    if (!std::isfinite(c.r)) throw InputError(file, field, "the height map holds NaN or infinite values");
}

Texture height_derivatives(const Texture& height, double height_scale) {
  Texture d;
  d.name = height.name + " (Fu, Fv)";
  d.width = height.width, d.height = height.height, d.wrap = height.wrap;
  d.texels.resize(size_t(d.width) * d.height);
  const int W = d.width, H = d.height;
  // One derivative along an axis of n texels at index i: the neighbours i ± 1 wrapped
  // (Repeat) or clamped (Clamp, where the difference then spans one texel, not two).
  auto difference = [&](int i, int n, auto value) {
    if (n == 1) return 0.0;
    int lo = i - 1, hi = i + 1;
    if (height.wrap == Wrap::Repeat) {
      lo = (lo + n) % n, hi = hi % n;
      return (value(hi) - value(lo)) * 0.5;
    }
    lo = std::max(lo, 0), hi = std::min(hi, n - 1);
    return (value(hi) - value(lo)) / double(hi - lo);
  };
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      // Per texel step, then per unit of u (W texels) and of v (H texels, rows run down).
      const double dx = difference(x, W, [&](int k) { return h_at(height, k, y); });
      const double dy = difference(y, H, [&](int k) { return h_at(height, x, k); });
      const double fu = height_scale * dx * W, fv = -height_scale * dy * H;
      d.texels[size_t(y) * W + x] = glm::vec4(float(fu), float(fv), 0.0f, 1.0f);
    }
  return d;
}

Texture square_normal_map(const Texture& height, double height_scale, double k) {
  Texture n = height_derivatives(height, height_scale);
  n.name = height.name + " (square-patch normals)";
  for (auto& t : n.texels) {
    const glm::dvec3 v = glm::normalize(glm::dvec3(-double(t.r) / k, -double(t.g) / k, 1.0));
    t = glm::vec4(glm::vec3(v), 1.0f);
  }
  return n;
}

const char* to_string(NormalMapForm form) {
  switch (form) {
    case NormalMapForm::Square: return "square";
    case NormalMapForm::Tangent: return "tangent";
    default: return "object";
  }
}

Texture surface_normal_map(const Texture& height, double height_scale, const Mesh& mesh, NormalMapForm form,
                           const glm::dmat3& to_object) {
  if (form == NormalMapForm::Square) return square_normal_map(height, height_scale, 1.0);
  const Texture d = height_derivatives(height, height_scale);
  Texture out = d;
  out.name = height.name + (form == NormalMapForm::Tangent ? " (tangent-space normals)" : " (object-space normals)");
  const int W = d.width, H = d.height;
  std::vector<char> done(size_t(W) * H, 0);
  size_t remaining = done.size();
  for (auto& t : out.texels) t = glm::vec4(0, 0, 1, 1);  // uncovered: unperturbed (tangent form), +z (object form)

  for (const auto& tri : mesh.triangles) {
    if (remaining == 0) break;
    const uint32_t idx[3] = {tri.x, tri.y, tri.z};
    // The uv triangle in texel coordinates (x right, y down, centres at +½), moved by
    // whole periods next to the origin (repeated uv wraps onto the same texels).
    const glm::dvec2 lowest = glm::floor(glm::min(glm::min(mesh.uvs[idx[0]], mesh.uvs[idx[1]]), mesh.uvs[idx[2]]));
    glm::dvec2 st[3];
    for (int k = 0; k < 3; ++k) {
      const glm::dvec2 uv = mesh.uvs[idx[k]] - lowest;
      st[k] = {uv.x * W, (1.0 - uv.y) * H};
    }
    const double area = (st[1].x - st[0].x) * (st[2].y - st[0].y) - (st[2].x - st[0].x) * (st[1].y - st[0].y);
    if (!(std::abs(area) > 1e-12)) continue;  // no uv area: no parameterization to read
    // Pu, Pv: P1 − P0 = Pu du1 + Pv dv1, P2 − P0 = Pu du2 + Pv dv2.
    const glm::dvec3 e1 = mesh.positions[idx[1]] - mesh.positions[idx[0]];
    const glm::dvec3 e2 = mesh.positions[idx[2]] - mesh.positions[idx[0]];
    const glm::dvec2 t1 = mesh.uvs[idx[1]] - mesh.uvs[idx[0]], t2 = mesh.uvs[idx[2]] - mesh.uvs[idx[0]];
    const double det = t1.x * t2.y - t2.x * t1.y;
    const glm::dvec3 Pu = (e1 * t2.y - e2 * t1.y) / det, Pv = (e2 * t1.x - e1 * t2.x) / det;
    const double c = glm::length(glm::cross(Pu, Pv));
    if (!(c > 0) || !std::isfinite(c)) continue;  // no surface: no frame
    // Mirrored parameterization (Pu × Pv against the normals): the relief keeps its sign.
    const double sign =
        glm::dot(glm::cross(Pu, Pv), mesh.normals[idx[0]] + mesh.normals[idx[1]] + mesh.normals[idx[2]]) < 0 ? -1 : 1;
    // The texels the triangle covers; a triangle spanning many periods is visited over
    // its first 4 (every texel of the map is reached long before).
    const double x_lo = std::min({st[0].x, st[1].x, st[2].x}), y_lo = std::min({st[0].y, st[1].y, st[2].y});
    const int x0 = int(std::floor(x_lo)), y0 = int(std::floor(y_lo));
    const int x1 = int(std::min(std::ceil(std::max({st[0].x, st[1].x, st[2].x})), x_lo + 4.0 * W));
    const int y1 = int(std::min(std::ceil(std::max({st[0].y, st[1].y, st[2].y})), y_lo + 4.0 * H));
    for (int y = y0; y <= y1 && remaining > 0; ++y)
      for (int x = x0; x <= x1; ++x) {
        const glm::dvec2 q(x + 0.5, y + 0.5);
        auto edge = [&](glm::dvec2 a, glm::dvec2 b) { return ((b.x - a.x) * (q.y - a.y) - (q.x - a.x) * (b.y - a.y)) / area; };
        const double b0 = edge(st[1], st[2]), b1 = edge(st[2], st[0]), b2 = edge(st[0], st[1]);
        const double eps = -1e-9;
        if (b0 < eps || b1 < eps || b2 < eps) continue;
        // Repeated uv (beyond [0, 1]) lands on the texel it wraps to; the first triangle wins.
        const int tx = ((x % W) + W) % W, ty = ((y % H) + H) % H;
        const size_t at = size_t(ty) * W + tx;
        if (done[at]) continue;
        const glm::dvec3 mixed = b0 * mesh.normals[idx[0]] + b1 * mesh.normals[idx[1]] + b2 * mesh.normals[idx[2]];
        const glm::dvec3 pu_t = Pu - glm::dot(Pu, mixed) / glm::dot(mixed, mixed) * mixed;
        if (!(glm::dot(mixed, mixed) > 0) || !(glm::dot(pu_t, pu_t) > 0)) continue;  // no frame here
        const glm::dvec3 n = glm::normalize(mixed);
        const double fu = sign * d.texels[at].r, fv = sign * d.texels[at].g;
        glm::dvec3 v;
        if (form == NormalMapForm::Object) {
          v = to_object * (c * n + fu * glm::cross(n, Pv) + fv * glm::cross(Pu, n));
        } else {
          const glm::dvec3 T = glm::normalize(pu_t), B = glm::cross(n, T);
          // (9): a = −Fu (B·Pv), b = Fu (T·Pv) − Fv |Pu|, c = |Pu × Pv| (Pu on the tangent plane).
          v = {-fu * glm::dot(B, Pv), fu * glm::dot(T, Pv) - fv * glm::length(pu_t), c};
        }
        const glm::dvec3 unit = glm::normalize(v);
        if (!std::isfinite(unit.x) || !std::isfinite(unit.y) || !std::isfinite(unit.z)) continue;
        out.texels[at] = glm::vec4(glm::vec3(unit), 1.0f);
        done[at] = 1;
        --remaining;
      }
  }
  return out;
}

std::vector<Texture> mip_levels(const Texture& base, bool renormalize) {
  std::vector<Texture> levels;
  const Texture* above = &base;
  while (above->width > 1 || above->height > 1) {
    Texture l;
    l.name = base.name;
    l.wrap = base.wrap;
    l.width = std::max(1, above->width / 2), l.height = std::max(1, above->height / 2);
    l.texels.resize(size_t(l.width) * l.height);
    const int sx = above->width / l.width, sy = above->height / l.height;  // 1 or 2
    for (int y = 0; y < l.height; ++y)
      for (int x = 0; x < l.width; ++x) {
        glm::dvec4 sum(0);
        for (int j = 0; j < sy; ++j)
          for (int i = 0; i < sx; ++i) sum += glm::dvec4(above->texels[size_t(y * sy + j) * above->width + x * sx + i]);
        sum /= double(sx * sy);
        if (renormalize) {
          const double len = glm::length(glm::dvec3(sum));
          if (len > 0) sum = glm::dvec4(glm::dvec3(sum) / len, sum.a);
        }
        l.texels[size_t(y) * l.width + x] = glm::vec4(sum);
      }
    levels.push_back(std::move(l));
    above = &levels.back();
  }
  return levels;
}

}  // namespace shadetlm::core
