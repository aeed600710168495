#pragma once
// Height fields and the maps the parallax tracers read (docs/parallax.md; the parallax
// paper, ../shared/papers/parallax-distance-map.md):
//
//  * Donnelly's distance map as published: per voxel, the Euclidean distance from its
//    centre to the nearest solid voxel's centre, read trilinearly;
//  * the box-gap map: per voxel, a distance to the relief that is safe for every
//    point of the voxel (the refined map's floor, read nearest);
//  * the paper's refined map: per voxel, the smallest remaining distance to the first
//    hit over the admissible view rays that cross the voxel unobstructed;
//  * a safe cone map: per texel cell, an apex height and a cone ratio.
//
// The tracer's space. x, y in texels, texel centres at integers (x = u·W − ½,
// y = (1 − v)·H − ½, wrapping: the maps tile); z in slices, the relief at z = D·h(x, y)
// with h the bilinear height in [0, 1] and D the number of slices; the base polygon is
// the top, z = D, where view rays enter. Voxel (i, j, k) is [i, i+1]×[j, j+1]×[k, k+1];
// its column is exactly the bilinear cell whose corners are texels (i, j) … (i+1, j+1).
// The maps do not depend on the relief's depth in the scene: a depth only scales z,
// and the first hit of a ray is the same in any linearly scaled space.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "shadetlm/core/texture.hpp"

namespace shadetlm::core {

struct HeightField {
  int width = 0, height = 0;
  std::vector<float> h;  // in [0, 1], row-major, row 0 at the top (v = 1)

