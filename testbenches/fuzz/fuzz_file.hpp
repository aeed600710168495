#pragma once
// The fuzzers' input as a file of its own (the loaders read paths): written once per
// input under /tmp, with the extension that picks the loader.
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

#include <unistd.h>

inline std::string fuzz_file(const uint8_t* data, size_t size, const std::string& extension) {
  const std::string path = "/tmp/shadetlm-fuzz-" + std::to_string(getpid()) + extension;
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path;
}
