// The safe relaxed cone map (docs/parallax.md, "Relaxed cones, made safe").
//
// Why it is safe, in short. Along a ray r(s) going down at elevation θ, let
// g(s) = z(s) − D·h(x(s), y(s)), the height above the relief in slices. Over one
// bilinear cell g'(s) = −|v̂xy|·(tan θ + D·∇h·ŵ), ŵ the ray's horizontal direction. So
// where the patch descends along ŵ by at most tan θ (slices per texel), g never rises: a ray there can enter the relief
// but never come out of it. A ray that starts over cell c and is still inside c's cone
// has ŵ among the directions from c's footprint to the footprint it is over. The
// generator keeps out of the cone every cell (higher than the apex) that, in one of
// those directions, descends more steeply than tan θmin. Then, for every ray at or
// above θmin inside the cone, {s : g(s) ≤ 0} is an interval reaching the step's end:
// the step enters the relief at most once and never leaves it, and a search on the
// sign of g finds the first hit.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "shadetlm/core/parallax_map.hpp"

namespace shadetlm::core {

namespace {

// Directions around the horizon, in sectors of 2π/64: a mask is 64 bits.
constexpr int kSectors = 64;
using Sectors = uint64_t;
constexpr double kPi = 3.14159265358979323846;
constexpr double kSector = 2 * kPi / kSectors;

// The sectors that meet the arc of half-width `half` around angle `middle` (two arcs
// meet when their middles are within the sum of their half-widths), rounded outward.
Sectors sectors_meeting(double middle, double half) {
  Sectors mask = 0;
  for (int k = 0; k < kSectors; ++k)
    if (std::abs(std::remainder((k + 0.5) * kSector - middle, 2 * kPi)) <= half + kSector / 2 + 1e-9)
      mask |= Sectors(1) << k;
  return mask;
}

// The sectors in which cell (i, j) may descend more steeply than tan_min (slices per
// texel): some direction ŵ of the sector and gradient g of the patch with −g·ŵ > tan_min.
// The bilinear patch's gradient (∂x, ∂y) has ∂x linear in y and ∂y linear in x, so it lies
// in the box of the edges' differences, and −g·ŵ is largest at one of the box's corners u
// = −g; u·ŵ > tan_min for the ŵ within acos(tan_min/|u|) of u's direction.
Sectors steep_sectors(const HeightField& f, int i, int j, double slices, double tan_min) {
  const auto c = f.corners(i, j);
  const double h00 = c.h00, h10 = c.h10, h01 = c.h01, h11 = c.h11;
  const double gx[2] = {slices * (h10 - h00), slices * (h11 - h01)};
  const double gy[2] = {slices * (h01 - h00), slices * (h11 - h10)};
  Sectors mask = 0;
  for (const double ux : {-gx[0], -gx[1]})
    for (const double uy : {-gy[0], -gy[1]}) {  // u = −g: the direction of steepest descent
      const double length = std::hypot(ux, uy);
      if (length <= tan_min) continue;  // no direction descends faster than |u|
      mask |= sectors_meeting(std::atan2(uy, ux), std::acos(tan_min / length));
    }
  return mask;
}

// The sectors a ray can head in from cell c to cell c + (dx, dy), (dx, dy) ≠ (0, 0): the
// directions of the nonzero vectors of the square F_e − F_c = [dx − 1, dx + 1] ×
// [dy − 1, dy + 1], spanned by its corners. A neighbour's square has the origin on its
// border: a half-plane of directions (edge neighbours) or a quadrant (diagonal ones).
Sectors heading_sectors(int dx, int dy) {
  const double middle = std::atan2(double(dy), double(dx));
  double lo = 0, hi = 0;
  for (const int cx : {dx - 1, dx + 1})
    for (const int cy : {dy - 1, dy + 1}) {
      if (cx == 0 && cy == 0) continue;  // the origin: no direction
      const double rel = std::remainder(std::atan2(double(cy), double(cx)) - middle, 2 * kPi);
      lo = std::min(lo, rel), hi = std::max(hi, rel);
    }
  return sectors_meeting(middle + (lo + hi) / 2, (hi - lo) / 2);
}

struct Offset {
  int dx, dy;
  float gap;  // between the footprints, texels
  Sectors heading;
};

// Every offset whose footprint is within `reach` texels of the cell's, nearest first.
std::vector<Offset> offsets_within(int reach) {
  std::vector<Offset> out;
  for (int dy = -reach - 1; dy <= reach + 1; ++dy)
    for (int dx = -reach - 1; dx <= reach + 1; ++dx) {
      const double gx = std::max(0, std::abs(dx) - 1), gy = std::max(0, std::abs(dy) - 1);
      const double gap = std::hypot(gx, gy);
      if ((dx || dy) && gap < reach) out.push_back({dx, dy, float(gap), heading_sectors(dx, dy)});
    }
  std::stable_sort(out.begin(), out.end(), [](const Offset& a, const Offset& b) { return a.gap < b.gap; });
  return out;
}

}  // namespace

ConeMap relaxed_cone_map(const HeightField& f, int slices, int levels, double min_elevation_deg) {
  const int W = f.width, H = f.height;
  const double D = slices, tan_min = std::tan(min_elevation_deg * kPi / 180);
  const std::vector<float> top = cell_tops(f);
  std::vector<Sectors> steep(top.size());
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) steep[size_t(j) * W + i] = steep_sectors(f, i, j, D, tan_min);
  const std::vector<Offset> offsets = offsets_within(kRelaxedConeReach);
  // A classic cone holds no box above its apex at all, so it is a safe relaxed cone too:
  // where it is wider than the reach lets the search go, it is kept.
  const ConeMap classic = cone_map(f, slices, levels);
  ConeMap m;
  m.width = W, m.height = H, m.slices = slices;
  m.apex.resize(top.size()), m.ratio.resize(top.size());
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      const size_t c = size_t(j) * W + i;
      const double apex = classic.apex[c];  // the classic map's: the box top rounded up to a level
      // The search reaches kRelaxedConeReach texels out at the top of the volume.
      double ratio = kRelaxedConeReach / std::max(D - apex, D / levels);
      for (const Offset& o : offsets) {
        if (o.gap >= ratio * (D - apex)) break;  // no cell this far can narrow the cone
        const int ei = ((i + o.dx) % W + W) % W, ej = ((j + o.dy) % H + H) % H;
        const size_t e = size_t(ej) * W + ei;
        const double rise = D * top[e] - apex;
        if (rise > 0 && (steep[e] & o.heading)) ratio = std::min(ratio, o.gap / rise);
      }
      m.apex[c] = classic.apex[c];
      // Rounded inward: a cell that narrowed the cone (or touches the classic one) stays
      // strictly outside it.
      m.ratio[c] = float(std::max(ratio, double(classic.ratio[c])) * (1 - 1e-6));
    }
  m.params = relaxed_cone_key(f, slices, levels, min_elevation_deg);
  m.params.insert({{"shadetlm:units", "apex in slices, ratio in texels across per slice up"},
                   {"shadetlm:safety",
                    "relaxed cones: the cone holds no cell above the apex that descends, in a direction from the "
                    "cell to it, more steeply than tan(min_elevation); a ray at or above min_elevation enters the "
                    "relief inside the cone at most once and never leaves it"}});
  return m;
}

}  // namespace shadetlm::core
