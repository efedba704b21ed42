// libFuzzer harness: bytes → a glTF file loaded as a whole scene (io/gltf_scene.h's translation,
// then the scene loader and the mesh reader). Inputs starting with the GLB magic "glTF" are read as
// fuzz.glb, others as fuzz.gltf (JSON; a relative buffer uri may name fuzz.bin, written empty).
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>

#include "fuzz_support.h"
#include "integrators/scene_loading.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  candela::fuzz::write_scratch_file("fuzz.bin", data, 0);
  const auto path = candela::fuzz::write_scratch_file(binary ? "fuzz.glb" : "fuzz.gltf", data, size);
  try {
    (void)candela::load_scene_file(path.string());
  } catch (const std::exception&) {
  }
  return 0;
}
