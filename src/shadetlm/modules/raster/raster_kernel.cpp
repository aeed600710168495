#include "shadetlm/modules/raster/raster_kernel.hpp"

#include <algorithm>

namespace shadetlm::modules {

RasterKernel::RasterKernel(int width, int height, std::optional<CacheConfig> cache)
    : width_(width), height_(height), inv_depth_(size_t(width) * height, 0.0f) {
  if (cache) {
    memory_ = std::make_unique<MemoryClient>(*cache);
    depth_surface_ = memory_->place(width, height, 4);
  }
}

// The hidden pixels of row y from where the accesses stand to `until`: a read each.
void RasterKernel::access_hidden(int y, int x_begin, int until) {
  for (int x = accessed_to_; x < until; ++x) {
    memory_->access(depth_surface_, x, y, false);
    if (const uint16_t lines = memory_->take_pixel_lines(); lines > 0)
      hidden_lines_.push_back({row_before_ + uint64_t(x - x_begin), lines});
  }
  accessed_to_ = std::max(accessed_to_, until);
}

// The packet's pixels, and the hidden ones before it: a visible pixel reads and writes.
void RasterKernel::access_packet(const SpanPacket& p, int x_begin) {
  access_hidden(p.y, x_begin, p.x0);
  for (int i = 0; i < p.count; ++i) {
    memory_->access(depth_surface_, p.x0 + i, p.y, true);
    lines_[i] = memory_->take_pixel_lines();
  }
  accessed_to_ = p.x0 + p.count;
}

}  // namespace shadetlm::modules
