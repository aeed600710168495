#pragma once
// The SystemC side shared by the blocks: statistics, the main pass's timing (MainPassTiming,
// timing/main_pass.hpp) and Stage<K>, the thin TLM-2.0 module around a span kernel K.
//
// A span packet travels through the whole chain by b_transport, each block computing
// its values and saying how much work each pixel was; once back at the raster, the
// packet's pixels are timed in one sweep (no wait() per pixel: loosely timed). The
// packet's delay annotation is the cycle the raster sent it, unchanged along the chain.
#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>

#include "shadetlm/numeric/ops.hpp"
#include "shadetlm/tlm/kernel_parts.hpp"
#include "shadetlm/tlm/packet.hpp"
#include "shadetlm/stats/report.hpp"
#include "shadetlm/trace/timeline.hpp"
#include "shadetlm/timing/main_pass.hpp"
#include "shadetlm/trace/trace.hpp"
#include "shadetlm/trace/test_vectors.hpp"

namespace shadetlm::modules {


// A frame pass's calendar (texel_project): work arriving at `arrival` starts when the
// block is free and keeps it busy II·work cycles.
class Schedule {
 public:
  explicit Schedule(Timing t) : timing_(t) {}
  void occupy(uint64_t arrival, uint64_t work) {
    const uint64_t start = std::max(arrival, free_);
    times_.add_busy(int64_t(start), timing_.ii * work);
    free_ = start + timing_.ii * work;
    times_.last = int64_t(free_ + timing_.latency) - 1;
  }
  const BlockTimes& times() const { return times_; }
  BlockTimes& times() { return times_; }
  const Timing& timing() const { return timing_; }

 private:
  Timing timing_;
  uint64_t free_ = 0;
  BlockTimes times_;
};

// What every block reports, whatever its kind.
class BlockInfo : public TimedObserver {
 public:
  virtual ~BlockInfo() = default;
  virtual std::string block_name() const = 0;
  virtual BlockStats stats() const = 0;
  virtual const Timing& timing() const = 0;
  virtual const BlockTimes& times() const = 0;
  // Where its times are kept: the main pass's MainPassTiming, at `slot` (the raster is 0; the
  // source, setup, reads the raster's FIFO depth from it). Frame passes keep their own.
  virtual void join_line(MainPassTiming*, int /*slot*/) {}
  // (Inspection, once a packet's pixels are timed: TimedObserver::timed.)
  // Keep utilization over time in bins of `cycles`.
  virtual void keep_histogram(uint64_t cycles) = 0;
  // A frame pass's block (texel_project): the cycle the pass began (the main pass's end)
  // and the work it scheduled, for the timing log (−1: not run; not a frame pass).
  struct PassWork {
    int64_t arrival = -1, work = -1;
  };
  virtual PassWork pass_work() const { return {}; }

  // Its place in a chain: the socket packets come in by (none at a pass's source), and
  // its output bound to the next block's input (left unbound at the end of the chain).
  virtual tlm::tlm_target_socket<32>* input() { return nullptr; }
  virtual void bind_output(tlm::tlm_target_socket<32>&) {}
  // The last block of a pass: its output reaches the next pass, which takes the end of
  // the pass and no packets (so none are sent).
  void set_last_of_pass() { last_of_pass_ = true; }

  // Inspection (docs/inspecting.md): waveforms of a region, the transaction timeline.
  // `filter`: the traced region and triangles (nullptr: everything), which limits the
  // timeline as well as the waveforms.
  void attach(Tracer* tracer, int probe, Timeline* timeline, uint32_t track, const TraceRegion* filter) {
    tracer_ = tracer, probe_ = probe, timeline_ = timeline, track_ = track, filter_ = filter;
  }
  // Test vectors (trace/test_vectors.hpp): what a block that has them writes, and
  // where (the region and triangles of attach()'s filter).
  virtual std::optional<VectorLayout> vector_layout() const { return std::nullopt; }
  void attach_vectors(VectorFile* vectors) { vectors_ = vectors; }

