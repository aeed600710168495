#pragma once
// The SystemC side shared by the blocks: timing bookkeeping, statistics, and Stage<K>,
// the thin TLM-2.0 module around a span kernel K.
//
// Timing model (docs/pipeline.md): each block has a latency L and an initiation
// interval II (cycles per unit of work: a pixel, a walker step, a pixel-light, a
// triangle). Blocks are joined by unbounded queues: a packet arriving at cycle t starts
// at max(t, the cycle the block becomes free), keeps it busy II·work cycles, and
// reaches the next block L cycles after it started. Arrival cycles travel in the
// packet; the b_transport delay annotation carries the same time relative to the
// simulation time, zero once that has passed (loosely timed, no wait() per pixel).
#include <algorithm>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>

#include "shadetlm/modules/common/ops.hpp"
#include "shadetlm/modules/common/packet.hpp"
#include "shadetlm/modules/common/report.hpp"
#include "shadetlm/modules/common/timeline.hpp"
#include "shadetlm/modules/common/trace.hpp"

namespace shadetlm::modules {


// A block's calendar: when it is free, how long it has been busy.
class Schedule {
 public:
  explicit Schedule(Timing t) : timing_(t) {}
  // Books II·work cycles for work arriving at `arrival`; returns the cycle its first
  // result reaches the next block.
  [[gnu::always_inline]] uint64_t occupy(uint64_t arrival, uint64_t work) {
    const uint64_t start = std::max(arrival, free_);
    const uint64_t busy = timing_.ii * work;
    free_ = start + busy;
    busy_ += busy;
    last_start_ = start;
    last_busy_ = busy;
    if (bin_cycles_ > 0) histogram(start, busy);
    return start + timing_.latency;
  }
  uint64_t free_cycle() const { return free_; }
  uint64_t busy_cycles() const { return busy_; }
  uint64_t last_start() const { return last_start_; }
  uint64_t last_busy() const { return last_busy_; }
  const Timing& timing() const { return timing_; }

  // Busy cycles per bin of `bin_cycles` (0: not kept).
  void keep_histogram(uint64_t bin_cycles) { bin_cycles_ = bin_cycles; }
  const std::vector<uint64_t>& busy_per_bin() const { return bins_; }

 private:
  // Out of line, so that occupy(), called for every packet, stays small and inlined.
  void histogram(uint64_t start, uint64_t busy);

  Timing timing_;
  uint64_t free_ = 0, busy_ = 0, last_start_ = 0, last_busy_ = 0, bin_cycles_ = 0;
  std::vector<uint64_t> bins_;
};

// What every block reports, whatever its kind.
class BlockInfo {
 public:
  virtual ~BlockInfo() = default;
  virtual std::string block_name() const = 0;
  virtual BlockStats stats() const = 0;
  virtual const Schedule& schedule() const = 0;
  virtual Schedule& schedule() = 0;

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

 protected:
  bool triangle_kept(uint32_t id) const {
    return !filter_ || (id >= filter_->triangle_first && id <= filter_->triangle_last);
  }

  const TraceRegion* filter_ = nullptr;
  Tracer* tracer_ = nullptr;
  int probe_ = -1;
  Timeline* timeline_ = nullptr;
  uint32_t track_ = 0;
  bool last_of_pass_ = false;

