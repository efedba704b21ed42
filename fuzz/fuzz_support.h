// Shared helpers for the libFuzzer harnesses (fuzz/README.md, scripts/fuzz.sh).
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace candela::fuzz {

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
