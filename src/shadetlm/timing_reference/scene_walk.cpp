#include "shadetlm/timing_reference/scene_walk.hpp"

#include <algorithm>
#include <climits>
#include <sstream>

#include "shadetlm/core/coverage.hpp"

namespace shadetlm::timing_reference {

int64_t TriangleWalk::index_of(int x, int y) const {
  if (rows.empty() || y < rows.front().y || y > rows.back().y) return -1;
  // Rows are consecutive except where a row has no covered pixel: search by y.
  const auto row = std::lower_bound(rows.begin(), rows.end(), y, [](const WalkRow& r, int v) { return r.y < v; });
  if (row == rows.end() || row->y != y || x < row->x_begin || x >= row->x_end) return -1;
  return row->steps_before + (x - row->x_begin);
}

namespace {
// The walk of a snapped triangle: its covered rows in order (none: it covers no pixel).
TriangleWalk walk_of(const core::SnappedTriangle& st) {
  TriangleWalk walk;
  for (int y = st.y0; y <= st.y1; ++y) {
    const auto [x_begin, x_end] = st.row_span(y);
    if (x_begin >= x_end) continue;
    walk.rows.push_back({y, x_begin, x_end, walk.steps});
    walk.steps += x_end - x_begin;
  }
  return walk;
}
}  // namespace

SceneWalk derive_walks(const core::Scene& scene) {
  SceneWalk out;
  const glm::dmat4 view_projection = scene.camera.projection() * scene.camera.view();
  const int width = scene.camera.width, height = scene.camera.height;
  int64_t rejected = 0;
  for (const core::Object& object : scene.objects) {
    const core::Mesh mesh = core::to_world(object);
    for (const auto& t : mesh.triangles) {
      const glm::dvec3 p[3] = {mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z]};
      const glm::dvec3 normal = glm::cross(p[1] - p[0], p[2] - p[0]);
      bool handed = false;
      if (glm::dot(normal, normal) > 0) {  // a plane to interpolate on
        const auto poly = core::clip_triangle(view_projection * glm::dvec4(p[0], 1), view_projection * glm::dvec4(p[1], 1),
                                              view_projection * glm::dvec4(p[2], 1));
        for (size_t k = 1; k + 1 < poly.size(); ++k) {
          core::SnappedTriangle st;
          if (!core::snap_triangle(core::to_screen(poly[0].clip, width, height),
                                   core::to_screen(poly[k].clip, width, height),
                                   core::to_screen(poly[k + 1].clip, width, height), width, height, st))
            continue;
          if (object.cull_back && !st.front_facing) continue;
          TriangleWalk walk = walk_of(st);
          if (walk.steps == 0) continue;
          walk.rejected_before = handed ? 0 : rejected;
          if (!handed) rejected = 0;
          handed = true;
          out.triangles.push_back(std::move(walk));
        }
      }
      if (!handed) ++rejected;
    }
  }
  out.rejected_after = rejected;
  return out;
}

namespace {
// What a log's pixels and statistics are held to, with the differences found.
class WalkCheck {
 public:
  WalkCheck(Workload& w, size_t show) : w_(w), show_(show) {}
  size_t differences = 0;
  std::ostringstream out;

