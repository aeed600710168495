// The fast timing model (timing/main_pass.hpp) on an example small enough to work
// by hand — the worked example of docs/pipeline.md. (The clocked reference checks it on
// whole frames: testbenches/timing_check_test.sh.)
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>

#include "shadetlm/timing/main_pass.hpp"

using namespace shadetlm;

TEST_CASE("MainPassTiming: four pixels through a raster and two blocks, worked by hand", "[timing]") {
  // raster: L 1, II 1 (C = 2); A: L 2, II 1, FIFO 1 (C = 3); B: L 1, II 2, FIFO 1 (C = 1).
  modules::MainPassTiming line({{1, 1, 4}, {2, 1, 1}, {1, 2, 1}});
  line.keep_times = true;
  line.set_work(1, {nullptr, 1});
  line.set_work(2, {nullptr, 1});
  CHECK(line.start_triangle(0) == 1);  // in the raster's FIFO from the cycle after setup handed it on
  modules::SpanPacket p{};
  p.count = 4;
  line.sweep(p, 0);
  // {start, valid at the output, handed on} of each pixel at raster, A, B.
  const int64_t expected[4][3][3] = {
      {{1, 2, 2}, {3, 5, 5}, {6, 7, 7}},
      {{2, 3, 4}, {5, 7, 7}, {8, 9, 9}},     // raster: A's FIFO of one is full until A starts pixel 0 (3)
      {{3, 5, 6}, {7, 9, 9}, {10, 11, 11}},  // B takes 2 cycles a pixel: A waits for its FIFO
      {{5, 7, 8}, {9, 11, 11}, {12, 13, 13}},  // raster: both its registers full until 4 leaves
  };
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) {
      INFO("pixel " << i << ", block " << j);
      CHECK(line.start(j, i) == expected[i][j][0]);
      CHECK(line.valid_from(j, i) == expected[i][j][1]);
      CHECK(line.handed(j, i) == expected[i][j][2]);
    }
  line.settle();
  CHECK(line.end() == 14);
  CHECK(line.times(0).blocked == 1);  // pixel 3 at the raster: cycle 4
  CHECK(line.times(1).busy == 4);
  CHECK(line.times(1).starved == 6);  // A: free at 0 until 3, then 4, 6, 8 until 5, 7, 9
  CHECK(line.times(1).fifo_peak == 1);
  CHECK(line.times(2).busy == 8);
  CHECK(line.times(2).starved == 6);
}

namespace {
// The figures a block's timing counted, the same in two timings of one pass.
void check_same_times(const modules::BlockTimes& a, const modules::BlockTimes& b) {
  CHECK(a.busy == b.busy);
  CHECK(a.starved == b.starved);
  CHECK(a.blocked == b.blocked);
  CHECK(a.fifo_cycles == b.fifo_cycles);
  CHECK(a.fifo_peak == b.fifo_peak);
  CHECK(a.last == b.last);
  CHECK(a.busy_per_bin == b.busy_per_bin);
}
}  // namespace

