#pragma once
// The transaction timeline (docs/inspecting.md): one slice per packet per block (per
// triangle for setup), named by what it carries, with the cycles its pixels stalled;
// flow arrows linking one packet's slices across the blocks; counter tracks of each
// block's FIFO occupancy, each block's utilization and the DRAM's bandwidth. Written as
// Chrome trace-event JSON with integer time stamps in cycles (so that slices never
// overlap), or as a self-contained HTML page that views it offline (a .html path).
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "shadetlm/core/output.hpp"

namespace shadetlm::modules {

class Timeline {
 public:
  struct Slice {
    uint32_t block;        // index into the names given to write()
    uint64_t start, busy;  // cycles
    uint32_t pixels, triangle;
    int32_t y, x;          // the packet's row and first pixel (setup: -1, -1)
    uint64_t stalled;         // cycles its last pixel waited, done, for room downstream (the slice's end)
    uint64_t stalled_pixels;  // the cycles all its pixels waited so, summed
  };
  // A counter sampled over bins of `bin` cycles up to cycle `end` (the last bin partial).
  struct Series {
    std::string name, unit;
    uint64_t bin = 0, end = 0;
    std::vector<double> per_bin;  // the counter's value over each bin
    double full = 0;              // the value that fills its track (a FIFO's depth; 0: its peak)
  };

  void add_triangle(uint32_t block, uint64_t start, uint64_t busy, uint32_t triangle) {
    slices_.push_back({block, start, busy, 0, triangle, -1, -1, 0, 0});
  }
  void add_packet(uint32_t block, uint64_t start, uint64_t busy, uint32_t pixels, uint32_t triangle, int y, int x,
                  uint64_t stalled, uint64_t stalled_pixels) {
    slices_.push_back({block, start, busy, pixels, triangle, y, x, stalled, stalled_pixels});
  }
  // Before the run: the bins of the FIFO counters, for blocks 0 … blocks − 1.
  void keep_fifos(uint32_t blocks, uint64_t bin) { fifo_bin_ = bin, waited_.assign(blocks, {}); }
  // A pixel in a block's input FIFO from cycle `arrived` to `left` (when the block
  // started it): every pixel, traced or not, so that the occupancy is the whole FIFO's.
  void count(uint32_t block, uint64_t arrived, uint64_t left) {
    std::vector<uint64_t>& bins = waited_[block];
    if (bins.empty()) bins.push_back(0);  // (a FIFO that never held a pixel is drawn too)
    for (uint64_t t = arrived; t < left;) {
      const uint64_t k = t / fifo_bin_, until = std::min((k + 1) * fifo_bin_, left);
      if (bins.size() <= k) bins.resize(k + 1, 0);
      bins[k] += until - t;
      t = until;
    }
  }
  // Per-bin totals (busy cycles, DRAM bytes) as a counter of their share of each bin's
  // cycles, times `scale` (100: a percentage).
  void add_series(const std::string& name, const std::string& unit, uint64_t bin, const std::vector<uint64_t>& totals,
                  uint64_t end, double scale);
  // After the run: each FIFO's mean occupancy over each bin, up to cycle `end` (the
  // frame's last), each track full at its FIFO's depth.
  void add_fifo_series(const std::vector<std::string>& block_names, const std::vector<uint64_t>& depths, uint64_t end);
  // A traced region: the counters' bins are written only where they overlap the slices.
  void limit_to_region() { region_ = true; }
  const std::vector<Slice>& slices() const { return slices_; }
  // Writes the JSON, or the viewer page with the JSON inside when `path` ends in
  // .html, to its temporary in `outputs` (core/output.hpp). The scene's file and the
  // clock go into its otherData.
  void write(core::OutputSet& outputs, const std::string& path, const std::vector<std::string>& block_names, double clock_mhz,
             const std::string& scene) const;
  std::string json(const std::vector<std::string>& block_names, double clock_mhz, const std::string& scene) const;

 private:
  std::vector<uint64_t> shown_cycles() const;
  std::vector<std::vector<uint32_t>> packets() const;
  void write_flows(std::string& out, const std::vector<std::vector<uint32_t>>& packets) const;

  std::vector<Slice> slices_;
  uint64_t fifo_bin_ = 1;
  std::vector<std::vector<uint64_t>> waited_;  // per block and bin: the cycles its pixels waited
  std::vector<Series> series_;
  bool region_ = false;
  uint64_t frame_cycles_ = 0;  // the frame's (add_fifo_series)
};

// The viewer's page (trace/timeline_viewer.html, built in) with `json` in place.
std::string timeline_page(const std::string& json);

}  // namespace shadetlm::modules
