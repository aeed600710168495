#include "core/number_format.hpp"

#include <cstdio>
#include <stdexcept>

namespace core {

NumberFormat NumberFormat::parse(const std::string& name) {
  if (name == "float32") return {};
  if (name == "float16") return {Kind::Float16, 0, 0};
  if (name.rfind("fixed:", 0) == 0) {
    int i = -1, f = -1, consumed = 0;
    const std::string body = name.substr(6);
    if (std::sscanf(body.c_str(), "%d.%d%n", &i, &f, &consumed) == 2 && size_t(consumed) == body.size() &&
        body.find_first_of("+- ") == std::string::npos) {
      if (i > kMaxIntBits) throw std::invalid_argument("at most " + std::to_string(kMaxIntBits) + " integer bits");
      if (f < 1 || f > kMaxFracBits)
        throw std::invalid_argument("1 to " + std::to_string(kMaxFracBits) + " fraction bits");
      if (i + f > kMaxBits)
        throw std::invalid_argument("at most " + std::to_string(kMaxBits) + " integer and fraction bits together");
      return fixed(i, f);
    }
  }
  throw std::invalid_argument("unknown number format \"" + name + "\" (float32, float16 or fixed:I.F, e.g. fixed:3.16)");
}

std::string NumberFormat::name() const {
  switch (kind) {
    case Kind::Float32: return "float32";
    case Kind::Float16: return "float16";
    default: return "fixed:" + std::to_string(int_bits) + "." + std::to_string(frac_bits);
  }
}

}  // namespace core
