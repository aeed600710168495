#pragma once
// The memory a run may take (docs/robustness.md). Before a large allocation — a decoded
// image, a mesh, the frame's layers and buffers, the golden model's image, a parallax or
// normal map, a trace — its size is estimated and counted against the budget; past it,
// the run stops with the file and field that drive the size, before allocating, rather
// than fail in the allocator (or the machine's out-of-memory killer) with no name.
//
// The budget is --max-memory, by default half the memory the process can have: the
// smallest of the machine's physical memory, its control group's limit and, under an
// address-space limit (ulimit -v, RLIMIT_AS), the address space left to the process when
// the budget is made (what the libraries and stacks have not mapped already). Counts are not given back: they bound
// what a run holds at its peak, from above.
#include <cstdint>
#include <string>

namespace shadetlm::core {

class MemoryBudget {
 public:
  // The process's budget (one run a process).
  static MemoryBudget& process();
  static uint64_t machine_default();  // half of the memory the process can have (above)

  void set_limit(uint64_t bytes) { limit_ = bytes; }
  uint64_t limit() const { return limit_; }
  uint64_t counted() const { return counted_; }
  // Counts `bytes` for what `file` and `field` ask for; throws InputError(file, field, …)
  // when the run would pass its budget.
  void take(uint64_t bytes, const std::string& file, const std::string& field);
  // The same without throwing: "" if counted, else why not.
  std::string claim(uint64_t bytes);

 private:
  uint64_t limit_ = machine_default(), counted_ = 0;
};

// A mesh's bytes as the run holds it: the scene's copy, the world-space copy the
// pipeline draws and the golden model's (positions, normals, tangents, uvs; indices).
constexpr uint64_t mesh_bytes(uint64_t vertices, uint64_t triangles) { return 3 * (vertices * 96 + triangles * 12); }

// A decoded image's bytes a texel at the peak of its loading: its float RGBA texels and
// the copy loading makes of them (measured: 32 bytes a texel on a 4000² PNG).
constexpr uint64_t kDecodedTexelBytes = 32;

// "1.5 GiB", "300 MiB": a size for messages.
std::string format_bytes(uint64_t bytes);
// "4G", "512M", "1048576": a size given on the command line (K, M, G, T: powers of 1024);
// throws InputError naming `option` otherwise.
uint64_t parse_bytes(const std::string& text, const std::string& option);

}  // namespace shadetlm::core
