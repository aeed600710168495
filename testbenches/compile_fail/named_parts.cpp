// Must build: the same kernel as misspelled_part.cpp with its parts and methods agreeing
// (so that the failing builds fail for the reason they test, not for a missing include).
#include <nlohmann/json.hpp>

#include "shadetlm/tlm/kernel_parts.hpp"

namespace {
struct Kernel {
  static constexpr unsigned optional = shadetlm::modules::Optional::details;
  nlohmann::json details() const { return {}; }
};
static_assert(shadetlm::modules::optional_parts_checked<Kernel>());
}  // namespace
