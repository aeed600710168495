#include "shadetlm/timing_reference/clocked.hpp"

#include <algorithm>
#include <chrono>
#include <climits>
#include <deque>
#include <functional>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <systemc>

namespace shadetlm::timing_reference {

namespace {

const sc_core::sc_time kPeriod(1, sc_core::SC_NS);

int64_t cycle_now() { return int64_t(sc_core::sc_time_stamp() / kPeriod + 0.5); }

// A valid/ready handshake carrying an index (a triangle's or a pixel's). The sender
// drives valid and data, the receiver ready; a transfer happens in a cycle where both
// are high, as registered at the end of the cycle before.
struct Link {
  sc_core::sc_signal<bool> valid, ready;
  sc_core::sc_signal<int64_t> data;
};

// What every clocked block has: a unit that issues one item per II·work cycles, room for
// C items between issue and hand-over (its pipeline and output registers), and an output
// handshake. Waiting cycles are counted as they pass and booked at the next issue (the
// fast model books the waits before each start, none after the last).
class Unit : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(Unit);
  // Each block's edge() runs at every rising edge of the clock.
  Unit(sc_core::sc_module_name name, const BlockSpec& spec, Link& out)
      : sc_core::sc_module(name),
        spec_(spec),
        capacity_((spec.latency + 1 + spec.ii - 1) / spec.ii + (spec.line_bytes > 0 ? spec.miss_queue : 0)),
        out_(out) {
    stats.name = spec.name;
    SC_METHOD(edge);
    sensitive << clk.pos();
    dont_initialize();
  }
  sc_core::sc_in<bool> clk;
  BlockStatsLine stats;
  std::vector<int64_t>* handed = nullptr;  // per item: the cycle it was handed on
  std::vector<int64_t>* valid = nullptr;   // per item: the first cycle it was valid at the output (none: not kept)
  int64_t last = -1;
  size_t handed_count = 0;

  // The DRAM: the data of the request (item, tag) made in cycle `made` is in the block
  // at `back`. A span block's item is a pixel waiting in it.
  virtual void data_back(int64_t item, int64_t /*tag*/, int64_t /*made*/, int64_t back) {
    for (Held& h : held_)
      if (h.item == item) {
        stats.memory_stall += std::max<int64_t>(back - h.work_end, 0);
        h.done = std::max(h.work_end, back) + spec_.latency;
      }
  }

 protected:
  static constexpr int64_t kNever = INT64_MAX / 2;
  // An item in the block: done at `done`; waiting for memory (done = kNever) its work
  // ends at `work_end`, and it is done L cycles after that and its data.
  struct Held { int64_t item, done, work_end; };
  virtual void edge() = 0;
  bool room() const { return int64_t(held_.size()) < capacity_; }
  // Issues `item` at t for `work` units (0: passes through in a cycle); `memory`: it
  // waits for data from the DRAM too.
  void issue(int64_t t, int64_t item, int64_t work, bool memory = false) {
    const int64_t busy = work > 0 ? spec_.ii * work : 1;
    const int64_t work_end = t + spec_.ii * (work - 1);
    held_.push_back({item, memory ? kNever : work > 0 ? work_end + spec_.latency : t + 1, work_end});
    free_ = t + busy;
    stats.busy += busy;
    stats.starved += starved_, stats.blocked += blocked_;
    starved_ = blocked_ = 0;
  }
  void wait_cycle() { (room() ? starved_ : blocked_) += 1; }
  // The output handshake of cycle t (before this cycle's registers change), then the
  // registers for the next cycle.
  bool handing_over() const { return out_.valid.read() && out_.ready.read(); }
  void hand_over(int64_t t) {
    (*handed)[size_t(held_.front().item)] = t;
    last = std::max(last, t);
    ++handed_count;
    held_.pop_front();
  }
  void drive_output(int64_t t) {
    const bool is_valid = !held_.empty() && held_.front().done <= t + 1;
    out_.valid.write(is_valid);
    out_.data.write(is_valid ? held_.front().item : -1);
    if (is_valid && valid && (*valid)[size_t(held_.front().item)] < 0) (*valid)[size_t(held_.front().item)] = t + 1;
  }

