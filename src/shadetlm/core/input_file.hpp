#pragma once
// Input files are checked before they are read: a folder, a FIFO, a device such as
// /dev/zero, a loop of symbolic links or a missing file is named for what it is, and a
// file larger than its kind allows is refused before it is read.
#include <cstdint>
#include <string>

namespace shadetlm::core {

constexpr uint64_t kMaxSceneBytes = uint64_t(256) << 20;  // a scene's JSON
constexpr uint64_t kMaxMeshBytes = uint64_t(4) << 30;     // a mesh file
constexpr uint64_t kMaxImageBytes = uint64_t(2) << 30;    // an image file

// Throws InputError(path, field, what is wrong) unless `path` is a regular file (after
// symbolic links) of at most max_bytes that can be opened for reading.
void check_input_file(const std::string& path, const std::string& field, uint64_t max_bytes);

}  // namespace shadetlm::core
