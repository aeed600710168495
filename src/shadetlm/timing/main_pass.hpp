#pragma once
// The fast timing model (docs/pipeline.md, "Timing"): every pixel's start and hand-over
// cycle at every block of the main pass, with bounded FIFOs and back-pressure, computed
// per packet in one pixel-major sweep once every block has seen the packet and said how
// much work each of its pixels is. timing_reference/ checks it cycle for cycle against a
// clocked model.
//
// A block j has a latency L, an initiation interval II, an input FIFO of depth b and
// room for C = ⌈(L + 1) / II⌉ pixels started and not yet handed on (its pipeline
// registers and its output register). Every signal is registered: what a block decides
// in cycle t it decides from the state at the start of cycle t. With w the pixel's work
// at the block (0: the block bypasses it), pixel n
//
//   starts      s_j(n) = max(d_{j−1}(n) + 1,            in the FIFO since the cycle before
//                            s_j(n−1) + o_j(n−1),       the unit has issued the pixel before
//                            d_j(n−C_j) + 1)            a register is free
//   occupies    o_j(n) = II·w, or 1 if w = 0
//   is done     f_j(n) = s_j(n) + II·(w − 1) + L, or s_j(n) + 1 if w = 0
//   is handed on d_j(n) = max(f_j(n),
//                            d_j(n−1) + 1,              one pixel a cycle, in order
//                            s_{j+1}(n − b_{j+1}) + 1)  the next FIFO had room at the start of the cycle
//
// Every term refers to an earlier pixel or to the block before, so the sweep is exact in
// pixel-major order (for each pixel, for each block). The raster (block 0) walks: its
// pixel n starts when the walk reaches it and a register is free; hidden pixels cost a
// step each and need no register (start_triangle, walk_hidden, sweep).
//
// Order of the sweep: a term of pixel n at block j reads block j + 1 only at pixel
// n − b_{j+1}. So in chunks of K ≤ every b_j pixels (K: the shallowest FIFO after the
// raster), every block can time the whole chunk before the next block does — block-major
// within the chunk, each block's state in registers — reading only chunks already done
// (sweep_chunk). Under the memory model the sweep stays pixel-major: the DRAM serves
// requests oldest pixel first, in the order they are made.
//
// Blocks that only delay (delay_packet; ideal memory only: under the DRAM model the sweep
// is pixel-major and no block is a delay). A block with II = 1 and L ≥ 1 whose every
// pixel so far had the same work w ∈ {0, 1}, followed only by such blocks, each with a
// FIFO of at least 2: then every term of its recurrence but the first is slack, for
// every pixel (D: its delay, L, or 1 when w = 0):
//   the unit:      s(n−1) + o = s(n−1) + 1 ≤ d_{j−1}(n) + 1       (hand-overs one a cycle)
//   a register:    d(n−C) + 1 = s(n−C) + D + 1 ≤ s(n−1) + 1       (C = L + 1 ≥ D + 1)
//   in order:      d(n−1) + 1 = s(n−1) + D + 1 ≤ s(n) + D         (the same delay for all)
//   the next FIFO: s_{j+1}(n−b) + 1 = d(n−b) + 2 ≤ d(n)           (b ≥ 2, it delays too)
// so s(n) = d_{j−1}(n) + 1 and d(n) = s(n) + D, and the block before them is never held
// up by the first of them. Such a suffix of the pass is timed by that formula, a packet
// at a time, and the block before it looks at no FIFO after it. A packet with other work
// at one of them ends that, from its first pixel and for the rest of the frame, for that
// block and every one before it in the suffix (keep_delaying): the recurrence times them
// from there, their state the recurrence's all along. Their windows are not written (a
// packet costs them no work a pixel): a term that looks back at a pixel they delayed —
// after their work changed, or in an inspected packet — is slack by the bounds above,
// which need only the pixels before n to be delays (C ≥ D + 1 and d(n) ≥ d(n−b) + b), and a
// window holds an older pixel's time or −1 in its place: smaller, so slack too.
//
// A packet in steady state (steady, extrapolate; ideal memory, not inspected). The sweep
// is max-plus: adding a constant P to every time it reads adds P to every time it
// computes and leaves every statistic's increment (a difference of two times) as it was.
// So if the state the sweep reads for pixel n + 1 — per timed block j its starts back to
// n + 1 − b_j (the block before reads s_j(n − b_j), the FIFO's oldest pixel is among
// them), its hand-overs back to n + 1 − C_j, its unit's free cycle — is the state it
// read for pixel n plus P, and every timed block's work stays what it was at n, then
// pixel n + 1 is pixel n plus P at every block, and so is every pixel after it in the
// packet: their times an arithmetic series, their statistics pixel n's. The state is
// checked a few pixels into a packet (once past a lead) and after each chunk, where the
// work stays the same to the packet's end; in steady state, a bottleneck's period P
// reaches every block before it through back-pressure and stays across packets.
// A packet after one that ended in a series is the same series from its first pixel
// (continue_packet) when what differs there cannot change a time: the walk reaches the
// pixel no later than the series starts it (the raster's term s(n−1) + II was slack, and
// a later walk stays so), and a lead makes pixel 0 done no later than its series
// hand-over and keeps the unit no longer than the period (so s(1) = max(…, s(0) + II·w,
// …) keeps its series value). Their statistics are the series', pixel 0's walk and lead
// and pixel 1's wait for a register counted apart.
//
// Memory (docs/memory.md): a memory client whose pixel moved m > 0 cache lines asks the
// shared DRAM for them as it starts the pixel; the data is back at r (memory/
// dram.hpp), and the pixel is done at f_j(n) = max(s_j(n) + II·(w − 1), r) + L. Its
// miss queue of Q pixels adds Q to C: the pixels a block can hold while they wait.
// The raster's depth reads (hidden pixels' too) are misses of its own: one may start
// when fewer than Q are in flight (its data back at r, the entry free at r + 1), a
// visible pixel is done at max(s, r) + L, and with Q = 0 the walk waits for each
// miss's data (its next step at r + 1 at the earliest).
#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "shadetlm/tlm/packet.hpp"
#include "shadetlm/stats/report.hpp"
#include "shadetlm/memory/dram.hpp"
#include "shadetlm/timing/timing.hpp"