  BlockSpec spec_;
  int64_t capacity_;
  Link& out_;
  std::deque<Held> held_;
  int64_t free_ = 0, starved_ = 0, blocked_ = 0;
};

// Setup: a triangle every II cycles, handed on to the raster's triangle FIFO; before
// each, the triangles it dropped (the scene's: SceneWalk), each `reject_cycles` of its
// unit, needing no register.
class Source : public Unit {
 public:
  Source(sc_core::sc_module_name name, const Workload& w, Link& out, std::vector<int64_t>& start)
      : Unit(name, w.blocks[0], out), w_(w), start_(start) {
    rejects_left_ = rejects_before(0);
  }
  bool done() const { return next_ == w_.triangles.size() && rejects_left_ == 0; }

 private:
  int64_t rejects_before(size_t k) const {
    if (w_.reject_cycles == 0) return 0;
    return k < w_.triangles.size() ? w_.triangles[k].rejected_before : w_.rejected_after;
  }
  void edge() override {
    const int64_t t = cycle_now();
    const bool out = handing_over();
    if (t >= free_ && rejects_left_ > 0) {
      free_ = t + w_.reject_cycles;
      stats.busy += w_.reject_cycles;
      last = std::max(last, free_ - 1);
      --rejects_left_;
    } else if (t >= free_ && next_ < w_.triangles.size()) {
      if (room()) {
        start_[next_] = t, issue(t, int64_t(next_), 1), ++next_;
        rejects_left_ = rejects_before(next_);
      } else {
        blocked_ += 1;
      }
    }
    if (out) hand_over(t);
    drive_output(t);
  }
  const Workload& w_;
  size_t next_ = 0;
  int64_t rejects_left_ = 0;
  std::vector<int64_t>& start_;
};

// The shared DRAM: each cycle it moves up to B bytes to the requests present, oldest
// pixel first (for one pixel, the earlier block first); a request made in cycle t is
// present from t + 1, and its data is back `latency` cycles after its last byte.
class DramUnit : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(DramUnit);
  DramUnit(sc_core::sc_module_name name, MemorySpec spec) : sc_core::sc_module(name), spec_(spec) {
    SC_METHOD(edge);
    sensitive << clk.pos();
    dont_initialize();
  }
  sc_core::sc_in<bool> clk;
  // A request's age: its pixel, then where along the pipeline (0: a hidden pixel the
  // raster walked before it, 1: the raster, 2 + j: span block j), then the order made.
  struct Age {
    int64_t pixel, place, order;
    bool operator<(const Age& o) const {
      return pixel != o.pixel ? pixel < o.pixel : place != o.place ? place < o.place : order < o.order;
    }
  };
  // `unit` asks for `bytes` in cycle `made`; told data_back(item, tag, made, back).
  void request(Age age, int64_t made, int64_t bytes, Unit* unit, int64_t item, int64_t tag) {
    pending_.push_back({age, made, made + 1, bytes, unit, item, tag});
  }

 private:
  struct Request {
    Age age;
    int64_t made, present, left;
    Unit* unit;
    int64_t item, tag;
  };
  void edge() {
    const int64_t t = cycle_now();
    std::sort(pending_.begin(), pending_.end(), [](const Request& a, const Request& b) { return a.age < b.age; });
    int64_t budget = spec_.bytes_per_cycle;
    for (Request& r : pending_) {
      if (budget == 0) break;
      if (r.present > t) continue;
      const int64_t take = std::min(budget, r.left);
      r.left -= take, budget -= take;
      if (r.left == 0) r.unit->data_back(r.item, r.tag, r.made, t + spec_.latency);
    }
    pending_.erase(std::remove_if(pending_.begin(), pending_.end(), [](const Request& r) { return r.left == 0; }),
                   pending_.end());
  }
  MemorySpec spec_;
  std::vector<Request> pending_;
};

// The raster: takes a triangle from its FIFO, walks it one step a II — hidden pixels
// need no register, a visible one waits for a free register and is handed on. With
// memory, a step whose depth read missed needs a miss entry (fewer than Q in flight; an
// entry is free the cycle after its data is back), and with Q = 0 the walk waits for
// the data before its next step.
class Walker : public Unit {
 public:
  Walker(sc_core::sc_module_name name, const BlockSpec& spec, Link& in, Link& out, const Workload& w,
         Measured& m, DramUnit* dram)
      : Unit(name, spec, out), in_(in), w_(w), m_(m), dram_(dram) {}
  bool done() const { return taken_ == w_.triangles.size() && cur_ < 0 && waiting_ == 0; }
  int64_t walk_end() const { return free_; }

