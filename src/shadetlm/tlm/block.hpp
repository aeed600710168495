#pragma once
// The pipeline as data (docs/development.md, "Adding a block"): each block declares
// itself once, beside its kernel, as a BlockDecl — its name, its settings, its default
// timing, when a scene needs it and how its kernel is built — and the pipeline is an
// ordered list of passes of such declarations (modules/pipeline/pipeline.hpp,
// standard_pipeline()). Both engines, the settings table, the statistics and the trace
// attachments are derived from that list; nothing else names a block.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "shadetlm/core/pipeline_config.hpp"
#include "shadetlm/core/scene.hpp"
#include "shadetlm/tlm/stage.hpp"
#include "shadetlm/tlm/packet.hpp"
#include "shadetlm/stats/report.hpp"
#include "shadetlm/memory/cache.hpp"

namespace shadetlm::modules {

// What a block is built from: the scene and every resolved setting. Reading its own
// settings needs no prefix (`ctx.string("mode")` is `<block>.mode`).
struct BlockContext {
  const core::Scene& scene;
  const core::Settings& settings;
  const std::string& name;

  const std::string& string(const std::string& key) const { return settings.string(name + "." + key); }
  int integer(const std::string& key) const { return settings.integer(name + "." + key); }
  double number(const std::string& key) const { return settings.number(name + "." + key); }
  bool boolean(const std::string& key) const { return settings.boolean(name + "." + key); }
  core::NumberFormat format() const { return settings.format(name); }
};

class Block;

// The loop engine's span blocks in order, called for every packet the raster puts out.
// (A type of its own, not a std::function: the raster's walk calls it inline.)
struct SpanChain {
  std::vector<Block*> blocks;
  uint64_t pixels = 0;  // that reached the end of the chain
  void operator()(SpanPacket& p);
};

// One elaborated block: its kernel, seen by both engines. The loop engine calls the
// kernel through it; the SystemC engine asks it for the module around the kernel.
class Block {
 public:
  enum class Kind {
    Source,  // starts a pass: triangles out (setup)
    Raster,  // triangles in, span packets out
    Span,    // span packets in and out
    Frame,   // a pass of its own over the frame, run when the pass before has ended
  };
  virtual ~Block() = default;
  virtual Kind kind() const = 0;

  // The loop engine: the source sets up every triangle and hands it to the raster,
  // whose packets go through the chain of span blocks.
  virtual void run_pass(Block& /*raster*/, SpanChain&) {}  // Source
  virtual void emit_spans(const TriangleSetup&, SpanChain&) {}  // Raster
  virtual void process(SpanPacket&) {}  // Span: bypass or work
  // The end of the pass before reaches every block in order: a block may hand data on
  // in it (the framebuffer its frame), a Frame block runs its pass.
  virtual void end_pass(PassEnd&) {}
  virtual void set_progress(std::function<void(double)>) {}  // Source: share of the frame done

  // The SystemC engine: the module around the kernel (a BlockInfo that is an sc_module).
  virtual std::unique_ptr<BlockInfo> module(const char* name, Timing timing, sc_core::sc_time period) = 0;
  // The values its waveform probe shows, in the order the module records them; "name:int"
  // for an integer (a 32-bit signal), the others are reals.
  virtual std::vector<std::string> trace_names() const { return {}; }

  // Statistics, after the run: its operations, and what else it counted into its own
  // report or the frame's (the framebuffer hands over the frame here).
  virtual Ops ops() const = 0;
  virtual void finish(BlockReport&, RenderResult&) {}
};

inline void SpanChain::operator()(SpanPacket& p) {
  for (Block* b : blocks) b->process(p);
  pixels += uint64_t(p.count);
}

struct BlockDecl {
  std::string name;                         // of its folder, settings, statistics, module
  Timing timing;                            // defaults of <name>.latency, .ii and .fifo_depth
  bool formatted = false;                   // has a <name>.format (a datapath in a number format)
  std::vector<core::SettingSpec> settings;  // its own, keys without "<name>."
  std::function<bool(const core::Scene&)> needed;  // empty: always elaborated
  // Builds the block, e.g. std::make_unique<SpanBlock<K>>(kernel arguments…): the
  // kernel is built in place (kernels may point into themselves).
  std::function<std::unique_ptr<Block>(const BlockContext&)> make;
  // Its input FIFO (<name>.fifo_depth): of pixels, of triangles (the raster), or none
  // (setup, the source; a frame pass).
  enum class Fifo { None, Pixels, Triangles } fifo = Fifo::Pixels;
  // The arithmetic units on its critical path for its settings (a mode): their latency
  // is added to <name>.latency, and its II is at least theirs. Empty: none.
  std::function<Timing(const BlockContext&)> units = nullptr;
  // A memory client (docs/memory.md): under pipeline.memory.model = dram it reads (or
  // writes) through a cache of its own, <name>.cache.{size,line,ways,layout}, and may
  // hold <name>.miss_queue pixels waiting for memory.
  bool memory = false;
  // Its kernel writes test vectors (`render --vectors`, trace/test_vectors.hpp).
  bool vectors = false;
};

// A memory client's cache under the DRAM model; none under ideal memory. Throws
// core::InputError naming the scene and the setting if it is not a cache.
std::optional<CacheConfig> cache_of(const BlockContext& ctx);

// An arithmetic unit's latency and II (pipeline.unit.<name>.latency and .ii, docs/
// configuration.md "Arithmetic units").
inline Timing unit(const core::Settings& s, const std::string& name) {
  return {uint64_t(s.integer("unit." + name + ".latency")), uint64_t(s.integer("unit." + name + ".ii")), 0};
}
// Units one after another: latencies add, the slowest II paces them.
inline Timing operator+(Timing a, Timing b) { return {a.latency + b.latency, std::max(a.ii, b.ii), 0}; }
inline Timing operator*(uint64_t n, Timing t) { return {n * t.latency, n > 0 ? t.ii : 1, 0}; }

// A block of a kernel and the SystemC module built around it as
// Module(name, kernel, timing, period).
template <class Kernel, class Module>
class KernelBlock : public Block {
 public:
  template <class... Args>
  explicit KernelBlock(Args&&... args) : kernel(std::forward<Args>(args)...) {}
  Kernel kernel;