namespace shadetlm::modules {

// What a block's timing counted (BlockStats holds the same, reported).
struct BlockTimes {
  uint64_t busy = 0;         // cycles its unit issued work
  uint64_t starved = 0;      // free, waiting for input
  uint64_t blocked = 0;      // free, every register full: waiting for room downstream
  uint64_t fifo_cycles = 0;  // Σ over its pixels of the cycles they spent in its input FIFO
  uint64_t fifo_peak = 0;    // the most pixels its input FIFO held at the end of a cycle
  uint64_t memory_stall = 0; // Σ over its pixels of the cycles their data came after their work
  uint64_t dram_lines = 0;   // cache lines its pixels moved to or from the DRAM
  int64_t last = -1;         // the cycle it handed on its last pixel
  uint64_t bin_cycles = 0;   // of busy_per_bin (0: not kept)
  std::vector<uint64_t> busy_per_bin;
  void add_busy(int64_t start, uint64_t cycles) {
    busy += cycles;
    add_to_bins(start, cycles);
  }
  // Busy cycles already counted in `busy`: into busy_per_bin only (when kept).
  void add_to_bins(int64_t start, uint64_t cycles) {
    if (bin_cycles > 0) histogram(uint64_t(start), cycles);
  }

 private:
  void histogram(uint64_t start, uint64_t cycles);
};

// Told of each packet once its pixels are timed (inspection: waveforms, timeline).
class TimedObserver {
 public:
  virtual ~TimedObserver() = default;
  virtual void timed(const SpanPacket&) {}
};

class MainPassTiming;

// Every triangle's and pixel's work and times at every block of the main pass, for the
// timing check against the clocked reference (timing_reference/, docs/pipeline.md): a
// text file, one line a record, kept in memory until written (small frames only).
//
//   block <name> <latency> <ii> <fifo_depth> <line_bytes> <miss_queue>
//                                                 setup, the raster, then each span block
//   memory <latency> <bytes_per_cycle>             the DRAM (none: ideal memory)
//   t <triangle> <start> <handed>                 setup hands a triangle on
//   r <cycle>                                     the raster takes it
//   k                                             a span packet starts: its pixels follow
//   p <x> <y> <hidden> <w_1> … <w_J> [<m_0> … <m_J>] <s_0> <v_0> <d_0> … <s_J> <v_J> <d_J>
//                                                 a pixel: hidden steps walked before it,
//                                                 its work at each span block, the DRAM
//                                                 lines it moved at the raster and each
//                                                 span block (with a memory record), its
//                                                 start, valid (at the output) and hand-over
//   h <step> <lines>                              a hidden pixel's depth read moved DRAM lines: its
//                                                 step in the hidden run before the next p (or e)
//   e <steps>                                     hidden steps after the triangle's last pixel
//   end <cycle>                                   the pass's end
//   stats <name> <busy> <starved> <blocked> <fifo_cycles> <fifo_peak> <memory_stall>
//   walked <pixels> <hidden> <add> <mul> <div>    the raster's statistics: pixels walked and
//                                                 hidden, its operations
//   shaded <name> <pixels>                        a span block's statistics: pixels it worked
//   pass <name> <latency> <ii> <arrival> <work> <busy> <last>
//                                                 a frame pass's block (the splat pass): when
//                                                 it began, its work, busy cycles, last cycle
//   frame_end <cycle>                             the frame's cycles (every pass)
// (The render puts `scene <file>` and `set <key=value>` records in front: what it drew.)
class TimingLog {
 public:
  void block(const std::string& name, const Timing& t);
  void memory(const DramTiming& t);
  void triangle(uint32_t id, int64_t start, int64_t handed);
  void taken(int64_t cycle);
  void pixels(const SpanPacket& p, uint64_t hidden, const MainPassTiming& line);
  void trailing(uint64_t steps);
  void hidden_lines(uint64_t step, uint32_t lines);
  void end(int64_t cycle);
  void stats(const std::string& name, const BlockTimes& t);
  void record(const std::string& line) { text_ += line + "\n"; }  // (the statistics' records)
  const std::string& text() const { return text_; }

