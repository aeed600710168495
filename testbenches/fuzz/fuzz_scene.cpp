// libFuzzer target: the scene parser (JSON text → core::Scene) and the pipeline settings
// resolved against the blocks' declarations, as the program checks them. Bad input may only end in
// core::InputError; anything else — a crash, a sanitizer report, another exception — is
// a bug. scripts/fuzz.sh builds and runs it.
#include <cstddef>
#include <cstdint>
#include <string>

#include "shadetlm/core/input_error.hpp"
#include "shadetlm/core/scene.hpp"
#include "shadetlm/modules/pipeline/pipeline.hpp"

using namespace shadetlm;  // core::, modules::, reference::

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    // Files it names resolve in a folder that does not exist: no disk reads.
    const core::Scene scene = core::load_scene_text(text, "fuzz.json", "/nonexistent-shadetlm-fuzz");
    scene.pipeline.resolve(modules::standard_pipeline().all_settings());
  } catch (const core::InputError&) {
  }
  return 0;
}

// libsystemc refers to sc_main; nothing here simulates.
int sc_main(int, char**) { return 0; }
