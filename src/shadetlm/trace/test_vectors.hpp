#pragma once
// Test vectors (docs/rtl.md, "Test vectors"): a block's inputs and outputs for each
// pixel of a region, as the words at its pins in its number format (fixed:I.F: the raw
// two's complement value; float32: the IEEE bits), for an RTL testbench to read with
// $readmemh: <block>.in.hex and <block>.out.hex, one line a pixel in the order the block
// took them, the fields packed into one hexadecimal word (the first field in the most
// significant bits), a header of `//` comments naming the fields and their widths.
#include <cstdint>
#include <string>
#include <vector>

namespace shadetlm::modules {

struct VectorField {
  std::string name;
  int bits;
};

// What a kernel with vectors declares: its fields in and out, and a line of what they
// hold (format, mode).
struct VectorLayout {
  std::string about;
  std::vector<VectorField> in, out;
};
constexpr int kMaxVectorFields = 16;

class VectorFile {
 public:
  VectorFile(std::string block, VectorLayout layout) : block_(std::move(block)), layout_(std::move(layout)) {}
  // One pixel: its fields' words (each below 2^bits).
  void add(int x, int y, const uint64_t* in, const uint64_t* out);
  const std::string& block() const { return block_; }
  uint64_t pixels() const { return pixels_; }
  // The file's text: the header, then a line a pixel.
  std::string text(bool inputs) const;

 private:
  std::string block_;
  VectorLayout layout_;
  std::string in_lines_, out_lines_;
  uint64_t pixels_ = 0;
};

// The two files of a block's vectors in `dir`.
inline std::string vector_path(const std::string& dir, const std::string& block, bool inputs) {
  return dir + "/" + block + (inputs ? ".in.hex" : ".out.hex");
}

}  // namespace shadetlm::modules