 protected:
  bool triangle_kept(uint32_t id) const {
    return !filter_ || (id >= filter_->triangle_first && id <= filter_->triangle_last);
  }

  const TraceRegion* filter_ = nullptr;
  VectorFile* vectors_ = nullptr;
  Tracer* tracer_ = nullptr;
  int probe_ = -1;
  Timeline* timeline_ = nullptr;
  uint32_t track_ = 0;
  bool last_of_pass_ = false;

  // Its FIFO in the timeline, for every packet traced or not (bypassed too): each pixel
  // from the end of its hand-over's cycle to its start, as the stats' fifo_cycles count.
  void count_fifo(const SpanPacket& p, const MainPassTiming& line, int slot) {
    if (timeline_ && slot > 0)
      for (int i = 0; i < p.count; ++i)
        timeline_->count(track_, uint64_t(line.handed(slot - 1, i)), uint64_t(line.start(slot, i)));
  }

  // Records the timed packet's pixels at `slot` of `line`: each pixel's values at the
  // cycle the block hands it on, and a timeline slice from its first start to its last
  // hand-over.
  template <class Values>
  void record_timed(const SpanPacket& p, const MainPassTiming& line, int slot, Values values) {
    count_fifo(p, line, slot);
    if (!triangle_kept(p.tri->id)) return;
    if (tracer_ && probe_ >= 0 && tracer_->region().covers(p.y, p.x0, p.x0 + p.count, p.tri->id)) {
      double v[16];
      for (int i = 0; i < p.count; ++i) {
        if (!tracer_->region().contains(p.x0 + i, p.y)) continue;
        values(i, v);
        tracer_->record(probe_, uint64_t(line.valid_from(slot, i)), uint64_t(line.handed(slot, i)), p.x0 + i, p.y,
                        p.tri->id, v);
      }
    }
    if (timeline_ && (!filter_ || filter_->covers(p.y, p.x0, p.x0 + p.count, p.tri->id))) {
      const int64_t first = line.start(slot, 0), last = line.handed(slot, p.count - 1);
      uint64_t stalled_pixels = 0;  // cycles its pixels waited, done, for room downstream
      for (int i = 0; i < p.count; ++i) stalled_pixels += uint64_t(line.handed(slot, i) - line.valid_from(slot, i));
      const uint64_t stalled = uint64_t(last - line.valid_from(slot, p.count - 1));  // the last one's: the slice's tail
      timeline_->add_packet(track_, uint64_t(first), uint64_t(last + 1 - first), uint32_t(p.count), p.tri->id, p.y, p.x0,
                            stalled, stalled_pixels);
    }
  }
};

// Whether a transaction is the end of a pass (PassEnd) rather than a packet: a
// platform's driver that leaves the command unset (TLM_IGNORE_COMMAND) still sends
// packets, as long as its data length is not that of a PassEnd.
inline bool is_pass_end(const tlm::tlm_generic_payload& trans) {
  return trans.get_command() == tlm::TLM_IGNORE_COMMAND && trans.get_data_length() == sizeof(PassEnd);
}

// A block's packet input: a plain TLM-2.0 target socket bound to the block, which
// implements the forward interface itself — one virtual call a packet. (tlm_utils'
// simple_target_socket adds a callback hop of about 30 instructions a packet and block,
// 4 % of the Phong path's run: docs/performance.md.) Blocking transport only.
class PacketTarget : public tlm::tlm_fw_transport_if<> {
 public:
  tlm::tlm_sync_enum nb_transport_fw(tlm::tlm_generic_payload&, tlm::tlm_phase&, sc_core::sc_time&) override {
    SC_REPORT_ERROR("shadetlm", "the blocks take blocking transport (b_transport) only");
    return tlm::TLM_COMPLETED;
  }
  bool get_direct_mem_ptr(tlm::tlm_generic_payload&, tlm::tlm_dmi&) override { return false; }
  unsigned int transport_dbg(tlm::tlm_generic_payload&) override { return 0; }
};

// The SystemC module around a span kernel: packets in, kernel, packets out; the work
// of each pixel into the main pass's MainPassTiming.
template <class Kernel>
class Stage : public sc_core::sc_module, public BlockInfo, public PacketTarget {
  static_assert(optional_parts_checked<Kernel>());

