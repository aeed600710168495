#include "shadetlm/core/number_format.hpp"

#include <stdexcept>

namespace shadetlm::core {

NumberFormat NumberFormat::parse(const std::string& name) {
  if (name == "float32") return {};
  if (name == "float16") return {Kind::Float16, 0, 0};
  if (name.rfind("fixed:", 0) == 0) {
    // fixed:<digits>.<digits>, nothing else (no sign, no space).
    const std::string body = name.substr(6);
    const size_t dot = body.find('.');
    auto digits = [](const std::string& t) {
      return !t.empty() && t.size() <= 3 && t.find_first_not_of("0123456789") == std::string::npos;
    };
    if (dot != std::string::npos && digits(body.substr(0, dot)) && digits(body.substr(dot + 1))) {
      const int i = std::stoi(body.substr(0, dot)), f = std::stoi(body.substr(dot + 1));
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

}  // namespace shadetlm::core
