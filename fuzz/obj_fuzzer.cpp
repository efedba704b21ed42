// libFuzzer harness: bytes → import_obj. The input is the OBJ; text after a line "#--mtl--"
// becomes fuzz.mtl next to it (so "mtllib fuzz.mtl" reaches the MTL parser too).
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

#include "fuzz_support.h"
#include "io/obj_import.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string separator = "#--mtl--";
  const std::size_t split = text.find(separator);
  const std::string obj = split == std::string::npos ? text : text.substr(0, split);
  const std::string mtl = split == std::string::npos ? std::string() : text.substr(split + separator.size());
  candela::fuzz::write_scratch_file("fuzz.mtl", reinterpret_cast<const std::uint8_t*>(mtl.data()),
                                    mtl.size());
  const auto path = candela::fuzz::write_scratch_file(
      "fuzz.obj", reinterpret_cast<const std::uint8_t*>(obj.data()), obj.size());
  try {
    (void)candela::import_obj(path.string(), candela::SourceLocation{"fuzz.json", 1, 1, "shapes[0].file"});
  } catch (const std::exception&) {
  }
  return 0;
}
