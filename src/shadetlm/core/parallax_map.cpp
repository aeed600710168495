#include "shadetlm/core/parallax_map.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>

#include "shadetlm/core/frame.hpp"
#include "shadetlm/core/input_error.hpp"

namespace shadetlm::core {

HeightField height_field(const Texture& map, const std::string& file, const std::string& field) {
  if (map.width <= 0 || map.height <= 0 || map.texels.size() != size_t(map.width) * size_t(map.height))
    throw InputError(file, field, "the height map is empty");
  HeightField f;
  f.width = map.width, f.height = map.height;
  f.h.resize(map.texels.size());
  for (size_t i = 0; i < map.texels.size(); ++i) {
    const float v = map.texels[i].r;
    if (!std::isfinite(v))
      throw InputError(file, field,
                       "the height map has a non-finite value at texel (" + std::to_string(i % size_t(map.width)) +
                           ", " + std::to_string(i / size_t(map.width)) + ")");
    f.h[i] = std::clamp(v, 0.0f, 1.0f);
  }
  return f;
}

float VolumeMap::sample(float x, float y, float z) const {
  int i = int(std::floor(x)) % width, j = int(std::floor(y)) % height;
  if (i < 0) i += width;
  if (j < 0) j += height;
  const int k = std::clamp(int(std::floor(z)), 0, slices - 1);
  return at(i, j, k);
}

std::vector<float> cell_tops(const HeightField& f) {
  std::vector<float> top(f.h.size());
  for (int j = 0; j < f.height; ++j)
    for (int i = 0; i < f.width; ++i) {
      const auto c = f.corners(i, j);
      top[size_t(j) * size_t(f.width) + size_t(i)] = std::max(std::max(c.h00, c.h10), std::max(c.h01, c.h11));
    }
  return top;
}

namespace {

constexpr float kFar = 1e20f;  // "no solid voxel on this line"

// One axis of the box-gap transform, in place on `line` (squared gaps so far):
//   out[i] = min over j of line[j] + max(0, |i − j| − 1)²,
// the one-voxel dilation first (min of the three neighbours), then the lower envelope of
// the parabolas line[j] + (i − j)² (Felzenszwalb & Huttenlocher 2012). Without `dilate`
// it is the squared Euclidean transform of centres, min over j of line[j] + (i − j)². A
// periodic line is laid out three times so that the envelope sees the wrapped neighbours.
// In double: the squares of positions in a tripled line of 4096 pass float's 2²⁴.
void gap_transform_1d(std::vector<float>& line, bool periodic, bool dilate, std::vector<double>& g,
                      std::vector<int>& v, std::vector<double>& z) {
  const int n = int(line.size());
  const int copies = periodic ? 3 : 1;
  const int m = n * copies;
  g.resize(size_t(m));
  for (int c = 0; c < copies; ++c)
    for (int i = 0; i < n; ++i) {
      double best = line[size_t(i)];
      for (int o : {-1, 1}) {
        if (!dilate) break;
        int k = i + o;
        if (periodic) k = (k + n) % n;
        if (k >= 0 && k < n) best = std::min(best, double(line[size_t(k)]));
      }
      g[size_t(c * n + i)] = best;
    }
  v.assign(size_t(m), 0);
  z.assign(size_t(m) + 1, 0);
  int k = -1;
  for (int q = 0; q < m; ++q) {
    if (g[size_t(q)] >= kFar) continue;
    while (k >= 0) {
      const int p = v[size_t(k)];
      const double s = ((g[size_t(q)] + double(q) * q) - (g[size_t(p)] + double(p) * p)) / double(2 * (q - p));
      if (s <= z[size_t(k)]) {
        --k;
        continue;
      }
      ++k;
      v[size_t(k)] = q, z[size_t(k)] = s, z[size_t(k) + 1] = std::numeric_limits<double>::infinity();
      break;
    }
    if (k < 0) {
      k = 0;
      v[0] = q, z[0] = -std::numeric_limits<double>::infinity(), z[1] = std::numeric_limits<double>::infinity();
    }
  }
  const int offset = periodic ? n : 0;  // the middle copy
  if (k < 0) {
    std::fill(line.begin(), line.end(), kFar);
    return;
  }
  int e = 0;
  for (int i = 0; i < n; ++i) {
    const double q = double(i + offset);
    while (z[size_t(e) + 1] < q) ++e;
    const double d = q - double(v[size_t(e)]);
    line[size_t(i)] = float(std::min(double(kFar), g[size_t(v[size_t(e)])] + d * d));
  }
}

// The box-gap (or, without `dilate`, Euclidean) transform along one axis of a grid of
// `dims` (x fastest), in place.
void gap_transform_axis(std::vector<float>& grid, const int dims[3], int axis, bool periodic, bool dilate = true) {
  const size_t stride[3] = {1, size_t(dims[0]), size_t(dims[0]) * size_t(dims[1])};
  const int n = dims[axis];
  const int a = (axis + 1) % 3, b = (axis + 2) % 3;
  std::vector<float> line(static_cast<size_t>(n));
  std::vector<double> g, z;
  std::vector<int> v;
  for (int ib = 0; ib < dims[b]; ++ib)
    for (int ia = 0; ia < dims[a]; ++ia) {
      const size_t base = size_t(ia) * stride[a] + size_t(ib) * stride[b];
      for (int i = 0; i < n; ++i) line[size_t(i)] = grid[base + size_t(i) * stride[axis]];
      gap_transform_1d(line, periodic, dilate, g, v, z);
      for (int i = 0; i < n; ++i) grid[base + size_t(i) * stride[axis]] = line[size_t(i)];
    }
}

// The shortest of 15 or 17 significant digits that reads back as v: a key holds every
// parameter exactly, and 0.25 stays "0.25".
std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.15g", v);
  if (std::strtod(buf, nullptr) != v) std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace

VolumeMap box_gap_map(const HeightField& f, int slices) {
  VolumeMap m;
  m.width = f.width, m.height = f.height, m.slices = slices;
  const std::vector<float> top = cell_tops(f);
  m.values.assign(size_t(f.width) * size_t(f.height) * size_t(slices), kFar);
  // Solid: the voxel meets the cell's box [0, D·top] (touching counts: safe).
  for (int k = 0; k < slices; ++k)
    for (size_t c = 0; c < top.size(); ++c)
      if (float(k) <= float(slices) * top[c]) m.values[size_t(k) * top.size() + c] = 0;
  const int dims[3] = {f.width, f.height, slices};
  gap_transform_axis(m.values, dims, 0, true);
  gap_transform_axis(m.values, dims, 1, true);
  gap_transform_axis(m.values, dims, 2, false);
  for (float& v : m.values) v = std::sqrt(v);
  m.params = map_key("box-gap", f, slices);
  m.params.insert({{"shadetlm:units", "voxels"},
                   {"shadetlm:safety", "box gap: no point of the voxel is nearer the cells' boxes [cell] x [0, D*max corner]"}});
  return m;
}

VolumeMap donnelly_map(const HeightField& f, int slices) {
  VolumeMap m;
  m.width = f.width, m.height = f.height, m.slices = slices;
  const size_t cells = size_t(f.width) * size_t(f.height);
  m.values.assign(cells * size_t(slices), kFar);
  for (int j = 0; j < f.height; ++j)
    for (int i = 0; i < f.width; ++i) {
      const double centre = double(slices) * bilinear_height<double>(f, i + 0.5, j + 0.5);
      for (int k = 0; k < slices && k + 0.5 <= centre; ++k)
        m.values[size_t(k) * cells + size_t(j) * size_t(f.width) + size_t(i)] = 0;
    }
  const int dims[3] = {f.width, f.height, slices};
  for (int axis = 0; axis < 3; ++axis) gap_transform_axis(m.values, dims, axis, axis < 2, false);
  // The floor is solid too: a solid slice at k = −1, k + 1 voxels below each centre.
  for (int k = 0; k < slices; ++k)
    for (size_t c = 0; c < cells; ++c) {
      float& v = m.values[size_t(k) * cells + c];
      v = std::sqrt(std::min(v, float((k + 1) * (k + 1))));
    }
  m.params = map_key("donnelly", f, slices);
  m.params.insert({{"shadetlm:units", "voxels"},
                   {"shadetlm:safety", "none: Euclidean distance between voxel centres, read trilinearly (Donnelly)"}});
  return m;
}

VolumeMap refined_map(const HeightField& f, const VolumeMap& distance, const RefinedParams& p) {
  const int W = f.width, H = f.height, D = distance.slices;
  const size_t cells = size_t(W) * size_t(H);
  const std::vector<float> top = cell_tops(f);
  std::vector<float> remaining(distance.values.size(), std::numeric_limits<float>::infinity());
  // The sampled directions, in the tracer's space (unit, pointing down).
  struct Dir {
    double x, y, z;
  };
  std::vector<Dir> dirs;
  const double pi = 3.14159265358979323846;
  const double lo = p.min_elevation_deg * pi / 180;
  for (int e = 0; e < p.elevations; ++e) {
    const double el = p.elevations == 1 ? lo : lo + (pi / 2 - lo) * double(e) / double(p.elevations);
    for (int a = 0; a < p.azimuths; ++a) {
      const double az = 2 * pi * (double(a) + 0.5 * (e % 2)) / double(p.azimuths);
      dirs.push_back({std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), -std::sin(el)});
    }
  }
  dirs.push_back({0, 0, -1});
  struct Visit {
    size_t voxel;
    double t_out;
  };
  std::vector<Visit> visits;
  const int n = std::max(1, p.rays_per_texel);
  const double inf = std::numeric_limits<double>::infinity();
  for (const Dir& d : dirs) {
    const double step_x = d.x != 0 ? 1 / std::abs(d.x) : inf, step_y = d.y != 0 ? 1 / std::abs(d.y) : inf;
    const double step_z = 1 / std::abs(d.z);
    for (int ry = 0; ry < H * n; ++ry)
      for (int rx = 0; rx < W * n; ++rx) {
        // The ray enters the top face at a lattice point; it is walked voxel by voxel (a
        // 3-D DDA), each voxel's column tested exactly against its bilinear cell.
        const double ox = (rx + 0.5) / n, oy = (ry + 0.5) / n, oz = D;
        double ci = std::floor(ox), cj = std::floor(oy);
        int k = D - 1;
        double t_x = d.x > 0 ? (ci + 1 - ox) / d.x : d.x < 0 ? (ci - ox) / d.x : inf;
        double t_y = d.y > 0 ? (cj + 1 - oy) / d.y : d.y < 0 ? (cj - oy) / d.y : inf;
        double t_z = step_z;
        double t = 0, t_hit = -1;
        visits.clear();
        while (k >= 0) {
          const double t_end = std::min(std::min(t_x, t_y), t_z);
          int i = int(ci) % W, j = int(cj) % H;
          if (i < 0) i += W;
          if (j < 0) j += H;
          const size_t cell = size_t(j) * size_t(W) + size_t(i);
          const double z_low = oz + t_end * d.z;  // the segment's lowest point
          if (z_low <= double(D) * top[cell]) {   // else it passes over the cell's box
            const double s = cell_hit<double>(f, int(ci), int(cj), ox + t * d.x - ci, oy + t * d.y - cj,
                                              oz + t * d.z, d.x, d.y, d.z, t_end - t, double(D));
            if (s >= 0) {
              t_hit = t + s;
              visits.push_back({size_t(k) * cells + cell, t_end});
              break;
            }
          }
          visits.push_back({size_t(k) * cells + cell, t_end});
          t = t_end;
          if (t_x <= t_y && t_x <= t_z) ci += d.x > 0 ? 1 : -1, t_x += step_x;
          else if (t_y <= t_z) cj += d.y > 0 ? 1 : -1, t_y += step_y;
          else --k, t_z += step_z;
        }
        if (t_hit < 0) t_hit = t;  // the floor (rounding): the ray ends at the bottom
        for (const Visit& v : visits)
          remaining[v.voxel] = std::min(remaining[v.voxel], float(std::max(0.0, t_hit - v.t_out)));
      }
  }
  VolumeMap m = distance;
  for (size_t v = 0; v < m.values.size(); ++v)
    if (std::isfinite(remaining[v]))
      m.values[v] = std::max(distance.values[v], remaining[v] - float(p.margin));
  RefinedParams used = p;
  used.rays_per_texel = n;
  for (const auto& [name, value] : map_key("refined", f, D, &used)) m.params[name] = value;
  m.params["shadetlm:safety"] =
      "max(distance map, smallest remaining distance from the voxel's exit to the first hit over the sampled rays "
      "crossing it - margin); elevations in the tracer's space (x, y in texels, z in slices)";
  return m;
}

ConeMap cone_map(const HeightField& f, int slices, int levels) {
  const int W = f.width, H = f.height;
  const size_t cells = size_t(W) * size_t(H);
  const std::vector<float> top = cell_tops(f);
  ConeMap m;
  m.width = W, m.height = H, m.slices = slices;
  m.apex.resize(cells);
  m.ratio.assign(cells, float(std::max(W, H)));  // nothing higher anywhere: as wide as the map
  std::vector<int> level(cells);
  for (size_t c = 0; c < cells; ++c) {
    level[c] = std::clamp(int(std::ceil(double(top[c]) * levels - 1e-9)), 0, levels);
    m.apex[c] = float(double(slices) * level[c] / levels);
  }
  const int dims[3] = {W, H, 1};
  std::vector<float> gap(cells);
  for (int l = 1; l <= levels; ++l) {
    bool any = false;
    for (size_t c = 0; c < cells; ++c) {
      gap[c] = level[c] >= l ? 0.0f : kFar;
      any = any || level[c] >= l;
    }
    if (!any) continue;
    gap_transform_axis(gap, dims, 0, true);
    gap_transform_axis(gap, dims, 1, true);
    for (size_t c = 0; c < cells; ++c)
      if (level[c] < l) {
        const double rise = double(slices) * double(l - level[c]) / levels;  // slices above the apex
        m.ratio[c] = std::min(m.ratio[c], float(std::sqrt(double(gap[c])) / rise));
      }
  }
  m.params = map_key("cone", f, slices, nullptr, levels);
  m.params.insert({{"shadetlm:units", "apex in slices, ratio in texels across per slice up"},
                   {"shadetlm:safety", "classic cones from the cell's footprint over the cells' boxes, heights rounded up"}});
  return m;
}

void Fnv1a::mix(const void* data, size_t size) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < size; ++i) h_ = (h_ ^ bytes[i]) * 1099511628211ull;
}

