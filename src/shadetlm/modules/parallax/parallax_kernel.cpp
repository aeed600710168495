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

// Operation counts of the tracer's steps (docs/parallax.md).
constexpr Ops kOpsRay{/*add*/ 9, /*mul*/ 16, 0, 0, /*rsqrt*/ 1};  // tangent-space ray, scaled and normalized
constexpr Ops kOpsHeightRead{/*add*/ 8, /*mul*/ 4, 0, 0, 0, 0, /*fetch*/ 4};  // bilinear height, ×D
constexpr Ops kOpsLayer{/*add*/ 11, /*mul*/ 4, 0, 0, 0, 0, /*fetch*/ 4};                     // one layer down
constexpr Ops kOpsSphere{/*add*/ 3, /*mul*/ 3, 0, 0, 0, 0, /*fetch*/ 1};        // p += d(p)·v̂
// Donnelly's step: a trilinear read (3 fractions, 7 lerps of 1 mul and 2 add, 8 voxels), then p += d·v̂.
constexpr Ops kOpsTrilinearSphere{/*add*/ 3 + 14 + 3, /*mul*/ 7 + 3, 0, 0, 0, 0, /*fetch*/ 8};
constexpr Ops kOpsCone{/*add*/ 5, /*mul*/ 3, /*div*/ 2, 0, 0, 0, /*fetch*/ 1};  // step to the cone's side
constexpr Ops kOpsCell{/*add*/ 16, /*mul*/ 18, /*div*/ 2, /*sqrt*/ 1, 0, 0, /*fetch*/ 4};  // exact cell test
constexpr Ops kOpsOut{/*add*/ 4, /*mul*/ 2};  // texels back to uv

// Whether a value of the tracer is finite (float16 overflows to infinity; the value
// must not reach a texel index). In float32 the tracer's values stay far below the
// range (a ray is at most ~10^7 texels long), and fixed point saturates: no test.
template <class T>
bool finite(T v) {
  if constexpr (std::is_same_v<T, Half>) return std::isfinite(float(v));
  return true;
}

// The texture unit's bilinear height at (x, y), in float32 like every texture read; the
// tracer takes it into its format.
template <class T>
T height_at(const core::HeightField& f, T x, T y, MapReads* reads) {
  if (reads) reads->bilinear(float(x), float(y));
  return T(core::bilinear_height<float>(f, float(x), float(y)));
}

// The exact cells from (x, y, z) on: the finish of the skipping tracers. The per-cell
// quadratic (core::march_cells, shared with the map builders) runs in float32 whatever
// the tracer's format; its result is taken back into the format.
template <class T>
void finish_cells(const core::ParallaxSettings& s, const ParallaxMaps& m, T& x, T& y, T& z, T dx, T dy, T dz,
                  ParallaxTrace& r, Ops* ops, MapReads* reads) {
  const int budget = std::max(1, s.max_iterations - r.iterations);
  if (!finite(x) || !finite(y) || !finite(z)) return;
  const float fdx = float(dx), fdy = float(dy), fdz = float(dz);
  const auto march = core::march_cells<float>(m.field, float(x), float(y), float(z), fdx, fdy, fdz,
                                              float(m.slices), budget, [&](int i, int j) {
                                                if (reads) reads->cell(i, j);
                                              });
  const T t = T(march.t);
  x += t * dx, y += t * dy, z += t * dz;
  r.iterations += march.cells;
  r.cells += march.cells;
  r.fetches += 4 * march.cells;
  if (ops) *ops += kOpsCell * uint64_t(march.cells);
}

// The view ray in the tracer's space (core/parallax_map.hpp): x along u, y down the
// rows, z in slices of the depth; (dx, dy, dz) unit there. In the number type T.
template <class T>
struct Ray {
  T x0, y0, a, b, c;  // the entry (texels) and the tangent-space direction
  T W, H, D;          // the map's size: texels across and down, slices deep
  T dx, dy, dz;
  MapReads* reads = nullptr;  // the map reads (DRAM model)
};

