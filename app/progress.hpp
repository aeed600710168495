#pragma once
// One progress line on stderr for a whole command (render, reference, precompute): the
// phase it is in (loading the scene and building meshes, the pipeline, the golden model,
// writing), the share done where the phase knows it, and the time so far. A thread of
// its own redraws it ten times a second, so that a phase which cannot report (a mesh
// being built, an EXR being written) still shows it is alive. Drawn only when stderr is
// a terminal, and only once the command has run half a second (short runs stay quiet).
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace shadetlm::app {

class Progress {
 public:
  explicit Progress(std::string command);
  ~Progress();  // clears the line (also when the command throws: its message starts clean)
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  bool enabled() const { return enabled_; }
  // A new phase, its share not known (yet); one with a `key` is timed (seconds()).
  void phase(const std::string& name, const std::string& key = "");
  // The timed phases so far, in order, as (key, seconds): the current one up to now.
  std::vector<std::pair<std::string, double>> seconds() const;
  void share(double done) { share_ = done; }  // of the phase, 0 … 1 (from any thread)
  void done();  // clears the line and stops drawing (before the results go to stdout)

 private:
  void run();
  void draw();

  const std::string command_;
  const bool enabled_;
  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::mutex mutex_;  // guards phase_, stop_, drawn_
  std::condition_variable wake_;
  std::string phase_ = "starting";
  bool stop_ = false, drawn_ = false;
  std::atomic<double> share_{-1};  // < 0: not known
  std::vector<std::pair<std::string, std::chrono::steady_clock::time_point>> starts_;  // keyed phases' starts
  std::chrono::steady_clock::time_point ended_{};  // when the last keyed phase ended (phase() or done())
  std::thread ticker_;
};

}  // namespace shadetlm::app