std::string Fnv1a::hex() const {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h_));
  return buf;
}

std::string height_checksum(const HeightField& f) {
  Fnv1a h;
  const int32_t sizes[2] = {f.width, f.height};
  h.mix(sizes, sizeof sizes);
  h.mix(f.h.data(), f.h.size() * sizeof(float));
  return h.hex();
}

MapKey map_key(const std::string& kind, const HeightField& f, int slices, const RefinedParams* refined, int levels) {
  MapKey k{{"shadetlm:map", kind}, {"shadetlm:slices", std::to_string(slices)},
           {"shadetlm:height_checksum", height_checksum(f)}};
  if (refined) {
    k["shadetlm:min_elevation_deg"] = fmt(refined->min_elevation_deg);
    k["shadetlm:azimuths"] = std::to_string(refined->azimuths);
    k["shadetlm:elevations"] = std::to_string(refined->elevations);
    k["shadetlm:rays_per_texel"] = std::to_string(refined->rays_per_texel);
    k["shadetlm:margin"] = fmt(refined->margin);
  }
  if (levels > 0) k["shadetlm:levels"] = std::to_string(levels);
  return k;
}

MapKey relaxed_cone_key(const HeightField& f, int slices, int levels, double min_elevation_deg) {
  MapKey k = map_key("relaxed-cone", f, slices, nullptr, levels);
  k["shadetlm:min_elevation_deg"] = fmt(min_elevation_deg);
  k["shadetlm:reach"] = std::to_string(kRelaxedConeReach);
  return k;
}

void check_map_key(const std::map<std::string, std::string>& params, const MapKey& key, int width, int height,
                   const HeightField& f, const std::string& file) {
  if (width != f.width || height != f.height)
    throw InputError(file, "size", std::to_string(width) + "x" + std::to_string(height) + ", the height map is " +
                                       std::to_string(f.width) + "x" + std::to_string(f.height));
  // The kind, the height map and the slices first: a mismatch there explains the rest.
  std::vector<std::string> order = {"shadetlm:map", "shadetlm:height_checksum", "shadetlm:slices"};
  for (const auto& entry : key)
    if (std::find(order.begin(), order.end(), entry.first) == order.end()) order.push_back(entry.first);
  for (const std::string& name : order) {
    if (!key.count(name)) continue;
    const std::string& value = key.at(name);
    auto it = params.find(name);
    if (it == params.end()) throw InputError(file, name, "missing: the scene needs " + value);
    if (it->second != value) {
      const std::string what = name == "shadetlm:height_checksum" ? " (a map of another height map)" : "";
      throw InputError(file, name, "is " + it->second + ", the scene's is " + value + what);
    }
  }
}

}  // namespace shadetlm::core
