// Shared helpers for the libFuzzer harnesses (fuzz/README.md, scripts/fuzz.sh).
#pragma once

#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/photometry.h"
#include "math/constants.h"

namespace candela::fuzz {

// The photometry readers' rule (issue 51: a candela multiplier × ballast factor of two large legal
// numbers made every intensity inf, and 0 × inf NaN): in a file that parses, every stored value
// and every intensity between them is finite, non-negative and at most the scene file's limit
// (1e16), and so are the lamps' numbers. Aborts (a finding) otherwise.
inline void check_photometry(const Photometry& photometry) {
  const auto in_range = [](double value) { return value >= 0 && value <= kMaxSceneMagnitude; };
  for (const double value : photometry.candela)
    if (!in_range(value)) std::abort();
  for (double v = -95; v <= 185; v += 7.5)
    for (double h = -100; h <= 370; h += 12.5)
      if (!in_range(photometry.intensity(v, h))) std::abort();
  for (const double value :
       {photometry.width, photometry.length, photometry.height, photometry.input_watts,
        photometry.candela_multiplier, photometry.ballast_factor, photometry.rated_lumens()})
    if (!std::isfinite(value)) std::abort();
}

// A scratch folder of this process (readers take paths, so the bytes go through a file).
inline const std::filesystem::path& scratch_directory() {
  static const std::filesystem::path directory = [] {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("candela-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(path);
    return path;
  }();
  return directory;
}

inline std::filesystem::path write_scratch_file(const std::string& name, const std::uint8_t* data,
                                                std::size_t size) {
  const std::filesystem::path path = scratch_directory() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

}  // namespace candela::fuzz
