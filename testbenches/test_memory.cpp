// The memory model (docs/memory.md): the cache against a second, plainer model of
// itself, the layouts' addresses, the DRAM's calendar on an example worked by hand,
// and what the DRAM model does to a frame. (The clocked reference checks the DRAM's
// timing on whole frames: testbenches/timing_check_test.sh.)
#include <catch2/catch.hpp>

#include <algorithm>
#include <list>
#include <random>
#include <set>

#include "shadetlm/timing/main_pass.hpp"
#include "shadetlm/memory/cache.hpp"
#include "shadetlm/memory/dram.hpp"
#include "shadetlm/modules/pipeline/pipeline.hpp"
#include "test_util.hpp"

using namespace shadetlm;
using modules::Cache;
using modules::CacheConfig;
using modules::Layout;

namespace {

// An LRU cache as a list per set, most recent first: what Cache must count.
struct PlainLru {
  CacheConfig c;
  std::vector<std::list<std::pair<uint64_t, bool>>> sets;  // (line, dirty)
  uint64_t hits = 0, misses = 0, writebacks = 0;
  explicit PlainLru(CacheConfig config) : c(config), sets(config.size / config.line / config.ways) {}
  void access(uint64_t address, bool write) {
    const uint64_t line = address / c.line;
    auto& set = sets[line % sets.size()];
    auto it = std::find_if(set.begin(), set.end(), [&](const auto& e) { return e.first == line; });
    if (it != set.end()) {
      ++hits;
      const bool dirty = it->second || write;
      set.erase(it);
      set.push_front({line, dirty});
      return;
    }
    ++misses;
    if (set.size() == c.ways) {
      writebacks += set.back().second;
      set.pop_back();
    }
    set.push_front({line, write});
  }
};

}  // namespace

TEST_CASE("Cache: hits, misses and write-backs as a plain LRU list counts them", "[memory]") {
  std::mt19937 rng(7);
  for (const CacheConfig& c : {CacheConfig{1024, 64, 1}, CacheConfig{1024, 64, 4}, CacheConfig{4096, 32, 128},
                               CacheConfig{256, 256, 1}, CacheConfig{16384, 64, 16}}) {
    INFO("cache " << c.size << " B, lines of " << c.line << ", " << c.ways << " ways");
    Cache cache(c);
    PlainLru plain(c);
    // Addresses with locality (a walk) and without (jumps), reads and writes.
    uint64_t address = 0;
    uint64_t moved = 0;
    for (int k = 0; k < 20000; ++k) {
      address = rng() % 4 == 0 ? rng() % (64 * c.size) : address + rng() % 96;
      const bool write = rng() % 3 == 0;
      moved += cache.access(address, write);
      plain.access(address, write);
    }
    CHECK(cache.counts().hits == plain.hits);
    CHECK(cache.counts().misses == plain.misses);
    CHECK(cache.counts().writebacks == plain.writebacks);
    CHECK(moved == plain.misses + plain.writebacks);  // what access() said it moved
    CHECK(cache.counts().accesses == 20000);
    CHECK(plain.misses > 0);
    CHECK(plain.hits > 0);
  }
}

TEST_CASE("Cache: refuses what is no cache, naming the setting", "[memory]") {
  CHECK(modules::check({1000, 64, 1}).setting == "size");
  CHECK(modules::check({1024, 48, 1}).setting == "line");
  CHECK(modules::check({256, 512, 1}).setting == "line");
  CHECK(modules::check({1024, 64, 3}).setting == "ways");
  CHECK(modules::check({1024, 64, 0}).setting == "ways");
  CHECK(modules::check({1024, 64, 32}).setting == "ways");  // 16 lines
  CHECK(modules::check({1024, 64, 16}).setting.empty());
}

TEST_CASE("Layouts: every element its own address inside its surface, a line a tile", "[memory]") {
  for (Layout layout : {Layout::Linear, Layout::Tiled, Layout::Morton})
    for (const auto& [w, h, bytes, line] : {std::tuple{13, 7, 4u, 64u}, std::tuple{16, 16, 8u, 64u},
                                            std::tuple{5, 9, 4u, 16u}, std::tuple{3, 2, 16u, 8u}}) {
      INFO(modules::layout_names()[size_t(layout)] << " " << w << "×" << h << ", " << bytes << " B, lines of " << line);
      modules::Surface s{4096, w, h, bytes};
      modules::tile_for(s, line);
      const uint64_t size = modules::surface_bytes(layout, s, line);
      CHECK(size % line == 0);
      std::set<uint64_t> seen;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const uint64_t a = modules::address(layout, s, x, y);
          CHECK(a >= s.base);
          CHECK(a + bytes <= s.base + size);
          CHECK(a % bytes == 0);
          CHECK(seen.insert(a).second);
        }
    }
  // Tiled, 4-byte texels in 64-byte lines: 4×4 tiles; linear: a row is contiguous.
  modules::Surface s{0, 64, 64, 4};
  modules::tile_for(s, 64);
  auto line_of = [&](Layout l, int x, int y) { return modules::address(l, s, x, y) / 64; };
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) CHECK(line_of(Layout::Tiled, x, y) == line_of(Layout::Tiled, 0, 0));
  CHECK(line_of(Layout::Tiled, 4, 0) != line_of(Layout::Tiled, 0, 0));
  CHECK(line_of(Layout::Tiled, 0, 4) != line_of(Layout::Tiled, 0, 0));
  CHECK(line_of(Layout::Linear, 15, 0) == line_of(Layout::Linear, 0, 0));
  CHECK(line_of(Layout::Linear, 0, 1) != line_of(Layout::Linear, 0, 0));
  // Morton: x in the even bits, y in the odd ones.
  CHECK(modules::address(Layout::Morton, s, 1, 0) == 4);
  CHECK(modules::address(Layout::Morton, s, 0, 1) == 8);
  CHECK(modules::address(Layout::Morton, s, 3, 3) == 15 * 4);
  CHECK(modules::address(Layout::Morton, s, 63, 0) == 0x555 * 4);  // 0b111111 spread
}

