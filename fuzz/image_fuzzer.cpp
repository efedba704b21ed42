// libFuzzer harness: bytes → read_image (and read_pfm), io/image_reader.h. The first byte picks the file
// extension, so one corpus covers every reader: 0 png, 1 jpg, 2 exr, 3 pfm, 4 hdr, 5 bmp,
// 6 tga, 7 gif, 8 psd, 9 ppm (taken modulo 10); the rest is the file.
#include <stb_image.h>  // declarations only; the implementation is in candela_core

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

#include "fuzz_support.h"
#include "io/image_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static constexpr std::array<const char*, 10> kExtensions = {"png", "jpg", "exr", "pfm", "hdr",
                                                              "bmp", "tga", "gif", "psd", "ppm"};
  const std::string extension = kExtensions[data[0] % kExtensions.size()];
  // Images over 2^22 pixels take more than -timeout=10 s to convert under ASan without being
  // wrong; skip them (the reader's own limits, 2^28 pixels and 2^14 pixels a file byte, are
  // covered by src/io/image_reader_test.cpp). Headers stb cannot parse still go through.
  // (Not for JPEG: stbi_info would reach the stb 2.27 Huffman bug that read_image
  // guards against before calling stb.)
  // stb takes 0xFF fill bytes before the D8 of the start-of-image marker.
  std::size_t soi = 1;
  while (soi < size && data[soi] == 0xFF) ++soi;
  const bool jpeg = size > 2 && data[1] == 0xFF && soi < size && data[soi] == 0xD8;
  // Nor for binary PNM: stbi_info would reach stb 2.27's header overflow that the loader guards.
  const bool pnm = size > 2 && data[1] == 'P' && (data[2] == '5' || data[2] == '6');
  int width = 0, height = 0, channels = 0;
  if (size > 1 && !jpeg && !pnm &&
      stbi_info_from_memory(data + 1, static_cast<int>(std::min<std::size_t>(size - 1, INT32_MAX)), &width,
                            &height, &channels) &&
      static_cast<long long>(width) * height > (1LL << 22))
    return 0;
  const auto path = candela::fuzz::write_scratch_file("fuzz." + extension, data + 1, size - 1);
  try {
    (void)candela::read_image(path);
  } catch (const std::exception&) {
  }
  if (extension == "pfm") {
    try {
      (void)candela::read_pfm(path.string());
    } catch (const std::exception&) {
    }
  }
  return 0;
}
