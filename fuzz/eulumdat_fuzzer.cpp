// libFuzzer harness: bytes → parse_eulumdat (the input is the whole EULUMDAT file), and every
// intensity of a file that parses is finite.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <string_view>

#include "io/eulumdat_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const candela::Photometry ies =
        candela::parse_eulumdat(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.ldt");
    for (double v = -95; v <= 185; v += 7.5)
      for (double h = -100; h <= 370; h += 12.5)
        if (!std::isfinite(ies.intensity(v, h))) std::abort();
  } catch (const std::exception&) {
  }
  return 0;
}
