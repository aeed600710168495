#include "shadetlm/memory/cache.hpp"

#include <stdexcept>

namespace shadetlm::modules {

const std::vector<std::string>& layout_names() {
  static const std::vector<std::string> names{"linear", "tiled", "morton"};
  return names;
}

namespace {

bool power_of_two(uint64_t n) { return n > 0 && (n & (n - 1)) == 0; }

uint32_t log2_of(uint64_t n) {
  uint32_t k = 0;
  while ((uint64_t(1) << (k + 1)) <= n) ++k;
  return k;
}

// A tile of one line: 2^k elements, w = 2^⌈k/2⌉ wide and h = 2^⌊k/2⌋ high.
struct Tile {
  uint32_t w_shift, h_shift;
};
Tile tile_of(uint32_t line_bytes, uint32_t element_bytes) {
  const uint32_t k = line_bytes > element_bytes ? log2_of(line_bytes / element_bytes) : 0;
  return {(k + 1) / 2, k / 2};
}

// The bits of v spread to the even positions.
uint64_t spread(uint32_t v) {
  uint64_t z = v;
  z = (z | (z << 16)) & 0x0000FFFF0000FFFFull;
  z = (z | (z << 8)) & 0x00FF00FF00FF00FFull;
  z = (z | (z << 4)) & 0x0F0F0F0F0F0F0F0Full;
  z = (z | (z << 2)) & 0x3333333333333333ull;
  z = (z | (z << 1)) & 0x5555555555555555ull;
  return z;
}
// Bits of x in the even positions, of y in the odd ones.
uint64_t interleave(uint32_t x, uint32_t y) { return spread(x) | (spread(y) << 1); }

uint64_t square_side(const Surface& s) {
  uint64_t side = 1;
  while (side < uint64_t(s.width) || side < uint64_t(s.height)) side *= 2;
  return side;
}

}  // namespace

void tile_for(Surface& s, uint32_t line_bytes) {
  const Tile t = tile_of(line_bytes, s.element_bytes);
  s.tile_w_shift = t.w_shift, s.tile_h_shift = t.h_shift;
  s.tile_bytes = std::max<uint64_t>(line_bytes, uint64_t(s.element_bytes) << (t.w_shift + t.h_shift));
  s.tiles_per_row = (uint64_t(s.width) + (1u << t.w_shift) - 1) >> t.w_shift;
}

uint64_t address(Layout layout, const Surface& s, int x, int y) {
  const uint64_t ux = uint32_t(x), uy = uint32_t(y), e = s.element_bytes;
  switch (layout) {
    case Layout::Linear:
      return s.base + (uy * uint64_t(s.width) + ux) * e;
    case Layout::Tiled: {
      const uint64_t tile = (uy >> s.tile_h_shift) * s.tiles_per_row + (ux >> s.tile_w_shift);
      const uint64_t within = ((uy & ((1u << s.tile_h_shift) - 1)) << s.tile_w_shift) + (ux & ((1u << s.tile_w_shift) - 1));
      return s.base + tile * s.tile_bytes + within * e;
    }
    case Layout::Morton:
      return s.base + interleave(uint32_t(x), uint32_t(y)) * e;
  }
  return s.base;
}

uint64_t surface_bytes(Layout layout, const Surface& s, uint32_t line_bytes) {
  uint64_t bytes = 0;
  const uint64_t e = s.element_bytes;
  switch (layout) {
    case Layout::Linear:
      bytes = uint64_t(s.width) * uint64_t(s.height) * e;
      break;
    case Layout::Tiled: {
      const Tile t = tile_of(line_bytes, s.element_bytes);
      const uint64_t across = (uint64_t(s.width) + (1u << t.w_shift) - 1) >> t.w_shift;
      const uint64_t down = (uint64_t(s.height) + (1u << t.h_shift) - 1) >> t.h_shift;
      bytes = across * down * std::max<uint64_t>(line_bytes, e << (t.w_shift + t.h_shift));
      break;
    }
    case Layout::Morton:
      bytes = square_side(s) * square_side(s) * e;
      break;
  }
  return (bytes + line_bytes - 1) / line_bytes * line_bytes;
}

CacheFault check(const CacheConfig& c) {
  if (!power_of_two(c.size)) return {"size", std::to_string(c.size) + " bytes is not a power of two"};
  if (!power_of_two(c.line)) return {"line", std::to_string(c.line) + " bytes is not a power of two"};
  if (c.line > c.size)
    return {"line", "a line of " + std::to_string(c.line) + " bytes is larger than the cache (" +
                        std::to_string(c.size) + " bytes)"};
  const uint64_t lines = c.size / c.line;
  if (c.ways == 0 || lines % c.ways != 0)
    return {"ways", std::to_string(c.ways) + " ways do not divide the cache's " + std::to_string(lines) + " lines"};
  return {};
}

Cache::Cache(const CacheConfig& config) : config_(config) {
  const CacheFault fault = check(config);
  if (!fault.setting.empty()) throw std::invalid_argument("cache." + fault.setting + ": " + fault.why);
  line_shift_ = log2_of(config.line);
  sets_ = config.size / config.line / config.ways;  // a power of two: size and line are, ways divides
  set_mask_ = sets_ - 1;
  tag_.assign(sets_ * config.ways, 0);
  used_.assign(tag_.size(), 0);
  dirty_.assign(tag_.size(), 0);
}

uint32_t Cache::access(uint64_t address, bool write) {
  const uint64_t line = address >> line_shift_;
  const uint64_t first = (line & set_mask_) * config_.ways;
  ++counts_.accesses, ++clock_;
  size_t victim = first;
  for (size_t w = first; w < first + config_.ways; ++w) {
    if (tag_[w] == line + 1) {
      ++counts_.hits;
      used_[w] = clock_;
      dirty_[w] |= uint8_t(write);
      return 0;
    }
    if (used_[w] < used_[victim]) victim = w;  // the least recently used (an empty way: never)
  }
  ++counts_.misses;
  const uint32_t moved = dirty_[victim] ? 2 : 1;
  counts_.writebacks += moved - 1;
  tag_[victim] = line + 1, used_[victim] = clock_, dirty_[victim] = uint8_t(write);
  return moved;
}

uint64_t Cache::dirty_lines() const {
  uint64_t n = 0;
  for (uint8_t d : dirty_) n += d;
  return n;
}

void LineBuffer::clear_more() { seen_.clear(), more_.clear(); }

void LineBuffer::add_many(uint64_t line) {
  if (seen_.insert(line).second) more_.push_back(line);
}

Surface MemoryClient::place(int width, int height, uint32_t element_bytes) {
  Surface s{next_, width, height, element_bytes};
  tile_for(s, line_bytes());
  next_ += surface_bytes(layout(), s, line_bytes());
  return s;
}

}  // namespace shadetlm::modules
