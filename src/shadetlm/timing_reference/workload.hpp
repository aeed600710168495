#pragma once
// What the clocked timing reference runs: the main pass's blocks (latency, II, FIFO
// depth), each triangle's walk and each pixel's work at each block, read from a timing
// log (`shadetlm render --timing-log`, format in timing/main_pass.hpp) — with the
// times the fast model gave, which the reference checks and never reads while it runs.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace shadetlm::timing_reference {

struct BlockSpec {
  std::string name;
  int64_t latency = 1, ii = 1, depth = 1;
  int64_t line_bytes = 0, miss_queue = 0;  // a memory client's (line_bytes 0: none)
};

struct Pixel {
  int x = 0, y = 0;
  int64_t hidden = 0;                // the raster's hidden steps just before it
  bool first = false;                // the first of its span packet (a `k` record before it)
  std::vector<uint32_t> work;        // per span block (units of its II; 0: bypassed)
  std::vector<uint32_t> lines;       // per span block: DRAM lines moved (a memory record only)
  uint32_t depth_lines = 0;          // the raster's depth read and write
  std::vector<std::pair<int64_t, uint32_t>> hidden_lines;  // hidden steps before it that missed: (step, lines)
  std::vector<int64_t> start, valid, handed;  // the fast model's, per line block (raster first)
};

struct Triangle {
  uint32_t id = 0;
  int64_t rejected_before = 0;  // triangles setup dropped just before it (from the scene: SceneWalk)
  int64_t start = 0, handed = 0, taken = 0;  // the fast model's: at setup, by the raster
  size_t first_pixel = 0, pixels = 0;
  int64_t trailing = 0;  // hidden steps after its last pixel
  std::vector<std::pair<int64_t, uint32_t>> trailing_lines;  // of which missed: (step, lines)
};

struct BlockStatsLine {
  std::string name;
  int64_t busy = 0, starved = 0, blocked = 0, fifo_cycles = 0, fifo_peak = 0;
  int64_t memory_stall = 0;  // Σ cycles its pixels' data came after their work
};

// The shared DRAM (memory/dram.hpp says what it does; this is its own model).
struct MemorySpec {
  int64_t latency = 0, bytes_per_cycle = 0;
};

// A frame pass's block (the splat pass): it begins when the main pass ends and is busy
// II·work cycles; the fast model's figures.
struct PassLine {
  std::string name;
  int64_t latency = 1, ii = 1, arrival = -1, work = -1, busy = 0, last = -1;  // work −1: not run
};

// The statistics the log's pixels must agree with (the render's, not its timing's).
struct LoggedCounts {
  bool given = false;
  int64_t walked = 0, hidden = 0;     // the raster's pixels walked and hidden
  int64_t add = 0, mul = 0, div = 0;  // the raster's operations
  std::vector<std::pair<std::string, int64_t>> shaded;  // per span block: pixels worked
};

struct Workload {
  std::string scene;              // what the render drew (`scene` record; "": the demo)
  bool scene_given = false;
  std::vector<std::string> sets;  // its --set overrides
  std::vector<BlockSpec> blocks;  // setup, the raster, the span blocks
  int64_t reject_cycles = 0;      // setup's cycles for a triangle it drops (from the scene)
  int64_t rejected_after = 0;     // triangles dropped after the last one handed on
  std::optional<MemorySpec> memory;  // none: ideal memory
  std::vector<Triangle> triangles;
  std::vector<Pixel> pixels;
  int64_t end = -1;                     // the fast model's (−1: no end record)
  std::vector<BlockStatsLine> stats;    // the fast model's
  LoggedCounts counts;                  // the render's statistics
  std::vector<PassLine> passes;         // the fast model's
  int64_t frame_end = -1;               // the fast model's frame cycles (−1: not given)
};

// Reads a timing log; throws core::InputError naming the file and line (a record out of
// place, a number missing or out of range: latencies, IIs and depths in 1 … 1000000),
// or the file, if the clocked model would step more than 10¹¹ cycles.
Workload read_workload(const std::string& path);

// A bound on the cycles of any run of `w`: every triangle and pixel through every block,
// one after another (in double: a hand-made log may overflow 64 bits).
double serial_cycles(const Workload& w);

}  // namespace shadetlm::timing_reference