  void data_back(int64_t item, int64_t tag, int64_t made, int64_t back) override {
    for (auto& e : entries_)
      if (e.first == tag) e.second = back;
    if (spec_.miss_queue == 0) {  // the walk waited for it
      const int64_t next = std::max(made + spec_.ii, back + 1);
      stats.blocked += next - (made + spec_.ii);
      free_ = next;
    }
    --waiting_;
    if (item >= 0) Unit::data_back(item, tag, made, back);  // a visible pixel
    else stats.memory_stall += std::max<int64_t>(back - made, 0);
  }

 private:
  bool triangle_left() const {
    const Triangle& tri = w_.triangles[size_t(cur_)];
    return hidden_ > 0 || pixel_ < tri.first_pixel + tri.pixels || trailing_ > 0;
  }
  void take(int64_t t) {
    cur_ = int64_t(in_fifo_.front());
    in_fifo_.pop_front();
    const Triangle& tri = w_.triangles[size_t(cur_)];
    m_.taken[size_t(cur_)] = t;
    last_take_ = t;
    ++taken_;
    pixel_ = tri.first_pixel;
    hidden_ = tri.pixels > 0 ? w_.pixels[pixel_].hidden : 0;
    trailing_ = tri.trailing;
    run_step_ = 0, miss_ = 0;
    stats.starved += starved_;
    starved_ = 0;
  }
  void step(int64_t t) {
    free_ = t + spec_.ii;
    stats.busy += spec_.ii;
    stats.blocked += blocked_;
    blocked_ = 0;
  }
  // The lines the next hidden step of the run moves (the run's misses, in order).
  uint32_t hidden_step_lines(const std::vector<std::pair<int64_t, uint32_t>>& misses) const {
    return miss_ < misses.size() && misses[miss_].first == run_step_ ? misses[miss_].second : 0;
  }
  // Whether a miss may start at t: an entry free (or, with no miss queue, none needed).
  bool entry_free(int64_t t) {
    entries_.erase(std::remove_if(entries_.begin(), entries_.end(), [&](const auto& e) { return e.second + 1 <= t; }),
                   entries_.end());
    return spec_.miss_queue == 0 || int64_t(entries_.size()) < spec_.miss_queue;
  }
  // The depth read of the step at t moved `lines`: ask the DRAM (item −1: a hidden pixel).
  void depth_read(int64_t t, uint32_t lines, int64_t item, DramUnit::Age age) {
    const int64_t tag = next_tag_++;
    entries_.push_back({tag, kNever});
    ++waiting_;
    dram_->request(age, t, int64_t(lines) * spec_.line_bytes, this, item, tag);
    if (spec_.miss_queue == 0) free_ = kNever;  // until the data is back
  }
  // A hidden step of a run whose misses are `misses`; false: it waits for an entry.
  bool hidden_step(int64_t t, const std::vector<std::pair<int64_t, uint32_t>>& misses) {
    const uint32_t lines = hidden_step_lines(misses);
    if (lines > 0 && !entry_free(t)) return false;
    step(t);
    if (lines > 0) depth_read(t, lines, -1, {int64_t(pixel_), 0, next_tag_}), ++miss_;
    ++run_step_;
    return true;
  }
  void edge() override {
    const int64_t t = cycle_now();
    const bool in = in_.valid.read() && in_.ready.read(), out = handing_over();
    if (t >= free_) {
      if (cur_ >= 0 && !triangle_left()) cur_ = -1;
      if (cur_ < 0 && !in_fifo_.empty() && t > last_take_) take(t);
      const Triangle* tri = cur_ >= 0 ? &w_.triangles[size_t(cur_)] : nullptr;
      if (tri && hidden_ > 0) {
        if (hidden_step(t, w_.pixels[pixel_].hidden_lines)) --hidden_;
        else blocked_ += 1;
      } else if (tri && pixel_ < tri->first_pixel + tri->pixels) {
        const uint32_t lines = w_.pixels[pixel_].depth_lines;
        if (room() && (lines == 0 || entry_free(t))) {
          m_.start[0][pixel_] = t;
          issue(t, int64_t(pixel_), 1, lines > 0);
          if (lines > 0) depth_read(t, lines, int64_t(pixel_), {int64_t(pixel_), 1, 0});
          ++pixel_;
          hidden_ = pixel_ < tri->first_pixel + tri->pixels ? w_.pixels[pixel_].hidden : 0;
          run_step_ = 0, miss_ = 0;
        } else {
          blocked_ += 1;
        }
      } else if (tri && trailing_ > 0) {
        if (hidden_step(t, tri->trailing_lines)) --trailing_;
        else blocked_ += 1;
      } else {
        starved_ += 1;  // no triangle to walk
      }
    }
    if (out) hand_over(t);
    if (in) in_fifo_.push_back(in_.data.read());
    drive_output(t);
    in_.ready.write(int64_t(in_fifo_.size()) < spec_.depth);
  }