 private:
  std::string text_;
};

// The main pass's pixel stream: the raster (slot 0) and the span blocks after it.
// A hidden pixel whose depth read moved `lines` DRAM lines: its step in its hidden run.
struct StepLines {
  uint64_t step;
  uint32_t lines;
};

class MainPassTiming {
 public:
  // `dram`: the shared DRAM's timing, when a block is a memory client (line_bytes > 0).
  explicit MainPassTiming(std::vector<Timing> blocks, DramTiming dram = {});
  MainPassTiming(const MainPassTiming&) = delete;  // its blocks point into its windows
  MainPassTiming& operator=(const MainPassTiming&) = delete;

  // Span blocks: the work of the packet now passing (set by each block as it passes).
  void set_work(int slot, Work w) { blocks_[size_t(slot)].work = w; }

  // The raster: triangle `arrival` was handed on by setup at that cycle; the walk goes
  // on through `steps` hidden pixels, of which `misses` moved DRAM lines (in order).
  int64_t start_triangle(int64_t arrival);
  void walk_hidden(uint64_t steps, const std::vector<StepLines>& misses = kNoMisses);
  // Times the pixels of packet `p` once every block has seen it; `hidden_before`: the
  // steps walked before its first pixel. Then tells the observers and the log.
  void sweep(const SpanPacket& p, uint64_t hidden_before, const std::vector<StepLines>& misses = kNoMisses);
  static inline const std::vector<StepLines> kNoMisses{};
  // At the pass's end: the span blocks' starved cycles (from their busy and blocked ones).
  void settle();
  void watch(TimedObserver* o) { observers_.push_back(o), keep_times = true; }
  // Only the packets `watched` accepts are timed for the observers (waveforms of a
  // region: the rest take the loop without inspection).
  void watch_only(std::function<bool(const SpanPacket&)> watched) { watched_ = std::move(watched); }
  void set_log(TimingLog* log) { log_ = log, keep_times = keep_times || log; }
  TimingLog* log() const { return log_; }
  Work work(int slot) const { return blocks_[size_t(slot)].work; }
  const Dram* dram() const { return dram_.get(); }
  Dram* dram() { return dram_.get(); }

