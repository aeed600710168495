#include "shadetlm/modules/parallax/parallax_kernel.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <type_traits>

namespace shadetlm::modules {

core::MapKey parallax_map_key(const core::HeightField& f, const core::ParallaxSettings& s) {
  if (s.method == core::ParallaxMethod::Cone)
    return s.cones == core::ConeKind::Relaxed ? core::relaxed_cone_key(f, s.slices, 4 * s.slices, s.min_elevation_deg)
                                              : core::map_key("cone", f, s.slices, nullptr, 4 * s.slices);
  if (s.map != core::DistanceMap::Refined) return core::map_key(core::to_string(s.map), f, s.slices);
  core::RefinedParams p;
  p.min_elevation_deg = s.min_elevation_deg;
  p.margin = s.margin;
  return core::map_key("refined", f, s.slices, &p);
}

ParallaxMaps build_parallax_maps(const core::Texture& height_map, const core::ParallaxSettings& s,
                                 const std::string& file) {
  const auto start = std::chrono::steady_clock::now();
  ParallaxMaps m;
  m.field = core::height_field(height_map, file, "height_map");
  m.slices = s.slices;
  const bool distance = s.method == core::ParallaxMethod::Distance, cone = s.method == core::ParallaxMethod::Cone;
  if (!s.map_file.empty() && (distance || cone)) {  // precomputed: read, and checked against the scene
    const core::MapKey key = parallax_map_key(m.field, s);
    if (distance) {
      m.volume = core::read_volume_map(s.map_file);
      core::check_map_key(m.volume.params, key, m.volume.width, m.volume.height, m.field, s.map_file);
    } else {
      m.cone = core::read_cone_map(s.map_file);
      core::check_map_key(m.cone.params, key, m.cone.width, m.cone.height, m.field, s.map_file);
    }
    m.loaded = true;
  } else if (distance && s.map == core::DistanceMap::Donnelly) {
    m.volume = core::donnelly_map(m.field, s.slices);
  } else if (distance) {
    m.volume = core::box_gap_map(m.field, s.slices);
    if (s.map == core::DistanceMap::Refined) {
      core::RefinedParams p;
      p.min_elevation_deg = s.min_elevation_deg;
      p.margin = s.margin;
      m.volume = core::refined_map(m.field, m.volume, p);
    }
  } else if (cone && s.cones == core::ConeKind::Relaxed) {
    m.cone = core::relaxed_cone_map(m.field, s.slices, 4 * s.slices, s.min_elevation_deg);
  } else if (cone) {
    m.cone = core::cone_map(m.field, s.slices, 4 * s.slices);
  }
  m.precompute_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return m;
}

namespace {

// Operation counts of the tracer's steps (docs/parallax.md), each what its code below
// does on the tracer's numbers (test_parallax runs it on a counting type). A product
// with ½ is an exponent shift: wiring.
// The ray: the direction scaled (a·W, −b·H, c·D/depth) and normalized (1/√|d|²).
constexpr Ops kOpsRay{/*add*/ 2, /*mul*/ 9, /*div*/ 2, /*sqrt*/ 1};
constexpr Ops kOpsBilinear{/*add*/ 8, /*mul*/ 4, 0, 0, 0, 0, /*fetch*/ 4};  // a bilinear height (2 fractions, 3 lerps)
constexpr Ops kOpsHeightRead = kOpsBilinear + Ops{/*add*/ 0, /*mul*/ 1};    // … ×D, in slices
// Offset limiting: 1/|v| (3 mul, 2 add, √, ÷), depth·(1 − h)·1/|v|, the shift along a and b.
constexpr Ops kOpsOffset = kOpsBilinear + Ops{/*add*/ 5, /*mul*/ 9, /*div*/ 1, /*sqrt*/ 1};
// The layers' setup: cos θ = −c/|v|, the layer count n (1 add, 1 mul), the step D/n/−v̂z.
constexpr Ops kOpsLayers{/*add*/ 3, /*mul*/ 4, /*div*/ 3, /*sqrt*/ 1};
constexpr Ops kOpsLayer = kOpsHeightRead + Ops{/*add*/ 3, /*mul*/ 4};  // one layer down: p = p₀ + (i·step)·v̂
constexpr Ops kOpsPom{/*add*/ 7, /*mul*/ 2, /*div*/ 1};                 // the layers' line through the two heights
constexpr Ops kOpsMidpoint = kOpsHeightRead + Ops{/*add*/ 3};           // a bisection: (p + q)·½ and its height
constexpr Ops kOpsBisect{/*add*/ 1, /*mul*/ 1, /*div*/ 1};              // its step's run across: (qz − pz)/v̂z·|v̂xy|
constexpr Ops kOpsAdvance{/*add*/ 3, /*mul*/ 3};  // p += t·v̂ (after the exact cells' march, or a step not taken)
constexpr Ops kOpsSphere = kOpsAdvance + Ops{0, 0, 0, 0, 0, 0, /*fetch*/ 1};  // p += d(p)·v̂, d read
// Donnelly's step: a trilinear read (3 offsets by ½, 3 fractions, 7 lerps of 1 mul and 2
// add, 8 voxels), then p += d·v̂; a step through the floor is put back on it.
constexpr Ops kOpsTrilinearSphere{/*add*/ 3 + 3 + 14 + 3, /*mul*/ 7 + 3, 0, 0, 0, 0, /*fetch*/ 8};
constexpr Ops kOpsFloor{/*add*/ 2, /*mul*/ 2, /*div*/ 1};
constexpr Ops kOpsAcross{/*add*/ 1, /*mul*/ 2, 0, /*sqrt*/ 1};                 // |v̂xy|, once a ray (cones)
constexpr Ops kOpsConeStep{/*add*/ 5, /*mul*/ 3, /*div*/ 2};       // to the cone's side, and p += t·v̂
constexpr Ops kOpsCone = kOpsConeStep + Ops{0, 0, 0, 0, 0, 0, /*fetch*/ 1};  // … with its cell's read

// Whether a value of the tracer is finite (float16 overflows to infinity; the value
// must not reach a texel index). In float32 the tracer's values stay far below the
// range (a ray is at most ~10^7 texels long), and fixed point saturates: no test.
template <class T>
bool finite(T v) {
  if constexpr (std::is_same_v<T, Half>) return std::isfinite(float(v));
  return true;
}

// The texture unit's bilinear height at (x, y), in float32 like every texture read; the
// tracer takes it into its format. (Counted: the same float32, each operation counted.)
template <class T>
T height_at(const core::HeightField& f, T x, T y, MapReads* reads) {
  if (reads) reads->bilinear(float(x), float(y));
  if constexpr (is_counted<T>::value) return core::bilinear_height<T>(f, x, y);
  else return T(core::bilinear_height<float>(f, float(x), float(y)));
}

// The distance map's trilinear value, in float32 as height_at.
template <class T>
T trilinear_at(const core::VolumeMap& v, T x, T y, T z) {
  if constexpr (is_counted<T>::value) return v.trilinear_as<T>(x, y, z);
  else return T(v.trilinear(float(x), float(y), float(z)));
}

// A point, or a direction, in the tracer's space (core/parallax_map.hpp): x along u, y
// down the rows, z in slices of the depth. In the number type T.
template <class T>
struct Point {
  T x, y, z;
};
// p + t·d (3 mul, 3 add).
template <class T>
Point<T> advance(Point<T> p, T t, Point<T> d) {
  return {p.x + t * d.x, p.y + t * d.y, p.z + t * d.z};
}
// Halfway between p and q (3 add; the halving a shift).
template <class T>
Point<T> midpoint(Point<T> p, Point<T> q) {
  const T half = T(0.5f);
  return {shifted(p.x + q.x, half), shifted(p.y + q.y, half), shifted(p.z + q.z, half)};
}
template <class T>
bool finite(Point<T> p) {
  return finite(p.x) && finite(p.y) && finite(p.z);
}

// The view ray of a pixel. In the number type T.
template <class T>
struct Ray {
  T a, b, c;          // the tangent-space direction
  T W, H, D;          // the map's size: texels across and down, slices deep
  Point<T> entry;     // where it enters the map's top (texels; z = D)
  Point<T> d;         // its direction, unit in the tracer's space
  MapReads* reads = nullptr;  // the map reads (DRAM model)
};

// The exact cells from p on: the finish of the skipping tracers. The per-cell quadratic
// (core::march_cells, shared with the map builders) runs in float32 whatever the
// tracer's format; its result is taken back into the format.
template <class T>
void finish_cells(const core::ParallaxSettings& s, const ParallaxMaps& m, const Ray<T>& ray, Point<T>& p,
                  ParallaxTrace& r, Ops* ops) {
  const int budget = std::max(1, s.max_iterations - r.iterations);
  if (!finite(p)) return;
  const auto march = core::march_cells<float>(m.field, float(p.x), float(p.y), float(p.z), float(ray.d.x),
                                              float(ray.d.y), float(ray.d.z), float(m.slices), budget,
                                              [&](int i, int j) {
                                                if (ray.reads) ray.reads->cell(i, j);
                                              });
  p = advance(p, T(march.t), ray.d);
  r.iterations += march.cells;
  r.cells += march.cells;
  r.fetches += 4 * march.cells;
  if (ops) *ops += kParallaxOpsCell * uint64_t(march.cells) + kOpsAdvance;
}

// The ray of a pixel; false where there is none to trace (no depth, a ray leaving the
// surface, no direction, or one so close to the surface it would run over 10⁶ texels):
// the entry is the answer then.
template <class T>
bool make_ray(const core::ParallaxSettings& s, const ParallaxMaps& m, float x0f, float y0f, float af, float bf,
              float cf, Ops* ops, Ray<T>& ray) {
  if (!(s.depth > 0) || !(cf < 0) || !std::isfinite(af) || !std::isfinite(bf)) return false;
  const core::HeightField& f = m.field;
  ray.W = T(float(f.width)), ray.H = T(float(f.height)), ray.D = T(float(m.slices));
  ray.entry = {T(x0f), T(y0f), ray.D};
  ray.a = T(af), ray.b = T(bf), ray.c = T(cf);
  const T one = T(1.0f), zero = T(0.0f);
  if (ops) *ops += kOpsRay;
  Point<T> d{ray.a * ray.W, -ray.b * ray.H, ray.c * ray.D / T(float(s.depth))};
  const T length2 = d.x * d.x + d.y * d.y + d.z * d.z;
  if (!(length2 > zero)) {  // no direction (before a reciprocal of 0): the rest not done here
    count_discarded<T>(Ops{0, /*mul*/ 3, /*div*/ 1, /*sqrt*/ 1});
    return false;
  }
  const T scale = one / sqrt_op(length2);
  if (!std::isfinite(float(scale)) || scale == zero) {
    count_discarded<T>(Ops{0, /*mul*/ 3});  // the scaling not done here
    return false;
  }
  d = {d.x * scale, d.y * scale, d.z * scale};  // unit in the tracer's space
  // A ray this close to the surface would run over 10⁶ texels: treated as parallel.
  if (-d.z < T(1e-6f) || !(d.z < zero)) return false;
  ray.d = d;
  return true;
}

// Offset limiting: T = T0 + depth·(1 − h(T0))·v̂xy with v̂ the unit physical direction:
// no division by v̂z, so the shift stays within the depth at grazing views.
template <class T>
void trace_offset(const core::ParallaxSettings& s, const ParallaxMaps& m, const Ray<T>& ray, ParallaxTrace& r,
                  Ops* ops) {
  const T one = T(1.0f), a = ray.a, b = ray.b, c = ray.c;
  const T h = height_at(m.field, ray.entry.x, ray.entry.y, ray.reads);
  const T inv = one / sqrt_op(a * a + b * b + c * c);
  const T shift = T(float(s.depth)) * (one - h) * inv;
  r.x = float(ray.entry.x + shift * a * ray.W), r.y = float(ray.entry.y - shift * b * ray.H);
  r.iterations = 1, r.fetches = 4;
  if (ops) *ops += kOpsOffset;
}

// The relief's height under p, in slices (a height read, one iteration).
template <class T>
T slices_under(const ParallaxMaps& m, const Ray<T>& ray, Point<T> p, ParallaxTrace& r, Ops* ops) {
  ++r.iterations, r.fetches += 4;
  if (ops) *ops += kOpsHeightRead;
  return ray.D * height_at(m.field, p.x, p.y, ray.reads);
}

// POM: where the line between the heights of the last layer above (`above`, its height
// `above_h`) and the first under (p, its height h) crosses the ray.
template <class T>
void pom_finish(const ParallaxMaps& m, const Ray<T>& ray, Point<T> above, T above_h, T h, Point<T>& p,
                ParallaxTrace& r, Ops* ops) {
  const T one = T(1.0f), zero = T(0.0f);
  // Under the relief at the first layer: the entry's height, for the line below.
  if (above.z == ray.D) above_h = slices_under(m, ray, ray.entry, r, ops);
  const T over = above.z - above_h, under = h - p.z, sum = over + under;
  const T w = sum > zero ? over / sum : one;
  if (!(sum > zero)) count_discarded<T>(Ops{0, 0, /*div*/ 1});
  p.x = above.x + (p.x - above.x) * w, p.y = above.y + (p.y - above.y) * w;
  if (ops) *ops += kOpsPom;
}

// One bisection between `above`, over the relief, and `under`, at or under it: the
// midpoint's height read (z − D·h's sign) says which half holds the hit.
template <class T>
void bisect_once(const ParallaxMaps& m, const Ray<T>& ray, Point<T>& above, Point<T>& under, ParallaxTrace& r,
                 Ops* ops) {
  const Point<T> mid = midpoint(above, under);
  const T h = ray.D * height_at(m.field, mid.x, mid.y, ray.reads);
  ++r.iterations, r.fetches += 4;
  if (ops) *ops += kOpsMidpoint;
  (mid.z <= h ? under : above) = mid;
}

// Relief's finish: binary_steps bisections, within the iteration cap.
template <class T>
void bisect_steps(const core::ParallaxSettings& s, const ParallaxMaps& m, const Ray<T>& ray, Point<T>& above,
                  Point<T>& under, ParallaxTrace& r, Ops* ops) {
  for (int i = 0; i < s.binary_steps && r.iterations < s.max_iterations; ++i) bisect_once(m, ray, above, under, r, ops);
}

// Relaxed cones' search: bisections until the step is at most a texel across (`run`
// texels now, halved each time: a shift), within the iteration cap.
template <class T>
void bisect_to_texel(const core::ParallaxSettings& s, const ParallaxMaps& m, const Ray<T>& ray, T run,
                     Point<T>& above, Point<T>& under, ParallaxTrace& r, Ops* ops) {
  for (; run > T(1.0f) && r.iterations < s.max_iterations; run = shifted(run, T(0.5f)))
    bisect_once(m, ray, above, under, r, ops);
}

// Steep parallax, POM and relief: the layer search, then each one's finish. False if
// the ray overflowed (float16: counted; the entry kept).
template <class T>
bool trace_layers(const core::ParallaxSettings& s, const ParallaxMaps& m, const Ray<T>& ray, Point<T>& p,
                  ParallaxTrace& r, Ops* ops) {
  const T D = ray.D, a = ray.a, b = ray.b, c = ray.c;
  // More layers the flatter the view: n = max + (min − max)·|cos θ|, θ from the normal.
  const float cos_view = float(-c / sqrt_op(a * a + b * b + c * c));
  // (n in float32 whatever the format, and counted so: one product, one sum)
  const int layers = std::max(1, int(std::lround(float(s.layers_max) + float(s.layers_min - s.layers_max) * cos_view)));
  count_discarded<T>(Ops{/*add*/ 1, /*mul*/ 1});
  const T step = (D / T(float(layers))) / -ray.d.z;  // ray length per layer
  if (ops) *ops += kOpsLayers;
  Point<T> above = p;  // the last point above (the entry)
  T above_h = D, h = D;
  for (int i = 1; i <= layers && r.iterations < s.max_iterations; ++i) {
    p = advance(ray.entry, T(float(i)) * step, ray.d);
    if (!finite(p.x) || !finite(p.y)) return false;
    h = D * height_at(m.field, p.x, p.y, ray.reads);
    ++r.iterations, r.fetches += 4;
    if (ops) *ops += kOpsLayer;
    if (p.z <= h) break;
    above = p, above_h = h;
  }
  if (!s.early_exit) {  // the loop runs every layer; the hit is the first one under
    const int idle = layers - std::min(layers, r.iterations);
    r.iterations += idle, r.fetches += 4 * idle;
    if (ops) *ops += kOpsLayer * uint64_t(idle);
    count_discarded<T>(kOpsLayer * uint64_t(idle));  // done in hardware, their results not needed
  }
  if (p.z <= h && s.method == core::ParallaxMethod::Pom) pom_finish(m, ray, above, above_h, h, p, r, ops);
  if (p.z <= h && s.method == core::ParallaxMethod::Relief) bisect_steps(s, m, ray, above, p, r, ops);
  return true;
}

// Sphere tracing: p ← p + d(p)·v̂, the voxel holding p read as stored (its value is safe
// for every point of the voxel); then the exact cells. False if the ray overflowed.
template <class T>
bool trace_spheres(const core::ParallaxSettings& s, const ParallaxMaps& m, const Ray<T>& ray, Point<T>& p,
                   ParallaxTrace& r, Ops* ops) {
  const T near = T(kParallaxNear);
  while (r.iterations < s.max_iterations) {
    if (!finite(p)) return false;
    if (ray.reads) ray.reads->voxel(float(p.x), float(p.y), float(p.z), m.volume);
    const T d = T(m.volume.sample(float(p.x), float(p.y), float(p.z)));
    ++r.iterations, ++r.fetches;
    if (ops) *ops += kOpsSphere;
    if (d < near) {
      count_discarded<T>(kOpsAdvance);  // the step not taken, done in hardware all the same
      break;
    }
    p = advance(p, d, ray.d);
    ++r.skips;
  }
  if (r.iterations < s.max_iterations) finish_cells(s, m, ray, p, r, ops);
  return true;
}

// Donnelly's tracing as published: a fixed count of sphere steps p ← p + d(p)·v̂, d read
// trilinearly from the Euclidean map, no finish; the point after the last step is the
// hit. Without early exit (as published) every pixel pays s.steps, capped at
// max_iterations; with it the loop stops once a step would move under
// kDonnellyConverged voxel, or at the floor, a little short of where the fixed count
// would end.
constexpr float kDonnellyConverged = 1.0f / 64;
template <class T>
bool trace_donnelly(const core::ParallaxSettings& s, const ParallaxMaps& m, const Ray<T>& ray, Point<T>& p,
                    ParallaxTrace& r, Ops* ops) {
  const int steps = std::min(s.steps, s.max_iterations);
  const T converged = T(kDonnellyConverged), zero = T(0.0f);
  while (r.iterations < steps) {
    if (!finite(p)) return false;
    if (ray.reads) ray.reads->trilinear(float(p.x), float(p.y), float(p.z), m.volume);
    const T d = trilinear_at(m.volume, p.x, p.y, p.z);
    ++r.iterations, ++r.trilinear, r.fetches += 8;
    if (ops) *ops += kOpsTrilinearSphere;
    if (s.early_exit && d < converged) {
      count_discarded<T>(kOpsAdvance);  // the step not taken
      break;
    }
    p = advance(p, d, ray.d);
    ++r.skips;
    if (p.z < zero) {  // through the floor (the map clamps there): back onto it, the hit
      const T back = p.z / ray.d.z;
      p = {p.x - back * ray.d.x, p.y - back * ray.d.y, zero};
      if (ops) *ops += kOpsFloor;
      break;
    }
  }
  if (!s.early_exit) {  // the fixed count: the steps after the floor still read the map
    const int idle = steps - std::min(steps, r.iterations);
    r.iterations += idle, r.trilinear += idle, r.fetches += 8 * idle;
    if (ops) *ops += kOpsTrilinearSphere * uint64_t(idle);
    count_discarded<T>(kOpsTrilinearSphere * uint64_t(idle));
  }
  return true;
}

// The cone map's cell under p, read (one fetch, one iteration): its apex and ratio.
template <class T>
void read_cone(const ParallaxMaps& m, const Ray<T>& ray, Point<T> p, T& apex, T& ratio, ParallaxTrace& r, Ops* ops) {
  const core::HeightField& f = m.field;
  int i = int(float(floor_op(p.x))) % f.width, j = int(float(floor_op(p.y))) % f.height;
  if (i < 0) i += f.width;
  if (j < 0) j += f.height;
  const size_t cell = size_t(j) * size_t(f.width) + size_t(i);
  if (ray.reads) ray.reads->cone(i, j);
  apex = T(m.cone.apex[cell]), ratio = T(m.cone.ratio[cell]);
  ++r.iterations, ++r.fetches;
  if (ops) *ops += kOpsCone;
}

// The step along the ray that stays inside the cone of the cell under p, which is
// `above` slices over the apex: its horizontal run grows by `ratio` a slice down.
template <class T>
T cone_step(T above, T ratio, T down, T across) {
  const T zero = T(0.0f);
  if (above > zero && ratio > zero) return above / (down + across / ratio);
  count_discarded<T>(Ops{/*add*/ 1, 0, /*div*/ 2});  // computed in hardware, then selected away
  return zero;
}

// The ray's run across a unit of its length, |v̂xy|, once a ray (the cone tracers).
template <class T>
T run_across(const Ray<T>& ray, Ops* ops) {
  if (ops) *ops += kOpsAcross;
  return sqrt_op(ray.d.x * ray.d.x + ray.d.y * ray.d.y);
}

// Cone stepping: from p over cell (i, j), the ray stays in the cone of the cell — free
// of relief — until it has come down to apex + (distance from the footprint)/ratio; then
// the exact cells. False if the ray overflowed.
template <class T>
bool trace_cones(const core::ParallaxSettings& s, const ParallaxMaps& m, const Ray<T>& ray, Point<T>& p,
                 ParallaxTrace& r, Ops* ops) {
  const T across = run_across(ray, ops), down = -ray.d.z;
  while (r.iterations < s.max_iterations) {
    if (!finite(p.x) || !finite(p.y)) return false;
    T apex, ratio;
    read_cone(m, ray, p, apex, ratio, r, ops);
    const T t = cone_step(p.z - apex, ratio, down, across);
    if (t < T(kParallaxNear)) {
      count_discarded<T>(kOpsAdvance);  // the step not taken
      break;
    }
    p = advance(p, t, ray.d);
    ++r.skips;
  }
  if (r.iterations < s.max_iterations) finish_cells(s, m, ray, p, r, ops);
  return true;
}

// Relaxed cone stepping on a safe relaxed map (core::relaxed_cone_map): the same steps,
// but a step may end under the relief, which it entered at most once. Where a step ends
// at or under its new cell's apex, one height read tells: above, the exact cells go on
// from there; under, the hit lies in the step, and bisections on the sign of z − D·h
// (each a height read) narrow it to one texel across before the exact cells finish.
// On a relaxed cone's step the sign is + then −, so the first hit stays between them.
template <class T>
bool trace_relaxed_cones(const core::ParallaxSettings& s, const ParallaxMaps& m, const Ray<T>& ray, Point<T>& p,
                         ParallaxTrace& r, Ops* ops) {
  const T across = run_across(ray, ops), down = -ray.d.z;
  Point<T> start = p;  // where the last step began: above the relief
  bool known_above = true;  // p is known to be above the relief (the entry is)
  while (r.iterations < s.max_iterations) {
    if (!finite(p.x) || !finite(p.y)) return false;
    T apex, ratio;
    read_cone(m, ray, p, apex, ratio, r, ops);
    if (p.z > apex) known_above = true;  // over the cell's box top
    if (!known_above) {                  // at or under it after a step: one height read tells
      if (r.iterations >= s.max_iterations) {
        count_discarded<T>(kOpsConeStep);  // the iteration's step, not taken
        break;
      }
      if (p.z <= slices_under(m, ray, p, r, ops)) {  // under: the hit is in the step from start, search it
        if (ops) *ops += kOpsBisect;
        const T run = (p.z - start.z) / ray.d.z * across;  // the step's length across, texels
        bisect_to_texel(s, m, ray, run, start, p, r, ops);
        p = start, known_above = true;       // above the relief, the hit within a texel or so on
        count_discarded<T>(kOpsConeStep);  // the iteration's step, not taken
        break;
      }
      known_above = true;
    }
    const T t = cone_step(p.z - apex, ratio, down, across);
    if (t < T(kParallaxNear)) {
      count_discarded<T>(kOpsAdvance);  // the step not taken
      break;
    }
    start = p;
    p = advance(p, t, ray.d);
    ++r.skips, known_above = false;
  }
  // The cap came before the last step's end was checked: it may be under the relief, past
  // the hit; the trace stops where that step began instead, before the hit.
  if (!known_above) p = start;
  if (r.iterations < s.max_iterations) finish_cells(s, m, ray, p, r, ops);
  return true;
}

// The tracer in the number type T (pipeline.parallax.format): the ray, one of the
// tracers; the hit in texels (the block takes it back to uv).
template <class T>
ParallaxTrace trace_as(const core::ParallaxSettings& s, const ParallaxMaps& m, float x0f, float y0f, float af,
                       float bf, float cf, Ops* ops, MapReads* reads) {
  ParallaxTrace r;
  r.x = x0f, r.y = y0f;
  Ray<T> ray;
  ray.reads = reads;
  if (!make_ray(s, m, x0f, y0f, af, bf, cf, ops, ray)) return r;
  if (s.method == core::ParallaxMethod::Offset) {
    trace_offset(s, m, ray, r, ops);
    return r;
  }
  Point<T> p = ray.entry;
  const bool distance = s.method == core::ParallaxMethod::Distance, cone = s.method == core::ParallaxMethod::Cone;
  const bool donnelly = distance && s.map == core::DistanceMap::Donnelly;
  const bool traced = donnelly ? trace_donnelly(s, m, ray, p, r, ops)
                      : distance ? trace_spheres(s, m, ray, p, r, ops)
                      : cone && s.cones == core::ConeKind::Relaxed ? trace_relaxed_cones(s, m, ray, p, r, ops)
                      : cone   ? trace_cones(s, m, ray, p, r, ops)
                               : trace_layers(s, m, ray, p, r, ops);
  if (!traced) return r;  // overflowed (float16): counted; the entry kept
  if (!s.early_exit && (distance || cone) && !donnelly) {
    // A fixed-length loop: the iterations after the hit still read the map (and find
    // the point where it is).
    const int idle = s.max_iterations - std::min(s.max_iterations, r.iterations);
    r.iterations += idle, r.fetches += idle;
    if (ops) *ops += (cone ? kOpsCone : kOpsSphere) * uint64_t(idle);
    count_discarded<T>((cone ? kOpsCone : kOpsSphere) * uint64_t(idle));
  }
  if (!finite(p.x) || !finite(p.y)) return r;  // overflowed (float16): counted; the entry kept
  r.x = float(p.x), r.y = float(p.y);
  return r;
}

}  // namespace

ParallaxTrace trace_parallax(const core::ParallaxSettings& s, const ParallaxMaps& m, float x0, float y0, float a,
                             float b, float c, Ops* ops, NumberContext* numbers, MapReads* reads) {
  if (!numbers || (numbers->format.kind == core::NumberFormat::Kind::Float32 && !count_float32_operations))
    return trace_as<float>(s, m, x0, y0, a, b, c, ops, reads);  // straight: one call a pixel
  ParallaxTrace r;
  with_number_type(*numbers, [&](auto zero) { r = trace_as<decltype(zero)>(s, m, x0, y0, a, b, c, ops, reads); });
  return r;
}

MapReads::Place MapReads::place(const ParallaxMaps& m, bool distance, bool cone) {
  Place p;
  p.height = memory_.place(m.field.width, m.field.height, 4);
  if (distance)
    for (int k = 0; k < m.volume.slices; ++k) p.slices.push_back(memory_.place(m.volume.width, m.volume.height, 4));
  if (cone) p.cone = memory_.place(m.cone.width, m.cone.height, 8);
  return p;
}

void MapReads::texel(const Surface& s, int x, int y) {
  x %= s.width, y %= s.height;
  if (x < 0) x += s.width;
  if (y < 0) y += s.height;
  lines_.add(memory_.line_of(s, x, y));
}

void MapReads::bilinear(float x, float y) {
  if (!std::isfinite(x) || !std::isfinite(y) || std::abs(x) > 1e9f || std::abs(y) > 1e9f) return;
  const int i = int(std::floor(x)), j = int(std::floor(y));
  cell(i, j);
}

void MapReads::cell(int i, int j) {
  const Surface& h = place_->height;
  texel(h, i, j), texel(h, i + 1, j), texel(h, i, j + 1), texel(h, i + 1, j + 1);
}

void MapReads::voxel(float x, float y, float z, const core::VolumeMap& v) {
  if (place_->slices.empty() || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z) ||
      std::abs(x) > 1e9f || std::abs(y) > 1e9f)
    return;
  const int k = std::clamp(int(std::floor(std::clamp(z, -1.0f, float(v.slices)))), 0, v.slices - 1);
  texel(place_->slices[size_t(k)], int(std::floor(x)), int(std::floor(y)));
}

