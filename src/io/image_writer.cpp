#include "io/image_writer.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "util/atomic_file.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#include <stb_image_write.h>

namespace candela {

bool image_format_for_path(const std::string& path, ImageFormat& format) {
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos) return false;
  std::string extension = path.substr(dot + 1);
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == "png")
    format = ImageFormat::png;
  else if (extension == "exr")
    format = ImageFormat::exr;
  else if (extension == "pfm")
    format = ImageFormat::pfm;
  else
    return false;
  return true;
}

namespace {
void write_bytes(const std::string& path, const void* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary);
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) throw std::runtime_error("cannot write " + path);
}
}  // namespace

void write_png(const Film& film, const std::string& path, const DisplaySettings& display) {
  const std::vector<uint8_t> bytes = to_display(film, display);
  std::vector<unsigned char> encoded;
  const auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(context);
    out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
  };
  if (!stbi_write_png_to_func(append, &encoded, film.width(), film.height(), 3, bytes.data(),
                              film.width() * 3))
    throw std::runtime_error("PNG encoding failed for " + path);
  write_atomically(
      path, [&](const std::string& temporary) { write_bytes(temporary, encoded.data(), encoded.size()); });
}

void write_exr(const Film& film, const std::string& path, double exposure) {
  const std::vector<Color> pixels = expose(film, exposure);
  const int width = film.width(), height = film.height();
  std::vector<float> channels[3];
  for (auto& channel : channels) channel.resize(pixels.size());
  for (std::size_t i = 0; i < pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) channels[c][i] = static_cast<float>(pixels[i][c]);
  write_atomically(path, [&](const std::string& temporary) {
    try {
      Imf::Header header(width, height);
      const char* names[3] = {"R", "G", "B"};
      Imf::FrameBuffer frame_buffer;
      for (int c = 0; c < 3; ++c) {
        header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
        frame_buffer.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(channels[c].data()),
                                                 sizeof(float), sizeof(float) * width));
      }
      Imf::OutputFile file(temporary.c_str(), header);
      file.setFrameBuffer(frame_buffer);
      file.writePixels(height);
    } catch (const std::exception& e) {
      throw std::runtime_error("cannot write " + path + ": " + e.what());
    }
  });
}

void write_pfm(const Film& film, const std::string& path, double exposure) {
  const std::vector<Color> pixels = expose(film, exposure);
  const int width = film.width(), height = film.height();
  std::string data = "PF\n" + std::to_string(width) + " " + std::to_string(height) + "\n-1.0\n";
  // PFM stores rows bottom to top, little-endian floats (scale -1).
  std::vector<float> row(std::size_t(width) * 3);
  for (int y = height - 1; y >= 0; --y) {
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c)
        row[std::size_t(x) * 3 + c] = static_cast<float>(pixels[std::size_t(y) * width + x][c]);
    data.append(reinterpret_cast<const char*>(row.data()), row.size() * sizeof(float));
  }
  write_atomically(path,
                   [&](const std::string& temporary) { write_bytes(temporary, data.data(), data.size()); });
}

void write_image(const Film& film, const std::string& path, const DisplaySettings& display) {
  ImageFormat format;
  if (!image_format_for_path(path, format))
    throw std::runtime_error("unsupported image extension: " + path + " (expected .png, .exr or .pfm)");
  switch (format) {
    case ImageFormat::png:
      write_png(film, path, display);
      break;
    case ImageFormat::exr:
      write_exr(film, path, display.exposure);
      break;
    case ImageFormat::pfm:
      write_pfm(film, path, display.exposure);
      break;
  }
}

}  // namespace candela