  // The times of the packet swept last, pixel i at block j: its start, the cycle it was
  // at the block's output (valid: done, the pixel before it gone), its hand-over (a
  // stall between the two), and its FIFO's pixels once it came in (j > 0).
  int64_t start(int j, int i) const { return times_[size_t(j)][size_t(i)].s; }
  int64_t valid_from(int j, int i) const { return times_[size_t(j)][size_t(i)].v; }
  int64_t handed(int j, int i) const { return times_[size_t(j)][size_t(i)].d; }
  uint64_t fifo_after(int j, int i) const { return times_[size_t(j)][size_t(i)].q; }
  bool keep_times = false;  // set to fill them (inspection, the timing log)

  // The first cycle at which every block of the pass is done.
  int64_t end() const;
  const BlockTimes& times(int slot) const { return blocks_[size_t(slot)].t; }
  BlockTimes& times(int slot) { return blocks_[size_t(slot)].t; }
  const Timing& timing(int slot) const { return blocks_[size_t(slot)].timing; }
  size_t size() const { return blocks_.size(); }
  // The first block of those the plain sweep times as fixed delays (size(): none).
  size_t delaying_from() const { return delay_from_; }
  // The pixels timed as a steady state's series so far ("A packet in steady state").
  uint64_t extrapolated() const { return extrapolated_; }
  // Of their packets, those continued whole from the series the one before ended in.
  uint64_t continued() const { return continued_; }
  // Times every block by the recurrence, delays or not (before the first sweep: the
  // tests' reference for the delays).
  void time_every_block();

 private:
  struct Slot {
    Timing timing;
    int64_t capacity = 1;
    int64_t next_depth = 0;  // the next block's FIFO depth
    int64_t free = 0;        // the cycle its unit can issue again
    int64_t head = 0;        // the oldest pixel still in its FIFO (for the peak)
    int64_t ii = 1, latency = 1;
    uint64_t line_bytes = 0;
    int64_t *s = nullptr, *d = nullptr;  // the starts and hand-overs of its last pixels (windows)
    int64_t* next_s = nullptr;           // the next block's starts (after the last: always room)
    Work work;
    const uint16_t* w = nullptr;         // the packet's work, per pixel
    uint16_t uniform[kSpanMax] = {};     // the same work for every pixel, as an array
    BlockTimes t;
  };
  struct Times {
    int64_t s, d, v;
    uint64_t q;
  };
  template <bool kInspect> void sweep_pixels(int count);  // (under the memory model)
  // Ideal memory: pixels [first, last) of the packet at the raster, then at span block j.
  template <bool kInspect> void raster_chunk(int first, int last);
  template <bool kInspect, bool kUniform> void span_chunk(size_t j, int first, int last);
  // Whether the state the sweep reads for pixel n + 1 (of the packet) is the one it read
  // for pixel n plus a constant ("A packet in steady state"), for blocks [0, timed), whose
  // work is the same from pixel n − 1 to the packet's end.
  bool steady(size_t timed, int n) const;
  // Pixels (n, count) of the packet at blocks [0, timed): pixel n's times plus a multiple
  // of the period, pixel n's statistics each (n = −1: the packet before's last pixel).
  void extrapolate(size_t timed, int n, int count);
  // The whole packet as the series the packet before ended in, when what differs at its
  // first pixel (the walk to it, a lead) is shown not to change a time; false: not so.
  // Every block's work is the same from pixel 1 on.
  bool continue_packet(size_t timed, int count);
  // How far back the sweep reads block j's starts and hand-overs from a pixel it times
  // (steady's state): the block before reads s_j(n − b_j), and the FIFO's oldest pixel is
  // among those; its register term reads d_j(n − C_j). (The raster's starts are read one
  // pixel back, for its walk: its FIFO holds triangles.)
  int64_t starts_back(size_t j) const { return j == 0 ? 1 : int64_t(blocks_[j].timing.fifo_depth); }
  // `count` pixels busy `busy` cycles each from `first`, one every `period`: into t's bins.
  static void series_bins(BlockTimes& t, int64_t first, int64_t period, int64_t count, int64_t busy);
  // The packet's pixels at the blocks that only delay ("Blocks that only delay"), timed
  // as delays: their figures only, not their windows.
  void delay_packet(int count);
  // Block j's delay, one that only delays: done L after its start, or 1 when bypassed.
  int64_t delay(size_t j) const { return delay_work_[j] > 0 ? blocks_[j].latency : 1; }
  // Pixels [first, last) of the packet at block j, timed: their `busy` cycles into its
  // histogram, at once where the bin of the first's start holds the last's end.
  void bin_busy(size_t j, int first, int last, uint64_t busy);
  // Before a packet is timed: ends the delays of the blocks whose work in it differs from
  // what every pixel before had there (or, first seen, is above 1 or has a lead), and of
  // those before them in the suffix.
  void keep_delaying(int count);
  // The delays from block `from` on (size(): none), the block before them looking at no
  // FIFO of theirs.
  void delay_from(size_t from);
  // The raster's depth read at cycle t moves `lines`: t waits for a miss entry; returns
  // the cycle its data is back.
  int64_t depth_read(int64_t& t, uint32_t lines);

