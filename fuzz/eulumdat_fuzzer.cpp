// libFuzzer harness: bytes → parse_eulumdat (the input is the whole EULUMDAT file), and every
// intensity of a file that parses is finite and at most 1e16 (fuzz_support.h check_photometry).
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string_view>

#include "fuzz_support.h"
#include "io/eulumdat_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const candela::Photometry ies =
        candela::parse_eulumdat(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.ldt");
    candela::fuzz::check_photometry(ies);
  } catch (const std::exception&) {
  }
  return 0;
}
