#pragma once
// The memory a block reads and writes (docs/memory.md): where a texel or a framebuffer
// pixel lies in memory (its layout), and the cache in front of the shared DRAM. A block
// that touches memory (a memory client: the texture units, the framebuffer) has a cache
// of its own, set with pipeline.<block>.cache.*; its misses go to the DRAM
// (memory/dram.hpp), which the main pass's timing shares between clients.
//
// The cache is a client's alone and the client is in order, so which access hits does
// not depend on time: the kernels run it as they fetch, and hand the timing the DRAM
// lines each pixel moved.
#include <algorithm>
#include <cstdint>
#include <string>
#include <unordered_set>
#include <vector>

namespace shadetlm::modules {

// How a 2-D array of elements (texels, framebuffer pixels) is laid out in memory:
//   linear  row after row
//   tiled   tiles of one cache line each (w × h elements, w = h or w = 2h), tile row after tile row
//   morton  Z-order: the bits of x and y interleaved, on the power-of-two square around the array
enum class Layout { Linear, Tiled, Morton };
const std::vector<std::string>& layout_names();  // in the order of Layout

struct Surface {
  uint64_t base = 0;  // address of element (0, 0), line-aligned
  int width = 0, height = 0;
  uint32_t element_bytes = 4;
  // Tiled: a tile's width and height as shifts, its bytes, the tiles a row (set by
  // MemoryClient::place, or by tile_for()).
  uint32_t tile_w_shift = 0, tile_h_shift = 0;
  uint64_t tile_bytes = 0, tiles_per_row = 0;
};
// Fills in `s`'s tile for lines of `line_bytes`.
void tile_for(Surface& s, uint32_t line_bytes);
// The address of element (x, y) of `s` (0 ≤ x < width, 0 ≤ y < height); tiled, `s`'s
// tile filled in (tile_for).
uint64_t address(Layout layout, const Surface& s, int x, int y);
// The bytes `s` spans in `layout`, rounded up to whole lines.
uint64_t surface_bytes(Layout layout, const Surface& s, uint32_t line_bytes);

struct CacheConfig {
  uint64_t size = 16384;  // bytes, a power of two
  uint32_t line = 64;     // bytes, a power of two, at most `size`
  uint32_t ways = 4;      // divides size / line (the lines)
  Layout layout = Layout::Tiled;
};
// Why `c` is not a cache: the setting at fault ("size", "line" or "ways") and why;
// two empty strings if it is one.
struct CacheFault {
  std::string setting, why;
};
CacheFault check(const CacheConfig& c);

// A set-associative write-back, write-allocate cache with least-recently-used
// replacement: a miss reads the line from the DRAM, and a dirty line it replaces is
// written back.
class Cache {
 public:
  explicit Cache(const CacheConfig& config);
  struct Counts {
    uint64_t accesses = 0, hits = 0, misses = 0, writebacks = 0;
  };
  // Reads (or writes) the line of `address`; returns the lines it moved to or from
  // the DRAM: 0 on a hit, 1 on a miss, 2 on a miss that wrote back a dirty line.
  uint32_t access(uint64_t address, bool write);
  const Counts& counts() const { return counts_; }
  const CacheConfig& config() const { return config_; }
  uint64_t dirty_lines() const;  // lines written and not yet written back

 private:
  CacheConfig config_;
  uint32_t line_shift_ = 0;
  uint64_t sets_ = 0, set_mask_ = 0;  // a power of two sets
  uint64_t clock_ = 0;               // accesses so far: the LRU stamp
  std::vector<uint64_t> tag_;        // per way of each set: the line + 1 (0: empty)
  std::vector<uint64_t> used_;       // per way: the stamp of its last access
  std::vector<uint8_t> dirty_;
  Counts counts_;
};

// The lines a pixel touches, each once (a texture unit's line buffer), in the order
// first touched.
class LineBuffer {
 public:
  void clear() {
    if (count_ == kScanned) clear_more();
    count_ = 0;
  }
  void add(uint64_t line) {  // inline: a texture unit adds every texel's line
    for (int k = 0; k < count_; ++k)
      if (first_[k] == line) return;
    if (count_ < kScanned) first_[count_++] = line;
    else add_many(line);
  }
  size_t size() const { return size_t(count_) + more_.size(); }
  template <class F> void for_each(F&& f) const {
    for (int k = 0; k < count_; ++k) f(first_[k]);
    for (uint64_t line : more_) f(line);
  }

 private:
  static constexpr int kScanned = 256;  // up to here a scan (an EWA footprint's lines, nearly always)
  [[gnu::noinline]] void add_many(uint64_t line);  // past the first kScanned
  [[gnu::noinline]] void clear_more();
  uint64_t first_[kScanned];
  int count_ = 0;
  std::vector<uint64_t> more_;         // the lines past the first kScanned (a long ray, a very wide footprint)
  std::unordered_set<uint64_t> seen_;  // the same, as a set
};

// A block's port to memory: its cache, its surfaces placed one after another from
// address 0, and the DRAM lines the current pixel moved.
class MemoryClient {
 public:
  explicit MemoryClient(const CacheConfig& config) : cache_(config) {}
  // Places a surface of `width` × `height` elements of `element_bytes` after the last one.
  Surface place(int width, int height, uint32_t element_bytes);
  // Reads (or writes) element (x, y) of `s`: every line it spans.
  void access(const Surface& s, int x, int y, bool write) {
    const uint64_t first = address(cache_.config().layout, s, x, y);
    const uint64_t line = cache_.config().line;
    for (uint64_t l = first / line; l <= (first + s.element_bytes - 1) / line; ++l)
      pixel_lines_ += cache_.access(l * line, write);
  }
  // The line holding element (x, y) of `s` (a texture unit gathers a pixel's, then reads them).
  uint64_t line_of(const Surface& s, int x, int y) const {
    return address(cache_.config().layout, s, x, y) / cache_.config().line;
  }
  // Reads line `line` (one line_of gave).
  void read_line(uint64_t line) { pixel_lines_ += cache_.access(line * cache_.config().line, false); }
  // The DRAM lines moved since the last call (the pixel's), at most 65535.
  uint16_t take_pixel_lines() {
    const uint64_t n = pixel_lines_;
    pixel_lines_ = 0;
    return uint16_t(n < 65535 ? n : 65535);
  }
  const Cache& cache() const { return cache_; }
  Layout layout() const { return cache_.config().layout; }
  uint32_t line_bytes() const { return cache_.config().line; }

 private:
  Cache cache_;
  uint64_t next_ = 0;  // the next free address
  uint64_t pixel_lines_ = 0;
};

}  // namespace shadetlm::modules