  // A pass ends here once this block has put out its last result.
  void pass_end(PassEnd& e) const { e.cycle = std::max(e.cycle, schedule().free_cycle() + schedule().timing().latency); }
};

// Whether a transaction is the end of a pass (PassEnd) rather than a packet: a
// platform's driver that leaves the command unset (TLM_IGNORE_COMMAND) still sends
// packets, as long as its data length is not that of a PassEnd.
inline bool is_pass_end(const tlm::tlm_generic_payload& trans) {
  return trans.get_command() == tlm::TLM_IGNORE_COMMAND && trans.get_data_length() == sizeof(PassEnd);
}

// Forwards a transaction to `next` (a bound socket's interface; none after the last
// block) with the delay annotation of `cycle`: its time relative to `now`, the
// simulation time (which no blocking call along a packet's way through the blocks
// advances, so the caller may know it without asking the kernel).
inline void forward(tlm::tlm_fw_transport_if<>* next, tlm::tlm_generic_payload& trans, uint64_t cycle,
                    const sc_core::sc_time& period, const sc_core::sc_time& now) {
  if (!next) return;  // the last block
  const sc_core::sc_time at = period * double(cycle);
  sc_core::sc_time delay = at > now ? at - now : sc_core::SC_ZERO_TIME;
  next->b_transport(trans, delay);
}
template <class Socket>
void forward(Socket& socket, tlm::tlm_generic_payload& trans, uint64_t cycle, const sc_core::sc_time& period,
             const sc_core::sc_time& now) {
  forward(socket.size() > 0 ? socket.operator->() : nullptr, trans, cycle, period, now);
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

// The SystemC module around a span kernel: packets in, kernel, packets out.
template <class Kernel>
class Stage : public sc_core::sc_module, public BlockInfo, public PacketTarget {
 public:
  tlm::tlm_target_socket<32> in;
  tlm_utils::simple_initiator_socket_optional<Stage> out;  // unbound at the last block

  Stage(sc_core::sc_module_name name, Kernel& kernel, Timing timing, sc_core::sc_time period)
      : sc_core::sc_module(name), in("in"), out("out"), kernel_(kernel), schedule_(timing), period_(period) {
    in.bind(*this);
  }

  std::string block_name() const override { return basename(); }
  BlockStats stats() const override {
    BlockStats s = stats_;
    s.ops = kernel_.ops();
    s.busy_cycles = schedule_.busy_cycles();
    return s;
  }
  const Schedule& schedule() const override { return schedule_; }
  Schedule& schedule() override { return schedule_; }
  tlm::tlm_target_socket<32>* input() override { return &in; }
  void bind_output(tlm::tlm_target_socket<32>& next) override { out.bind(next); }

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
      // Through the bypass wire: no work, no cycles; the packet goes on with the time
      // annotation it came with. Kept this short (a tail call, the work in a function
      // of its own) because every packet crosses every elaborated block of its pass.
      ++stats_.bypassed;
      trans.set_response_status(tlm::TLM_OK_RESPONSE);
      if (packet_next_) packet_next_->b_transport(trans, delay);
      return;
    }
    work(trans, p, delay);
  }

  [[gnu::noinline]] void work(tlm::tlm_generic_payload& trans, SpanPacket& p, const sc_core::sc_time& delay) {
    // The packet's delay annotation is its arrival cycle's time relative to now: where
    // it is positive, the delay it leaves with is that plus the cycles it spent here
    // (no call into the kernel for the time, a packet and block); else the time is
    // asked for.
    const uint64_t arrival = p.cycle;
    if (!kTracing || (!tracer_ && !timeline_)) {  // nothing inspected: the fast path
      kernel_.process(p);
      ++stats_.packets;
      stats_.pixels += uint64_t(p.count);
      p.cycle = schedule_.occupy(p.cycle, kernel_.work(p));
    } else {
      const bool kept = !filter_ || filter_->covers(p.y, p.x0, p.x0 + p.count, p.tri->id);
      const bool traced = tracer_ && kept;
      kernel_.set_capture(traced);
      kernel_.process(p);
      ++stats_.packets;
      stats_.pixels += uint64_t(p.count);
      p.cycle = schedule_.occupy(p.cycle, kernel_.work(p));
      if (traced) record(p);
      if (timeline_ && kept)
        timeline_->add(track_, schedule_.last_start(), schedule_.last_busy(), uint32_t(p.count), p.tri->id);
    }
    trans.set_response_status(tlm::TLM_OK_RESPONSE);
    if (!packet_next_) return;
    if (delay > sc_core::SC_ZERO_TIME) {  // now = arrival − delay: the new delay follows from the old
      sc_core::sc_time later = delay + period_ * double(p.cycle - arrival);
      packet_next_->b_transport(trans, later);
    } else {
      forward(packet_next_, trans, p.cycle, period_, sc_core::sc_time_stamp());
    }
  }

  [[gnu::noinline]] void end_pass(tlm::tlm_generic_payload& trans, sc_core::sc_time& delay) {
    PassEnd& e = *reinterpret_cast<PassEnd*>(trans.get_data_ptr());
    if constexpr (has_end_pass<Kernel>::value) kernel_.end_pass(e);
    pass_end(e);
    trans.set_response_status(tlm::TLM_OK_RESPONSE);
    if (next_) next_->b_transport(trans, delay);
  }

  // Pixel i leaves at the packet's first result plus its share of the packet's busy
  // cycles before it (exact where every pixel is the same work, e.g. II per light in
  // lighting; spread evenly where it is not, e.g. the walker's steps through gaps).
  void record(const SpanPacket& p) {
    double values[16];
    const uint64_t busy = schedule_.last_busy();
    for (int i = 0; i < p.count; ++i) {
      if (!tracer_->region().contains(p.x0 + i, p.y)) continue;
      kernel_.trace(p, i, values);
      tracer_->record(probe_, p.cycle + busy * uint64_t(i) / uint64_t(p.count), p.x0 + i, p.y, p.tri->id, values);
    }
  }

  Kernel& kernel_;
  Schedule schedule_;
  sc_core::sc_time period_;
  BlockStats stats_;
  tlm::tlm_fw_transport_if<>* next_ = nullptr;         // the next block
  tlm::tlm_fw_transport_if<>* packet_next_ = nullptr;  // the same, unless this block ends its pass
};

}  // namespace shadetlm::modules