  void differ(const std::string& what) {
    if (differences++ < show_) out << "  walk: " << what << "\n";
  }
  void expect(int64_t logged, int64_t derived, const std::string& what) {
    if (logged != derived)
      differ(what + ": the log " + std::to_string(logged) + ", the scene " + std::to_string(derived));
  }
  // Triangle k's pixels against its walk; the scene's hidden steps, packet starts and
  // trailing steps put in the log's place.
  void triangle(size_t k, const TriangleWalk& walk) {
    Triangle& t = w_.triangles[k];
    const std::string name = "triangle " + std::to_string(k);
    expect(t.id, int64_t(k), name + "'s number");
    t.rejected_before = walk.rejected_before;
    int64_t before = -1;  // the walk index of the pixel before
    int y_before = INT_MIN, in_packet = 0;
    for (size_t n = t.first_pixel; n < t.first_pixel + t.pixels; ++n) {
      Pixel& p = w_.pixels[n];
      const std::string pixel = name + ", pixel (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ")";
      const int64_t index = walk.index_of(p.x, p.y);
      if (index <= before) {
        differ(pixel + (index < 0 ? ": not covered by the triangle" : ": out of the walk's order"));
        continue;
      }
      const bool first = index != before + 1 || p.y != y_before || in_packet == kPacketPixels;
      in_packet = first ? 1 : in_packet + 1;
      expect(p.hidden, index - before - 1, pixel + ", hidden steps before it");
      expect(p.first, first, pixel + ", starts a packet");
      p.hidden = index - before - 1, p.first = first;
      drop_misses_past(p.hidden_lines, p.hidden, pixel);
      before = index, y_before = p.y;
    }
    expect(t.trailing, walk.steps - (before + 1), name + ", hidden steps after its last pixel");
    t.trailing = walk.steps - (before + 1);
    drop_misses_past(t.trailing_lines, t.trailing, name + "'s trailing steps");
  }
  // The render's statistics against the walk and the log's pixels.
  void statistics(const SceneWalk& walk) {
    if (!w_.counts.given) return differ("the log has no walked record (a log of an older build? render again)");
    int64_t walked = 0, seeds = 0;
    for (const TriangleWalk& t : walk.triangles)
      for (const WalkRow& r : t.rows) walked += r.x_end - r.x_begin, seeds += (r.x_end - r.x_begin + kPacketPixels - 1) / kPacketPixels;
    const int64_t visible = int64_t(w_.pixels.size());
    expect(w_.counts.walked, walked, "pixels walked");
    expect(w_.counts.hidden, walked - visible, "pixels hidden");
    // The raster's cost model (modules/raster/raster_kernel.hpp): an add a step; a plane
    // evaluated (2 add, 2 mul) at each seed, every kPacketPixels of a row; a reciprocal a
    // visible pixel.
    expect(w_.counts.add, walked + 2 * seeds, "the raster's additions");
    expect(w_.counts.mul, 2 * seeds, "the raster's multiplications");
    expect(w_.counts.div, visible, "the raster's divisions");
    for (const auto& [name, pixels] : w_.counts.shaded) {
      size_t j = 2;
      while (j < w_.blocks.size() && w_.blocks[j].name != name) ++j;
      if (j == w_.blocks.size()) return differ("statistics of " + name + ", which the log has no block of");
      const int64_t worked = std::count_if(w_.pixels.begin(), w_.pixels.end(), [&](const Pixel& p) { return p.work[j - 2] > 0; });
      expect(pixels, worked, name + "'s pixels worked");
    }
  }

 private:
  // A run's misses must lie in it (the scene's run): those past it are dropped.
  void drop_misses_past(std::vector<std::pair<int64_t, uint32_t>>& misses, int64_t steps, const std::string& where) {
    const auto past = std::find_if(misses.begin(), misses.end(), [&](const auto& m) { return m.first >= steps; });
    if (past == misses.end()) return;
    differ(where + ": a depth miss at a step past the scene's run of " + std::to_string(steps));
    misses.erase(past, misses.end());
  }
  Workload& w_;
  size_t show_;
};
}  // namespace

size_t apply_walk(const SceneWalk& walk, Workload& w, std::string& report, size_t show) {
  WalkCheck check(w, show);
  check.expect(int64_t(w.triangles.size()), int64_t(walk.triangles.size()), "triangles handed on by setup");
  const size_t both = std::min(w.triangles.size(), walk.triangles.size());
  for (size_t k = 0; k < both; ++k) check.triangle(k, walk.triangles[k]);
  w.rejected_after = walk.rejected_after;
  check.statistics(walk);
  report = check.out.str();
  return check.differences;
}

}  // namespace shadetlm::timing_reference
