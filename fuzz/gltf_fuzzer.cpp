// libFuzzer harness: bytes → import_gltf. Inputs starting with the GLB magic "glTF" are read as
// fuzz.glb, others as fuzz.gltf (JSON; a relative buffer uri may name fuzz.bin, written empty).
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>

#include "fuzz_support.h"
#include "io/gltf_import.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  candela::fuzz::write_scratch_file("fuzz.bin", data, 0);
  const auto path = candela::fuzz::write_scratch_file(binary ? "fuzz.glb" : "fuzz.gltf", data, size);
  try {
    (void)candela::import_gltf(path.string(), candela::SourceLocation{"fuzz.json", 1, 1, "shapes[0].file"});
  } catch (const std::exception&) {
  }
  return 0;
}
