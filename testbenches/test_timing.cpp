// The fast timing model (modules/common/timing.hpp) on an example small enough to work
// by hand — the worked example of docs/pipeline.md. (The clocked reference checks it on
// whole frames: testbenches/timing_check_test.sh.)
#include <catch2/catch.hpp>

#include "shadetlm/modules/common/timing.hpp"

using namespace shadetlm;

TEST_CASE("PixelLine: four pixels through a raster and two blocks, worked by hand", "[timing]") {
  // raster: L 1, II 1 (C = 2); A: L 2, II 1, FIFO 1 (C = 3); B: L 1, II 2, FIFO 1 (C = 1).
  modules::PixelLine line({{1, 1, 4}, {2, 1, 1}, {1, 2, 1}});
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
