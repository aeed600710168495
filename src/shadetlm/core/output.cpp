#include "shadetlm/core/output.hpp"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>

#include <fcntl.h>
#include <pthread.h>
#include <sys/stat.h>
#include <unistd.h>

namespace shadetlm::core {

namespace {

// The temporaries being written, for the signal handler: fixed slots, since a handler
// may not allocate. A slot is taken, then its path written, then marked ready for the
// handler.
constexpr int kSlots = 64;
char slot_path[kSlots][4096];
std::atomic<bool> slot_taken[kSlots], slot_ready[kSlots];

int register_temporary(const std::string& tmp) {
  if (tmp.size() >= sizeof(slot_path[0])) return -1;
  for (int i = 0; i < kSlots; ++i) {
    bool expected = false;
    if (!slot_taken[i].compare_exchange_strong(expected, true)) continue;
    std::memcpy(slot_path[i], tmp.c_str(), tmp.size() + 1);
    slot_ready[i] = true;
    return i;
  }
  return -1;  // more outputs at once than slots: only a signal's clean-up misses it
}

void unregister_temporary(int slot) {
  if (slot < 0) return;
  slot_ready[slot] = false;
  slot_taken[slot] = false;
}

// While an OutputSet renames its files (OutputSet::commit), a signal that another thread
// takes is held here and raised once the renames are done.
std::atomic<bool> committing{false};
std::atomic<int> held_signal{0};

extern "C" void on_signal(int signal) {
  if (committing) {
    held_signal = signal;
    return;
  }
  for (int i = 0; i < kSlots; ++i)
    if (slot_ready[i]) ::unlink(slot_path[i]);
  std::signal(signal, SIG_DFL);
  std::raise(signal);  // ends the process by the signal: its status is 128 + signal
}

// This host's name as it goes into a temporary's name: letters, digits and '-' only.
// With the process number it tells writers apart on a filesystem that several machines
// share (a cluster's shards), where a process number alone is not unique.
const std::string& host_tag() {
  static const std::string tag = [] {
    char name[256] = {};
    std::string t = ::gethostname(name, sizeof name - 1) == 0 ? name : "";
    for (char& c : t)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-') c = '-';
    return t.empty() ? std::string("host") : t;
  }();
  return tag;
}

// Temporaries "<name>.tmp.<host>.<pid>" of `path` that this host wrote and whose process
// is gone: a run killed outright. Another host's are left alone: their process cannot be
// asked from here.
void remove_stale_temporaries(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path output(path);
  const fs::path folder = output.has_parent_path() ? output.parent_path() : fs::path(".");
  const std::string prefix = output.filename().string() + ".tmp." + host_tag() + ".";
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    // "<pid>", or "<pid>.tmp.<host>.<pid>…" (a writer's own temporary of one)
    const size_t end_of_pid = std::min(name.find('.', prefix.size()), name.size());
    const std::string pid = name.substr(prefix.size(), end_of_pid - prefix.size());
    if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos || pid.size() > 9) continue;
    if (end_of_pid < name.size() && name.compare(end_of_pid, 5, ".tmp.") != 0) continue;
    // Still running, unless it is this process's number: then a run before it with the
    // same number (a container's process 1) left it, since this run has not written yet.
    const pid_t owner = pid_t(std::stol(pid));
    if (owner != ::getpid() && (::kill(owner, 0) == 0 || errno != ESRCH)) continue;
    if (fs::remove(it->path(), ec))
      std::cerr << "shadetlm: removed " << it->path().string() << ", left by a run that was killed (process "
                << pid << ")\n";
  }
}

}  // namespace

std::string temporary_path_for(const std::string& path) {
  return path + ".tmp." + host_tag() + "." + std::to_string(::getpid());
}

void remove_quietly(const std::string& path) {
  std::error_code ec;
  std::filesystem::remove(path, ec);
}

void rename_into_place(const std::string& tmp, const std::string& path) {
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    remove_quietly(tmp);
    throw std::runtime_error(path + ": cannot write the file: " + ec.message());
  }
}

std::string naming_output(std::string what, const std::string& tmp, const std::string& path) {
  for (size_t at = what.find(tmp); at != std::string::npos; at = what.find(tmp, at + path.size()))
    what.replace(at, tmp.size(), path);
  if (what.find(path) == std::string::npos) what = path + ": " + what;
  return what;
}

