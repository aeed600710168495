#include "app/progress.hpp"

#include "shadetlm/core/output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <system_error>

#include <unistd.h>

namespace shadetlm::app {

Progress::Progress(std::string command) : command_(std::move(command)), enabled_(isatty(fileno(stderr)) != 0) {
  if (!enabled_) return;
  try {
    core::SignalsHeld held;  // the ticker never takes SIGINT or SIGTERM: the main thread does
    ticker_ = std::thread([this] { run(); });
  } catch (const std::system_error&) {  // no thread to be had (a limit): the run goes on without the line
  }
}

Progress::~Progress() {
  done();
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (ticker_.joinable()) ticker_.join();
}

void Progress::phase(const std::string& name, const std::string& key) {
  {
    std::lock_guard lock(mutex_);
    phase_ = name;
    share_ = -1;
    const auto now = std::chrono::steady_clock::now();
    ended_ = now;
    if (!key.empty()) starts_.emplace_back(key, now);
  }
  core::pause_point(name.c_str());
}

std::vector<std::pair<std::string, double>> Progress::seconds() const {
  const auto now = std::chrono::steady_clock::now();
  std::vector<std::pair<std::string, double>> times;
  for (size_t i = 0; i < starts_.size(); ++i) {
    const auto end = i + 1 < starts_.size() ? starts_[i + 1].second : (stop_ ? ended_ : now);
    times.emplace_back(starts_[i].first, std::chrono::duration<double>(end - starts_[i].second).count());
  }
  return times;
}

void Progress::done() {
  std::lock_guard lock(mutex_);
  if (!stop_) ended_ = std::chrono::steady_clock::now();
  if (drawn_) std::fprintf(stderr, "\r%s\r", std::string(72, ' ').c_str());
  drawn_ = false;
  stop_ = true;
}

void Progress::run() {
  std::unique_lock lock(mutex_);
  while (!wake_.wait_for(lock, std::chrono::milliseconds(100), [this] { return stop_; }))
    if (std::chrono::steady_clock::now() - start_ >= std::chrono::milliseconds(500)) draw();
}

// "render: pipeline [#########           ]  45 %   3.2 s" (the bar only where the share is known).
void Progress::draw() {
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double done = share_;
  std::string bar;
  if (done >= 0) {
    const int filled = int(std::lround(std::clamp(done, 0.0, 1.0) * 20));
    bar = " [" + std::string(size_t(filled), '#') + std::string(size_t(20 - filled), ' ') + "] " +
          std::to_string(int(std::lround(std::clamp(done, 0.0, 1.0) * 100))) + " %";
  }
  std::string line = command_ + ": " + phase_ + bar + "  " + std::to_string(int(seconds * 10) / 10) + "." +
                     std::to_string(int(seconds * 10) % 10) + " s";
  line.resize(std::max<size_t>(line.size(), 72), ' ');  // over what the last line left
  std::fprintf(stderr, "\r%s", line.c_str());
  std::fflush(stderr);
  drawn_ = true;
}

}  // namespace shadetlm::app
