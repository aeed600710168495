// libFuzzer target: the image loaders (PNG through libpng, JPEG through stb, EXR through OpenEXR).
// The first byte picks the extension; the rest is the file. Bad input may only end in
// core::InputError. scripts/fuzz.sh builds and runs it.
#include <cstdio>

#include "shadetlm/core/input_error.hpp"
#include "shadetlm/core/texture.hpp"
#include "fuzz_file.hpp"

using namespace shadetlm;  // core::, modules::, reference::

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const char* extensions[3] = {".png", ".jpg", ".exr"};
  const std::string path = fuzz_file(data + 1, size - 1, extensions[data[0] % 3]);
  try {
    core::load_texture_file(path);
  } catch (const core::InputError&) {
  }
  std::remove(path.c_str());
  return 0;
}