// The sweep has two forms (timing.hpp, "Order of the sweep"): inspected (every time
// kept, as the timing log and the clocked reference see them) and not (a block's uniform
// work folded, its FIFO's oldest pixel no longer followed once the peak is the depth).
// Both must count the same on any configuration: random ones here, with seeds printed;
// and a uniform block's work (Work::lead included) the same as that work spelled per pixel.
TEST_CASE("MainPassTiming: the inspected sweep and the plain one count the same", "[timing]") {
  for (uint32_t seed = 1; seed <= 300; ++seed) {
    std::mt19937 rng(seed);
    auto pick = [&](int lo, int hi) { return int(std::uniform_int_distribution<int>(lo, hi)(rng)); };
    std::vector<modules::Timing> blocks(size_t(pick(2, 6)));
    for (auto& t : blocks) t = {uint64_t(pick(1, 40)), uint64_t(pick(1, 6)), uint64_t(pick(1, 16))};
    // spelled: the same work, a uniform block's given per pixel (its lead on the first)
    modules::MainPassTiming inspected(blocks), plain(blocks), spelled(blocks);
    inspected.time_every_block();  // (the recurrence on every block: the reference)
    inspected.keep_times = true;
    const uint64_t bin = uint64_t(pick(1, 60));  // (utilization over time: the same histogram)
    for (size_t j = 0; j < blocks.size(); ++j)
      for (auto* line : {&inspected, &plain, &spelled}) line->times(int(j)).bin_cycles = bin;
    std::vector<std::vector<uint16_t>> work(blocks.size(), std::vector<uint16_t>(modules::kSpanMax));
    std::vector<std::vector<uint16_t>> spelled_work = work;
    int64_t arrival = 0;
    for (int packet = 0; packet < 60; ++packet) {
      if (pick(0, 3) == 0) {  // a new triangle, after some hidden steps
        const int64_t taken = inspected.start_triangle(arrival);
        REQUIRE(plain.start_triangle(arrival) == taken);
        REQUIRE(spelled.start_triangle(arrival) == taken);
        arrival = taken + pick(0, 30);
      }
      modules::SpanPacket p{};
      p.count = pick(1, modules::kSpanMax);
      for (size_t j = 1; j < blocks.size(); ++j) {
        // uniform (0: bypassed), with a lead on the first pixel or not, or per pixel
        modules::Work w{nullptr, uint32_t(pick(0, 3)), nullptr, uint32_t(pick(0, 1) ? pick(1, 5) : 0)};
        if (pick(0, 1)) {
          for (int i = 0; i < p.count; ++i) work[j][size_t(i)] = uint16_t(pick(0, 4));
          w = {work[j].data(), 0};
        }
        for (int i = 0; i < p.count; ++i) spelled_work[j][size_t(i)] = uint16_t(w.at(i));
        inspected.set_work(int(j), w), plain.set_work(int(j), w);
        spelled.set_work(int(j), {spelled_work[j].data(), 0});
      }
      const uint64_t hidden = uint64_t(pick(0, 5));
      inspected.sweep(p, hidden), plain.sweep(p, hidden), spelled.sweep(p, hidden);
    }
    inspected.settle(), plain.settle(), spelled.settle();
    INFO("seed " << seed);
    CHECK(inspected.end() == plain.end());
    CHECK(spelled.end() == plain.end());
    for (size_t j = 0; j < blocks.size(); ++j) {
      const modules::BlockTimes &a = inspected.times(int(j)), &b = plain.times(int(j)), &c = spelled.times(int(j));
      INFO("block " << j);
      check_same_times(a, b);
      check_same_times(c, b);
    }
  }
}

