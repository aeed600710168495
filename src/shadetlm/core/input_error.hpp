#pragma once
// Bad input — a scene, a texture, a mesh, a frame — reported with the file and the
// field it came from, so that a user can find and fix it.
#include <cstdint>
#include <stdexcept>
#include <string>

namespace shadetlm::core {

// Text from an input, fit for a terminal: control characters (escape, bell, C1's CSI …)
// and bytes that are not well-formed UTF-8 shown as \xNN, and at most about `max` bytes
// kept (the cut said). Values echoed from an input are cut at 80; whole messages at more.
inline std::string printable(const std::string& text, size_t max = 80) {
  static const char* hex = "0123456789abcdef";
  std::string out;
  size_t i = 0;
  while (i < text.size() && out.size() < max) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    // A UTF-8 sequence: its length from the lead byte, continuation bytes 10xxxxxx, and
    // its code point neither overlong, a surrogate, past U+10FFFF, nor a control.
    const size_t length = c < 0x80 ? 1 : (c >> 5) == 6 ? 2 : (c >> 4) == 14 ? 3 : (c >> 3) == 30 ? 4 : 0;
    bool whole = length > 0 && i + length <= text.size();
    uint32_t point = length == 1 ? c : length == 2 ? c & 0x1f : length == 3 ? c & 0x0f : c & 0x07;
    for (size_t k = 1; whole && k < length; ++k) {
      const unsigned char next = static_cast<unsigned char>(text[i + k]);
      whole = (next >> 6) == 2;
      point = point << 6 | (next & 0x3f);
    }
    const uint32_t least[5] = {0, 0, 0x80, 0x800, 0x10000};
    whole = whole && point >= least[length] && point <= 0x10ffff && !(point >= 0xd800 && point <= 0xdfff) &&
            point >= 0x20 && !(point >= 0x7f && point <= 0x9f);
    if (whole) {
      out.append(text, i, length);
      i += length;
    } else {
      out += std::string("\\x") + hex[c >> 4] + hex[c & 15];
      ++i;
    }
  }
  if (i < text.size()) out += "… (" + std::to_string(text.size()) + " bytes)";
  return out;
}

class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, const std::string& field, const std::string& what)
      : std::runtime_error(compose(file, field, what)), file_(file), field_(field) {}

  const std::string& file() const { return file_; }
  const std::string& field() const { return field_; }

 private:
  static std::string compose(const std::string& file, const std::string& field,
                             const std::string& what) {
    std::string s = file.empty() ? std::string("<input>") : printable(file, 1000);
    if (!field.empty()) s += ": " + printable(field, 1000);
    return s + ": " + printable(what, 2000);
  }
  std::string file_, field_;
};

}  // namespace shadetlm::core