  // v wrapped into [0, n): the map tiles.
  static int wrap(int v, int n) {
    v %= n;
    return v < 0 ? v + n : v;
  }
  float at(int x, int y) const {  // wrapped
    return h[size_t(wrap(y, height)) * size_t(width) + size_t(wrap(x, width))];
  }
  // The four texels of the cell whose corner is (x, y): h00 = at(x, y), h10 = at(x + 1, y),
  // h01 = at(x, y + 1), h11 = at(x + 1, y + 1), with two modulos, not eight (the tracers'
  // hot read), and no overflow of x + 1.
  struct Corners {
    float h00, h10, h01, h11;
  };
  Corners corners(int x, int y) const {
    x = wrap(x, width), y = wrap(y, height);
    const size_t x1 = x + 1 == width ? 0 : size_t(x) + 1, row = size_t(y) * size_t(width);
    const size_t row1 = y + 1 == height ? 0 : row + size_t(width);
    return {h[row + size_t(x)], h[row + x1], h[row1 + size_t(x)], h[row1 + x1]};
  }
};

// The height field of a height map: its first channel, clamped to [0, 1]. Throws
// InputError naming `file` and `field` for an empty map or a non-finite value.
HeightField height_field(const Texture& map, const std::string& file, const std::string& field);

// A height field's bilinear value at (x, y) in texels (wrapped). Real: a floating type,
// or the tracer's counting one (floor found by its argument's type).
template <class Real>
Real bilinear_height(const HeightField& f, Real x, Real y) {
  using std::floor;
  const Real fx = floor(x), fy = floor(y);
  const int i = int(fx), j = int(fy);
  const Real a = x - fx, b = y - fy;
  const auto c = f.corners(i, j);
  const Real h00 = c.h00, h10 = c.h10, h01 = c.h01, h11 = c.h11;  // in Real, so counted
  return (h00 + (h10 - h00) * a) * (Real(1) - b) + (h01 + (h11 - h01) * a) * b;
}

// The smallest s in [0, length] where the segment p + s·d (p relative to the cell's
// corner texel (i, j), so p.x, p.y in [0, 1]) is at or under the bilinear patch of cell
// (i, j), or −1 if none. The patch is A + B·x + C·y + E·x·y, so z − D·h along the
// segment is a quadratic in s: the test is exact up to rounding.
template <class Real>
Real cell_hit(const HeightField& f, int i, int j, Real px, Real py, Real pz, Real dx, Real dy, Real dz,
              Real length, Real slices) {
  const auto c = f.corners(i, j);
  const Real h00 = c.h00, h10 = c.h10, h01 = c.h01, h11 = c.h11;  // in Real, so counted
  const Real B = h10 - h00, C = h01 - h00, E = h00 - h10 - h01 + h11;
  const Real q0 = pz - slices * (h00 + B * px + C * py + E * px * py);
  if (q0 <= 0) return 0;
  const Real q1 = dz - slices * (B * dx + C * dy + E * (px * dy + py * dx));
  const Real q2 = -slices * E * dx * dy;
  Real best = -1;
  // A root that rounding puts just outside [0, length] (a ray meeting or grazing the
  // relief on the cell's border) is taken, clamped in: else this cell and the next may
  // both miss it. The price: a ray that passes within |q′|·slack over the relief at the
  // border, rounding's order, counts as touching it.
  const Real slack = Real(64) * std::numeric_limits<Real>::epsilon() * (length + 1);
  auto take = [&](Real s) {
    if (s >= -slack && s <= length + slack) {
      s = std::clamp(s, Real(0), length);
      if (best < 0 || s < best) best = s;
    }
  };
  if (std::abs(q2) * length < Real(1e-7) * (std::abs(q1) + std::abs(q0) + Real(1e-30))) {
    if (q1 < 0) take(-q0 / q1);  // (nearly) linear
  } else {
    const Real disc = q1 * q1 - 4 * q2 * q0;
    if (disc >= 0) {
      // The stable pair of roots: q = −½(q1 + sign(q1)·√disc), roots q/q2 and q0/q.
      const Real q = Real(-0.5) * (q1 + std::copysign(std::sqrt(disc), q1));
      take(q / q2);
      if (q != 0) take(q0 / q);
    }
  }
  // Rounding can hide a root at the segment's end that the end value shows.
  if (best < 0 && q0 + length * (q1 + length * q2) <= 0) best = length;
  return best;
}

// The first point at or under the relief along o + t·d from t = 0, walking the cells the
// ray crosses and testing each exactly (cell_hit). Stops at the floor z = 0 at the
// latest (every ray with d.z < 0 ends there); rays with d.z ≥ 0 return t = 0 (a ray
// parallel to the surface or leaving it meets nothing: the entry point is kept).
// `cells` counts the cells tested; at most `max_cells` are (then t where it stopped).
template <class Real>
struct CellMarch {
  Real t = 0;
  int cells = 0;
  bool hit = false;
};
// `visit(i, j)` is told each cell before its test (the tracer's map reads).
template <class Real, class Visit>
CellMarch<Real> march_cells(const HeightField& f, Real ox, Real oy, Real oz, Real dx, Real dy, Real dz,
                            Real slices, int max_cells, Visit&& visit) {
  CellMarch<Real> r;
  if (!(dz < 0)) return r;
  const Real t_floor = std::max(Real(0), oz) / -dz;
  Real ci = std::floor(ox), cj = std::floor(oy);
  // On a cell border going back: start in the cell behind (no empty test of the other).
  if (dx < 0 && ci == ox) ci -= 1;
  if (dy < 0 && cj == oy) cj -= 1;
  const Real inf = std::numeric_limits<Real>::infinity();
  Real t_x = dx > 0 ? (ci + 1 - ox) / dx : dx < 0 ? (ci - ox) / dx : inf;
  Real t_y = dy > 0 ? (cj + 1 - oy) / dy : dy < 0 ? (cj - oy) / dy : inf;
  const Real step_x = dx != 0 ? 1 / std::abs(dx) : inf, step_y = dy != 0 ? 1 / std::abs(dy) : inf;
  Real t = 0;
  while (r.cells < max_cells) {
    const Real t_end = std::min(std::min(t_x, t_y), t_floor);
    ++r.cells;
    const Real px = ox + t * dx - ci, py = oy + t * dy - cj, pz = oz + t * dz;
    visit(int(ci), int(cj));
    const Real s = cell_hit(f, int(ci), int(cj), std::clamp(px, Real(0), Real(1)), std::clamp(py, Real(0), Real(1)),
                            pz, dx, dy, dz, std::max(Real(0), t_end - t), slices);
    if (s >= 0) {
      r.t = t + s, r.hit = true;
      return r;
    }
    if (t_end >= t_floor) {  // rounding only: the floor is under every relief
      r.t = t_floor, r.hit = true;
      return r;
    }
    t = t_end;
    if (t_x <= t_y) ci += dx > 0 ? 1 : -1, t_x += step_x;
    else cj += dy > 0 ? 1 : -1, t_y += step_y;
  }
  r.t = t;
  return r;
}
template <class Real>
CellMarch<Real> march_cells(const HeightField& f, Real ox, Real oy, Real oz, Real dx, Real dy, Real dz,
                            Real slices, int max_cells = 1 << 30) {
  return march_cells(f, ox, oy, oz, dx, dy, dz, slices, max_cells, [](int, int) {});
}

// A volume of W × H × D values, voxel (i, j, k) at (k·H + j)·W + i, with the parameters
// it was made with (written to the EXR header as shadetlm:* attributes).
struct VolumeMap {
  int width = 0, height = 0, slices = 0;
  std::vector<float> values;
  std::map<std::string, std::string> params;