void MapReads::trilinear(float x, float y, float z, const core::VolumeMap& v) {
  if (place_->slices.empty() || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z) ||
      std::abs(x) > 1e9f || std::abs(y) > 1e9f)
    return;
  const int i = int(std::floor(x - 0.5f)), j = int(std::floor(y - 0.5f));
  const int k = int(std::floor(std::clamp(z - 0.5f, 0.0f, float(v.slices - 1))));
  for (int kk : {k, std::min(k + 1, v.slices - 1)}) {
    const Surface& slice = place_->slices[size_t(kk)];
    texel(slice, i, j), texel(slice, i + 1, j), texel(slice, i, j + 1), texel(slice, i + 1, j + 1);
  }
}

void MapReads::cone(int i, int j) {
  if (place_->cone.width > 0) texel(place_->cone, i, j);
}

uint16_t MapReads::end() {
  lines_.for_each([&](uint64_t line) { memory_.read_line(line); });
  lines_.clear();
  return memory_.take_pixel_lines();
}

bool ParallaxKernel::needed(const core::Scene& scene) {
  for (const auto& o : scene.objects)
    if (scene.materials[size_t(o.material)].path == core::ShadingPath::Parallax) return true;
  return false;
}

ParallaxKernel::ParallaxKernel(const core::Scene& scene, core::NumberFormat format, int64_t cell_cycles,
                               std::optional<CacheConfig> cache)
    : scene_(scene), cell_cycles_(cell_cycles), numbers_(format) {
  maps_.resize(scene.materials.size());
  for (const auto& o : scene.objects) {
    const core::Material& m = scene.materials[size_t(o.material)];
    auto& slot = maps_[size_t(o.material)];
    if (m.path != core::ShadingPath::Parallax || slot) continue;
    slot = std::make_unique<ParallaxMaps>(
        build_parallax_maps(scene.textures[size_t(m.height_map)], m.parallax, scene.file));
    precompute_s_ += slot->precompute_s;
  }
  if (cache) {  // every material's maps one after another in the tracer's memory
    memory_ = std::make_unique<MemoryClient>(*cache);
    reads_ = std::make_unique<MapReads>(*memory_);
    places_.resize(scene.materials.size());
    for (size_t k = 0; k < maps_.size(); ++k)
      if (maps_[k]) {
        const core::ParallaxMethod method = scene.materials[k].parallax.method;
        places_[k] = reads_->place(*maps_[k], method == core::ParallaxMethod::Distance,
                                   method == core::ParallaxMethod::Cone);
      }
  }
}