  // Per block, the starts and then the hand-overs of its last pixels, in windows: pixel n
  // at index n − base_, so that a term's look back (n − C, n − b) is a plain index. When
  // a packet would run past a window's end, the last `reach_` pixels move to its front.
  void slide_windows(int count);
  int64_t at(uint64_t n) const { return int64_t(n) - base_; }
  std::vector<Slot> blocks_;
  std::vector<int64_t> windows_;
  int64_t window_ = 0, reach_ = 0, base_ = 0;
  int chunk_ = 1;              // pixels timed block-major at a time (K)
  size_t delay_from_ = 0;      // the first block of the suffix that only delays (size(): none)
  std::vector<int> delay_work_;  // the work every pixel had at such a block (-1: none yet)
  int64_t* room_ = nullptr;    // a window of starts "before cycle 0": a FIFO always with room
  uint64_t n_ = 0;             // pixels swept so far
  uint64_t extrapolated_ = 0;  // of them, the pixels timed by extrapolate
  // The last packet extrapolated ended at pixel series_end_ in a series of that period,
  // at blocks [0, series_timed_): their windows' last pixels need no check (steady).
  uint64_t series_end_ = 0;
  int64_t series_period_ = 0;
  size_t series_timed_ = 0;
  struct Increments {  // a pixel's, at a block, in that series
    uint32_t w = 0;       // its work
    int64_t o = 1;        // its unit's cycles (II · w, or 1)
    int64_t blocked = 0;  // cycles its unit waited for a register
    int64_t fifo = 0;     // cycles it spent in the block's FIFO
  };
  std::vector<Increments> series_;
  uint64_t continued_ = 0;         // packets continue_packet timed
  int64_t triangle_start_ = -1;  // when the raster took its last triangle
  std::vector<std::vector<Times>> times_;
  std::vector<TimedObserver*> observers_;
  std::function<bool(const SpanPacket&)> watched_;  // (empty: every packet)
  TimingLog* log_ = nullptr;
  std::unique_ptr<Dram> dram_;  // none: ideal memory
  std::vector<int64_t> depth_back_;  // the raster's last misses: when their data came back (a ring)
  uint64_t depth_misses_ = 0;
};

// Setup's triangles into the raster's triangle FIFO: triangle k starts when setup's unit
// is free and a register is, and is handed on when done and the FIFO had room — it had
// when the raster took triangle k − b at least a cycle before. A triangle setup drops
// (culled, clipped away) starts when the unit is free, needs no register (it leaves in
// the unit's first stage) and keeps the unit `cycles` cycles; setup's `last` is then the
// later of its last hand-over and the last such cycle.
class TriangleLine {
 public:
  TriangleLine(Timing setup, uint64_t raster_depth);
  // The cycle triangle k (the next) is handed on to the raster.
  int64_t next();
  // The raster took triangle k at `cycle`.
  void taken(int64_t cycle);
  // `count` triangles dropped, each `cycles` cycles of the unit, before the next.
  void reject(uint64_t count, uint64_t cycles);
  int64_t last_start() const { return last_start_; }
  const BlockTimes& times() const { return t_; }
  BlockTimes& times() { return t_; }
  const Timing& timing() const { return timing_; }

 private:
  Timing timing_;
  int64_t capacity_;
  int64_t depth_;
  int64_t free_ = 0, last_start_ = -1, last_d_ = -1;
  uint64_t k_ = 0;                        // triangles handed on so far
  std::vector<int64_t> handed_, taken_;  // of the last triangles (a ring)
  uint64_t mask_ = 0;
  BlockTimes t_;
};

}  // namespace shadetlm::modules