// The plain sweep's blocks that only delay (main_pass.hpp, "Blocks that only delay")
// against the recurrence on every block (time_every_block): random passes whose last
// blocks have II 1 and the same work (0 or 1) on every pixel, so that the plain sweep
// times those after the last FIFO of 1 among them as delays; empty packets among
// them. In half the seeds one
// of them then takes other work at packet 40 (more work, a lead, or one pixel's work
// spelled otherwise) and the recurrence takes over from the delays' state. A third line
// inspects only every other packet (a traced region), mixing both sweeps.
TEST_CASE("MainPassTiming: blocks that only delay, timed as delays, count as the recurrence does", "[timing]") {
  int delayed = 0;
  for (uint32_t seed = 1; seed <= 300; ++seed) {
    std::mt19937 rng(seed);
    auto pick = [&](int lo, int hi) { return int(std::uniform_int_distribution<int>(lo, hi)(rng)); };
    const size_t count = size_t(pick(2, 6)), suffix = size_t(pick(1, int(count) - 1));
    std::vector<modules::Timing> blocks(count);
    std::vector<uint32_t> kept(count);  // each delaying block's work on every pixel
    for (size_t j = 0; j < count; ++j) {
      const bool delays = j >= count - suffix;
      blocks[j] = {uint64_t(pick(1, 40)), delays ? 1u : uint64_t(pick(1, 6)), uint64_t(pick(1, 16))};
      kept[j] = uint32_t(pick(0, 1));
    }
    modules::MainPassTiming recurrence(blocks), plain(blocks), mixed(blocks);
    recurrence.time_every_block();
    recurrence.keep_times = true;
    mixed.watch_only([](const modules::SpanPacket& p) { return p.y % 2 == 1; });
    mixed.keep_times = true;
    const uint64_t bin = uint64_t(pick(1, 60));
    for (size_t j = 0; j < count; ++j)
      for (auto* line : {&recurrence, &plain, &mixed}) line->times(int(j)).bin_cycles = bin;
    const bool change = seed % 2 == 0;
    const size_t changed = count - suffix + size_t(pick(0, int(suffix) - 1));  // the block whose work changes
    const int how = pick(0, 2);
    // The delays: the last of those blocks with a FIFO of 2 or more (with one of 1 the
    // block before could be held up), less those before a block whose work changed.
    size_t expected_from = count;
    while (expected_from > count - suffix && blocks[expected_from - 1].fifo_depth >= 2) --expected_from;
    if (change) expected_from = std::max(expected_from, changed + 1);
    std::vector<std::vector<uint16_t>> work(count, std::vector<uint16_t>(modules::kSpanMax));
    int64_t arrival = 0;
    for (int packet = 0; packet < 80; ++packet) {
      if (pick(0, 3) == 0) {
        const int64_t taken = recurrence.start_triangle(arrival);
        REQUIRE(plain.start_triangle(arrival) == taken);
        REQUIRE(mixed.start_triangle(arrival) == taken);
        arrival = taken + pick(0, 30);
      }
      modules::SpanPacket p{};
      p.count = packet != 40 && pick(0, 9) == 0 ? 0 : pick(1, modules::kSpanMax);
      p.y = packet;
      for (size_t j = 1; j < count; ++j) {
        modules::Work w{nullptr, uint32_t(pick(0, 3)), nullptr, uint32_t(pick(0, 1) ? pick(1, 5) : 0)};
        if (j >= count - suffix) w = {nullptr, kept[j]};  // a delay: the same work, uniform or spelled per pixel
        if (j >= count - suffix && pick(0, 1)) {
          std::fill(work[j].begin(), work[j].end(), uint16_t(kept[j]));
          w = {work[j].data(), 0};
        }
        if (change && packet == 40 && j == changed) {
          if (how == 0) w = {nullptr, kept[j] + 1};
          if (how == 1) w = {nullptr, kept[j], nullptr, 1};  // a lead on its first pixel
          if (how == 2) {
            std::fill(work[j].begin(), work[j].end(), uint16_t(kept[j]));
            work[j][size_t(pick(0, p.count - 1))] = uint16_t(1 - kept[j]);
            w = {work[j].data(), 0};
          }
        }
        for (auto* line : {&recurrence, &plain, &mixed}) line->set_work(int(j), w);
      }
      const uint64_t hidden = uint64_t(pick(0, 5));
      for (auto* line : {&recurrence, &plain, &mixed}) line->sweep(p, hidden);
    }
    for (auto* line : {&recurrence, &plain, &mixed}) line->settle();
    INFO("seed " << seed << (change ? ", work changed" : ""));
    CHECK(plain.delaying_from() == expected_from);  // the delays were taken (and ended where the work changed)
    CHECK(mixed.delaying_from() == expected_from);
    delayed += plain.delaying_from() < count;
    CHECK(recurrence.end() == plain.end());
    CHECK(recurrence.end() == mixed.end());
    for (size_t j = 0; j < count; ++j) {
      const modules::BlockTimes& a = recurrence.times(int(j));
      for (const auto* line : {&plain, &mixed}) {
        const modules::BlockTimes& b = line->times(int(j));
        INFO("block " << j << (line == &mixed ? ", every other packet inspected" : ""));
        check_same_times(a, b);
      }
    }
  }
  CHECK(delayed > 100);  // (coverage, not the code: most seeds must end with a block still delaying)
}

