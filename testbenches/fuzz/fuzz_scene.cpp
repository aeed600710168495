// libFuzzer target: the scene parser (JSON text → core::Scene). Bad input may only end in
// core::InputError; anything else — a crash, a sanitizer report, another exception — is
// a bug. scripts/fuzz.sh builds and runs it.
#include <cstddef>
#include <cstdint>
#include <string>

#include "shadetlm/core/input_error.hpp"
#include "shadetlm/core/scene.hpp"

using namespace shadetlm;  // core::, modules::, reference::

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    // Files it names resolve in a folder that does not exist: no disk reads.
    core::load_scene_text(text, "fuzz.json", "/nonexistent-shadetlm-fuzz");
  } catch (const core::InputError&) {
  }
  return 0;
}