void remove_temporaries_on_signals() {
  for (int s : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction current {};
    // A signal the run was started ignoring (nohup, a script's background job) stays ignored.
    if (::sigaction(s, nullptr, &current) == 0 && current.sa_handler == SIG_IGN) continue;
    std::signal(s, on_signal);
  }
  // Past a file size limit (ulimit -f) a write fails with EFBIG, reported as any
  // failed write, instead of the signal ending the process mid-file.
  std::signal(SIGXFSZ, SIG_IGN);
}

void pause_point(const char* point) {
  static const char* const wanted = std::getenv("SHADETLM_PAUSE_AT");
  if (wanted == nullptr || std::strcmp(wanted, point) != 0) return;
  std::cerr << "shadetlm: paused at " << point << " (SHADETLM_PAUSE_AT)" << std::endl;
  std::raise(SIGSTOP);
}

Temporary::Temporary(std::string path) : path_(std::move(path)), tmp_(temporary_path_for(path_)) {
  const std::filesystem::path folder = std::filesystem::path(path_).parent_path();
  std::error_code ec;
  if (!folder.empty()) std::filesystem::create_directories(folder, ec);  // (else the write names the problem)
  remove_stale_temporaries(path_);
  slot_ = register_temporary(tmp_);
}

Temporary::~Temporary() { discard(); }

void Temporary::sync() const {
  const int fd = ::open(tmp_.c_str(), O_RDONLY | O_CLOEXEC);
  const bool synced = fd >= 0 && (::fsync(fd) == 0 || errno == EINVAL || errno == EROFS);
  const int error = errno;
  if (fd >= 0) ::close(fd);
  if (!synced) throw std::runtime_error(path_ + ": cannot write the file: " + std::strerror(error));
}

void Temporary::commit(bool synced) {
  if (done_) return;
  try {
    if (!synced) sync();
    rename_into_place(tmp_, path_);
  } catch (...) {
    discard();
    throw;
  }
  done_ = true;
  unregister_temporary(slot_);
}

void Temporary::discard() {
  if (done_) return;
  done_ = true;
  remove_quietly(tmp_);
  unregister_temporary(slot_);
}

CheckedFile::CheckedFile(const std::string& file, const std::string& output) : output_(output) {
  fd_ = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd_ < 0) fail(errno);
}

CheckedFile::~CheckedFile() {
  if (fd_ >= 0) ::close(fd_);
}

void CheckedFile::fail(int error) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  throw std::runtime_error(output_ + ": cannot write the file: " + std::strerror(error));
}

void CheckedFile::write(std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd_, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail(n < 0 ? errno : ENOSPC);
    bytes.remove_prefix(size_t(n));
  }
}

void CheckedFile::close() {
  if (fd_ < 0) return;
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail(errno);
}

void write_file(const std::string& path, std::string_view bytes) {
  Temporary tmp(path);
  CheckedFile out(tmp.path(), path);
  out.write(bytes);
  out.close();
  tmp.commit();
}

const std::string& OutputSet::temporary(const std::string& path) {
  files_.push_back(std::make_unique<Temporary>(path));
  return files_.back()->path();
}

void OutputSet::write(const std::string& path, std::string_view bytes) {
  CheckedFile out(temporary(path), path);
  out.write(bytes);
  out.close();
}

SignalsHeld::SignalsHeld() {
  sigset_t held;
  sigemptyset(&held);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&held, s);
  ::pthread_sigmask(SIG_BLOCK, &held, &before_);
}

SignalsHeld::~SignalsHeld() { ::pthread_sigmask(SIG_SETMASK, &before_, nullptr); }

void OutputSet::commit() {
  for (const auto& f : files_) f->sync();  // a full disk shows before anything is in place
  pause_point("commit");
  // No signal between two renames: held back on this thread, and on any other thread
  // recorded by the handler and raised when the renames are done.
  {
    SignalsHeld held;
    committing = true;
    for (size_t i = 0; i < files_.size(); ++i) {
      try {
        files_[i]->commit(true);
      } catch (...) {  // take back what is already in place
        for (size_t k = 0; k < i; ++k) remove_quietly(files_[k]->output());
        committing = false;
        if (const int signal = held_signal.exchange(0)) on_signal(signal);  // (not lost to the error)
        throw;
      }
    }
    committing = false;
  }
  if (const int signal = held_signal.exchange(0)) on_signal(signal);
}

}  // namespace shadetlm::core