  std::unique_ptr<BlockInfo> module(const char* name, Timing timing, sc_core::sc_time period) override {
    return std::make_unique<Module>(name, kernel, timing, period);
  }
  Ops ops() const override { return kernel.ops(); }
};

// The span kernels' optional reports, found by their signatures.
template <class K, class = void> struct has_ranges : std::false_type {};
template <class K> struct has_ranges<K, std::void_t<decltype(std::declval<const K&>().ranges())>> : std::true_type {};
template <class K, class = void> struct has_numbers : std::false_type {};
template <class K> struct has_numbers<K, std::void_t<decltype(std::declval<const K&>().numbers())>> : std::true_type {};
template <class K, class = void> struct has_details : std::false_type {};
template <class K> struct has_details<K, std::void_t<decltype(std::declval<const K&>().details())>> : std::true_type {};
template <class K, class = void> struct has_memory : std::false_type {};
template <class K> struct has_memory<K, std::void_t<decltype(std::declval<const K&>().memory())>> : std::true_type {};
template <class K, class = void> struct has_precompute : std::false_type {};
template <class K>
struct has_precompute<K, std::void_t<decltype(std::declval<const K&>().precompute_seconds())>> : std::true_type {};

// A span block (Stage<K> in SystemC): K has process, bypass, work, ops, trace_names,
// trace and set_capture (modules/README.md), and may have ranges(), numbers(),
// details() (JSON), precompute_seconds(), memory() and end_pass(PassEnd&), which are reported
// or called where present.
template <class K>
class SpanBlock : public KernelBlock<K, Stage<K>> {
 public:
  using KernelBlock<K, Stage<K>>::KernelBlock;
  using KernelBlock<K, Stage<K>>::kernel;

  Block::Kind kind() const override { return Block::Kind::Span; }
  void process(SpanPacket& p) override {
    if (!kernel.bypass(p)) kernel.process(p);
  }
  void end_pass(PassEnd& e) override {
    if constexpr (has_end_pass<K>::value) kernel.end_pass(e);
  }
  std::vector<std::string> trace_names() const override { return K::trace_names(); }
  void finish(BlockReport& b, RenderResult& r) override {
    if constexpr (has_ranges<K>::value) b.ranges = kernel.ranges();
    if constexpr (has_numbers<K>::value) b.numbers = kernel.numbers();
    if constexpr (has_details<K>::value) b.details = kernel.details();
    if constexpr (has_precompute<K>::value) r.precompute_s += kernel.precompute_seconds();
    if constexpr (has_memory<K>::value) {
      if (const MemoryClient* m = kernel.memory()) b.stats.memory = memory_stats(*m, b.stats.memory_stall_cycles);
    }
  }
};

// A pass: blocks joined in a chain. The first pass starts with a Source block; a later
// one is started by the end of the pass before (PassEnd), which every block forwards.
struct PassDecl {
  std::string name;
  std::vector<BlockDecl> blocks;
};

struct PipelineDecl {
  std::vector<core::SettingSpec> settings;  // the pipeline's own (clock_mhz, number_format, …)
  std::vector<PassDecl> passes;             // in order

  // Every block's name, in pipeline order.
  std::vector<std::string> block_names() const;
  // The settings table: the pipeline's own, then each block's (latency, ii, format and
  // its own, named <block>.<key>).
  std::vector<core::SettingSpec> all_settings() const;
  // Adds `block` right after the block named `after` (a testbench's or a user's block);
  // throws std::invalid_argument if there is none of that name or the name is taken.
  void insert_after(const std::string& after, BlockDecl block);
};

}  // namespace shadetlm::modules
