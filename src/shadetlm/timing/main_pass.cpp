#include "shadetlm/timing/main_pass.hpp"


namespace shadetlm::modules {

void BlockTimes::histogram(uint64_t start, uint64_t cycles) {
  for (uint64_t t = start, end = start + cycles; t < end;) {
    const uint64_t bin = t / bin_cycles, bin_end = (bin + 1) * bin_cycles;
    if (busy_per_bin.size() <= bin) busy_per_bin.resize(bin + 1, 0);
    const uint64_t until = std::min(end, bin_end);
    busy_per_bin[bin] += until - t;
    t = until;
  }
}

namespace {
// The smallest power of two above n.
uint64_t ring_above(uint64_t n) {
  uint64_t r = 1;
  while (r <= n) r *= 2;
  return r;
}
}  // namespace

MainPassTiming::MainPassTiming(std::vector<Timing> blocks, DramTiming dram) {
  uint64_t reach = 1;  // the furthest back a term looks, in pixels
  for (size_t j = 0; j < blocks.size(); ++j) {
    Slot s;
    s.timing = blocks[j];
    s.capacity = int64_t(capacity(blocks[j]));
    s.next_depth = j + 1 < blocks.size() ? int64_t(blocks[j + 1].fifo_depth) : 0;
    s.line_bytes = blocks[j].line_bytes;
    if (s.line_bytes > 0 && !dram_) dram_ = std::make_unique<Dram>(dram);
    // (the raster's own FIFO holds triangles: no term looks back through it)
    reach = std::max({reach, uint64_t(s.capacity), uint64_t(s.next_depth), j > 0 ? blocks[j].fifo_depth : 0});
    blocks_.push_back(s);
  }
  uint64_t chunk = kSpanMax;  // K: at most every span block's FIFO depth
  for (size_t j = 1; j < blocks.size(); ++j) chunk = std::min<uint64_t>(chunk, blocks[j].fifo_depth);
  chunk_ = int(std::max<uint64_t>(chunk, 1));
  // Windows of twice the reach and at least a few thousand pixels: a slide copies `reach`
  // pixels at most once every `reach` pixels swept, mostly far less often.
  reach_ = int64_t(reach);
  window_ = reach_ + std::max<int64_t>(reach_, 2048) + kSpanMax;
  base_ = -reach_;  // pixel 0 after `reach` pixels "handed on and started before cycle 0"
  windows_.assign((blocks_.size() * 2 + 1) * size_t(window_), -1);
  for (size_t j = 0; j < blocks_.size(); ++j) {
    Slot& b = blocks_[j];
    b.s = &windows_[j * 2 * size_t(window_)];
    b.d = b.s + window_;
    b.ii = int64_t(b.timing.ii), b.latency = int64_t(b.timing.latency);
  }
  for (size_t j = 0; j + 1 < blocks_.size(); ++j) blocks_[j].next_s = blocks_[j + 1].s;
  // After the last block, a FIFO always with room: a window of "started before cycle 0".
  room_ = &windows_[blocks_.size() * 2 * size_t(window_)];
  blocks_.back().next_s = room_;
  blocks_.back().next_depth = 1;
  // The blocks that may only delay ("Blocks that only delay"): a suffix, ideal memory.
  size_t from = blocks_.size();
  while (!dram_ && from > 1) {
    const Timing& t = blocks_[from - 1].timing;
    if (t.ii != 1 || t.latency < 1 || t.line_bytes > 0 || t.fifo_depth < 2) break;
    --from;
  }
  delay_work_.assign(blocks_.size(), -1);
  series_.assign(blocks_.size(), Increments{});
  delay_from_ = blocks_.size();
  delay_from(from);
  times_.assign(blocks_.size(), std::vector<Times>(64));
  depth_back_.assign(ring_above(blocks_[0].timing.miss_queue), -1);
}

void MainPassTiming::slide_windows(int count) {
  if (at(n_) + count <= window_) return;
  const int64_t shift = at(n_) - reach_;
  for (size_t w = 0; w < blocks_.size() * 2 + 1; ++w) {
    int64_t* const window = &windows_[w * size_t(window_)];
    std::copy(window + shift, window + shift + reach_, window);
  }
  base_ += shift;
}

int64_t MainPassTiming::depth_read(int64_t& t, uint32_t lines) {
  Slot& r = blocks_[0];
  const uint64_t entries = r.timing.miss_queue;
  const uint64_t mask = depth_back_.size() - 1;
  if (entries > 0 && depth_misses_ >= entries) t = std::max(t, depth_back_[(depth_misses_ - entries) & mask] + 1);
  dram_->forget_before(t);  // nothing later is asked before the walk's step
  const int64_t back = dram_->request(t, uint64_t(lines) * r.line_bytes);
  depth_back_[depth_misses_++ & mask] = back;
  r.t.memory_stall += uint64_t(std::max<int64_t>(back - t, 0));
  r.t.dram_lines += lines;
  return back;
}

int64_t MainPassTiming::start_triangle(int64_t arrival) {
  Slot& r = blocks_[0];
  // In the raster's FIFO from the cycle after setup handed it on; one taken a cycle.
  const int64_t taken = std::max({arrival + 1, r.free, triangle_start_ + 1});
  r.t.starved += uint64_t(taken - r.free);
  r.free = taken;
  triangle_start_ = taken;
  return taken;
}

void MainPassTiming::walk_hidden(uint64_t steps, const std::vector<StepLines>& misses) {
  Slot& r = blocks_[0];
  uint64_t walked = 0;
  for (const StepLines& m : misses) {  // the steps up to a miss at a II each, then the miss
    if (log_) log_->hidden_lines(m.step, m.lines);
    r.t.add_busy(r.free, r.timing.ii * (m.step - walked));
    r.free += int64_t(r.timing.ii * (m.step - walked));
    int64_t t = r.free;
    const int64_t back = depth_read(t, m.lines);
    r.t.blocked += uint64_t(t - r.free);  // every miss entry taken
    r.t.add_busy(t, r.timing.ii);
    r.free = t + r.ii;
    if (r.timing.miss_queue == 0 && back + 1 > r.free) {  // no miss queue: the walk waits for the data
      r.t.blocked += uint64_t(back + 1 - r.free);
      r.free = back + 1;
    }
    walked = m.step + 1;
  }
  const uint64_t cycles = r.timing.ii * (steps - walked);
  r.t.add_busy(r.free, cycles);
  r.free += int64_t(cycles);
}

// Under the memory model: the pixels of the packet, pixel by pixel, block by block
// (timing.hpp's recurrence), so that the DRAM sees the requests in their order.
template <bool kInspect>
void MainPassTiming::sweep_pixels(int count) {
  const size_t blocks = blocks_.size();
  for (int i = 0; i < count; ++i, ++n_) {
    const int64_t slot = at(n_);
    // The raster: the walk has reached the pixel (a step of its own) and a register is free.
    Slot& r = blocks_[0];
    int64_t s = std::max(r.free, r.d[slot - r.capacity] + 1);
    int64_t done = s + r.latency;
    int64_t depth_back = -1;
    if (const uint32_t lines = r.work.lines_at(i); lines > 0) {  // its depth read missed
      depth_back = depth_read(s, lines);
      done = std::max(s, depth_back) + r.latency;
    }
    dram_->forget_before(s);  // every later request is made after s
    r.t.blocked += uint64_t(s - r.free);
    r.t.add_busy(s, uint64_t(r.ii));  // (into the histogram too, when kept)
    r.free = s + r.ii;
    if (r.timing.miss_queue == 0 && depth_back + 1 > r.free) {  // the walk waits for the data
      r.t.blocked += uint64_t(depth_back + 1 - r.free);
      r.free = depth_back + 1;
    }
    int64_t d = std::max(std::max(done, r.t.last + 1), r.next_s[slot - r.next_depth] + 1);
    if constexpr (kInspect) times_[0][size_t(i)] = {s, d, std::max(done, r.t.last + 1), 0};
    r.s[slot] = s, r.d[slot] = d, r.t.last = d;
    for (size_t j = 1; j < blocks; ++j) {  // the span blocks, timing.hpp's recurrence
      Slot& b = blocks_[j];
      const int64_t arrived = d + 1;  // in its FIFO since the cycle before
      const int64_t room = b.d[slot - b.capacity] + 1;  // a register free
      s = std::max(arrived, std::max(b.free, room));
      b.t.blocked += uint64_t(std::max<int64_t>(room - b.free, 0));  // every register full
      // Its FIFO held the pixel from the end of cycle d_{j−1}(n) to s; the peak: the pixels
      // in it once this one came in.
      b.t.fifo_cycles += uint64_t(s - d);
      while (b.head < int64_t(n_) && b.s[b.head - base_] < arrived) ++b.head;
      b.t.fifo_peak = std::max(b.t.fifo_peak, n_ + 1 - uint64_t(b.head));
      const uint32_t w = b.w[i];
      const int64_t o = std::max<int64_t>(b.ii * int64_t(w), 1);  // 1: bypassed
      b.t.add_busy(s, uint64_t(o));
      b.free = s + o;
      int64_t f = b.free + (w > 0 ? b.latency - b.ii : 0);
      if (const uint32_t lines = b.work.lines_at(i); lines > 0) {  // its data from the DRAM
        const int64_t back = dram_->request(s, uint64_t(lines) * b.line_bytes);
        b.t.memory_stall += uint64_t(std::max<int64_t>(back + b.latency - f, 0));
        b.t.dram_lines += lines;
        f = std::max(f, back + b.latency);
      }
      const int64_t valid = std::max(f, b.t.last + 1);
      d = std::max(valid, b.next_s[slot - b.next_depth] + 1);
      if constexpr (kInspect) times_[j][size_t(i)] = {s, d, valid, n_ + 1 - uint64_t(b.head)};
      b.s[slot] = s, b.d[slot] = d, b.t.last = d;
    }
  }
}

// The raster's pixels [first, last) (its part of sweep_pixels, without memory).
template <bool kInspect>
void MainPassTiming::raster_chunk(int first, int last) {
  Slot& r = blocks_[0];
  // The windows from the packet's first pixel: index i is its pixel i.
  int64_t* const starts = r.s + at(n_);
  int64_t* const handed = r.d + at(n_);
  const int64_t* const register_freed = handed - r.capacity;        // d(n − C)
  const int64_t* const next_started = r.next_s + at(n_) - r.next_depth;  // s_{j+1}(n − b)
  const int64_t ii = r.ii, latency = r.latency;
  int64_t free = r.free, last_d = r.t.last;
  uint64_t blocked = 0;
  for (int i = first; i < last; ++i) {
    // The walk has reached the pixel (a step of its own) and a register is free.
    const int64_t s = std::max(free, register_freed[i] + 1);
    blocked += uint64_t(s - free);
    if constexpr (kInspect) r.t.add_busy(s, uint64_t(ii));
    free = s + ii;
    const int64_t valid = std::max(s + latency, last_d + 1);
    const int64_t d = std::max(valid, next_started[i] + 1);
    if constexpr (kInspect) times_[0][size_t(i)] = {s, d, valid, 0};
    starts[i] = s, handed[i] = d, last_d = d;
  }
  r.t.blocked += blocked;
  r.free = free, r.t.last = last_d;
  if constexpr (!kInspect) {
    r.t.busy += uint64_t(ii) * uint64_t(last - first);
    if (r.t.bin_cycles > 0) bin_busy(0, first, last, uint64_t(ii) * uint64_t(last - first));
  }
}

// Span block j's pixels [first, last) (its part of sweep_pixels, without memory).
// kUniform: every pixel the same work (Work::each; the packet's first pixel its lead
// more), its occupancy and latency known before the loop. Once the FIFO's peak is its
// depth it can grow no more, and the oldest pixel waiting (`head`) is no longer followed
// unless its occupancy is kept.
template <bool kInspect, bool kUniform>
void MainPassTiming::span_chunk(size_t j, int first, int last) {
  Slot& b = blocks_[j];
  // The windows from the packet's first pixel: index i is its pixel i.
  const int64_t* const before = blocks_[j - 1].d + at(n_);  // the block before's hand-overs
  int64_t* const starts = b.s + at(n_);
  int64_t* const handed = b.d + at(n_);
  const int64_t* const register_freed = handed - b.capacity;        // d(n − C)
  const int64_t* const next_started = b.next_s + at(n_) - b.next_depth;  // s_{j+1}(n − b)
  const int64_t ii = b.ii, tail = b.latency - b.ii;  // done at the end of its work + L − II
  const int64_t depth = int64_t(b.timing.fifo_depth);
  int64_t free = b.free, last_d = b.t.last;
  int64_t head = b.head - int64_t(n_);  // the oldest pixel in its FIFO, from the packet's first
  uint64_t busy = 0, blocked = 0, fifo_cycles = 0;
  int64_t fifo_peak = int64_t(b.t.fifo_peak);
  // The pixels in its FIFO once pixel i came in: from the oldest not yet started (when the
  // pixel before it had started, it alone). Inspected, as each pixel is timed; else after
  // the chunk (fewer values live in its loop), and only until the peak is the depth.
  auto follow_head = [&](int i) {
    const int64_t arrived = before[i] + 1;
    if (!kInspect && starts[i - 1] < arrived) return;
    while (head < i && starts[head] < arrived) ++head;
    fifo_peak = std::max<int64_t>(fifo_peak, i + 1 - head);
  };
  // Pixel i with work w: its occupancy of the unit, max(II · w, 1) (1: bypassed), and the
  // cycles from the end of that to done.
  auto pixel = [&](int i, uint32_t w) {
    const int64_t o = std::max<int64_t>(ii * int64_t(w), 1), done_after = w > 0 ? tail : 0;
    const int64_t arrived = before[i] + 1;  // in its FIFO since the cycle before
    const int64_t ready = std::max(free, register_freed[i] + 1);  // the unit and a register free
    const int64_t s = std::max(arrived, ready);
    blocked += uint64_t(ready - free);  // every register full
    fifo_cycles += uint64_t(s - arrived + 1);
    if constexpr (kInspect) follow_head(i);
    if constexpr (!kUniform) busy += uint64_t(o);
    if constexpr (kInspect) b.t.add_busy(s, uint64_t(o));
    free = s + o;
    const int64_t valid = std::max(free + done_after, last_d + 1);
    const int64_t d = std::max(valid, next_started[i] + 1);
    if constexpr (kInspect) times_[j][size_t(i)] = {s, d, valid, uint64_t(i + 1 - head)};
    starts[i] = s, handed[i] = d, last_d = d;
  };
  if constexpr (kUniform) {
    const uint32_t each = b.work.each;
    int i = first;
    if (first == 0 && last > 0) {  // the packet's first pixel: its lead too
      const uint32_t lead_w = b.work.first();
      pixel(i++, lead_w);
      busy = uint64_t(std::max<int64_t>(ii * int64_t(lead_w), 1) - std::max<int64_t>(ii * int64_t(each), 1));
    }
    for (; i < last; ++i) pixel(i, each);
    busy += uint64_t(std::max<int64_t>(ii * int64_t(each), 1)) * uint64_t(last - first);
  } else {
    for (int i = first; i < last; ++i) pixel(i, b.w[i]);
  }
  if constexpr (!kInspect) {
    b.t.busy += busy;
    for (int i = first; i < last && fifo_peak < depth; ++i) follow_head(i);
  }
  if (last > first) fifo_peak = std::max<int64_t>(fifo_peak, 1);  // (a pixel that came to a started FIFO)
  b.t.blocked += blocked, b.t.fifo_cycles += fifo_cycles, b.t.fifo_peak = uint64_t(fifo_peak);
  b.free = free, b.t.last = last_d;
  if constexpr (!kInspect)
    if (b.t.bin_cycles > 0) bin_busy(j, first, last, busy);
  // (Behind the FIFO's pixels when no longer followed: the next that follows it catches up.)
  b.head = int64_t(n_) + std::max<int64_t>(head, last - depth);
}

// The packet's pixels at the blocks that only delay ("Blocks that only delay"): each
// starts the cycle after the block before handed it on and is handed on when done. Only
// their figures are counted, not their windows (main_pass.hpp: no term that reads them
// binds).
void MainPassTiming::delay_packet(int count) {
  const int64_t* const base = blocks_[delay_from_ - 1].d + at(n_);  // the base block's hand-overs
  int64_t after = 1;  // from the base block's hand-over to the start at block j
  for (size_t j = delay_from_; j < blocks_.size(); ++j) {
    Slot& b = blocks_[j];
    const int64_t done = delay(j), last = base[count - 1] + after;
    b.t.busy += uint64_t(count);         // one cycle a pixel (II·w or 1)
    b.t.fifo_cycles += uint64_t(count);  // in its FIFO from the end of cycle d_{j−1} to s
    b.t.fifo_peak = std::max<uint64_t>(b.t.fifo_peak, 1);
    b.free = last + 1, b.t.last = last + done;
    b.head = int64_t(n_) + count;  // every pixel started before the next comes in
    if (b.t.bin_cycles > 0) {  // (bin_busy, the starts being the base's hand-overs + after)
      const int64_t first = base[0] + after;  // (the only read of the base's first pixels)
      if (uint64_t(first) / b.t.bin_cycles == uint64_t(last) / b.t.bin_cycles) b.t.add_to_bins(first, uint64_t(count));
      else
        for (int i = 0; i < count; ++i) b.t.add_to_bins(base[i] + after, 1);
    }
    after += done + 1;
  }
}

namespace {
// Whether window[k] − window[k − 1] = step for every k in [from, to]. (A few k, mostly:
// without a branch a step, and not vectorized, whose set-up would cost more.)
__attribute__((optimize("no-tree-vectorize"))) bool arithmetic(const int64_t* window, int64_t from, int64_t to, int64_t step) {
  int64_t off = 0;
  for (int64_t k = from; k <= to; ++k) off |= (window[k] - window[k - 1]) ^ step;
  return off == 0;
}
// window[i] = window[n] + (i − n) · step for i in (from, end), from ≥ n.
void continue_series(int64_t* window, int64_t n, int64_t from, int64_t end, int64_t step) {
  const int64_t at_n = window[n];
  for (int64_t i = from + 1; i < end; ++i) window[i] = at_n + (i - n) * step;
}
}  // namespace

bool MainPassTiming::steady(size_t timed, int n) const {
  const int64_t at_n = at(n_);
  const int64_t period = blocks_[0].s[at_n + n] - blocks_[0].s[at_n + n - 1];
  // The packet before ended in a series of this period: its last pixels need no check.
  const bool known = series_end_ == n_ && series_timed_ == timed && series_period_ == period;
  for (size_t j = 0; j < timed; ++j) {
    const Slot& b = blocks_[j];
    const int64_t s_from = n + 1 - starts_back(j), d_from = n + 1 - b.capacity;
    if (!arithmetic(b.s + at_n, known ? std::max<int64_t>(s_from, 0) : s_from, n, period)) return false;
    if (!arithmetic(b.d + at_n, known ? std::max<int64_t>(d_from, 0) : d_from, n, period)) return false;
  }
  return true;
}

void MainPassTiming::extrapolate(size_t timed, int n, int count) {
  const int64_t at_n = at(n_), more = count - 1 - n;
  const int64_t period = n < 0 ? series_period_ : blocks_[0].s[at_n + n] - blocks_[0].s[at_n + n - 1];
  // Later reads of the packet's windows are of its last pixels: the recurrence's, of the
  // last starts_back starts and C hand-overs, and steady's, of fewer; but the delays read
  // their base block's hand-overs over the whole packet when they keep a histogram
  // (delay_packet).
  bool base_read = false;
  for (size_t j = timed; j < blocks_.size(); ++j) base_read = base_read || blocks_[j].t.bin_cycles > 0;
  for (size_t j = 0; j < timed; ++j) {
    Slot& b = blocks_[j];
    int64_t* const starts = b.s + at_n;
    int64_t* const handed = b.d + at_n;
    Increments& each = series_[j];
    if (n >= 0) {  // pixel n's increments (raster_chunk's and span_chunk's): each pixel's after it
      each.w = j == 0 ? 1 : b.w[n];
      each.o = j == 0 ? b.ii : std::max<int64_t>(b.ii * int64_t(each.w), 1);
      const int64_t freed_before = starts[n - 1] + each.o;  // the unit free for pixel n
      const int64_t ready = j == 0 ? starts[n] : std::max(freed_before, handed[n - b.capacity] + 1);
      each.blocked = ready - freed_before;
      each.fifo = j == 0 ? 0 : starts[n] - blocks_[j - 1].d[at_n + n];
    }  // (n = −1: the series' own, from the packet before)
    b.t.blocked += uint64_t(more * each.blocked);
    b.t.fifo_cycles += uint64_t(more * each.fifo);
    b.t.busy += uint64_t(more * each.o);
    // (the FIFO's pixels once each came in: pixel n's, already in the peak)
    if (j > 0) b.head = std::max(b.head, int64_t(n_) + count - int64_t(b.timing.fifo_depth));
    const int64_t start_n = starts[n];
    continue_series(starts, n, std::max<int64_t>(n, count - 1 - starts_back(j)), count, period);
    const bool all = base_read && j + 1 == timed;
    continue_series(handed, n, all ? n : std::max<int64_t>(n, count - 1 - b.capacity), count, period);
    b.free = start_n + more * period + each.o, b.t.last = handed[count - 1];
    if (b.t.bin_cycles > 0) series_bins(b.t, start_n + period, period, more, each.o);
  }
  series_end_ = n_ + uint64_t(count), series_period_ = period, series_timed_ = timed;
  extrapolated_ += uint64_t(more);
}

bool MainPassTiming::continue_packet(size_t timed, int count) {
  if (series_end_ != n_ || series_timed_ != timed || count < 2) return false;
  const int64_t at_n = at(n_), period = series_period_;
  // The series' pixel i (i ≥ 0: of this packet) in a window.
  auto series = [&](const int64_t* window, int64_t i) { return i < 0 ? window[at_n + i] : window[at_n - 1] + (i + 1) * period; };
  Slot& r = blocks_[0];
  const int64_t walked = r.free;  // the walk to the packet's first pixel (a new triangle, hidden steps)
  if (walked > series(r.s, 0)) return false;
  for (size_t j = 1; j < timed; ++j) {
    const Slot& b = blocks_[j];
    const uint32_t each = b.w[count - 1], first = b.w[0];  // (work per pixel: the same from pixel 1 on)
    if (each != series_[j].w || first < each) return false;
    if (first == each) continue;
    // A lead: pixel 0 done later and its unit busy longer, neither past the series' times.
    const int64_t s0 = series(b.s, 0), done = s0 + b.ii * (int64_t(first) - 1) + b.latency;
    if (b.ii * int64_t(first) > period || done > series(b.d, 0)) return false;
  }
  extrapolate(timed, -1, count);
  // Corrections to the series' increments: the raster's first start waited for the series,
  // not for the walk; a lead's pixel 0 kept its unit longer, so pixel 1 waited less for a
  // register.
  r.t.blocked += uint64_t((series(r.s, 0) - walked) - series_[0].blocked);
  for (size_t j = 1; j < timed; ++j) {
    Slot& b = blocks_[j];
    const int64_t o_each = series_[j].o, o_first = std::max<int64_t>(b.ii * int64_t(b.w[0]), 1);
    if (o_first == o_each) continue;
    const int64_t s0 = series(b.s, 0), room = series(b.d, 1 - b.capacity) + 1;
    const int64_t waited = std::max<int64_t>(room - (s0 + o_first), 0), in_series = std::max<int64_t>(room - (s0 + o_each), 0);
    b.t.blocked += uint64_t(waited - in_series);
    b.t.busy += uint64_t(o_first - o_each);
    if (b.t.bin_cycles > 0) b.t.add_to_bins(s0 + o_each, uint64_t(o_first - o_each));
  }
  ++continued_;
  return true;
}

void MainPassTiming::series_bins(BlockTimes& t, int64_t first, int64_t period, int64_t count, int64_t busy) {
  const int64_t end = first + (count - 1) * period + busy;  // the end of the last one's work
  if (uint64_t(first) / t.bin_cycles == uint64_t(end - 1) / t.bin_cycles)
    return t.add_to_bins(first, uint64_t(count * busy));
  for (int64_t k = 0; k < count; ++k) t.add_to_bins(first + k * period, uint64_t(busy));
}

void MainPassTiming::bin_busy(size_t j, int first, int last, uint64_t busy) {
  if (last <= first) return;
  BlockTimes& t = blocks_[j].t;
  const int64_t* const starts = blocks_[j].s + at(n_);
  const int64_t end = blocks_[j].free;  // the end of the last one's work
  if (uint64_t(starts[first]) / t.bin_cycles == uint64_t(end - 1) / t.bin_cycles)
    return t.add_to_bins(starts[first], busy);
  // Pixel by pixel: the raster's take II, a span block's II·w (1: bypassed).
  const int64_t ii = blocks_[j].ii;
  for (int i = first; i < last; ++i)
    t.add_to_bins(starts[i], uint64_t(j == 0 ? ii : std::max<int64_t>(ii * int64_t(blocks_[j].w[i]), 1)));
}

void MainPassTiming::delay_from(size_t from) {
  if (delay_from_ < blocks_.size()) blocks_[delay_from_ - 1].next_s = blocks_[delay_from_].s;  // its FIFO may fill
  delay_from_ = from;
  if (delay_from_ < blocks_.size()) blocks_[delay_from_ - 1].next_s = room_;  // never full
}

void MainPassTiming::time_every_block() { delay_from(blocks_.size()); }

void MainPassTiming::keep_delaying(int count) {
  if (count == 0) return;
  size_t from = delay_from_;
  for (size_t j = delay_from_; j < blocks_.size(); ++j) {
    const Work& w = blocks_[j].work;
    int& kept = delay_work_[j];
    if (kept < 0) kept = int(w.at(0));
    bool same = kept <= 1;
    if (w.per_pixel)
      for (int i = 0; i < count && same; ++i) same = w.per_pixel[i] == kept;
    else
      same = same && w.each == uint32_t(kept) && w.first() == uint32_t(kept);
    if (!same) from = j + 1;
  }
  if (from != delay_from_) delay_from(from);
}

void MainPassTiming::sweep(const SpanPacket& p, uint64_t hidden_before, const std::vector<StepLines>& misses) {
  const int count = p.count;
  walk_hidden(hidden_before, misses);
  slide_windows(count);
  if (keep_times && times_[0].size() < size_t(count))
    for (auto& t : times_) t.resize(size_t(count));
  const size_t blocks = blocks_.size();
  for (size_t j = 1; j < blocks; ++j) {  // each block's work as an array: a load a pixel, no branch
    Slot& b = blocks_[j];
    if (b.work.per_pixel) {
      b.w = b.work.per_pixel;
    } else {
      if (b.uniform[1] != b.work.each) std::fill(std::begin(b.uniform), std::end(b.uniform), uint16_t(b.work.each));
      b.uniform[0] = uint16_t(b.work.first());
      b.w = b.uniform;
    }
  }
  // Inspecting (every time kept: the timing log, waveforms, the timeline) or not: two
  // copies of the loop, so that the common one carries no test for it.
  const bool watched = !watched_ || watched_(p);
  const bool inspect = keep_times && (watched || log_);
  if (dram_) {
    if (inspect) sweep_pixels<true>(count);
    else sweep_pixels<false>(count);
  } else {
    if (delay_from_ < blocks) keep_delaying(count);
    // Inspected, every block by the recurrence (the same times: "Blocks that only delay").
    const size_t timed = inspect ? blocks : delay_from_;
    // The first pixel after which the state may be steady ("A packet in steady state"):
    // the second of the packet, the third after a lead, and the second of those whose work
    // given per pixel is the same to the packet's end (same_from: the first of them).
    int steady_from = inspect ? count : 1, same_from = 0;
    for (size_t j = 1; j < timed && !inspect; ++j) {
      const Work& w = blocks_[j].work;
      if (w.per_pixel) {
        int first_same = count - 1;
        while (first_same > 0 && w.per_pixel[first_same - 1] == w.per_pixel[count - 1]) --first_same;
        same_from = std::max(same_from, first_same);
      } else if (w.first() != w.each) {
        steady_from = std::max(steady_from, 2);
      }
    }
    steady_from = std::max(steady_from, same_from + 1);
    const bool continued = !inspect && same_from <= 1 && continue_packet(timed, count);
    for (int first = continued ? count : 0; first < count;) {  // block-major in chunks ("Order of the sweep")
      int last = std::min(count, first + chunk_);
      if (first <= steady_from) last = std::min(last, steady_from + 1);  // a chunk ends where the check begins
      if (inspect) {
        raster_chunk<true>(first, last);
        for (size_t j = 1; j < blocks; ++j) span_chunk<true, false>(j, first, last);
      } else {
        raster_chunk<false>(first, last);
        for (size_t j = 1; j < timed; ++j)
          if (blocks_[j].work.per_pixel) span_chunk<false, false>(j, first, last);
          else span_chunk<false, true>(j, first, last);
      }
      first = last;
      if (last > steady_from && last < count && steady(timed, last - 1)) {
        extrapolate(timed, last - 1, count);
        first = count;
      }
    }
    if (count > 0 && timed < blocks) delay_packet(count);
    n_ += uint64_t(count);
  }
  if (log_) log_->pixels(p, hidden_before, *this);
  if (watched)
    for (TimedObserver* o : observers_) o->timed(p);
}

void MainPassTiming::settle() {
  // A span block waits s − (the cycle its unit was free) before each pixel; summed over
  // its pixels that telescopes to (its last issue's end − its busy cycles). What it did
  // not spend blocked it spent starved.
  for (size_t j = 1; j < blocks_.size(); ++j) {
    BlockTimes& t = blocks_[j].t;
    t.starved = uint64_t(blocks_[j].free) - t.busy - t.blocked;
  }
}

int64_t MainPassTiming::end() const {
  int64_t end = blocks_.empty() ? 0 : blocks_[0].free;  // the raster's walk
  for (const Slot& b : blocks_) end = std::max(end, b.t.last + 1);
  return end;
}

TriangleLine::TriangleLine(Timing setup, uint64_t raster_depth)
    : timing_(setup), capacity_(int64_t(capacity(setup))), depth_(int64_t(raster_depth)) {
  const uint64_t size = ring_above(std::max<uint64_t>(uint64_t(capacity_), raster_depth));
  handed_.assign(size, -1);
  taken_.assign(size, -1);
  mask_ = size - 1;
}

int64_t TriangleLine::next() {
  const int64_t room = handed_[(k_ - uint64_t(capacity_)) & mask_] + 1;
  const int64_t s = std::max(free_, room);
  t_.blocked += uint64_t(s - free_);
  t_.add_busy(s, timing_.ii);
  free_ = s + int64_t(timing_.ii);
  const int64_t fifo_room = taken_[(k_ - uint64_t(depth_)) & mask_] + 1;
  const int64_t d = std::max({s + int64_t(timing_.latency), last_d_ + 1, fifo_room});
  handed_[k_ & mask_] = d;
  last_start_ = s;
  last_d_ = d;
  t_.last = std::max(t_.last, d);
  return d;
}

void TriangleLine::reject(uint64_t count, uint64_t cycles) {
  if (count == 0) return;
  t_.add_busy(free_, count * cycles);
  free_ += int64_t(count * cycles);
  t_.last = std::max(t_.last, free_ - 1);
}

void TriangleLine::taken(int64_t cycle) {
  taken_[k_ & mask_] = cycle;
  ++k_;
}

void TimingLog::block(const std::string& name, const Timing& t) {
  text_ += "block " + name + " " + std::to_string(t.latency) + " " + std::to_string(t.ii) + " " +
           std::to_string(t.fifo_depth) + " " + std::to_string(t.line_bytes) + " " + std::to_string(t.miss_queue) + "\n";
}
void TimingLog::memory(const DramTiming& t) {
  text_ += "memory " + std::to_string(t.latency) + " " + std::to_string(t.bytes_per_cycle) + "\n";
}
void TimingLog::triangle(uint32_t id, int64_t start, int64_t handed) {
  text_ += "t " + std::to_string(id) + " " + std::to_string(start) + " " + std::to_string(handed) + "\n";
}
void TimingLog::taken(int64_t cycle) { text_ += "r " + std::to_string(cycle) + "\n"; }
void TimingLog::hidden_lines(uint64_t step, uint32_t lines) {
  text_ += "h " + std::to_string(step) + " " + std::to_string(lines) + "\n";
}
void TimingLog::trailing(uint64_t steps) { text_ += "e " + std::to_string(steps) + "\n"; }
void TimingLog::end(int64_t cycle) { text_ += "end " + std::to_string(cycle) + "\n"; }
void TimingLog::stats(const std::string& name, const BlockTimes& t) {
  text_ += "stats " + name + " " + std::to_string(t.busy) + " " + std::to_string(t.starved) + " " +
           std::to_string(t.blocked) + " " + std::to_string(t.fifo_cycles) + " " + std::to_string(t.fifo_peak) + " " + std::to_string(t.memory_stall) + "\n";
}
void TimingLog::pixels(const SpanPacket& p, uint64_t hidden, const MainPassTiming& line) {
  if (p.count > 0) text_ += "k\n";
  for (int i = 0; i < p.count; ++i) {
    text_ += "p " + std::to_string(p.x0 + i) + " " + std::to_string(p.y) + " " +
             std::to_string(i == 0 ? hidden : 0);
    for (size_t j = 1; j < line.size(); ++j) text_ += " " + std::to_string(line.work(int(j)).at(i));
    if (line.dram())
      for (size_t j = 0; j < line.size(); ++j) text_ += " " + std::to_string(line.work(int(j)).lines_at(i));
    for (size_t j = 0; j < line.size(); ++j)
      text_ += " " + std::to_string(line.start(int(j), i)) + " " + std::to_string(line.valid_from(int(j), i)) + " " +
               std::to_string(line.handed(int(j), i));
    text_ += "\n";
  }
}

}  // namespace shadetlm::modules
