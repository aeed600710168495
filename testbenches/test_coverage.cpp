// The coverage convention: no pixel covered twice and none missed on meshes of shared
// edges, spans that agree with the per-pixel test, and clipping that keeps the
// triangle's geometry.
#include <random>

#include "shadetlm/core/coverage.hpp"
#include "test_util.hpp"

using namespace shadetlm;  // core::, modules::, reference::

namespace {
constexpr int W = 61, H = 47;

// Adds one to every pixel the screen triangle covers, walking the row spans.
void rasterize(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, std::vector<int>& count) {
  core::SnappedTriangle t;
  if (!core::snap_triangle(a, b, c, W, H, t)) return;
  for (int y = t.y0; y <= t.y1; ++y) {
    auto [x0, x1] = t.row_span(y);
    for (int x = x0; x < x1; ++x) ++count[size_t(y) * W + x];
  }
}

// A grid of (n+1)² vertices over [-2, W+2] × [-2, H+2] (beyond the viewport), jittered,
// with some vertices put exactly on pixel centres, pixel corners and sub-pixel grid
// points so that edges pass through pixel centres.
std::vector<glm::dvec2> grid(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  std::uniform_int_distribution<int> kind(0, 3);
  std::vector<glm::dvec2> v;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      glm::dvec2 p(-2 + (W + 4.0) * i / n, -2 + (H + 4.0) * j / n);
      const bool border = i == 0 || j == 0 || i == n || j == n;
      if (!border) {
        p += glm::dvec2(jitter(rng), jitter(rng)) * ((W + 4.0) / n);
        switch (kind(rng)) {
          case 0: p = glm::floor(p) + 0.5; break;  // a pixel centre
          case 1: p = glm::floor(p); break;        // a pixel corner
          case 2: p = glm::floor(p * 256.0) / 256.0; break;
          default: break;
        }
      }
      v.push_back(p);
    }
  return v;
}
}  // namespace

TEST_CASE("a mesh of shared edges covers every pixel exactly once", "[coverage]") {
  std::mt19937 rng(7);
  // Snapped signed area (y down) of a triangle of the undistorted grid's winding.
  auto area = [](glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
    auto s = [](glm::dvec2 p) { return glm::dvec2(std::llround(p.x * 256), std::llround(p.y * 256)); };
    a = s(a), b = s(b), c = s(c);
    return (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
  };
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 3 + trial % 9;
    std::vector<glm::dvec2> v;
    // Jitter can fold a quad over itself, and folded triangles overlap for real:
    // draw grids until no triangle is folded.
    for (bool folded = true; folded;) {
      v = grid(n, rng);
      folded = false;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
          folded = folded || area(v[a], v[b], v[d]) <= 0 || area(v[a], v[d], v[c]) <= 0 ||
                   area(v[a], v[b], v[c]) <= 0 || area(v[c], v[b], v[d]) <= 0;
        }
    }
    std::vector<int> count(size_t(W) * H, 0);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
        // Alternate the diagonal, and alternate the winding, which must not matter.
        if ((i + j + trial) % 2) {
          rasterize(v[a], v[b], v[d], count);
          rasterize(v[a], v[c], v[d], count);
        } else {
          rasterize(v[a], v[b], v[c], count);
          rasterize(v[c], v[b], v[d], count);
        }
      }
    int missed = 0, twice = 0;
    for (int k : count) {
      missed += k == 0;
      twice += k > 1;
    }
    INFO("trial " << trial << ", n " << n);
    CHECK(missed == 0);
    CHECK(twice == 0);
  }
}

TEST_CASE("a fan around a pixel centre covers each pixel once", "[coverage]") {
  // Eight triangles around a vertex on a pixel centre, with edges along rows, columns
  // and diagonals through pixel centres: the cases where the fill rule decides.
  const glm::dvec2 c(30.5, 20.5);
  const glm::dvec2 ring[8] = {{40.5, 20.5}, {40.5, 30.5}, {30.5, 30.5}, {20.5, 30.5},
                              {20.5, 20.5}, {20.5, 10.5}, {30.5, 10.5}, {40.5, 10.5}};
  std::vector<int> count(size_t(W) * H, 0);
  for (int k = 0; k < 8; ++k) rasterize(c, ring[k], ring[(k + 1) % 8], count);
  int inside = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const int k = count[size_t(y) * W + x];
      CHECK(k <= 1);
      // The square [20.5, 40.5]²: its top and left sides are in, bottom and right out.
      const bool expected = x >= 20 && x < 40 && y >= 10 && y < 30;
      CHECK((k == 1) == expected);
      inside += k;
    }
  CHECK(inside == 400);
}

TEST_CASE("row spans agree with the per-pixel coverage test", "[coverage]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> pos(-10, 70);
  for (int trial = 0; trial < 300; ++trial) {
    glm::dvec2 p[3];
    for (auto& q : p) {
      q = {pos(rng), pos(rng)};
      if (trial % 3 == 0) q = glm::floor(q) + 0.5;  // vertices on pixel centres
    }
    core::SnappedTriangle t;
    if (!core::snap_triangle(p[0], p[1], p[2], W, H, t)) continue;
    for (int y = 0; y < H; ++y) {
      auto [x0, x1] = (y >= t.y0 && y <= t.y1) ? t.row_span(y) : std::pair<int, int>{0, 0};
      for (int x = 0; x < W; ++x) {
        const bool in_span = x >= x0 && x < x1;
        CHECK(in_span == (y >= t.y0 && y <= t.y1 && t.covers(x, y)));
      }
    }
  }
}