  float at(int i, int j, int k) const {
    return values[(size_t(k) * size_t(height) + size_t(j)) * size_t(width) + size_t(i)];
  }
  // The voxel that holds (x, y, z), z clamped into the volume.
  float sample(float x, float y, float z) const;
  // The trilinear value at (x, y, z), voxel centres at (i + ½, j + ½, k + ½); wrapping
  // in x and y, clamped to the centres of the first and last slice in z. Real: float,
  // or the tracer's counting type.
  template <class Real>
  Real trilinear_as(Real x, Real y, Real z) const;
  float trilinear(float x, float y, float z) const { return trilinear_as(x, y, z); }
};

template <class Real>
Real VolumeMap::trilinear_as(Real x, Real y, Real z) const {
  using std::floor;
  const Real half = Real(0.5f);
  const Real gx = x - half, gy = y - half, gz = std::clamp(z - half, Real(0.0f), Real(float(slices - 1)));
  const Real fx = floor(gx), fy = floor(gy), fz = floor(gz);
  const Real a = gx - fx, b = gy - fy, c = gz - fz;
  int i0 = int(fx) % width, j0 = int(fy) % height;
  if (i0 < 0) i0 += width;
  if (j0 < 0) j0 += height;
  const int i1 = (i0 + 1) % width, j1 = (j0 + 1) % height;
  const int k0 = int(fz), k1 = std::min(k0 + 1, slices - 1);
  auto plane = [&](int k) {
    const Real v00 = at(i0, j0, k), v10 = at(i1, j0, k), v01 = at(i0, j1, k), v11 = at(i1, j1, k);
    const Real top = v00 + (v10 - v00) * a, bottom = v01 + (v11 - v01) * a;
    return top + (bottom - top) * b;
  };
  const Real p0 = plane(k0), p1 = plane(k1);
  return p0 + (p1 - p0) * c;
}

// The cell's conservative top: the largest of its four corners. The bilinear patch never
// rises above it, so the boxes [cell] × [0, D·top] hold the relief.
std::vector<float> cell_tops(const HeightField& f);

// The box-gap map, Donnelly's map made safe for nearest reads: per voxel, the Euclidean
// gap between the voxel's box and the nearest voxel that meets a cell's box (so 0 next
// to the relief); no point of the voxel is nearer the relief than that. Computed by a
// separable linear-time distance transform (Felzenszwalb–Huttenlocher lower envelopes,
// after a one-voxel dilation per axis, which turns centre distances into box gaps),
// wrapping in x and y. In voxels.
VolumeMap box_gap_map(const HeightField& f, int slices);

// Donnelly's distance map as published (GPU Gems 2, ch. 8): a voxel is solid when its
// centre is at or under the relief (z = k + ½ ≤ D·h at the cell's centre); every voxel
// stores the Euclidean distance from its centre to the nearest solid voxel's centre (0
// inside). Donnelly used Danielsson's sweeps, which approximate this distance; here it is
// exact (the same separable transform, without the dilation). Not safe: a trilinear
// read can exceed the distance to the relief, which the tracer's fixed step count and
// the report measure. In voxels.
VolumeMap donnelly_map(const HeightField& f, int slices);

// The paper's refined map. For each sampled admissible direction (elevation ≥
// min_elevation_deg in the tracer's space; `azimuths` × `elevations` directions up to
// the vertical), parallel rays enter the top face on a lattice of `rays_per_texel`² per
// texel and are walked through the voxels to their exact first hit; every voxel crossed
// on the way keeps the smallest remaining distance from its exit point to the hit (so the
// value is safe at every point of that ray in the voxel). Stored: max(distance map,
// smallest remaining − margin); voxels no sampled ray reaches keep the distance map's
// value. O(directions × rays × voxels per ray).
struct RefinedParams {
  double min_elevation_deg = 10;
  int azimuths = 16;
  int elevations = 4;
  int rays_per_texel = 2;
  double margin = 0;  // voxels taken off every ray-derived value
};
VolumeMap refined_map(const HeightField& f, const VolumeMap& distance, const RefinedParams& p);

// A safe cone map: per cell, an apex height (the cell's top rounded up to one of `levels`
// heights, in slices) and a cone ratio (texels across per slice up) such that the cone
// widening from the cell's footprint at the apex holds no relief. Computed per level by a
// 2-D box-gap distance transform to the cells at least that high: O(levels × cells).
// Classic (not relaxed) cones: a ray stepping inside one never crosses the surface, so
// the generator is safe for any sampling point in the cell.
struct ConeMap {
  int width = 0, height = 0, slices = 0;
  std::vector<float> apex, ratio;  // per cell, row-major
  std::map<std::string, std::string> params;
};
ConeMap cone_map(const HeightField& f, int slices, int levels);

// A safe relaxed cone map (docs/parallax.md): the classic map's apexes, and per cell the
// widest ratio such that the cone holds no cell higher than the apex that descends, in a
// direction a ray can take from the cell to it, more steeply than tan(min_elevation_deg)
// (slices per texel). A ray at or above that elevation then enters the relief inside
// the cone at most once and never leaves it again, so the tracer may step into the
// relief and search back on the sign of z − D·h. The cone reaches at most
// kRelaxedConeReach texels from its footprint (which bounds the generator's search:
// O(cells × reach²) at worst, far less where cones are narrow), unless the classic cone
// is wider still: it is never narrower than the classic map's. Rays below the bound are
// not covered, as for the refined map.
constexpr int kRelaxedConeReach = 64;
ConeMap relaxed_cone_map(const HeightField& f, int slices, int levels, double min_elevation_deg);

// What identifies a map, written into it by its builder as shadetlm:* parameters: its
// kind ("box-gap", "donnelly", "refined", "cone", "relaxed-cone"), slices, the height
// field's checksum, and the builder's own parameters (refined: the elevation bound,
// directions, rays and margin; cone: the levels; relaxed cone: the levels, the elevation
// bound and the reach). A map read back for a scene is checked against the scene's key,
// and a map cache files maps under it.
using MapKey = std::map<std::string, std::string>;
MapKey map_key(const std::string& kind, const HeightField& f, int slices, const RefinedParams* refined = nullptr,
               int levels = 0);
// The relaxed cone map's key: map_key("relaxed-cone", …, levels) with its elevation bound and reach.
MapKey relaxed_cone_key(const HeightField& f, int slices, int levels, double min_elevation_deg);
// The first parameter of `key` that `params` lacks or holds another value of, as an
// InputError naming `file` and the parameter; also the map's size against the field's.
void check_map_key(const std::map<std::string, std::string>& params, const MapKey& key, int width, int height,
                   const HeightField& f, const std::string& file);
// A checksum of a height field's size and values (FNV-1a, 64 bits, 16 hex digits).
std::string height_checksum(const HeightField& f);
// FNV-1a, 64 bits, over the bytes mixed in; hex(): as 16 hex digits. Height checksums and
// the map cache's file names.
class Fnv1a {
 public:
  void mix(const void* data, size_t size);
  std::string hex() const;

 private:
  uint64_t h_ = 14695981039346656037ull;
};

// ---- The io component (shadetlm::io, linked apart: file formats) from here on.
// Maps as EXR: a volume's slices as channels "d.000" …, a cone map as "apex" and
// "ratio", the parameters as shadetlm:* string attributes. Reading checks the kind (a
// volume: box-gap, donnelly or refined; the caller checks which with check_map_key) and
// the sizes and throws InputError naming the file and the field.
void write_volume_map(const std::string& path, const VolumeMap& map, const std::string& kind);
VolumeMap read_volume_map(const std::string& path);
void write_cone_map(const std::string& path, const ConeMap& map);
ConeMap read_cone_map(const std::string& path);

}  // namespace shadetlm::core
