#include "shadetlm/timing_reference/workload.hpp"

#include "shadetlm/core/input_file.hpp"

#include <fstream>
#include <sstream>

#include "shadetlm/core/input_error.hpp"

namespace shadetlm::timing_reference {

Workload read_workload(const std::string& path) {
  core::check_input_file(path, "", core::kMaxSceneBytes * 4);  // (a 1 MP frame's log is about 100 MB)
  std::ifstream in(path);
  if (!in) throw core::InputError(path, "", "cannot open the timing log");
  Workload w;
  std::string line;
  size_t number = 0;
  auto fail = [&](const std::string& why) {
    throw core::InputError(path, "line " + std::to_string(number), why);
  };
  std::vector<std::pair<int64_t, uint32_t>> misses;  // h records, for the next p or e
  bool packet_start = false;  // a k record: the next pixel starts a span packet
  // The h records before a run of `steps` hidden steps: in order, within it.
  auto take_misses = [&](int64_t steps, std::vector<std::pair<int64_t, uint32_t>>& into) {
    for (size_t k = 0; k < misses.size(); ++k)
      if (misses[k].first >= steps || (k > 0 && misses[k].first <= misses[k - 1].first))
        fail("h records must name hidden steps of the run, in order");
    into = std::move(misses);
    misses.clear();
  };
  while (std::getline(in, line)) {
    ++number;
    std::istringstream s(line);
    std::string kind;
    s >> kind;
    if (kind == "scene" || kind == "set") {  // the rest of the line, as written
      if (!w.blocks.empty()) fail("a " + kind + " record after the first block");
      const std::string value = line.size() > kind.size() + 1 ? line.substr(kind.size() + 1) : "";
      if (kind == "scene") w.scene = value, w.scene_given = true;
      else w.sets.push_back(value);
    } else if (kind == "block") {
      BlockSpec b;
      s >> b.name >> b.latency >> b.ii >> b.depth;
      constexpr int64_t kMost = 1000000;
      if (!s || b.latency < 1 || b.ii < 1 || b.depth < 0 || b.latency > kMost || b.ii > kMost || b.depth > kMost)
        fail("expected: block <name> <latency> <ii> <depth>, latency and ii in 1 … 1000000, depth in 0 … 1000000");
      if (s >> b.line_bytes) {  // a memory client's line and miss queue
        if (!(s >> b.miss_queue) || b.line_bytes < 0 || b.line_bytes > 65536 || b.miss_queue < 0 ||
            b.miss_queue > 65536)
          fail("expected: block … <line_bytes> <miss_queue>, each in 0 … 65536");
      }
      if (!w.triangles.empty()) fail("a block after the first triangle");
      if (w.blocks.size() >= 2 && b.depth < 1) fail("a span block's FIFO depth must be at least 1");
      w.blocks.push_back(b);
    } else if (kind == "memory") {
      MemorySpec m;
      s >> m.latency >> m.bytes_per_cycle;
      if (!s || m.latency < 1 || m.latency > 100000 || m.bytes_per_cycle < 1 || m.bytes_per_cycle > 4096)
        fail("expected: memory <latency in 1 … 100000> <bytes_per_cycle in 1 … 4096>");
      if (!w.triangles.empty()) fail("a memory record after the first triangle");
      w.memory = m;
    } else if (kind == "t") {
      Triangle t;
      s >> t.id >> t.start >> t.handed;
      if (!s) fail("expected: t <triangle> <start> <handed>");
      t.first_pixel = w.pixels.size();
      w.triangles.push_back(t);
    } else if (kind == "r") {
      if (w.triangles.empty() || !(s >> w.triangles.back().taken)) fail("expected: r <cycle>, after a triangle");
    } else if (kind == "h") {
      int64_t step = -1;
      uint32_t lines = 0;
      s >> step >> lines;
      if (!s || step < 0 || lines < 1 || lines > 65535 || !w.memory || w.blocks.size() < 2 ||
          w.blocks[1].line_bytes == 0)
        fail("expected: h <step> <lines in 1 … 65535>, after a memory record, the raster a memory client");
      misses.push_back({step, lines});
    } else if (kind == "k") {
      std::string extra;
      if (s >> extra) fail("expected: k (alone: a span packet starts)");
      packet_start = true;
    } else if (kind == "p") {
      if (w.triangles.empty() || w.blocks.size() < 2) fail("a pixel before its blocks and triangle");
      Pixel p;
      p.first = packet_start;
      packet_start = false;
      s >> p.x >> p.y >> p.hidden;
      const size_t line_blocks = w.blocks.size() - 1;
      p.work.resize(line_blocks - 1);
      p.start.resize(line_blocks), p.valid.resize(line_blocks), p.handed.resize(line_blocks);
      for (auto& x : p.work) s >> x;
      if (w.memory) {
        s >> p.depth_lines;
        p.lines.resize(line_blocks - 1);
        for (auto& x : p.lines) s >> x;
      }
      for (size_t j = 0; j < line_blocks; ++j) s >> p.start[j] >> p.valid[j] >> p.handed[j];
      std::string extra;
      if (!s || p.hidden < 0 || p.hidden > 100000000 || (s >> extra))
        fail("expected: p <x> <y> <hidden> <a work per span block> <start valid handed per line block>");
      for (uint32_t x : p.work)
        if (x > 65535) fail("a pixel's work is at most 65535 units");
      if (p.depth_lines > 65535 || (p.depth_lines > 0 && w.blocks[1].line_bytes == 0))
        fail("the raster's depth lines: at most 65535, and the raster a memory client");
      take_misses(p.hidden, p.hidden_lines);
      for (size_t j = 0; j < p.lines.size(); ++j) {
        if (p.lines[j] > 65535) fail("a pixel moves at most 65535 lines at a block");
        if (p.lines[j] > 0 && (w.blocks[j + 2].line_bytes == 0 || p.work[j] == 0))
          fail("DRAM lines at a block that is no memory client, or that bypassed the pixel");
      }
      w.pixels.push_back(std::move(p));
      ++w.triangles.back().pixels;
    } else if (kind == "e") {
      if (w.triangles.empty() || !(s >> w.triangles.back().trailing) || w.triangles.back().trailing < 0 ||
          w.triangles.back().trailing > 100000000)
        fail("expected: e <steps>, after a triangle");
      take_misses(w.triangles.back().trailing, w.triangles.back().trailing_lines);
    } else if (kind == "end") {
      if (!(s >> w.end) || w.end < 0) fail("expected: end <cycle ≥ 0>");
    } else if (kind == "stats") {
      BlockStatsLine b;
      s >> b.name >> b.busy >> b.starved >> b.blocked >> b.fifo_cycles >> b.fifo_peak;
      if (!s) fail("expected: stats <name> <busy> <starved> <blocked> <fifo_cycles> <fifo_peak> [<memory_stall>]");
      s >> b.memory_stall;
      w.stats.push_back(b);
    } else if (kind == "walked") {
      LoggedCounts& c = w.counts;
      s >> c.walked >> c.hidden >> c.add >> c.mul >> c.div;
      if (!s || c.walked < 0 || c.hidden < 0) fail("expected: walked <pixels> <hidden> <add> <mul> <div>");
      c.given = true;
    } else if (kind == "shaded") {
      std::pair<std::string, int64_t> b;
      if (!(s >> b.first >> b.second) || b.second < 0) fail("expected: shaded <block> <pixels>");
      w.counts.shaded.push_back(b);
    } else if (kind == "pass") {
      PassLine p;
      s >> p.name >> p.latency >> p.ii >> p.arrival >> p.work >> p.busy >> p.last;
      if (!s || p.latency < 1 || p.ii < 1 || p.latency > 1000000 || p.ii > 1000000 || p.work < -1 ||
          p.work > (int64_t(1) << 40))
        fail("expected: pass <name> <latency> <ii> <arrival> <work> <busy> <last>, latency and ii in 1 … 1000000");
      w.passes.push_back(p);
    } else if (kind == "frame_end") {
      if (!(s >> w.frame_end) || w.frame_end < 0) fail("expected: frame_end <cycle ≥ 0>");
    } else if (!kind.empty()) {
      fail("unknown record '" + kind + "'");
    }
  }
  if (w.blocks.size() < 2) throw core::InputError(path, "block", "needs setup and the raster at least");
  if (!misses.empty()) throw core::InputError(path, "h", "h records after the last pixel or e record");
  if (w.end < 0) throw core::InputError(path, "end", "no end record: a log cut short?");
  if (serial_cycles(w) > 1e11) throw core::InputError(path, "", "more than 10^11 cycles to step: too long to check");
  return w;
}

double serial_cycles(const Workload& w) {
  double bound = 1000;
  for (const BlockSpec& b : w.blocks) bound += double(w.triangles.size() + w.pixels.size()) * double(b.latency + b.ii + 2);
  for (const Pixel& p : w.pixels) {
    bound += double(p.hidden) * double(w.blocks[1].ii);
    for (size_t j = 0; j < p.work.size(); ++j) bound += double(p.work[j]) * double(w.blocks[j + 2].ii);
  }
  for (const Triangle& t : w.triangles) bound += double(t.trailing) * double(w.blocks[1].ii);
  double rejected = double(w.rejected_after);
  for (const Triangle& t : w.triangles) rejected += double(t.rejected_before);
  bound += rejected * double(w.reject_cycles);
  if (!w.memory) return bound;
  // Every request alone: its bytes at the DRAM's rate, then its latency.
  auto request = [&](double lines, int64_t line_bytes) {
    return lines * double(line_bytes) / double(w.memory->bytes_per_cycle) + double(w.memory->latency) + 2;
  };
  for (const Pixel& p : w.pixels) {
    for (size_t j = 0; j < p.lines.size(); ++j)
      if (p.lines[j] > 0) bound += request(p.lines[j], w.blocks[j + 2].line_bytes);
    if (p.depth_lines > 0) bound += request(p.depth_lines, w.blocks[1].line_bytes);
    for (const auto& m : p.hidden_lines) bound += request(m.second, w.blocks[1].line_bytes);
  }
  for (const Triangle& t : w.triangles)
    for (const auto& m : t.trailing_lines) bound += request(m.second, w.blocks[1].line_bytes);
  return bound;
}

}  // namespace shadetlm::timing_reference
