#include "shadetlm/core/memory_budget.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>

#include <sys/resource.h>
#include <unistd.h>

#include "shadetlm/core/input_error.hpp"

namespace shadetlm::core {

MemoryBudget& MemoryBudget::process() {
  static MemoryBudget budget;
  return budget;
}

uint64_t MemoryBudget::machine_default() {
  uint64_t memory = uint64_t(sysconf(_SC_PHYS_PAGES)) * uint64_t(sysconf(_SC_PAGE_SIZE));
  std::ifstream cgroup("/sys/fs/cgroup/memory.max");  // "max" when unlimited
  uint64_t limit = 0;
  if (cgroup >> limit && limit > 0 && limit < memory) memory = limit;
  // Under ulimit -v every allocation fails past the limit, whatever the machine has.
  struct rlimit space {};
  if (::getrlimit(RLIMIT_AS, &space) == 0 && space.rlim_cur != RLIM_INFINITY) {
    std::ifstream statm("/proc/self/statm");  // the address space mapped now, in pages
    uint64_t mapped_pages = 0;
    statm >> mapped_pages;
    const uint64_t mapped = mapped_pages * uint64_t(sysconf(_SC_PAGE_SIZE));
    const uint64_t left = uint64_t(space.rlim_cur) > mapped ? uint64_t(space.rlim_cur) - mapped : 0;
    if (left < memory) memory = left;
  }
  return memory / 2;
}

std::string MemoryBudget::claim(uint64_t bytes) {
  if (bytes > limit_ || counted_ > limit_ - bytes)
    return "needs about " + format_bytes(bytes) + " of memory, past the run's budget of " + format_bytes(limit_) +
           " (" + format_bytes(counted_) + " taken; --max-memory)";
  counted_ += bytes;
  return "";
}

void MemoryBudget::take(uint64_t bytes, const std::string& file, const std::string& field) {
  const std::string why = claim(bytes);
  if (!why.empty()) throw InputError(file, field, why);
}

std::string format_bytes(uint64_t bytes) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB"};
  double value = double(bytes);
  int unit = 0;
  while (value >= 1024 && unit < 4) value /= 1024, ++unit;
  char text[32];
  std::snprintf(text, sizeof text, unit == 0 ? "%.0f %s" : "%.1f %s", value, units[unit]);
  return text;
}

uint64_t parse_bytes(const std::string& text, const std::string& option) {
  char* end = nullptr;
  const double number = std::strtod(text.c_str(), &end);
  double scale = 1;
  std::string unit = end ? std::string(end) : "";
  if (!unit.empty() && (unit.back() == 'B' || unit.back() == 'b')) unit.pop_back();
  if (unit == "K" || unit == "k") scale = 1024.0;
  else if (unit == "M" || unit == "m") scale = 1024.0 * 1024;
  else if (unit == "G" || unit == "g") scale = 1024.0 * 1024 * 1024;
  else if (unit == "T" || unit == "t") scale = 1024.0 * 1024 * 1024 * 1024;
  else if (!unit.empty()) throw InputError(option, text, "expected a size such as 4G, 512M or 1048576");
  const double bytes = number * scale;
  if (end == text.c_str() || !std::isfinite(bytes) || bytes < 1024 * 1024 || bytes > 1e18)
    throw InputError(option, text, "expected a size from 1M to 1e18 bytes, such as 4G");
  return uint64_t(bytes);
}

}  // namespace shadetlm::core
