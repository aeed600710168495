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
#include "shadetlm/core/setting_fields.hpp"
#include "shadetlm/tlm/stage.hpp"
#include "shadetlm/tlm/packet.hpp"
#include "shadetlm/stats/report.hpp"
#include "shadetlm/memory/cache.hpp"
#include "shadetlm/tlm/settings.hpp"

namespace shadetlm::modules {

// The settings struct S of block S::block, read from resolved settings.
template <class S>
S read_settings(const core::Settings& settings) {
  return core::read<S>(settings, std::string(S::block) + ".");
}

// What a block is built from: the scene and every resolved setting, typed: the
// pipeline's own, the block's basics, and its own settings struct as ctx.read<S>()
// (S::block names the block whose settings it holds; core/setting_fields.hpp).
struct BlockContext {
  const core::Scene& scene;
  const core::Settings& settings;  // every resolved value, by key (what read<S>() reads)
  const std::string& name;
  const PipelineSettings& pipeline;
  const BlockBasics& basics;

  template <class S>
  S read() const {
    return read_settings<S>(settings);
  }
  // Its datapath's number format: its own, or the pipeline's where that is "default".
  core::NumberFormat format() const {
    return core::NumberFormat::parse(basics.format.name == "default" ? pipeline.number_format.name : basics.format.name);
  }
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

// A block's declaration, its fields set by name (modules/normalize/normalize_block.cpp):
//   BlockDecl d = declare<NormalizeSettings>();  // its name and its own settings' table
//   d.basics.timing = {1, 1};                     // the defaults of latency and ii
//   d.make = [](const BlockContext& ctx) { … ctx.read<NormalizeSettings>() … };
struct BlockDecl {
  std::string name;  // of its folder, settings, statistics, module
  // What it has (an input FIFO, a cache, a number format) and the defaults of its
  // <name>.latency, .ii and .fifo_depth (tlm/settings.hpp).
  BlockBasics basics;
  std::vector<core::SettingSpec> settings;         // its own, keys without "<name>." (specs_of its struct)
  std::function<bool(const core::Scene&)> needed;  // empty: always elaborated
  // Builds the block, e.g. std::make_unique<SpanBlock<K>>(kernel arguments…): the
  // kernel is built in place (kernels may point into themselves).
  std::function<std::unique_ptr<Block>(const BlockContext&)> make;
  // The arithmetic units on its critical path for its settings (a mode): their latency
  // is added to <name>.latency, and its II is at least theirs. Empty: none.
  std::function<Timing(const BlockContext&)> units = nullptr;
  // Its kernel writes test vectors (`render --vectors`, trace/test_vectors.hpp).
  bool vectors = false;
};

// The declaration of the block whose own settings are the struct S: its name S::block
// and its settings' table from S's fields and defaults.
template <class S>
BlockDecl declare() {
  BlockDecl d;
  d.name = S::block;
  d.settings = core::specs_of(S{});
  return d;
}
// A block with no settings of its own.
inline BlockDecl declare(const std::string& name) {
  BlockDecl d;
  d.name = name;
  return d;
}

// A memory client's cache under the DRAM model; none under ideal memory. Throws
// core::InputError naming the scene and the setting if it is not a cache.
std::optional<CacheConfig> cache_of(const BlockContext& ctx);

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

// A span block (Stage<K> in SystemC): K has process, bypass, work, ops, trace_names,
// trace and set_capture (modules/README.md), and the optional parts it names
// (tlm/kernel_parts.hpp), which are reported or called.
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