 public:
  tlm::tlm_target_socket<32> in;
  tlm_utils::simple_initiator_socket_optional<Stage> out;  // unbound at the last block

  Stage(sc_core::sc_module_name name, Kernel& kernel, Timing timing, sc_core::sc_time)
      : sc_core::sc_module(name), in("in"), out("out"), kernel_(kernel), timing_(timing) {
    in.bind(*this);
  }

  std::string block_name() const override { return basename(); }
  BlockStats stats() const override {
    BlockStats s = stats_;
    s.ops = kernel_.ops();
    const BlockTimes& t = times();
    s.busy_cycles = t.busy, s.starved_cycles = t.starved, s.blocked_cycles = t.blocked;
    s.fifo_cycles = t.fifo_cycles, s.fifo_peak = t.fifo_peak;
    s.fifo_measured = line_ != nullptr;
    s.memory_stall_cycles = t.memory_stall;
    return s;
  }
  const Timing& timing() const override { return timing_; }
  const BlockTimes& times() const override { return line_ ? line_->times(slot_) : alone_; }
  void join_line(MainPassTiming* line, int slot) override { line_ = line, slot_ = slot; }
  void keep_histogram(uint64_t cycles) override {
    if (line_) line_->times(slot_).bin_cycles = cycles;
  }
  tlm::tlm_target_socket<32>* input() override { return &in; }
  void bind_output(tlm::tlm_target_socket<32>& next) override { out.bind(next); }
  std::optional<VectorLayout> vector_layout() const override {
    if constexpr (has_vectors<Kernel>::value) return kernel_.vector_layout();
    return std::nullopt;
  }

  void timed(const SpanPacket& p) override {  // its waveforms and timeline slice
    if (!kTracing || !line_ || p.count == 0) return;
    if (!worked_) return count_fifo(p, *line_, slot_);  // bypassed: no values, no slice
    record_timed(p, *line_, slot_, [&](int i, double* v) { std::copy(traced_values_[i], traced_values_[i] + 16, v); });
  }

 private:
  // The next block's interface, once bound (what out-> returns, without the port's
  // checks on every packet).
  // Span packets stop at the last block of their pass: only its end goes on to the next.
  void end_of_elaboration() override {
    next_ = out.size() > 0 ? out.operator->() : nullptr;
    packet_next_ = last_of_pass_ ? nullptr : next_;
  }

  void b_transport(tlm::tlm_generic_payload& trans, sc_core::sc_time& delay) override {
    if (is_pass_end(trans)) return end_pass(trans, delay);
    SpanPacket& p = *reinterpret_cast<SpanPacket*>(trans.get_data_ptr());
    if (kernel_.bypass(p)) {
      // Through the bypass wire: no work (a cycle a pixel, docs/pipeline.md). Kept this
      // short (a tail call, the work in a function of its own) because every packet
      // crosses every elaborated block of its pass.
      ++stats_.bypassed;
      if (line_) line_->set_work(slot_, Work{});
      else count_alone(Work{}, p.count);
      worked_ = false;
      trans.set_response_status(tlm::TLM_OK_RESPONSE);
      if (packet_next_) packet_next_->b_transport(trans, delay);
      return;
    }
    work(trans, p, delay);
  }

