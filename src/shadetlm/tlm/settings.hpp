#pragma once
// The settings every pipeline has, as structs (core/setting_fields.hpp): the pipeline's
// own (PipelineSettings: pipeline.<key>) and those each block has by its declaration
// (BlockBasics: pipeline.<block>.<key>). A block's own settings are a struct of its own,
// beside it (e.g. modules/normalize/normalize_settings.hpp). Each field is declared once,
// in fields(); its default is the member's initializer (docs/configuration.md lists them).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "shadetlm/core/setting_fields.hpp"
#include "shadetlm/memory/cache.hpp"
#include "shadetlm/memory/dram.hpp"
#include "shadetlm/timing/timing.hpp"

namespace shadetlm::modules {

struct PipelineSettings {
  double clock_mhz = 500;
  core::FormatName number_format{"float32"};
  enum class Elaborate { Needed, All } elaborate = Elaborate::Needed;
  // Memory (docs/memory.md): ideal (every access hits, no bandwidth limit) or the memory
  // clients' caches in front of one shared DRAM.
  enum class Memory { Ideal, Dram } memory = Memory::Ideal;
  DramTiming dram;
  // The arithmetic units (docs/configuration.md, "Arithmetic units"): single-precision
  // latency and reciprocal throughput of Intel Skylake's ADDSS, MULSS, DIVSS, SQRTSS and
  // RSQRTSS (Agner Fog, Instruction tables, 2022), the throughput rounded up to whole
  // cycles; log2 and exp2 have no x86 instruction: assumed a table and a polynomial step,
  // as the estimate.
  struct Units {
    Timing add{4, 1}, mul{4, 1}, div{11, 3}, sqrt{12, 3}, rsqrt_table{4, 1}, log2{4, 1}, exp2{4, 1};
  } unit;

  // The DRAM's timing under memory.model = dram (none: ideal memory).
  std::optional<DramTiming> dram_timing() const {
    return memory == Memory::Dram ? std::optional<DramTiming>(dram) : std::nullopt;
  }

  template <class F>
  void fields(F& f) {
    // Read by the SystemC pipeline (`shadetlm render`); the golden model reads none.
    f(clock_mhz, "clock_mhz", {1, 100000}, "clock of every block, for simulated time");
    f(number_format, "number_format",
      "number format of every datapath: float32, float16 or fixed:I.F (docs/numerical-stability.md)");
    f(elaborate, "elaborate", {"needed", "all"},
      "elaborate the blocks some material needs, or every block (to measure what skipping saves)");
    f(memory, "memory.model", {"ideal", "dram"}, "ideal memory, or caches and a shared DRAM (docs/memory.md)");
    f(dram.latency, "memory.latency", {1, 100000}, "cycles from a DRAM request's last byte to its data in the block");
    f(dram.bytes_per_cycle, "memory.bytes_per_cycle", {1, 4096}, "the DRAM's bandwidth, shared by its clients");
    const struct { Timing& t; const char* name; const char* what; } units[] = {
        {unit.add, "add", "floating-point adder"},
        {unit.mul, "mul", "floating-point multiplier"},
        {unit.div, "div", "divider"},
        {unit.sqrt, "sqrt", "square root"},
        {unit.rsqrt_table, "rsqrt_table", "reciprocal square root estimate (table)"},
        {unit.log2, "log2", "base-2 logarithm (the specular power)"},
        {unit.exp2, "exp2", "base-2 exponential (the specular power)"},
    };
    for (const auto& u : units) {
      const std::string key = std::string("unit.") + u.name;
      f(u.t.latency, key + ".latency", {1, 10000}, std::string("latency of the ") + u.what);
      f(u.t.ii, key + ".ii", {1, 10000}, std::string("cycles between operations of the ") + u.what);
    }
  }

};

// What every block has, by what its declaration says it is (BlockDecl): its timing, its
// input FIFO, its cache and miss queue as a memory client, its number format. The
// defaults of latency, ii and fifo_depth are its declaration's.
struct BlockBasics {
  Timing timing;
  CacheConfig cache;
  uint64_t miss_queue = 64;
  core::FormatName format{"default"};
  // Which of them it has (from its declaration; not settings).
  enum class Fifo { None, Pixels, Triangles } fifo = Fifo::Pixels;
  bool memory = false, formatted = false;

  template <class F>
  void fields(F& f) {
    f(timing.latency, "latency", {1, 1000000}, "cycles from a pixel's start to its hand-over (docs/pipeline.md, Timing)");
    f(timing.ii, "ii", {1, 1000000}, "cycles per unit of work");
    if (fifo != Fifo::None)
      f(timing.fifo_depth, "fifo_depth", {1, 65536},
        fifo == Fifo::Triangles ? "triangles its input FIFO holds" : "pixels its input FIFO holds");
    if (memory) {
      // At most 16 MiB, 2^20 lines and 64 ways: a cache of silicon, and a model that fits
      // in memory and looks up a line in a few steps.
      f(cache.size, "cache.size", {16, 1 << 24}, "bytes of its cache (a power of two)");
      f(cache.line, "cache.line", {16, 4096}, "bytes of its cache's line (a power of two)");
      f(cache.ways, "cache.ways", {1, 64}, "its cache's associativity (dividing its lines)");
      f(cache.layout, "cache.layout", layout_names(),
        "how its surfaces lie in memory: linear, tiled (a line a tile) or morton");
      if (fifo != Fifo::None)  // (a frame pass is timed as a whole)
        f(miss_queue, "miss_queue", {0, 65536}, "pixels it may hold waiting for memory, besides its pipeline registers");
    }
    if (formatted)
      f(format, "format", "number format of the block's datapath (default: pipeline.number_format)");
  }
};

}  // namespace shadetlm::modules
