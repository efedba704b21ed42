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
  std::vector<uint32_t> data(std::size_t(width) * height * channels);
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
