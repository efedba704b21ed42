#include "io/image_writer.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "util/atomic_file.h"

// Files are written here (atomically), never by stb; but Debian's stb (2022) compiles its HDR
// encoder, stbi_write_hdr_to_func included, only without STBI_WRITE_NO_STDIO, so stdio stays on.
#define STB_IMAGE_WRITE_IMPLEMENTATION
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
  else if (extension == "hdr")
    format = ImageFormat::hdr;
  else
    return false;
  return true;
}

namespace {
// Writes the bytes to `file` (the temporary); a failure names `target`, the file the user asked for.
void write_bytes(const std::string& file, const std::string& target, const void* data, std::size_t size) {
  std::ofstream out(file, std::ios::binary);
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) throw std::runtime_error("cannot write " + target);
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
  write_atomically(path, [&](const std::string& temporary) {
    write_bytes(temporary, path, encoded.data(), encoded.size());
  });
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
  write_atomically(
      path, [&](const std::string& temporary) { write_bytes(temporary, path, data.data(), data.size()); });
}

void write_hdr(const Film& film, const std::string& path, double exposure) {
  const std::vector<Color> pixels = expose(film, exposure);
  std::vector<float> rgb(pixels.size() * 3);
  for (std::size_t i = 0; i < pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) rgb[i * 3 + c] = static_cast<float>(std::max(0.0, pixels[i][c]));
  std::vector<unsigned char> encoded;
  const auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(context);
    out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
  };
  if (!stbi_write_hdr_to_func(append, &encoded, film.width(), film.height(), 3, rgb.data()))
    throw std::runtime_error("HDR encoding failed for " + path);
  write_atomically(path, [&](const std::string& temporary) {
    write_bytes(temporary, path, encoded.data(), encoded.size());
  });
}

std::string non_finite_image_problem(const Film& film, ImageFormat format, double exposure) {
  const double scale = std::exp2(exposure);  // as expose() applies it
  const double largest = format == ImageFormat::png ? std::numeric_limits<double>::max()
                                                    : static_cast<double>(std::numeric_limits<float>::max());
  std::size_t not_finite = 0, too_large = 0, first = 0;
  const std::vector<Color>& pixels = film.pixels();
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    bool bad = false;
    for (int c = 0; c < 3; ++c) {
      const double value = pixels[i][c];
      if (!std::isfinite(value)) {
        bad = true;
        ++not_finite;
        break;
      }
      if (std::abs(value * scale) > largest) {
        bad = true;
        ++too_large;
        break;
      }
    }
    if (bad && not_finite + too_large == 1) first = i;
  }
  if (not_finite + too_large == 0) return {};
  const int x = static_cast<int>(first % static_cast<std::size_t>(film.width()));
  const int y = static_cast<int>(first / static_cast<std::size_t>(film.width()));
  const Color& value = pixels[first];
  const std::string where =
      fmt::format("first at pixel ({}, {}): ({:g}, {:g}, {:g})", x, y, value[0], value[1], value[2]);
  if (not_finite > 0)
    return fmt::format(
        "the image has {} pixel{} that {} not finite ({}): a light, emission or texture value of the scene "
        "is "
        "so large that the arithmetic overflowed; scale the scene's values down",
        not_finite + too_large, not_finite + too_large == 1 ? "" : "s",
        not_finite + too_large == 1 ? "is" : "are", where);
  return fmt::format(
      "the image has {} pixel{} beyond the largest single-precision float (3.4e38) once film.exposure ({:g} "
      "stops) is applied ({}): lower the exposure or the scene's light values, or write a .png",
      too_large, too_large == 1 ? "" : "s", exposure, where);
}

void write_image(const Film& film, const std::string& path, const DisplaySettings& display) {
  ImageFormat format;
  if (!image_format_for_path(path, format))
    throw std::runtime_error("unsupported image extension: " + path + " (expected " + kImageExtensions + ")");
  if (const std::string problem = non_finite_image_problem(film, format, display.exposure); !problem.empty())
    throw std::runtime_error("cannot write " + path + ": " + problem);
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
    case ImageFormat::hdr:
      write_hdr(film, path, display.exposure);
      break;
  }
}

}  // namespace candela
