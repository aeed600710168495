#include "shadetlm/core/parallel.hpp"

#include <algorithm>
#include <exception>
#include <system_error>
#include <thread>
#include <vector>

#include "shadetlm/core/output.hpp"

namespace shadetlm::core {

int threads_or_cores(int threads) {
  return threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
}

void run_parts(int parts, const std::function<void(int part)>& part) {
  std::vector<std::exception_ptr> errors(static_cast<size_t>(std::max(parts, 0)));
  const auto run = [&](int k) {
    try {
      part(k);
    } catch (...) {
      errors[size_t(k)] = std::current_exception();
    }
  };
  std::vector<std::thread> workers;
  workers.reserve(errors.size());
  std::vector<int> left_over;
  for (int k = 0; k + 1 < parts; ++k) {
    try {
      SignalsHeld held;  // SIGINT, SIGTERM and SIGHUP stay with the main thread
      workers.emplace_back(run, k);
    } catch (const std::system_error&) {
      left_over.push_back(k);
    }
  }
  if (parts > 0) run(parts - 1);
  for (int k : left_over) run(k);
  for (auto& w : workers) w.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace shadetlm::core
