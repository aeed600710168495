#include "shadetlm/stats/report.hpp"

#include <algorithm>

#include "shadetlm/cost/silicon.hpp"

namespace shadetlm::modules {

const BlockReport* RenderResult::bottleneck() const {
  const BlockReport* best = nullptr;
  for (const auto& b : blocks)
    if (!best || b.stats.busy_cycles > best->stats.busy_cycles) best = &b;
  return best;
}

Ops RenderResult::total_ops() const {
  Ops o;
  for (const auto& b : blocks) o += b.stats.ops;
  return o;
}

// Area, energy and power of every block's operators and of the whole (docs/silicon.md);
// it also writes each block's own figures into its entry of `blocks_json`.
nlohmann::json RenderResult::silicon_json(nlohmann::json& blocks_json) const {
  double area_um2 = 0, energy_pj = 0;
  uint64_t unpriced_ops = 0;
  nlohmann::json unpriced_blocks = nlohmann::json::array();
  for (const auto& b : blocks) {
    const std::string format = b.numbers ? b.numbers->format : "float32";
    const uint64_t items = b.stats.pixels > 0 ? b.stats.pixels : b.stats.packets;  // setup: triangles
    const bool counted = frame_cycles > 0;  // the loop has no timing: no cycles, no units
    // The cycles it computed in: busy, less a cycle for each pixel it only passed on.
    const uint64_t work_cycles = b.stats.busy_cycles - std::min(b.stats.bypassed, b.stats.busy_cycles);
    const cost::BlockSilicon s = cost::block_silicon(b.stats.ops, work_cycles, core::NumberFormat::parse(format),
                                                     "pipeline." + b.name + ".format");
    nlohmann::json& bj = blocks_json[b.name]["silicon"];
    bj = {{"format", format}, {"priced", s.priced}};
    if (!s.priced) {
      bj["why"] = s.why;
      unpriced_blocks.push_back(b.name);
      continue;
    }
    nlohmann::json units = nlohmann::json::object();
    for (size_t k = 0; k < std::size(cost::kOperations); ++k) units[cost::name_of(cost::kOperations[k])] = s.units[k];
    bj["units"] = counted ? units : nlohmann::json();
    bj["area_mm2"] = counted ? nlohmann::json(s.area_um2 * 1e-6) : nlohmann::json();
    bj["energy_nj"] = s.energy_pj * 1e-3;
    bj["energy_nj_per_item"] = counted && items > 0 ? nlohmann::json(s.energy_pj * 1e-3 / double(items)) : nlohmann::json();
    bj["unpriced_ops"] = s.unpriced_ops;
    area_um2 += s.area_um2, energy_pj += s.energy_pj, unpriced_ops += s.unpriced_ops;
  }
  nlohmann::json j = {{"node", cost::kNode},
                      {"activity", cost::kActivity},
                      {"priced", "the arithmetic operators of each block (add, mul, div, sqrt, rsqrt); not its "
                                 "registers, tables, caches or the DRAM"},
                      {"area_mm2", frame_cycles > 0 ? nlohmann::json(area_um2 * 1e-6) : nlohmann::json()},
                      {"energy_nj", energy_pj * 1e-3},
                      {"energy_nj_per_shaded_pixel",
                       pixels_shaded > 0 ? nlohmann::json(energy_pj * 1e-3 / double(pixels_shaded)) : nlohmann::json()},
                      {"unpriced_ops", unpriced_ops},
                      {"unpriced_blocks", unpriced_blocks}};
  // Power at the model's clock: the frame's energy over its simulated time. The loop has
  // no timing and counts no block's pixels: no power and no area (null).
  j["power_mw"] = frame_cycles > 0 ? nlohmann::json(energy_pj * 1e-3 * clock_mhz / double(frame_cycles)) : nlohmann::json();
  return j;
}

nlohmann::json RenderResult::stats_json() const {
  nlohmann::json j;
  j["engine"] = engine;
  j["wall_s"] = wall_s;
  j["clock_mhz"] = clock_mhz;
  j["frame_cycles"] = frame_cycles;
  j["sim_time_s"] = double(frame_cycles) / (clock_mhz * 1e6);
  j["bottleneck"] = frame_cycles > 0 && bottleneck() ? nlohmann::json(bottleneck()->name) : nlohmann::json();
  j["precompute_s"] = precompute_s;
  j["nonfinite_replaced"] = nonfinite_replaced;
  j["elaborated"] = nlohmann::json::array();
  for (const auto& b : blocks) j["elaborated"].push_back(b.name);
  j["triangles"] = {{"in", triangles_in}, {"drawn", triangles_drawn}};
  j["pixels"] = {{"walked", pixels_walked}, {"hidden", pixels_hidden}, {"shaded", pixels_shaded}};
  j["blocks"] = nlohmann::json::object();
  // Every block's non-finite outputs and number events, summed (docs/numerical-stability.md).
  nlohmann::json numbers = {{"nonfinite", uint64_t(0)}, {"overflows", uint64_t(0)}, {"invalid", uint64_t(0)}};
  for (const auto& b : blocks) {
    nlohmann::json bj = {{"packets", b.stats.packets},     {"pixels", b.stats.pixels},
                         {"bypassed", b.stats.bypassed},   {"busy_cycles", b.stats.busy_cycles},
                         {"latency", b.timing.latency},    {"ii", b.timing.ii},
                         {"ops", b.stats.ops.to_json()}};
    bj["utilization"] = frame_cycles > 0 ? double(b.stats.busy_cycles) / double(frame_cycles) : 0.0;
    if (frame_cycles > 0) {  // the timing model's (docs/pipeline.md, "Timing")
      bj["last_cycle"] = b.last_cycle;  // its last hand-over: every latency shows in it
      bj["starved_cycles"] = b.stats.starved_cycles;
      bj["blocked_cycles"] = b.stats.blocked_cycles;
      if (b.timing.fifo_depth > 0) bj["fifo_depth"] = b.timing.fifo_depth;  // none: setup, texel_project
      if (b.stats.fifo_measured) {  // the span blocks' (the raster's FIFO of triangles is not measured)
        bj["fifo_peak"] = b.stats.fifo_peak;
        bj["fifo_mean"] = double(b.stats.fifo_cycles) / double(frame_cycles);
      }
    }
    if (b.stats.memory) {  // docs/memory.md
      const MemoryStats& m = *b.stats.memory;
      const Cache::Counts& c = m.counts;
      bj["memory"] = {{"cache", {{"size", m.cache.size}, {"line", m.cache.line}, {"ways", m.cache.ways},
                                 {"layout", layout_names()[size_t(m.cache.layout)]}}},
                      {"accesses", c.accesses},
                      {"hits", c.hits},
                      {"misses", c.misses},
                      {"writebacks", c.writebacks + m.flushed},
                      {"writebacks_at_end", m.flushed},  // dirty at the frame's end (not timed)
                      {"hit_rate", c.accesses > 0 ? double(c.hits) / double(c.accesses) : 1.0},
                      {"dram_bytes", m.dram_bytes()},
                      {"stall_cycles", m.stall_cycles}};
    }
    if (!b.ranges.empty()) bj["ranges"] = to_json(b.ranges);
    if (!b.details.is_null()) bj["details"] = b.details;
    if (b.numbers) {
      bj["numbers"] = {{"format", b.numbers->format},
                       {"nonfinite", b.numbers->counted ? nlohmann::json(b.numbers->nonfinite) : nlohmann::json()},
                       {"overflows", b.numbers->events.overflows}, {"invalid", b.numbers->events.invalid}};
      numbers["nonfinite"] = numbers["nonfinite"].get<uint64_t>() + b.numbers->nonfinite;
      numbers["overflows"] = numbers["overflows"].get<uint64_t>() + b.numbers->events.overflows;
      numbers["invalid"] = numbers["invalid"].get<uint64_t>() + b.numbers->events.invalid;
    }
    j["blocks"][b.name] = bj;
  }
  j["numbers"] = numbers;
  // The shared memory: DRAM bytes by client, and per shaded pixel (docs/memory.md).
  nlohmann::json memory = {{"model", dram ? "dram" : "ideal"}};
  if (dram) {
    uint64_t bytes = 0;
    nlohmann::json by_client = nlohmann::json::object(), per_pixel_by_client = nlohmann::json::object();
    const double shaded = double(std::max<uint64_t>(pixels_shaded, 1));
    for (const auto& b : blocks)
      if (b.stats.memory) {
        bytes += b.stats.memory->dram_bytes();
        by_client[b.name] = b.stats.memory->dram_bytes();
        per_pixel_by_client[b.name] = double(b.stats.memory->dram_bytes()) / shaded;
      }
    memory["latency"] = dram->latency, memory["bytes_per_cycle"] = dram->bytes_per_cycle;
    memory["dram_bytes"] = bytes;
    memory["dram_bytes_per_shaded_pixel"] = double(bytes) / shaded;
    memory["dram_bytes_by_client"] = by_client;
    memory["dram_bytes_per_shaded_pixel_by_client"] = per_pixel_by_client;
    memory["bandwidth_use"] = frame_cycles > 0 ? double(bytes) / (double(frame_cycles) * double(dram->bytes_per_cycle)) : 0.0;
  }
  j["memory"] = memory;
  if (bin_cycles > 0 && frame_cycles > 0) {
    // Utilization over time: each block's busy share of every bin, and the busiest
    // block per bin.
    nlohmann::json over_time = {{"bin_cycles", bin_cycles}, {"blocks", nlohmann::json::object()}};
    const size_t bins = size_t((frame_cycles + bin_cycles - 1) / bin_cycles);
    std::vector<std::pair<uint64_t, std::string>> busiest(bins, {0, ""});
    for (const auto& b : blocks) {
      std::vector<double> share(bins, 0.0);
      for (size_t i = 0; i < bins && i < b.busy_per_bin.size(); ++i) {
        const uint64_t length = std::min<uint64_t>(bin_cycles, frame_cycles - i * bin_cycles);  // last one partial
        share[i] = double(b.busy_per_bin[i]) / double(length);
        if (b.busy_per_bin[i] > busiest[i].first) busiest[i] = {b.busy_per_bin[i], b.name};
      }
      over_time["blocks"][b.name] = share;
      j["blocks"][b.name]["idle_cycles"] = frame_cycles - b.stats.busy_cycles;
    }
    nlohmann::json names = nlohmann::json::array();
    for (const auto& [busy, name] : busiest) names.push_back(busy > 0 ? nlohmann::json(name) : nlohmann::json());
    over_time["bottleneck"] = names;
    if (dram) {  // the DRAM's share of its bandwidth per bin (docs/memory.md)
      std::vector<double> use(bins, 0.0);
      for (size_t i = 0; i < bins && i < dram_bytes_per_bin.size(); ++i) {
        const uint64_t length = std::min<uint64_t>(bin_cycles, frame_cycles - i * bin_cycles);
        use[i] = double(dram_bytes_per_bin[i]) / (double(length) * double(dram->bytes_per_cycle));
      }
      over_time["dram"] = use;
    }
    j["utilization_over_time"] = over_time;
  }
  j["silicon"] = silicon_json(j["blocks"]);
  const nlohmann::json total = total_ops().to_json();
  j["ops"] = total;
  nlohmann::json per_pixel;
  const double n = pixels_shaded > 0 ? double(pixels_shaded) : 1.0;
  for (const auto& [kind, count] : total.items()) per_pixel[kind] = count.get<double>() / n;
  j["ops_per_shaded_pixel"] = per_pixel;
  return j;
}

}  // namespace shadetlm::modules