  Link& in_;
  const Workload& w_;
  Measured& m_;
  DramUnit* dram_;
  std::deque<int64_t> in_fifo_;
  int64_t cur_ = -1, last_take_ = -1, hidden_ = 0, trailing_ = 0;
  size_t pixel_ = 0, taken_ = 0;
  int64_t run_step_ = 0;  // the hidden run's steps walked
  size_t miss_ = 0;       // the hidden run's misses walked
  std::vector<std::pair<int64_t, int64_t>> entries_;  // misses in flight: (tag, data back; kNever: not yet)
  int64_t next_tag_ = 0, waiting_ = 0;
};

// A span block: its input FIFO, its unit, its output.
class SpanUnit : public Unit {
 public:
  SpanUnit(sc_core::sc_module_name name, const BlockSpec& spec, size_t index, Link& in, Link& out,
           const Workload& w, std::vector<int64_t>& start, DramUnit* dram)
      : Unit(name, spec, out), index_(index), in_(in), w_(w), start_(start), dram_(dram) {}

 private:
  void edge() override {
    const int64_t t = cycle_now();
    const bool in = in_.valid.read() && in_.ready.read(), out = handing_over();
    if (t >= free_) {
      if (!fifo_.empty() && room()) {
        const int64_t n = fifo_.front();
        fifo_.pop_front();
        start_[size_t(n)] = t;
        const Pixel& p = w_.pixels[size_t(n)];
        const int64_t lines = dram_ && !p.lines.empty() ? int64_t(p.lines[index_]) : 0;
        issue(t, n, int64_t(p.work[index_]), lines > 0);
        if (lines > 0) dram_->request({n, 2 + int64_t(index_), 0}, t, lines * spec_.line_bytes, this, n, 0);
      } else {
        wait_cycle();
      }
    }
    if (out) hand_over(t);
    if (in) fifo_.push_back(in_.data.read());
    stats.fifo_cycles += int64_t(fifo_.size());
    stats.fifo_peak = std::max(stats.fifo_peak, int64_t(fifo_.size()));
    drive_output(t);
    in_.ready.write(int64_t(fifo_.size()) < spec_.depth);
  }

  size_t index_;
  Link& in_;
  const Workload& w_;
  std::vector<int64_t>& start_;
  DramUnit* dram_;
  std::deque<int64_t> fifo_;
};

// A span block whose unit is pins (UnitPins): its input FIFO here, the unit's issue,
// pipeline and output register in the RTL. At each edge: the unit took the item offered
// if it was ready; the output handshake is the RTL's valid and the next block's ready.
class PinsSpanUnit : public Unit {
 public:
  PinsSpanUnit(sc_core::sc_module_name name, const BlockSpec& spec, Link& in, Link& out, const Workload& w,
               std::vector<int64_t>& start, UnitPins& pins)
      : Unit(name, spec, out), in_(in), w_(w), start_(start), pins_(pins) {}

 private:
  void edge() override {
    const int64_t t = cycle_now();
    const bool in = in_.valid.read() && in_.ready.read(), out = handing_over();
    if (offered_ && pins_.in_ready()) {  // the RTL took the FIFO's head at this edge
      start_[size_t(fifo_.front())] = t;
      fifo_.pop_front();
    }
    if (out_.valid.read()) {
      const size_t item = size_t(out_.data.read());
      if (item >= handed->size())  // (a unit that puts out what it was never given)
        throw std::logic_error(spec_.name + ": the unit's pins put out item " + std::to_string(item) + ", of " +
                               std::to_string(handed->size()));
      if (valid && (*valid)[item] < 0) (*valid)[item] = t;
      if (out) (*handed)[item] = t, last = t, ++handed_count;
    }
    if (in) fifo_.push_back(in_.data.read());
    stats.fifo_cycles += int64_t(fifo_.size());
    stats.fifo_peak = std::max(stats.fifo_peak, int64_t(fifo_.size()));
    offered_ = !fifo_.empty();
    pins_.offer(offered_, offered_ ? fifo_.front() : 0, offered_ && w_.pixels[size_t(fifo_.front())].first);
    in_.ready.write(int64_t(fifo_.size()) < spec_.depth);
  }

