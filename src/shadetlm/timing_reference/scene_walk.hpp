#pragma once
// What the clocked timing reference derives from the scene itself rather than from the
// timing log it judges: which of the scene's triangles setup hands on and which it culls
// or clips away (each of those costs setup `reject_cycles`), and each triangle's walk —
// the raster's steps, row by row, over exactly the pixels the coverage convention
// (core/coverage.hpp) gives it. Only what the kernels alone know stays in the log: which
// walked pixels the early depth test hides, each pixel's work at each block, the misses.
#include <cstdint>
#include <string>
#include <vector>

#include "shadetlm/core/scene.hpp"
#include "shadetlm/timing_reference/workload.hpp"

namespace shadetlm::timing_reference {

// A row of a triangle's walk: its covered pixels [x_begin, x_end) of row y, and the walk's
// steps before it.
struct WalkRow {
  int y = 0, x_begin = 0, x_end = 0;
  int64_t steps_before = 0;
};

struct TriangleWalk {
  int64_t rejected_before = 0;  // the scene's triangles setup dropped since the triangle before
  std::vector<WalkRow> rows;    // its covered rows, top to bottom
  int64_t steps = 0;            // pixels walked (its covered pixels)
  // The walk's index of pixel (x, y), or −1 if the triangle does not cover it.
  int64_t index_of(int x, int y) const;
};

struct SceneWalk {
  std::vector<TriangleWalk> triangles;  // in the order setup hands them on
  int64_t rejected_after = 0;           // dropped after the last one handed on
};

// Every triangle of every object, in the scene's order: with no area in space, clipped
// away, snapped to no area or no pixel, or culled as back-facing, it is rejected; each
// piece of its clipped polygon (a fan) that covers pixels is a triangle handed on. A
// scene triangle none of whose pieces is handed on counts one rejection.
SceneWalk derive_walks(const core::Scene& scene);

// Holds the log `w` to the scene's walk `walk`: the triangles handed on, and for each
// pixel the hidden steps before it and whether it starts a packet, each triangle's
// trailing steps; the raster's statistics (pixels walked and hidden, its operations)
// and the pixels each span block worked. Puts the scene's figures (and setup's dropped
// triangles) in the log's place, so that the clocked model runs on them. Returns the
// differences, the first `show` described in `report`.
size_t apply_walk(const SceneWalk& walk, Workload& w, std::string& report, size_t show);

// Pixels a span packet holds at most (docs/pipeline.md): a run of visible pixels of a row
// is cut into packets of this many from its first pixel.
constexpr int kPacketPixels = 64;

}  // namespace shadetlm::timing_reference