  [[gnu::noinline]] void work(tlm::tlm_generic_payload& trans, SpanPacket& p, sc_core::sc_time& delay) {
    if constexpr (kTracing) {
      // (The tracer's region is the filter, when one is given.)
      traced_ = tracer_ && tracer_->region().covers(p.y, p.x0, p.x0 + p.count, p.tri->id);
      if (tracer_) kernel_.set_capture(traced_);
    }
    const bool vectors = has_vectors<Kernel>::value && vectors_ && triangle_kept(p.tri->id);
    if (vectors) vector_inputs(p);
    kernel_.process(p);
    if (vectors) vector_outputs(p);
    ++stats_.packets;
    stats_.pixels += uint64_t(p.count);
    // The waveforms' values now: a later block may rewrite the packet's arrays (normalize
    // its normals) before the packet is timed.
    if (kTracing && traced_)
      for (int i = 0; i < p.count; ++i)
        if (tracer_->region().contains(p.x0 + i, p.y)) kernel_.trace(p, i, traced_values_[i]);
    if (line_) line_->set_work(slot_, kernel_.work(p));
    else count_alone(kernel_.work(p), p.count);
    worked_ = true;
    trans.set_response_status(tlm::TLM_OK_RESPONSE);
    if (packet_next_) packet_next_->b_transport(trans, delay);
  }

  [[gnu::noinline]] void end_pass(tlm::tlm_generic_payload& trans, sc_core::sc_time& delay) {
    PassEnd& e = *reinterpret_cast<PassEnd*>(trans.get_data_ptr());
    if constexpr (has_end_pass<Kernel>::value) kernel_.end_pass(e);  // (the raster has set e.cycle: it holds the line)
    trans.set_response_status(tlm::TLM_OK_RESPONSE);
    if (next_) next_->b_transport(trans, delay);
  }

  // Test vectors: every packet that touches the region, whole (a block may carry state
  // from a packet's first pixel to the next: the forward-difference radicand) — its
  // words in (before the kernel), then out.
  bool in_vector_region(const SpanPacket& p) const { return !filter_ || filter_->covers(p.y, p.x0, p.x0 + p.count, p.tri->id); }
  void vector_inputs(const SpanPacket& p) {
    if constexpr (has_vectors<Kernel>::value) {
      vector_in_.resize(size_t(kSpanMax) * kMaxVectorFields);
      if (in_vector_region(p))
        for (int i = 0; i < p.count; ++i) kernel_.vector_in(p, i, &vector_in_[size_t(i) * kMaxVectorFields]);
    }
  }
  void vector_outputs(const SpanPacket& p) {
    if constexpr (has_vectors<Kernel>::value) {
      uint64_t out[kMaxVectorFields];
      if (in_vector_region(p))
        for (int i = 0; i < p.count; ++i) {
          kernel_.vector_out(p, i, out);
          vectors_->add(p.x0 + i, p.y, &vector_in_[size_t(i) * kMaxVectorFields], out);
        }
    }
  }

  // A block on its own (a testbench, a platform of one's own: no MainPassTiming) still counts
  // its busy cycles, II · work a pixel; its times need a pipeline.
  void count_alone(Work w, int count) {
    for (int i = 0; i < count; ++i) alone_.busy += std::max<uint64_t>(timing_.ii * w.at(i), 1);
  }

  Kernel& kernel_;
  Timing timing_;
  MainPassTiming* line_ = nullptr;  // none in a testbench of the block alone
  int slot_ = 0;
  bool traced_ = false, worked_ = false;  // the packet now passing: traced, not bypassed
  double traced_values_[kSpanMax][16] = {};  // its waveform values, for the traced pixels
  BlockStats stats_;
  BlockTimes alone_;
  std::vector<uint64_t> vector_in_;  // a packet's vector inputs, while vectors are written
  tlm::tlm_fw_transport_if<>* next_ = nullptr;         // the next block
  tlm::tlm_fw_transport_if<>* packet_next_ = nullptr;  // the same, unless this block ends its pass
};

}  // namespace shadetlm::modules