// The ray of a pixel; false where there is none to trace (no depth, a ray leaving the
// surface, no direction, or one so close to the surface it would run over 10⁶ texels):
// the entry is the answer then.
template <class T>
bool make_ray(const core::ParallaxSettings& s, const ParallaxMaps& m, float x0f, float y0f, float af, float bf,
              float cf, Ops* ops, Ray<T>& ray) {
  if (!(s.depth > 0) || !(cf < 0) || !std::isfinite(af) || !std::isfinite(bf)) return false;
  const core::HeightField& f = m.field;
  ray.W = T(float(f.width)), ray.H = T(float(f.height)), ray.D = T(float(m.slices));
  ray.x0 = T(x0f), ray.y0 = T(y0f), ray.a = T(af), ray.b = T(bf), ray.c = T(cf);
  const T one = T(1.0f), zero = T(0.0f);
  if (ops) *ops += kOpsRay;
  T dx = ray.a * ray.W, dy = -ray.b * ray.H, dz = ray.c * ray.D / T(float(s.depth));
  const T length2 = dx * dx + dy * dy + dz * dz;
  if (!(length2 > zero)) return false;  // no direction (before a reciprocal of 0)
  const T scale = one / sqrt_op(length2);
  if (!std::isfinite(float(scale)) || scale == zero) return false;
  dx *= scale, dy *= scale, dz *= scale;  // unit in the tracer's space
  // A ray this close to the surface would run over 10⁶ texels: treated as parallel.
  if (-dz < T(1e-6f) || !(dz < zero)) return false;
  ray.dx = dx, ray.dy = dy, ray.dz = dz;
  return true;
}

// Offset limiting: T = T0 + depth·(1 − h(T0))·v̂xy with v̂ the unit physical direction:
// no division by v̂z, so the shift stays within the depth at grazing views.
template <class T>
void trace_offset(const core::ParallaxSettings& s, const ParallaxMaps& m, const Ray<T>& ray, ParallaxTrace& r,
                  Ops* ops) {
  const T one = T(1.0f), a = ray.a, b = ray.b, c = ray.c;
  const T h = height_at(m.field, ray.x0, ray.y0, ray.reads);
  const T inv = one / sqrt_op(a * a + b * b + c * c);
  const T shift = T(float(s.depth)) * (one - h) * inv;
  r.x = float(ray.x0 + shift * a * ray.W), r.y = float(ray.y0 - shift * b * ray.H);
  r.iterations = 1, r.fetches = 4;
  if (ops) *ops += kOpsHeightRead + Ops{/*add*/ 3, /*mul*/ 6, 0, 0, /*rsqrt*/ 1} + kOpsOut;
}

// POM: where the line between the two layers' heights crosses the ray.
template <class T>
void pom_finish(const core::ParallaxSettings&, const ParallaxMaps& m, const Ray<T>& ray, T px, T py, T pz, T ph, T h,
                T& x, T& y, T z, ParallaxTrace& r, Ops* ops) {
  const T D = ray.D, one = T(1.0f), zero = T(0.0f);
  if (pz == D) {
    // Under the relief at the first layer: the entry's height, for the line below.
    ph = D * height_at(m.field, ray.x0, ray.y0, ray.reads);
    ++r.iterations, r.fetches += 4;
    if (ops) *ops += kOpsHeightRead;
  }
  const T above = pz - ph, below = h - z;
  const T w = above + below > zero ? above / (above + below) : one;
  x = px + (x - px) * w, y = py + (y - py) * w;
  if (ops) *ops += Ops{/*add*/ 6, /*mul*/ 2, /*div*/ 1};
}

// Relief: a binary search between the last layer above and the first one under.
template <class T>
void relief_finish(const core::ParallaxSettings& s, const ParallaxMaps& m, const Ray<T>& ray, T px, T py, T pz, T& x,
                   T& y, T& z, ParallaxTrace& r, Ops* ops) {
  const T half = T(0.5f);
  for (int i = 0; i < s.binary_steps && r.iterations < s.max_iterations; ++i) {
    const T mx = (px + x) * half, my = (py + y) * half, mz = (pz + z) * half;
    const T mh = ray.D * height_at(m.field, mx, my, ray.reads);
    ++r.iterations, r.fetches += 4;
    if (ops) *ops += kOpsHeightRead + Ops{/*add*/ 3, /*mul*/ 3};
    if (mz <= mh) x = mx, y = my, z = mz;
    else px = mx, py = my, pz = mz;
  }
}