// A packet in steady state (main_pass.hpp): the plain sweep times a few pixels by the
// recurrence, finds the state the sweep reads a shift of the one before, and continues
// the rest of the packet as a series. Random passes whose work stays the same for runs
// of packets (so that FIFOs fill and a bottleneck's period reaches every block), with a
// change now and then (other work, a lead, work per pixel: random, or the same from some
// pixel on), and new triangles and hidden steps that the walk may or may not hide behind
// the series (a packet then continued whole), against the recurrence on
// every block; a third line inspects every fifth packet, whose every time must be the
// recurrence's: the windows the series left behind are read back there.
TEST_CASE("MainPassTiming: a packet in steady state, continued as a series, counts as the recurrence does", "[timing]") {
  uint64_t extrapolated = 0, pixels = 0, continued = 0;
  int seeds_extrapolated = 0;
  for (uint32_t seed = 1; seed <= 300; ++seed) {
    std::mt19937 rng(seed);
    auto pick = [&](int lo, int hi) { return int(std::uniform_int_distribution<int>(lo, hi)(rng)); };
    std::vector<modules::Timing> blocks(size_t(pick(2, 6)));
    for (auto& t : blocks) t = {uint64_t(pick(1, 40)), uint64_t(pick(1, 6)), uint64_t(pick(1, 16))};
    modules::MainPassTiming recurrence(blocks), plain(blocks), mixed(blocks);
    recurrence.time_every_block();
    recurrence.keep_times = true;
    mixed.watch_only([](const modules::SpanPacket& p) { return p.y % 5 == 0; });
    mixed.keep_times = true;
    const uint64_t bin = pick(0, 1) ? uint64_t(pick(1, 60)) : 0;  // (0: no histogram, whose reads the windows keep)
    for (size_t j = 0; j < blocks.size(); ++j)
      for (auto* line : {&recurrence, &plain, &mixed}) line->times(int(j)).bin_cycles = bin;
    std::vector<modules::Work> work(blocks.size());
    std::vector<std::vector<uint16_t>> per_pixel(blocks.size(), std::vector<uint16_t>(modules::kSpanMax));
    auto new_work = [&](size_t j) {
      work[j] = {nullptr, uint32_t(pick(0, 3)), nullptr, uint32_t(pick(0, 2) == 0 ? pick(1, 5) : 0)};
      if (pick(0, 3) == 0) {  // per pixel: random, or the same from a random pixel on
        const int same_from = pick(0, 1) ? pick(0, modules::kSpanMax) : modules::kSpanMax;
        const auto same = uint16_t(pick(0, 3));
        for (int i = 0; i < modules::kSpanMax; ++i) per_pixel[j][size_t(i)] = i < same_from ? uint16_t(pick(0, 3)) : same;
        work[j] = {per_pixel[j].data(), 0};
      }
    };
    for (size_t j = 1; j < blocks.size(); ++j) new_work(j);
    int64_t arrival = 0;
    for (int packet = 0; packet < 120; ++packet) {
      if (pick(0, 7) == 0) {  // a new triangle, soon after
        const int64_t taken = recurrence.start_triangle(arrival);
        REQUIRE(plain.start_triangle(arrival) == taken);
        REQUIRE(mixed.start_triangle(arrival) == taken);
        arrival = taken + pick(0, 8);
      }
      if (pick(0, 9) == 0) new_work(size_t(pick(1, int(blocks.size()) - 1)));
      modules::SpanPacket p{};
      p.count = pick(1, modules::kSpanMax);
      p.y = packet;
      for (size_t j = 1; j < blocks.size(); ++j)
        for (auto* line : {&recurrence, &plain, &mixed}) line->set_work(int(j), work[j]);
      const uint64_t hidden = uint64_t(pick(0, 2));
      for (auto* line : {&recurrence, &plain, &mixed}) line->sweep(p, hidden);
      if (p.y % 5 == 0) {
        INFO("seed " << seed << ", packet " << packet);
        for (size_t j = 0; j < blocks.size(); ++j)
          for (int i = 0; i < p.count; ++i) {
            REQUIRE(mixed.start(int(j), i) == recurrence.start(int(j), i));
            REQUIRE(mixed.handed(int(j), i) == recurrence.handed(int(j), i));
          }
      }
      pixels += uint64_t(p.count);
    }
    for (auto* line : {&recurrence, &plain, &mixed}) line->settle();
    INFO("seed " << seed);
    CHECK(recurrence.extrapolated() == 0);
    CHECK(recurrence.end() == plain.end());
    CHECK(recurrence.end() == mixed.end());
    for (size_t j = 0; j < blocks.size(); ++j) {
      INFO("block " << j);
      check_same_times(recurrence.times(int(j)), plain.times(int(j)));
      check_same_times(recurrence.times(int(j)), mixed.times(int(j)));
    }
    extrapolated += plain.extrapolated();
    continued += plain.continued();
    seeds_extrapolated += plain.extrapolated() > 0;
  }
  // (coverage, not the code: most seeds reach a steady state, and many pixels are series)
  INFO(extrapolated << " of " << pixels << " pixels continued as series, " << continued << " packets whole");
  CHECK(seeds_extrapolated > 200);
  CHECK(extrapolated > pixels / 6);
  CHECK(continued > 1000);
}
