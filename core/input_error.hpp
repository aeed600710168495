#pragma once
// Bad input — a scene, a texture, a mesh, a frame — reported with the file and the
// field it came from, so that a user can find and fix it.
#include <stdexcept>
#include <string>

namespace shadetlm::core {

// Text from an input, fit for a terminal: control bytes (escape, bell, …) and bytes that
// are not UTF-8 shown as \xNN, and at most about `max` bytes kept (the cut said).
inline std::string printable(const std::string& text, size_t max = 80) {
  static const char* hex = "0123456789abcdef";
  std::string out;
  size_t i = 0;
  while (i < text.size() && out.size() < max) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    // A whole UTF-8 sequence: its length from the lead byte, continuation bytes 10xxxxxx.
    const size_t length = c < 0x80 ? 1 : (c >> 5) == 6 && c >= 0xc2 ? 2 : (c >> 4) == 14 ? 3 : (c >> 3) == 30 && c <= 0xf4 ? 4 : 0;
    bool whole = length > 0 && i + length <= text.size();
    for (size_t k = 1; whole && k < length; ++k) whole = (static_cast<unsigned char>(text[i + k]) >> 6) == 2;
    if (whole && !(c < 0x20 || c == 0x7f)) {
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
    std::string s = file.empty() ? std::string("<input>") : printable(file, 160);
    if (!field.empty()) s += ": " + printable(field, 100);
    return s + ": " + printable(what, 200);
  }
  std::string file_, field_;
};

}  // namespace shadetlm::core