// Steep parallax, POM and relief: the layer search, then each one's finish. False if
// the ray overflowed (float16: counted; the entry kept).
template <class T>
bool trace_layers(const core::ParallaxSettings& s, const ParallaxMaps& m, const Ray<T>& ray, T& x, T& y, T& z,
                  ParallaxTrace& r, Ops* ops) {
  const core::HeightField& f = m.field;
  const T D = ray.D, a = ray.a, b = ray.b, c = ray.c;
  // More layers the flatter the view: n = max + (min − max)·|cos θ|, θ from the normal.
  const float cos_view = float(-c / sqrt_op(a * a + b * b + c * c));
  const int layers = std::max(1, int(std::lround(float(s.layers_max) + float(s.layers_min - s.layers_max) * cos_view)));
  const T step = (D / T(float(layers))) / -ray.dz;  // ray length per layer
  T px = x, py = y, pz = z, ph = D;                  // the last point above (the entry)
  T h = ph;
  for (int i = 1; i <= layers && r.iterations < s.max_iterations; ++i) {
    const T along = T(float(i)) * step;
    x = ray.x0 + along * ray.dx, y = ray.y0 + along * ray.dy, z = D + along * ray.dz;
    if (!finite(x) || !finite(y)) return false;
    h = D * height_at(f, x, y, ray.reads);
    ++r.iterations, r.fetches += 4;
    if (ops) *ops += kOpsLayer;
    if (z <= h) break;
    px = x, py = y, pz = z, ph = h;
  }
  if (!s.early_exit) {  // the loop runs every layer; the hit is the first one under
    const int idle = layers - std::min(layers, r.iterations);
    r.iterations += idle, r.fetches += 4 * idle;
    if (ops) *ops += kOpsLayer * uint64_t(idle);
  }
  if (s.method == core::ParallaxMethod::Pom && z <= h) pom_finish(s, m, ray, px, py, pz, ph, h, x, y, z, r, ops);
  else if (s.method == core::ParallaxMethod::Relief && z <= h) relief_finish(s, m, ray, px, py, pz, x, y, z, r, ops);
  return true;
}