TEST_CASE("snapping rounds to 1/256 pixel and orders the vertices", "[coverage]") {
  core::SnappedTriangle t;
  // Counter-clockwise on screen with y up is clockwise with y down: front-facing.
  REQUIRE(core::snap_triangle({10.001, 10}, {10, 20}, {20, 10}, W, H, t));
  CHECK(t.front_facing);
  CHECK(t.x[0] == std::llround(10.001 * 256));
  REQUIRE(core::snap_triangle({10, 10}, {20, 10}, {10, 20}, W, H, t));
  CHECK(!t.front_facing);
  // Zero area after snapping.
  CHECK(!core::snap_triangle({10, 10}, {20, 10}, {30, 10.001}, W, H, t));
  // Entirely off screen.
  CHECK(!core::snap_triangle({-30, -30}, {-20, -30}, {-30, -20}, W, H, t));
}

TEST_CASE("clipping keeps the triangle's geometry and its barycentric weights", "[coverage]") {
  // A triangle crossing the near plane (z_clip = −w), the +x guard band (x/w = 10 at
  // the second vertex) and the far plane (z/w = 1.5 at the third).
  const glm::dvec4 c[3] = {{0, 0, -3, 1}, {60, 0, 5, 6}, {0, 1, 4.5, 3}};
  const auto poly = core::clip_triangle(c[0], c[1], c[2]);
  REQUIRE(poly.size() >= 5);
  for (const auto& v : poly) {
    const glm::dvec4 mix = v.bary.x * c[0] + v.bary.y * c[1] + v.bary.z * c[2];
    for (int k = 0; k < 4; ++k) CHECK(mix[k] == Approx(v.clip[k]).margin(1e-12));
    const glm::dvec4 p = v.clip;
    const double g = core::kGuardBand;
    for (double d : {p.z + p.w, p.w - p.z, g * p.w - p.x, g * p.w + p.x, g * p.w - p.y, g * p.w + p.y})
      CHECK(d >= -1e-12);  // inside all six planes
    CHECK(v.bary.x + v.bary.y + v.bary.z == Approx(1.0));
  }
  // A shared edge is cut at bitwise the same point whichever way it is walked.
  const auto other = core::clip_triangle(c[1], c[0], {0, -1, 0, 1});
  int shared = 0;
  for (const auto& a : poly)
    for (const auto& b : other) shared += a.clip == b.clip && a.clip.z + a.clip.w == 0;
  CHECK(shared == 1);
  // Entirely behind the camera: nothing left.
  CHECK(core::clip_triangle({0, 0, -5, -1}, {1, 0, -5, -1}, {0, 1, -5, -1}).empty());
  // Entirely inside: unchanged.
  const auto inside = core::clip_triangle({0, 0, 0, 1}, {0.5, 0, 0, 1}, {0, 0.5, 0, 1});
  REQUIRE(inside.size() == 3);
  CHECK(inside[1].clip == glm::dvec4(0.5, 0, 0, 1));
  CHECK(inside[1].bary == glm::dvec3(0, 1, 0));
  // Non-finite input: nothing.
  CHECK(core::clip_triangle({0, 0, 0, 1}, {NAN, 0, 0, 1}, {0, 1, 0, 1}).empty());
}

TEST_CASE("a triangle across any one clipping plane is cut by it", "[coverage]") {
  // One vertex past one plane at a time (the others inside every plane): the early
  // accept must see each plane, and the cut leaves a quad inside all six.
  const glm::dvec4 past[6] = {{0.5, 0, -2, 1}, {0.5, 0, 2, 1}, {9, 0, 0, 1},
                              {-9, 0, 0, 1},   {0.5, 9, 0, 1}, {0.5, -9, 0, 1}};
  for (int plane = 0; plane < 6; ++plane) {
    INFO("plane " << plane);
    const auto poly = core::clip_triangle({0, 0, 0, 1}, past[plane], {0, 0.5, 0, 1});
    CHECK(poly.size() == 4);
    for (const auto& v : poly) {
      const glm::dvec4 c = v.clip;
      const double band = core::kGuardBand * c.w;
      CHECK(c.z + c.w >= -1e-12);
      CHECK(c.w - c.z >= -1e-12);
      CHECK(std::abs(c.x) <= band + 1e-12);
      CHECK(std::abs(c.y) <= band + 1e-12);
    }
  }
}

TEST_CASE("snapping's rounding is std::llround's", "[coverage]") {
  // Halves (both signs, where the two directions differ), their neighbours one ulp
  // away, values past 2⁵² (already integers) and past 2⁶² (llround's own path).
  std::vector<double> values = {0.0, -0.0, 0.5, -0.5, 1.5, -1.5, 2.5, -2.5, 0x1p52 + 1, -0x1p53, 0x1p62, -0x1p62 - 4096.0};
  for (double h : {0.5, -0.5, 1.5, -1.5, 1e6 + 0.5, -1e6 - 0.5, 0x1p51 + 0.5, -0x1p51 - 0.5}) {
    values.push_back(std::nextafter(h, 0.0));
    values.push_back(std::nextafter(h, h * 2));
  }
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> screen(-8.0 * 4096 * 256, 8.0 * 4096 * 256);
  for (int i = 0; i < 100000; ++i) {
    values.push_back(screen(rng));
    values.push_back(std::round(screen(rng)) + 0.5);  // exact halves
  }
  for (double v : values) {
    INFO(std::hexfloat << v);
    CHECK(core::round_half_away(v) == std::llround(v));
  }
}