TEST_CASE("Dram: oldest first, each request taking what the older ones left, worked by hand", "[memory]") {
  modules::Dram dram({10, 4});  // latency 10, 4 bytes a cycle
  // A (oldest), made in cycle 0, 8 bytes: cycles 1 and 2, back at 12.
  CHECK(dram.request(0, 8) == 12);
  // B, made in cycle 0, 6 bytes: cycles 3 (4 bytes) and 4 (2 bytes), back at 14.
  CHECK(dram.request(0, 6) == 14);
  // C, made in cycle 3 (present from 4), 4 bytes: 2 left in cycle 4, then cycle 5.
  CHECK(dram.request(3, 4) == 15);
  // D, younger but made later still, in cycle 9: the DRAM is idle from 6, cycle 10.
  CHECK(dram.request(9, 3) == 20);
  // E, the youngest, made in cycle 0: cycles 1 to 4 are full, cycle 5 has 2 bytes left.
  CHECK(dram.request(0, 1) == 15);
  // F, made in cycle 0, 4 bytes: 1 byte left in cycle 5, then cycles 6 to 9 were idle —
  // the calendar fills the gap before D's cycle 10.
  CHECK(dram.request(0, 4) == 16);
  CHECK(dram.bytes() == 26);
  dram.forget_before(100);  // nothing is made before 100 any more
  CHECK(dram.request(100, 4000) == 101 + 999 + 10);  // 1000 cycles of 4 bytes from 101: the calendar grows
}

TEST_CASE("Dram: the calendar of runs against one of every cycle, on random requests", "[memory]") {
  std::mt19937 rng(11);
  for (uint64_t per_cycle : {1u, 3u, 7u, 32u}) {
    INFO(per_cycle << " bytes a cycle");
    modules::Dram dram({5, per_cycle});
    std::vector<uint64_t> taken(1 << 21, 0);  // the plain calendar: bytes taken per cycle (enough for every byte asked)
    int64_t base = 0;
    for (int k = 0; k < 3000; ++k) {
      if (rng() % 50 == 0) base += int64_t(rng() % 40), dram.forget_before(base);  // time moves on
      const int64_t made = base + int64_t(rng() % 60);
      const uint64_t asked = 1 + rng() % (rng() % 8 == 0 ? 400 : 40);
      uint64_t bytes = asked;
      int64_t t = made + 1;
      for (;; ++t) {  // oldest first: what the requests before left of each cycle
        const uint64_t take = std::min(per_cycle - taken[size_t(t)], bytes);
        taken[size_t(t)] += take, bytes -= take;
        if (bytes == 0) break;
      }
      REQUIRE(dram.request(made, asked) == t + 5);  // the last byte's cycle, then the latency
    }
  }
}

TEST_CASE("DRAM model: the DRAM's bytes are the clients' lines, the same in both engines", "[memory]") {
  // (Cycles against cache size, bandwidth and miss queue: testbenches/memory_test.sh,
  // a process a configuration.)
  core::Scene scene = core::load_scene(test::source_path("golden/bump-plane/scene.json"),
                                       {"pipeline.memory.model=dram"});
  const nlohmann::json sc = modules::render_systemc(scene).stats_json();
  const nlohmann::json loop = modules::render_loop(scene).stats_json();
  REQUIRE(sc["memory"]["model"] == "dram");
  uint64_t sum = 0;
  for (const auto& [name, bytes] : sc["memory"]["dram_bytes_by_client"].items()) {
    INFO(name);
    const auto& m = sc["blocks"][name]["memory"];
    CHECK(bytes.get<uint64_t>() == (m["misses"].get<uint64_t>() + m["writebacks"].get<uint64_t>()) * 64);
    CHECK(m["hits"].get<uint64_t>() + m["misses"].get<uint64_t>() == m["accesses"].get<uint64_t>());
    sum += bytes.get<uint64_t>();
    // The caches are the kernels': the plain loop counts the same.
    CHECK(loop["blocks"][name]["memory"]["misses"] == m["misses"]);
    CHECK(loop["blocks"][name]["memory"]["hits"] == m["hits"]);
  }
  CHECK(sum == sc["memory"]["dram_bytes"].get<uint64_t>());
  CHECK(sum > 0);
  // Every covered pixel written once: each colour line read once, written back once.
  const auto& fb = sc["blocks"]["framebuffer"]["memory"];
  CHECK(fb["accesses"].get<uint64_t>() == sc["pixels"]["shaded"].get<uint64_t>());
  CHECK(fb["writebacks"].get<uint64_t>() == fb["misses"].get<uint64_t>());
  CHECK(sc["blocks"]["bump_fetch"]["memory"]["stall_cycles"].get<uint64_t>() > 0);
}