  Link& in_;
  const Workload& w_;
  std::vector<int64_t>& start_;
  UnitPins& pins_;
  std::deque<int64_t> fifo_;
  bool offered_ = false;  // what the RTL sees in this cycle: the FIFO's head offered
};

// Stops the simulation once every pixel has left the last block and the walk is over,
// or at `bound` cycles (everything done one after another finishes before it).
class Monitor : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(Monitor);
  Monitor(sc_core::sc_module_name name, std::function<bool()> done, int64_t bound)
      : sc_core::sc_module(name), done_(std::move(done)), bound_(bound) {
    SC_METHOD(edge);
    sensitive << clk.pos();
    dont_initialize();
  }
  sc_core::sc_in<bool> clk;
  bool finished = false;

 private:
  void edge() {
    if (done_()) finished = true;
    if (finished || cycle_now() >= bound_) sc_core::sc_stop();
  }
  std::function<bool()> done_;
  int64_t bound_;
};

// A frame pass's block (the splat pass), timed as a whole: it begins at the main pass's
// end and is busy II·work cycles, then its latency. Returns the first cycle it is done.
int64_t run_pass(const PassLine& p, Measured& m) {
  Measured::Pass r;
  if (p.work >= 0) {
    r.arrival = m.main_end;
    r.busy = p.ii * p.work;
    r.last = r.arrival + r.busy + p.latency - 1;
  }
  m.passes.push_back(r);
  return r.last + 1;
}

}  // namespace

Measured run_clocked(const Workload& w, const std::string& pins_block, UnitPins* pins) {
  Measured m;
  const size_t line = w.blocks.size() - 1, pixels = w.pixels.size(), triangles = w.triangles.size();
  m.start.assign(line, std::vector<int64_t>(pixels, -1));
  m.valid = m.handed = m.start;
  m.setup_start.assign(triangles, -1);
  m.setup_handed = m.taken = m.setup_start;

  sc_core::sc_clock clk("clk", kPeriod);
  std::vector<std::unique_ptr<Link>> links;
  for (size_t j = 0; j <= line; ++j) links.push_back(std::make_unique<Link>());
  Source setup("setup", w, *links[0], m.setup_start);
  setup.handed = &m.setup_handed;
  std::unique_ptr<DramUnit> dram;
  if (w.memory) {
    dram = std::make_unique<DramUnit>("dram", *w.memory);
    dram->clk(clk);
  }
  Walker raster("raster", w.blocks[1], *links[0], *links[1], w, m, dram.get());
  raster.handed = &m.handed[0], raster.valid = &m.valid[0];
  std::vector<std::unique_ptr<Unit>> units;
  for (size_t j = 1; j < line; ++j) {
    const BlockSpec& spec = w.blocks[j + 1];
    if (pins && spec.name == pins_block) {
      units.push_back(std::make_unique<PinsSpanUnit>(spec.name.c_str(), spec, *links[j], *links[j + 1], w, m.start[j],
                                                     *pins));
      pins->bind(clk, links[j + 1]->valid, links[j + 1]->ready, links[j + 1]->data);
      m.pins_block = spec.name;
    } else {
      units.push_back(std::make_unique<SpanUnit>(spec.name.c_str(), spec, j - 1, *links[j], *links[j + 1], w,
                                                 m.start[j], dram.get()));
    }
    units.back()->handed = &m.handed[j], units.back()->valid = &m.valid[j];
  }
  if (pins && m.pins_block.empty())
    throw std::invalid_argument("the timing log has no span block named " + pins_block);
  setup.clk(clk), raster.clk(clk);
  for (auto& u : units) u->clk(clk);
  // Registers start empty: nothing valid, every FIFO ready — and the last block's
  // output always taken.
  for (auto& l : links) l->ready.write(true);
  const int64_t bound = int64_t(serial_cycles(w));  // no run can reach it (read_workload keeps it small)
  const Unit& last_block = units.empty() ? static_cast<const Unit&>(raster) : *units.back();
  auto done = [&] { return setup.done() && raster.done() && last_block.handed_count == pixels; };
  Monitor monitor("monitor", done, bound);
  monitor.clk(clk);

  const auto t0 = std::chrono::steady_clock::now();
  sc_core::sc_start();
  m.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  m.finished = monitor.finished;
  m.end = std::max(raster.walk_end(), setup.last + 1);
  m.end = std::max(m.end, raster.last + 1);
  for (auto& u : units) m.end = std::max(m.end, u->last + 1);
  m.main_end = m.end;
  for (const PassLine& p : w.passes) m.end = std::max(m.end, run_pass(p, m));
  m.stats.push_back(setup.stats);
  m.stats.push_back(raster.stats);
  for (auto& u : units) m.stats.push_back(u->stats);
  return m;
}

