#pragma once
// Every file the program writes appears whole or not at all (docs/robustness.md):
//  - it is written to a temporary beside it, "<path>.tmp.<host>.<pid>", and renamed
//    into place only once every write, the flush to disk and the close have succeeded;
//  - a failure (a full disk, a file size limit) removes the temporary and names the
//    output, not the temporary;
//  - SIGINT, SIGTERM and SIGHUP remove the temporaries being written and end the
//    process by the same signal (exit status 128 + its number); past a file size
//    limit (SIGXFSZ, ignored) a write fails like any other;
//  - a temporary left by a run that was killed outright (SIGKILL, a power cut) is named
//    and removed by the next run on the same host that writes the same output;
//  - the outputs of one run form one OutputSet: all renamed into place at its commit,
//    with SIGINT, SIGTERM and SIGHUP held back for the renames, or none.
#include <csignal>
#include <stdexcept>
#include <string>
#include <string_view>
#include <memory>
#include <vector>

#include "shadetlm/core/input_error.hpp"

namespace shadetlm::core {

std::string temporary_path_for(const std::string& path);
void remove_quietly(const std::string& path);
// Renames a finished temporary to its output; throws std::runtime_error naming `path`.
void rename_into_place(const std::string& tmp, const std::string& path);

// Once, at start-up: the signal handlers that take back temporaries.
void remove_temporaries_on_signals();

// For tests that signal a run at a known point, never after a guessed delay: when the
// environment's SHADETLM_PAUSE_AT equals `point`, the process says so on stderr and stops
// itself (SIGSTOP); the test waits for the stop, signals it and lets it continue. The
// points: every progress phase ("loading the scene", "pipeline", "golden model",
// "writing", ...), "pipeline half" (from setup's progress, reported every 64 triangles:
// a scene of fewer never stops there) and "commit" (the process's first OutputSet commit:
// for render, every output of the run written to its temporary, none renamed yet).
void pause_point(const char* point);

// Holds SIGINT, SIGTERM and SIGHUP back on this thread while it lives; they are delivered
// at its end. Around an OutputSet's renames (a signal between two would leave a run's
// outputs half in place), and around starting a helper thread, which inherits the
// mask and so never takes these signals (the main thread does, at a safe point).
class SignalsHeld {
 public:
  SignalsHeld();
  ~SignalsHeld();
  SignalsHeld(const SignalsHeld&) = delete;
  SignalsHeld& operator=(const SignalsHeld&) = delete;

 private:
  sigset_t before_;
};

// A temporary being written, registered so that a signal removes it; removed on
// destruction unless committed.
class Temporary {
 public:
  explicit Temporary(std::string path);
  ~Temporary();
  Temporary(const Temporary&) = delete;
  Temporary& operator=(const Temporary&) = delete;
  const std::string& path() const { return tmp_; }
  const std::string& output() const { return path_; }
  void sync() const;  // to disk (a full disk may show only then); throws naming the output
  void commit(bool synced = false);  // sync() unless done, then renamed into place
  void discard();

 private:
  std::string path_, tmp_;
  int slot_;
  bool done_ = false;
};

// Writes to `file` (a temporary), every write checked; close() checks the last. Errors
// name `output`, the file it becomes.
class CheckedFile {
 public:
  CheckedFile(const std::string& file, const std::string& output);
  ~CheckedFile();
  CheckedFile(const CheckedFile&) = delete;
  CheckedFile& operator=(const CheckedFile&) = delete;
  void write(std::string_view bytes);
  void close();

 private:
  [[noreturn]] void fail(int error);
  std::string output_;
  int fd_ = -1;
};

// A whole file at once: a temporary, checked writes, synced, renamed into place.
void write_file(const std::string& path, std::string_view bytes);

// Outputs that appear together or not at all: each written whole to its temporary,
// then all synced and renamed at commit(); none appears if one fails.
class OutputSet {
 public:
  const std::string& temporary(const std::string& path);  // the temporary to write `path` to
  void write(const std::string& path, std::string_view bytes);
  // Calls write(temporary) for a writer that takes a file name; its errors name `path`.
  template <class F>
  void write_with(const std::string& path, F write);
  void commit();

 private:
  std::vector<std::unique_ptr<Temporary>> files_;
};

// `what` with every mention of the temporary replaced by the output's path.
std::string naming_output(std::string what, const std::string& tmp, const std::string& path);

// Calls write(tmp) with a registered temporary beside `path`, then renames it to `path`;
// the temporary goes if write throws. An error that names the temporary is reworded to
// name the output.
template <class F>
void write_atomically(const std::string& path, F write) {
  OutputSet one;
  one.write_with(path, write);
  one.commit();
}

template <class F>
void OutputSet::write_with(const std::string& path, F write) {
  const std::string& tmp = temporary(path);
  try {
    write(tmp);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw std::runtime_error(naming_output(e.what(), tmp, path));
  }
}

}  // namespace shadetlm::core
