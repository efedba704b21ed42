// libFuzzer harness: bytes → load_scene_text. An exception (InputError or any std::exception)
// is the expected answer to bad input; a crash, a sanitizer report, a hang or an out-of-memory
// is a bug.
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

#include "fuzz_support.h"
#include "integrators/scene_loading.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    // Relative mesh and texture paths resolve in an empty scratch folder: they are missing.
    (void)candela::load_scene_text(text, "fuzz.json", candela::fuzz::scratch_directory().string());
  } catch (const std::exception&) {
  }
  return 0;
}
