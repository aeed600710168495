// Must not build (ctest kernel_parts_checked): a kernel whose optional parts and methods
// disagree. MISSPELLED: it names details but spells the method detials(); UNNAMED: it has
// details() but does not name it.
#include <nlohmann/json.hpp>

#include "shadetlm/tlm/kernel_parts.hpp"

namespace {
struct Kernel {
#ifdef MISSPELLED
  static constexpr unsigned optional = shadetlm::modules::Optional::details;
  nlohmann::json detials() const { return {}; }
#else
  static constexpr unsigned optional = shadetlm::modules::Optional::none;
  nlohmann::json details() const { return {}; }
#endif
};
static_assert(shadetlm::modules::optional_parts_checked<Kernel>());
}  // namespace
