// libFuzzer target: the mesh loader (assimp: OBJ, PLY, STL, glTF, …). The first byte
// picks the extension; the rest is the file. Bad input may only end in
// core::InputError. scripts/fuzz.sh builds and runs it.
#include <cstdio>

#include "shadetlm/core/input_error.hpp"
#include "shadetlm/core/mesh_io.hpp"
#include "fuzz_file.hpp"

using namespace shadetlm;  // core::, modules::, reference::

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const char* extensions[4] = {".obj", ".ply", ".stl", ".gltf"};
  const std::string path = fuzz_file(data + 1, size - 1, extensions[data[0] % 4]);
  try {
    core::load_mesh_file(path);
  } catch (const core::InputError&) {
  }
  std::remove(path.c_str());
  return 0;
}
