#include "io/image_reader.h"

#include <bit>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace candela {

Film read_pfm(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::string magic;
  int width = 0, height = 0;
  double scale = 0;
  in >> magic >> width >> height >> scale;
  in.get();  // the single white-space character before the data
  if (!in || (magic != "PF" && magic != "Pf") || width <= 0 || height <= 0 || scale == 0)
    throw std::runtime_error(path + ": not a PFM file");
  const int channels = magic == "PF" ? 3 : 1;
  // The header's size must fit in what is left of the file: refuse before allocating (a
  // 20-byte file announcing 2^31 × 2^31 pixels would otherwise ask for exabytes).
  const std::size_t values = std::size_t(width) * std::size_t(height) * std::size_t(channels);
  const std::streampos data_start = in.tellg();
  in.seekg(0, std::ios::end);
  const std::streampos file_end = in.tellg();
  in.seekg(data_start);
  if (!in || data_start < 0 || file_end < data_start ||
      values > static_cast<std::size_t>(file_end - data_start) / 4)
    throw std::runtime_error(path + ": truncated PFM data (the header announces " + std::to_string(width) + "×" +
                             std::to_string(height) + " pixels, more than the file holds)");
  std::vector<uint32_t> data(values);
  in.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(data.size() * 4));
  if (!in) throw std::runtime_error(path + ": truncated PFM data");
  const bool file_little_endian = scale < 0;
  const bool host_little_endian = std::endian::native == std::endian::little;
  Film film(width, height);
  for (std::size_t i = 0; i < data.size(); ++i) {
    uint32_t bits = data[i];
    if (file_little_endian != host_little_endian) bits = __builtin_bswap32(bits);
    float value;
    std::memcpy(&value, &bits, 4);
    const std::size_t pixel = i / channels;
    const int x = static_cast<int>(pixel % width);
    const int y = height - 1 - static_cast<int>(pixel / width);  // rows stored bottom-up
    if (channels == 3) film.at(x, y)[static_cast<int>(i % 3)] = value;
    else film.at(x, y) = Color(value);
  }
  return film;
}

}  // namespace candela