void ParallaxKernel::process(SpanPacket& p) {
  const TriangleSetup& t = *p.tri;
  const core::Material& m = *t.material;
  const ParallaxMaps& maps = *maps_[size_t(&m - scene_.materials.data())];
  const float W = float(maps.field.width), H = float(maps.field.height);
  const int dx = p.x0 - t.x_ref, dy = p.y - t.y_ref;
  float u_w = t.uv[0].at(dx, dy), v_w = t.uv[1].at(dx, dy);
  float e_w[3];
  for (int k = 0; k < 3; ++k) e_w[k] = t.eye_t[k].at(dx, dy);
  uint64_t iterations = 0;
  for (int i = 0; i < p.count; ++i) {
    const float u = u_w * p.w[i], v = v_w * p.w[i];
    if (capture_) captured_[0][i] = u, captured_[1][i] = v;
    // d = P − eye in tangent space: the view ray's direction.
    const float a = -e_w[0] * p.w[i], b = -e_w[1] * p.w[i], c = -e_w[2] * p.w[i];
    u_w += t.uv[0].ax, v_w += t.uv[1].ax;
    for (int k = 0; k < 3; ++k) e_w[k] += t.eye_t[k].ax;
    ParallaxTrace r;
    // The entry brought into the map's first tile (far tiled uv keeps its precision);
    // the shift found is added to the uv as it came.
    float x0 = u * W - 0.5f, y0 = (1 - v) * H - 0.5f;
    x0 -= W * std::floor(x0 / W), y0 -= H * std::floor(y0 / H);
    if (reads_) reads_->begin(places_[size_t(&m - scene_.materials.data())]);
    if (t.parallax_frame) r = trace_parallax(m.parallax, maps, x0, y0, a, b, c, &ops_, &numbers_, reads_.get());
    if (reads_) lines_[i] = reads_->end();
    const bool moved = r.iterations > 0;
    p.uvp[0][i] = moved ? u + (r.x - x0) / W : u;
    p.uvp[1][i] = moved ? v - (r.y - y0) / H : v;
    p.iterations[i] = float(r.iterations);
    // For the hit layers (an observation: no operation, read or cycle of the tracer).
    p.hit_height[i] = moved ? core::bilinear_height<float>(maps.field, r.x, r.y) : 1.0f;
    iterations += uint64_t(r.iterations);
    work_[i] = uint16_t(std::min<int64_t>(parallax_cycles(r, cell_cycles_), 65535));
  }
  // Per pixel, in float32 (declared by hand, not run on a counting type): uv and the
  // tangent-space eye vector (5 add, 5 mul); the entry in texels, u·W − ½ and
  // (1 − v)·H − ½ (3 add, 2 mul), wrapped into the first tile (x − W·⌊x·(1/W)⌋: 2 add,
  // 4 mul); the hit back to uv, u + (x − x₀)·(1/W) (4 add, 2 mul). 1/W and 1/H are the
  // map's constants, so hardware multiplies; the model divides, a rounding apart.
  // (With the five plane seeds per packet below, these are the block's own operations,
  // outside the tracer's.)
  ops_ += Ops{/*add*/ 14, /*mul*/ 13} * uint64_t(p.count);
  if (p.count > 0) ops_ += Ops{/*add*/ 10, /*mul*/ 10};   // five plane seeds
  nonfinite_ += count_nonfinite(p.uvp, p.count);
  iterations_ += iterations;
}

}  // namespace shadetlm::modules