bool compare(const Workload& w, const Measured& m, std::string& report, size_t show) {
  std::ostringstream out;
  size_t mismatches = 0, compared = 0;
  auto check = [&](int64_t fast, int64_t clocked, const std::string& what) {
    ++compared;
    if (fast == clocked) return;
    if (mismatches++ < show) out << "  " << what << ": fast " << fast << ", clocked " << clocked << "\n";
  };
  if (!m.finished) out << "  the clocked model did not finish (a deadlock?)\n", ++mismatches;
  for (size_t k = 0; k < w.triangles.size(); ++k) {
    const Triangle& t = w.triangles[k];
    const std::string name = "triangle " + std::to_string(t.id);
    check(t.start, m.setup_start[k], name + " starts at setup");
    check(t.handed, m.setup_handed[k], name + " leaves setup");
    check(t.taken, m.taken[k], name + " taken by the raster");
  }
  for (size_t n = 0; n < w.pixels.size(); ++n) {
    const Pixel& p = w.pixels[n];
    for (size_t j = 0; j < p.start.size(); ++j) {
      const std::string name = "pixel (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ") at " + w.blocks[j + 1].name;
      check(p.start[j], m.start[j][n], name + ", start");
      check(p.valid[j], m.valid[j][n], name + ", valid at the output");
      check(p.handed[j], m.handed[j][n], name + ", hand-over");
    }
  }
  check(w.end, m.main_end, "the main pass's end");
  for (size_t k = 0; k < w.passes.size() && k < m.passes.size(); ++k) {
    const PassLine& p = w.passes[k];
    check(p.arrival, m.passes[k].arrival, p.name + " pass begins");
    check(p.busy, m.passes[k].busy, p.name + " busy cycles");
    check(p.last, m.passes[k].last, p.name + " last cycle");
  }
  if (w.frame_end >= 0) check(w.frame_end, m.end, "the frame's cycles");
  if (w.stats.size() != m.stats.size()) {
    ++mismatches;
    out << "  the log has statistics of " << w.stats.size() << " blocks, the pass " << m.stats.size() << "\n";
  }
  for (size_t j = 0; j < w.stats.size() && j < m.stats.size(); ++j) {
    const BlockStatsLine &a = w.stats[j], &b = m.stats[j];
    if (a.name != b.name && mismatches++ < show) out << "  statistics of " << a.name << " where " << b.name << " is\n";
    if (a.name != m.pins_block) {  // (the RTL's issue logic is not seen from its pins)
      check(a.busy, b.busy, a.name + " busy cycles");
      check(a.starved, b.starved, a.name + " starved cycles");
      check(a.blocked, b.blocked, a.name + " blocked cycles");
    }
    if (j >= 2) {  // span blocks: their FIFOs
      check(a.fifo_cycles, b.fifo_cycles, a.name + " FIFO pixel-cycles");
      check(a.fifo_peak, b.fifo_peak, a.name + " FIFO peak");
    }
    check(a.memory_stall, b.memory_stall, a.name + " memory stall cycles");  // (the raster's depth misses too)
  }
  std::ostringstream head;
  head << compared << " times compared (" << w.pixels.size() << " pixels, " << w.triangles.size()
       << " triangles, " << w.blocks.size() << " blocks";
  if (!m.pins_block.empty()) head << "; " << m.pins_block << " as RTL";
  head << "), " << mismatches << " different\n";
  report = head.str() + out.str();
  return mismatches == 0;
}

}  // namespace shadetlm::timing_reference