// Sphere tracing: p ← p + d(p)·v̂, the voxel holding p read as stored (its value is safe
// for every point of the voxel); then the exact cells. False if the ray overflowed.
template <class T>
bool trace_spheres(const core::ParallaxSettings& s, const ParallaxMaps& m, const Ray<T>& ray, T& x, T& y, T& z,
                   ParallaxTrace& r, Ops* ops) {
  const T near = T(kParallaxNear);
  while (r.iterations < s.max_iterations) {
    if (!finite(x) || !finite(y) || !finite(z)) return false;
    if (ray.reads) ray.reads->voxel(float(x), float(y), float(z), m.volume);
    const T d = T(m.volume.sample(float(x), float(y), float(z)));
    ++r.iterations, ++r.fetches;
    if (ops) *ops += kOpsSphere;
    if (d < near) break;
    x += d * ray.dx, y += d * ray.dy, z += d * ray.dz;
    ++r.skips;
  }
  if (r.iterations < s.max_iterations) finish_cells(s, m, x, y, z, ray.dx, ray.dy, ray.dz, r, ops, ray.reads);
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
bool trace_donnelly(const core::ParallaxSettings& s, const ParallaxMaps& m, const Ray<T>& ray, T& x, T& y, T& z,
                    ParallaxTrace& r, Ops* ops) {
  const int steps = std::min(s.steps, s.max_iterations);
  const T converged = T(kDonnellyConverged);
  while (r.iterations < steps) {
    if (!finite(x) || !finite(y) || !finite(z)) return false;
    if (ray.reads) ray.reads->trilinear(float(x), float(y), float(z), m.volume);
    const T d = T(m.volume.trilinear(float(x), float(y), float(z)));
    ++r.iterations, ++r.trilinear, r.fetches += 8;
    if (ops) *ops += kOpsTrilinearSphere;
    if (s.early_exit && d < converged) break;
    x += d * ray.dx, y += d * ray.dy, z += d * ray.dz;
    ++r.skips;
    if (z < T(0.0f)) {  // through the floor (the map clamps there): back onto it, the hit
      const T back = z / ray.dz;
      x -= back * ray.dx, y -= back * ray.dy, z = T(0.0f);
      if (ops) *ops += Ops{/*add*/ 2, /*mul*/ 2, /*div*/ 1};
      break;
    }
  }
  if (!s.early_exit) {  // the fixed count: the steps after the floor still read the map
    const int idle = steps - std::min(steps, r.iterations);
    r.iterations += idle, r.trilinear += idle, r.fetches += 8 * idle;
    if (ops) *ops += kOpsTrilinearSphere * uint64_t(idle);
  }
  return true;
}

// The cone map's cell under (x, y), read (one fetch, one iteration): its apex and ratio.
template <class T>
void read_cone(const ParallaxMaps& m, const Ray<T>& ray, T x, T y, T& apex, T& ratio, ParallaxTrace& r, Ops* ops) {
  const core::HeightField& f = m.field;
  int i = int(float(floor_op(x))) % f.width, j = int(float(floor_op(y))) % f.height;
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
  return above > zero && ratio > zero ? above / (down + across / ratio) : zero;
}

// Cone stepping: from p over cell (i, j), the ray stays in the cone of the cell — free
// of relief — until it has come down to apex + (distance from the footprint)/ratio; then
// the exact cells. False if the ray overflowed.
template <class T>
bool trace_cones(const core::ParallaxSettings& s, const ParallaxMaps& m, const Ray<T>& ray, T& x, T& y, T& z,
                 ParallaxTrace& r, Ops* ops) {
  const T across = sqrt_op(ray.dx * ray.dx + ray.dy * ray.dy), down = -ray.dz;
  while (r.iterations < s.max_iterations) {
    if (!finite(x) || !finite(y)) return false;
    T apex, ratio;
    read_cone(m, ray, x, y, apex, ratio, r, ops);
    const T t = cone_step(z - apex, ratio, down, across);
    if (t < T(kParallaxNear)) break;
    x += t * ray.dx, y += t * ray.dy, z += t * ray.dz;
    ++r.skips;
  }
  if (r.iterations < s.max_iterations) finish_cells(s, m, x, y, z, ray.dx, ray.dy, ray.dz, r, ops, ray.reads);
  return true;
}

// Bisections on the sign of z − D·h (a height read each) between p, above the relief,
// and q, at or under it, until the step is at most a texel across or the cap is reached.
// On a relaxed cone's step the sign is + then −, so the first hit stays between them.
template <class T>
void bisect_step(const core::ParallaxSettings& s, const ParallaxMaps& m, const Ray<T>& ray, T& px, T& py, T& pz, T& qx,
                 T& qy, T& qz, ParallaxTrace& r, Ops* ops) {
  const T half = T(0.5f), across = sqrt_op(ray.dx * ray.dx + ray.dy * ray.dy);
  T run = (qz - pz) / ray.dz * across;  // the step's length across, texels
  while (run > T(1.0f) && r.iterations < s.max_iterations) {
    const T mx = (px + qx) * half, my = (py + qy) * half, mz = (pz + qz) * half;
    const T mh = ray.D * height_at(m.field, mx, my, ray.reads);
    ++r.iterations, r.fetches += 4;
    if (ops) *ops += kOpsHeightRead + Ops{/*add*/ 3, /*mul*/ 3};
    if (mz <= mh) qx = mx, qy = my, qz = mz;
    else px = mx, py = my, pz = mz;
    run = run * half;
  }
}

// Relaxed cone stepping on a safe relaxed map (core::relaxed_cone_map): the same steps,
// but a step may end under the relief, which it entered at most once. Where a step ends
// at or under its new cell's apex, one height read tells: above, the exact cells go on
// from there; under, the hit lies in the step, and bisections on the sign of z − D·h
// (each a height read) narrow it to one texel across before the exact cells finish.
template <class T>
bool trace_relaxed_cones(const core::ParallaxSettings& s, const ParallaxMaps& m, const Ray<T>& ray, T& x, T& y,
                         T& z, ParallaxTrace& r, Ops* ops) {
  const T across = sqrt_op(ray.dx * ray.dx + ray.dy * ray.dy), down = -ray.dz;
  T px = x, py = y, pz = z;  // where the last step began: above the relief
  bool above = true;         // (x, y, z) is known to be above the relief (the entry is)
  while (r.iterations < s.max_iterations) {
    if (!finite(x) || !finite(y)) return false;
    T apex, ratio;
    read_cone(m, ray, x, y, apex, ratio, r, ops);
    if (z > apex) above = true;  // over the cell's box top
    if (!above) {                // at or under it after a step: one height read tells
      if (r.iterations >= s.max_iterations) break;
      const T h = ray.D * height_at(m.field, x, y, ray.reads);
      ++r.iterations, r.fetches += 4;
      if (ops) *ops += kOpsHeightRead;
      if (z <= h) {  // under: the hit is in the step from p, search it
        bisect_step(s, m, ray, px, py, pz, x, y, z, r, ops);
        x = px, y = py, z = pz, above = true;  // above the relief, the hit within a texel or so on
        break;
      }
      above = true;
    }
    const T t = cone_step(z - apex, ratio, down, across);
    if (t < T(kParallaxNear)) break;
    px = x, py = y, pz = z;
    x += t * ray.dx, y += t * ray.dy, z += t * ray.dz;
    ++r.skips, above = false;
  }
  // The cap came before the last step's end was checked: it may be under the relief, past
  // the hit; the trace stops where that step began instead, before the hit.
  if (!above) x = px, y = py, z = pz;
  if (r.iterations < s.max_iterations) finish_cells(s, m, x, y, z, ray.dx, ray.dy, ray.dz, r, ops, ray.reads);
  return true;
}

// The tracer in the number type T (pipeline.parallax.format): the ray, one of the
// tracers, and the uv out.
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
  T x = ray.x0, y = ray.y0, z = ray.D;
  const bool distance = s.method == core::ParallaxMethod::Distance, cone = s.method == core::ParallaxMethod::Cone;
  const bool donnelly = distance && s.map == core::DistanceMap::Donnelly;
  const bool traced = donnelly ? trace_donnelly(s, m, ray, x, y, z, r, ops)
                      : distance ? trace_spheres(s, m, ray, x, y, z, r, ops)
                      : cone && s.cones == core::ConeKind::Relaxed ? trace_relaxed_cones(s, m, ray, x, y, z, r, ops)
                      : cone   ? trace_cones(s, m, ray, x, y, z, r, ops)
                               : trace_layers(s, m, ray, x, y, z, r, ops);
  if (!traced) return r;  // overflowed (float16): counted; the entry kept
  if (!s.early_exit && (distance || cone) && !donnelly) {
    // A fixed-length loop: the iterations after the hit still read the map (and find
    // the point where it is).
    const int idle = s.max_iterations - std::min(s.max_iterations, r.iterations);
    r.iterations += idle, r.fetches += idle;
    if (ops) *ops += (cone ? kOpsCone : kOpsSphere) * uint64_t(idle);
  }
  if (!finite(x) || !finite(y)) return r;  // overflowed (float16): counted; the entry kept
  r.x = float(x), r.y = float(y);
  if (ops) *ops += kOpsOut;
  return r;
}

}  // namespace

ParallaxTrace trace_parallax(const core::ParallaxSettings& s, const ParallaxMaps& m, float x0, float y0, float a,
                             float b, float c, Ops* ops, NumberContext* numbers, MapReads* reads) {
  if (!numbers || numbers->format.kind == core::NumberFormat::Kind::Float32)
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
  ops_ += Ops{/*add*/ 5, /*mul*/ 5} * uint64_t(p.count);  // uv and the tangent-space eye vector, per pixel
  if (p.count > 0) ops_ += Ops{/*add*/ 10, /*mul*/ 10};   // five plane seeds
  nonfinite_ += count_nonfinite(p.uvp, p.count);
  iterations_ += iterations;
}

}  // namespace shadetlm::modules
