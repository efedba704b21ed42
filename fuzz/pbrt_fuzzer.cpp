// libFuzzer harness: bytes → pbrt_scene_document, the text written as fuzz.pbrt (so an Include of
// itself, or of a file beside it, takes the reader's file paths too).
#include <cstddef>
#include <cstdint>
#include <exception>

#include "fuzz_support.h"
#include "io/pbrt_scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = candela::fuzz::write_scratch_file("fuzz.pbrt", data, size);
  try {
    (void)candela::pbrt_scene_document(path.string());
  } catch (const std::exception&) {
  }
  return 0;
}
