#include "shadetlm/core/input_file.hpp"

#include <cerrno>
#include <cstring>

#include <sys/stat.h>
#include <unistd.h>

#include "shadetlm/core/input_error.hpp"

namespace shadetlm::core {

void check_input_file(const std::string& path, const std::string& field, uint64_t max_bytes) {
  if (path.empty()) throw InputError(path, field, "no file named (an empty path)");
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    const int error = errno;
    throw InputError(path, field, error == ENOENT ? "no such file" : std::strerror(error));
  }
  if (S_ISDIR(st.st_mode)) throw InputError(path, field, "is a folder, not a file");
  if (S_ISFIFO(st.st_mode)) throw InputError(path, field, "is a FIFO (a named pipe), not a file");
  if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) throw InputError(path, field, "is a device, not a file");
  if (!S_ISREG(st.st_mode)) throw InputError(path, field, "is not a regular file");
  if (uint64_t(st.st_size) > max_bytes)
    throw InputError(path, field, "is " + std::to_string(uint64_t(st.st_size) >> 20) + " MiB, more than the " +
                                      std::to_string(max_bytes >> 20) + " MiB such a file may have");
  if (::access(path.c_str(), R_OK) != 0) throw InputError(path, field, std::strerror(errno));
}

}  // namespace shadetlm::core
