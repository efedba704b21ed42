// libFuzzer harness: bytes → import_ply (the input is the whole PLY file, header and body).
#include <cstddef>
#include <cstdint>
#include <exception>

#include "fuzz_support.h"
#include "io/ply_import.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = candela::fuzz::write_scratch_file("fuzz.ply", data, size);
  try {
    (void)candela::import_ply(path.string(), candela::SourceLocation{"fuzz.json", 1, 1, "shapes[0].file"});
  } catch (const std::exception&) {
  }
  return 0;
}
