#include "shadetlm/trace/test_vectors.hpp"

namespace shadetlm::modules {

namespace {

// The fields packed into one hexadecimal word, the first field in the top bits.
std::string packed(const std::vector<VectorField>& fields, const uint64_t* words) {
  std::vector<bool> bits;  // most significant first
  for (size_t f = 0; f < fields.size(); ++f)
    for (int b = fields[f].bits - 1; b >= 0; --b) bits.push_back(((words[f] >> b) & 1) != 0);
  while (bits.size() % 4) bits.insert(bits.begin(), false);
  std::string hex;
  for (size_t i = 0; i < bits.size(); i += 4)
    hex += "0123456789abcdef"[bits[i] * 8 + bits[i + 1] * 4 + bits[i + 2] * 2 + bits[i + 3]];
  return hex;
}

int total_bits(const std::vector<VectorField>& fields) {
  int n = 0;
  for (const auto& f : fields) n += f.bits;
  return n;
}

}  // namespace

void VectorFile::add(int x, int y, const uint64_t* in, const uint64_t* out) {
  const std::string where = " // " + std::to_string(x) + " " + std::to_string(y) + "\n";
  in_lines_ += packed(layout_.in, in) + where;
  out_lines_ += packed(layout_.out, out) + where;
  ++pixels_;
}

std::string VectorFile::text(bool inputs) const {
  const auto& fields = inputs ? layout_.in : layout_.out;
  std::string head = "// shadetlm test vectors: " + block_ + (inputs ? " inputs" : " outputs") + ", " +
                     std::to_string(pixels_) + " pixels in the order the block took them (docs/rtl.md)\n// " +
                     layout_.about + "\n// " + std::to_string(total_bits(fields)) +
                     " bits a line, fields from the most significant:";
  for (const auto& f : fields) head += " " + f.name + "[" + std::to_string(f.bits) + "]";
  head += "\n// after each line: the pixel's x y\n";
  return head + (inputs ? in_lines_ : out_lines_);
}

}  // namespace shadetlm::modules
