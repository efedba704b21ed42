#include "io/image_reader.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>

#include "math/srgb.h"
#include "util/file_extension.h"
#include "util/input_file.h"

// The one translation unit with stb_image's implementation (image_writer.cpp holds
// stb_image_write's; the two share no symbols). Files are read here, so stb needs no stdio;
// STBI_FAILURE_USERMSG gives the longer failure reasons ("Image not of any known type, or
// corrupt" rather than "unknown image type").
#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_STDIO
#define STBI_FAILURE_USERMSG
#include <stb_image.h>

namespace candela {

RgbImage::RgbImage(int width, int height, std::vector<float> rgb)
    : width_(width), height_(height), rgb_(std::move(rgb)) {
  if (width <= 0 || height <= 0)
    throw std::invalid_argument("texture image size must be positive, got " + std::to_string(width) + "×" +
                                std::to_string(height));
  if (std::size_t(width) * std::size_t(height) > kMaxPixels)
    throw std::invalid_argument("texture image of " + std::to_string(width) + "×" + std::to_string(height) +
                                " pixels is over the limit of 2^28 pixels");
  if (rgb_.size() != std::size_t(width) * std::size_t(height) * 3)
    throw std::invalid_argument("texture image data has " + std::to_string(rgb_.size()) +
                                " floats, expected " +
                                std::to_string(std::size_t(width) * std::size_t(height) * 3));
}

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
    throw std::runtime_error(path + ": truncated PFM data (the header announces " + std::to_string(width) +
                             "×" + std::to_string(height) + " pixels, more than the file holds)");
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
    if (channels == 3)
      film.at(x, y)[static_cast<int>(i % 3)] = value;
    else
      film.at(x, y) = Color(value);
  }
  return film;
}

namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& reason) {
  throw std::runtime_error("cannot load image " + path.string() + ": " + reason);
}

void check_size(const std::filesystem::path& path, long long width, long long height) {
  if (width <= 0 || height <= 0)
    fail(path, "the image has no pixels (" + std::to_string(width) + "×" + std::to_string(height) + ")");
  if (width > INT_MAX || height > INT_MAX ||
      static_cast<unsigned long long>(width) * static_cast<unsigned long long>(height) > RgbImage::kMaxPixels)
    fail(path,
         std::to_string(width) + "×" + std::to_string(height) + " pixels is over the limit of 2^28 pixels");
}

// No image format Candela reads packs more than 2^14 pixels into one byte of file (1-bit PNG
// at deflate's best ratio of 1032:1 gives about 8300; GIF's LZW about 2700; JPEG, HDR, PSD and
// TGA run lengths far fewer). A header announcing more is corrupt: refuse it before stb or
// OpenEXR allocate the announced size (fuzz/image_fuzzer found a 60-byte BMP announcing
// 16384 × 16384 pixels, read as 4 GiB of zeros).
constexpr unsigned long long kMaxPixelsPerFileByte = 1ull << 14;

// BMP (at best RLE8: 255 pixels in 2 bytes), TGA and PSD (run lengths of 128 in 2 bytes) and
// binary PNM (a byte a sample) pack no more than 256 pixels into a byte: stb decodes a 2 KB TGA
// announcing 4112² pixels as 50 MB of garbage instead of refusing it (found by fuzz/image_fuzzer).
constexpr unsigned long long kMaxPixelsPerFileByteUncompressed = 256;

// The limit for the format stb will find in these bytes (by the magic numbers stb tests; TGA has
// none and is what stb tries last).
unsigned long long max_pixels_per_file_byte(const std::vector<unsigned char>& bytes) {
  const auto starts = [&](std::string_view magic) {
    return bytes.size() >= magic.size() &&
           std::equal(magic.begin(), magic.end(), bytes.begin(),
                      [](char a, unsigned char b) { return static_cast<unsigned char>(a) == b; });
  };
  const bool compressed = starts("\x89PNG") || starts("GIF8") || starts("#?") || starts("S\x80\xF6\x34") ||
                          (bytes.size() >= 2 && bytes[0] == 0xFF);  // JPEG (fill bytes, then D8)
  return compressed ? kMaxPixelsPerFileByte : kMaxPixelsPerFileByteUncompressed;
}

void check_plausible_size(const std::filesystem::path& path, long long width, long long height,
                          std::uintmax_t file_bytes,
                          unsigned long long max_per_byte = kMaxPixelsPerFileByte) {
  const unsigned long long pixels =
      static_cast<unsigned long long>(width) * static_cast<unsigned long long>(height);
  if (pixels / max_per_byte > file_bytes)
    fail(path, "the header announces " + std::to_string(width) + "×" + std::to_string(height) +
                   " pixels but the file has only " + std::to_string(file_bytes) +
                   " bytes (corrupt or truncated)");
}

// The extension without its dot ("png"), as kStbExtensions lists them.
std::string extension_name(const std::filesystem::path& path) {
  std::string extension = lower_case_extension(path);
  if (!extension.empty()) extension.erase(0, 1);
  return extension;
}

// Applies the encoding to values that are already in linear-or-encoded float form.
void decode_floats(std::vector<float>& values, bool srgb_encoded) {
  if (!srgb_encoded) return;
  for (float& value : values) value = static_cast<float>(srgb_decode(value));
}

// --- stb_image: 8- and 16-bit formats, and Radiance HDR -----------------------------------

std::vector<unsigned char> read_file_bytes(const std::filesystem::path& path) {
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) fail(path, "cannot read the file size: " + error.message());
  if (size == 0) fail(path, "the file is empty");
  if (size > std::uintmax_t(INT_MAX)) fail(path, "the file is over 2 GiB, which stb_image cannot read");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the file");
  std::vector<unsigned char> bytes(static_cast<std::size_t>(size));
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size));
  if (!in) fail(path, "read error");
  return bytes;
}

// stb_image 2.27 (Debian 12) trusts a JPEG's tables and scans (all found by fuzz/image_fuzzer or
// valgrind). It writes past its 257-entry Huffman size table when a DHT table's 16 code counts
// add up to more than 256 (fixed in stb_image 2.28: "bad DHT header"). Its quantisation and
// Huffman tables and its component planes live in memory it allocates without clearing, so a
// scan that uses a table no DQT or DHT segment defined, a component no scan codes (or, in a
// progressive JPEG, an AC or refinement scan before the component's first DC scan) make the
// picture depend on leftover memory (valgrind: a conditional jump on an uninitialised value;
// UBSan: signed overflow dequantising). Walk the markers as stb does and refuse such a file
// before stb sees it. libjpeg refuses the same files ("Quantization table 0x02 was not defined").
void check_jpeg_markers(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
  // stb takes any run of 0xFF fill bytes before the start-of-image marker D8 as SOI.
  const std::size_t size = bytes.size();
  std::size_t i = 0;
  if (size < 2 || bytes[0] != 0xFF) return;  // not a JPEG
  while (i < size && bytes[i] == 0xFF) ++i;
  if (i >= size || bytes[i] != 0xD8) return;
  ++i;
  const auto length_at = [&](std::size_t at) {
    return at + 1 < size ? (std::size_t(bytes[at]) << 8) | bytes[at + 1] : 0;
  };
  // stb reads bytes past the end of the file as 0 and goes on: read them the same way.
  const auto byte_at = [&](std::size_t at) -> unsigned { return at < size ? bytes[at] : 0; };
  std::array<bool, 4> quantisation_defined{};
  std::array<std::array<bool, 4>, 2> huffman_defined{};  // [0: DC, 1: AC][table]
  struct Component {
    unsigned id = 0, quantisation = 0;
    bool coded = false;  // a scan has written its coefficients (the first DC scan if progressive)
  };
  std::vector<Component> frame;
  bool progressive = false;
  const auto missing = [&](std::string_view table, unsigned number, std::string_view segment,
                           std::size_t component) {
    fail(path, fmt::format("corrupt JPEG: component {} (id {}) uses {} {}, which no {} segment defines",
                           component, frame[component].id, table, number, segment));
  };
  while (i < size) {
    if (bytes[i] != 0xFF) {  // stb skips stray bytes looking for the next marker
      ++i;
      continue;
    }
    while (i < size && bytes[i] == 0xFF) ++i;  // fill bytes
    if (i >= size) return;
    const unsigned char marker = bytes[i++];
    if (marker == 0xD9) {  // end of image: every component coded, progressive ones dequantised now
      for (std::size_t c = 0; c < frame.size(); ++c) {
        if (!frame[c].coded)
          fail(path, fmt::format("corrupt JPEG: no scan codes component {} (id {})", c, frame[c].id));
        if (progressive && !quantisation_defined[frame[c].quantisation])
          missing("quantisation table", frame[c].quantisation, "DQT", c);
      }
      return;
    }
    if (marker == 0x00 || marker == 0x01 || (marker >= 0xD0 && marker <= 0xD8)) continue;  // no length
    const std::size_t length = length_at(i);
    if (length < 2) return;  // stb refuses it
    if (marker == 0xDB) {    // DQT: 8- or 16-bit tables until the length is used up
      long long left = static_cast<long long>(length) - 2;
      std::size_t at = i + 2;
      while (left > 0) {
        const unsigned precision = byte_at(at) >> 4, table = byte_at(at) & 15;
        if (precision > 1 || table > 3) return;  // stb refuses it
        quantisation_defined[table] = true;
        const std::size_t table_bytes = 1 + 64 * (precision + 1);
        at += table_bytes;
        left -= static_cast<long long>(table_bytes);
      }
    }
    if (marker == 0xC4) {  // DHT: as stb reads it, tables until the length is used up
      long long left = static_cast<long long>(length) - 2;
      std::size_t at = i + 2;
      while (left > 0) {
        if (at >= size) return;
        const unsigned table_class = bytes[at] >> 4, table = bytes[at] & 15;
        if (table_class > 1 || table > 3) return;  // stb refuses it
        std::size_t symbols = 0;
        for (std::size_t k = 1; k <= 16; ++k) symbols += byte_at(at + k);
        if (symbols > 256)
          fail(path, "corrupt JPEG: a Huffman table (DHT) declares " + std::to_string(symbols) +
                         " codes, more than the 256 possible");
        huffman_defined[table_class][table] = true;
        at += 17 + symbols;
        left -= static_cast<long long>(17 + symbols);
      }
    }
    if ((marker == 0xC0 || marker == 0xC1 || marker == 0xC2) && frame.empty()) {  // the frame stb decodes
      progressive = marker == 0xC2;
      const unsigned count = byte_at(i + 7);
      for (unsigned c = 0; c < count && c < 4; ++c)
        frame.push_back({byte_at(i + 8 + 3 * c), byte_at(i + 10 + 3 * c)});
      for (const Component& component : frame)
        if (component.quantisation > 3) return;  // stb refuses it
    }
    if (marker == 0xDA) {  // start of scan: the tables it uses must exist now
      const unsigned count = byte_at(i + 2);
      const std::size_t after = i + 3 + 2 * std::size_t(count);
      const unsigned spectral_start = byte_at(after), approximation_high = byte_at(after + 2) >> 4;
      for (unsigned k = 0; k < count; ++k) {
        const unsigned id = byte_at(i + 3 + 2 * k), tables = byte_at(i + 4 + 2 * k);
        const unsigned dc = tables >> 4, ac = tables & 15;
        const auto found =
            std::find_if(frame.begin(), frame.end(), [&](const Component& c) { return c.id == id; });
        if (found == frame.end() || dc > 3 || ac > 3) return;  // stb refuses it
        const std::size_t c = static_cast<std::size_t>(found - frame.begin());
        if (!quantisation_defined[found->quantisation])
          missing("quantisation table", found->quantisation, "DQT", c);
        const bool first_dc = spectral_start == 0 && approximation_high == 0;
        if ((!progressive || first_dc) && !huffman_defined[0][dc]) missing("DC Huffman table", dc, "DHT", c);
        if ((!progressive || spectral_start > 0) && !huffman_defined[1][ac])
          missing("AC Huffman table", ac, "DHT", c);
        if (progressive && !first_dc && !found->coded)
          fail(path, fmt::format("corrupt JPEG: a progressive scan refines component {} (id {}) before its "
                                 "first DC scan",
                                 c, id));
        if (!progressive || first_dc) found->coded = true;
      }
    }
    i += length;
    if (marker == 0xDA) {  // start of scan: skip the entropy-coded data to the next marker
      while (i + 1 < size &&
             !(bytes[i] == 0xFF && bytes[i + 1] != 0x00 && !(bytes[i + 1] >= 0xD0 && bytes[i + 1] <= 0xD7)))
        ++i;
    }
  }
}

// stb_image 2.27 reads the width, height and maximum of a binary PNM (P5, P6) into an int
// without an overflow check: more than 9 digits is undefined behaviour (found by
// fuzz/image_fuzzer). Refuse such a header before stb reads it, skipping whitespace and '#'
// comments as stb does.
void check_pnm_header(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
  if (bytes.size() < 2 || bytes[0] != 'P' || (bytes[1] != '5' && bytes[1] != '6')) return;  // not a PNM
  std::size_t i = 2;
  const auto space = [](unsigned char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r';
  };
  for (int field = 0; field < 3; ++field) {
    while (i < bytes.size() && (space(bytes[i]) || bytes[i] == '#')) {
      if (bytes[i] == '#')
        while (i < bytes.size() && bytes[i] != '\n' && bytes[i] != '\r') ++i;
      else
        ++i;
    }
    std::size_t digits = 0;
    while (i < bytes.size() && bytes[i] >= '0' && bytes[i] <= '9') ++i, ++digits;
    if (digits > 9)
      fail(path, "corrupt PNM header: a number of " + std::to_string(digits) + " digits (at most 9)");
    if (digits == 0) return;  // stb refuses it itself
  }
}

std::string stb_reason() {
  const char* reason = stbi_failure_reason();
  return std::string("stb_image: ") + (reason ? reason : "unknown failure");
}

// Copies decoded samples (rows top first, 3 channels) into bottom-row-first linear floats
// through a lookup table from sample value to linear value.
template <typename Sample>
std::vector<float> to_linear_rows(const Sample* samples, int width, int height,
                                  const std::vector<float>& table) {
  std::vector<float> rgb(std::size_t(width) * std::size_t(height) * 3);
  const std::size_t row_floats = std::size_t(width) * 3;
  for (int row = 0; row < height; ++row) {
    const Sample* source = samples + std::size_t(row) * row_floats;
    float* target = rgb.data() + std::size_t(height - 1 - row) * row_floats;
    for (std::size_t i = 0; i < row_floats; ++i) target[i] = table[source[i]];
  }
  return rgb;
}

std::vector<float> sample_table(std::size_t levels, bool srgb_encoded) {
  std::vector<float> table(levels);
  const double maximum = static_cast<double>(levels - 1);
  for (std::size_t i = 0; i < levels; ++i) {
    const double encoded = static_cast<double>(i) / maximum;
    table[i] = static_cast<float>(srgb_encoded ? srgb_decode(encoded) : encoded);
  }
  return table;
}

RgbImage load_with_stb(const std::filesystem::path& path, ColorEncoding encoding) {
  const std::vector<unsigned char> bytes = read_file_bytes(path);
  const int length = static_cast<int>(bytes.size());
  int width = 0, height = 0, channels_in_file = 0;
  check_jpeg_markers(path, bytes);
  check_pnm_header(path, bytes);
  if (!stbi_info_from_memory(bytes.data(), length, &width, &height, &channels_in_file))
    fail(path, stb_reason());
  check_size(path, width, height);
  check_plausible_size(path, width, height, bytes.size(), max_pixels_per_file_byte(bytes));

  // Asking for 3 channels makes stb replicate grey and drop alpha.
  constexpr int kRgb = 3;
  if (stbi_is_hdr_from_memory(bytes.data(), length)) {
    float* data = stbi_loadf_from_memory(bytes.data(), length, &width, &height, &channels_in_file, kRgb);
    if (!data) fail(path, stb_reason());
    std::vector<float> rgb(std::size_t(width) * std::size_t(height) * 3);
    const std::size_t row_floats = std::size_t(width) * 3;
    for (int row = 0; row < height; ++row)
      std::copy_n(data + std::size_t(row) * row_floats, row_floats,
                  rgb.data() + std::size_t(height - 1 - row) * row_floats);
    stbi_image_free(data);
    decode_floats(rgb, encoding == ColorEncoding::srgb);  // HDR is linear unless told otherwise
    return RgbImage(width, height, std::move(rgb));
  }

  const bool srgb_encoded = encoding != ColorEncoding::linear;  // integer formats are sRGB by default
  if (stbi_is_16_bit_from_memory(bytes.data(), length)) {
    // stb_image 2.27 (Debian 12) reads 16-bit PNM samples in the wrong byte order and
    // scrambles them when expanding grey to RGB; refuse rather than return wrong values.
    if (bytes[0] == 'P' && (bytes[1] == '5' || bytes[1] == '6'))
      fail(path, "16-bit PNM (PPM/PGM) is not supported; use a 16-bit PNG");
    stbi_us* data = stbi_load_16_from_memory(bytes.data(), length, &width, &height, &channels_in_file, kRgb);
    if (!data) fail(path, stb_reason());
    std::vector<float> rgb = to_linear_rows(data, width, height, sample_table(65536, srgb_encoded));
    stbi_image_free(data);
    return RgbImage(width, height, std::move(rgb));
  }
  stbi_uc* data = stbi_load_from_memory(bytes.data(), length, &width, &height, &channels_in_file, kRgb);
  if (!data) fail(path, stb_reason());
  std::vector<float> rgb = to_linear_rows(data, width, height, sample_table(256, srgb_encoded));
  stbi_image_free(data);
  return RgbImage(width, height, std::move(rgb));
}

// --- OpenEXR --------------------------------------------------------------------------------

RgbImage load_exr(const std::filesystem::path& path, ColorEncoding encoding) {
  try {
    Imf::InputFile file(path.c_str());
    // The data window holds the stored pixels; that is the texture (the display window only
    // frames it for viewers).
    const Imath::Box2i window = file.header().dataWindow();
    const long long width = static_cast<long long>(window.max.x) - window.min.x + 1;
    const long long height = static_cast<long long>(window.max.y) - window.min.y + 1;
    check_size(path, width, height);
    std::error_code size_error;
    const std::uintmax_t file_bytes = std::filesystem::file_size(path, size_error);
    if (!size_error) check_plausible_size(path, width, height, file_bytes);

    // R, G, B (a missing one reads as 0), else a luminance-only Y image as grey.
    const Imf::ChannelList& channels = file.header().channels();
    const bool has_rgb = channels.findChannel("R") || channels.findChannel("G") || channels.findChannel("B");
    if (!has_rgb && !channels.findChannel("Y")) {
      std::string names;
      for (auto channel = channels.begin(); channel != channels.end(); ++channel)
        names += (names.empty() ? "" : ", ") + std::string(channel.name());
      fail(path, "no R, G, B or Y channel (found: " + (names.empty() ? std::string("none") : names) + ")");
    }
    // Read top row first, interleaved, every channel type converted to float by OpenEXR.
    std::vector<float> top_first(std::size_t(width) * std::size_t(height) * 3);
    Imf::FrameBuffer frame_buffer;
    const std::size_t x_stride = 3 * sizeof(float), y_stride = x_stride * std::size_t(width);
    const auto slice = [&](int channel) {
      return Imf::Slice::Make(Imf::FLOAT, top_first.data() + channel, window, x_stride, y_stride);
    };
    if (has_rgb) {
      frame_buffer.insert("R", slice(0));
      frame_buffer.insert("G", slice(1));
      frame_buffer.insert("B", slice(2));
    } else {
      frame_buffer.insert("Y", slice(0));  // into the red slots; copied to green and blue below
    }
    file.setFrameBuffer(frame_buffer);
    file.readPixels(window.min.y, window.max.y);
    if (!has_rgb)
      for (std::size_t i = 0; i < top_first.size(); i += 3)
        top_first[i + 1] = top_first[i + 2] = top_first[i];

    // Bottom row first, as RgbImage keeps it.
    std::vector<float> rgb(top_first.size());
    const std::size_t row_floats = std::size_t(width) * 3;
    for (long long row = 0; row < height; ++row)
      std::copy_n(top_first.data() + std::size_t(row) * row_floats, row_floats,
                  rgb.data() + std::size_t(height - 1 - row) * row_floats);
    decode_floats(rgb, encoding == ColorEncoding::srgb);  // EXR is linear unless told otherwise
    return RgbImage(static_cast<int>(width), static_cast<int>(height), std::move(rgb));
  } catch (const std::runtime_error&) {
    throw;  // ours, already naming the file
  } catch (const std::exception& e) {
    // OpenEXR's Iex exceptions: missing file, not an EXR, truncated data.
    fail(path, std::string("OpenEXR: ") + e.what());
  }
}

// --- PFM --------------------------------------------------------------------------------------

RgbImage load_pfm(const std::filesystem::path& path, ColorEncoding encoding) {
  // read_pfm allocates what the header announces; check that against the limit first.
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, "cannot open the file");
    std::string magic;
    long long width = 0, height = 0;
    in >> magic >> width >> height;
    if (!in || (magic != "PF" && magic != "Pf")) fail(path, "not a PFM file (expected a PF or Pf header)");
    check_size(path, width, height);
  }
  const Film film = [&] {
    try {
      return read_pfm(path.string());
    } catch (const std::exception& e) {
      // read_pfm's reasons start with the file name ("PATH: truncated PFM data"); say it once.
      std::string reason = e.what();
      const std::string prefix = path.string() + ": ";
      if (reason.starts_with(prefix)) reason.erase(0, prefix.size());
      fail(path, reason);
    }
  }();
  const int width = film.width(), height = film.height();
  std::vector<float> rgb(std::size_t(width) * std::size_t(height) * 3);
  // Film rows run top first; RgbImage rows bottom first.
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Color& c = film.at(x, height - 1 - y);
      float* target = &rgb[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3];
      target[0] = static_cast<float>(c.r);
      target[1] = static_cast<float>(c.g);
      target[2] = static_cast<float>(c.b);
    }
  decode_floats(rgb, encoding == ColorEncoding::srgb);  // PFM is linear unless told otherwise
  return RgbImage(width, height, std::move(rgb));
}

// Extensions stb_image decodes (it detects the format from the bytes; the extension only
// tells us to hand the file to it).
constexpr std::array<std::string_view, 13> kStbExtensions = {"png", "jpg", "jpeg", "bmp", "tga", "gif", "psd",
                                                             "hdr", "pic", "ppm",  "pgm", "pnm", "jpe"};

}  // namespace

namespace {

// A NaN or infinite texel would spread through every pixel that sees it (and one infinity
// turns a whole `out_of_range: scale` image black): float files must hold finite values, and
// values of at most max_magnitude. The first bad value is named by pixel and channel.
RgbImage checked_values(const std::filesystem::path& path, RgbImage image, double max_magnitude) {
  const std::vector<float>& rgb = image.rgb();
  for (std::size_t i = 0; i < rgb.size(); ++i)
    if (!std::isfinite(rgb[i]) || std::fabs(rgb[i]) > max_magnitude) {
      const std::size_t pixel = i / 3;
      const std::size_t x = pixel % std::size_t(image.width());
      const std::size_t y = pixel / std::size_t(image.width());
      const std::string where = fmt::format("texel ({}, {}) counted from the bottom-left, channel {} ({}),",
                                            x, y, i % 3, std::array{"red", "green", "blue"}[i % 3]);
      if (!std::isfinite(rgb[i]))
        fail(path, fmt::format("{} is {}; image values must be finite", where,
                               std::isnan(rgb[i]) ? "NaN" : "infinite"));
      fail(path, fmt::format("{} is {}, above the limit of {:g} for texture values (scale the image down and "
                             "raise the texture's multiplier)",
                             where, rgb[i], max_magnitude));
    }
  return image;
}

}  // namespace

RgbImage read_image(const std::filesystem::path& path, ColorEncoding encoding, double max_magnitude) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) fail(path, "no such file");
  // A regular file only (a FIFO blocked, a device was read without end), at most 4 GiB.
  const std::string problem = input_file_problem(path.string(), "it", kLargeInputLimit);
  if (!problem.empty()) fail(path, problem);
  const std::string extension = extension_name(path);
  if (extension == "exr") return checked_values(path, load_exr(path, encoding), max_magnitude);
  if (extension == "pfm") return checked_values(path, load_pfm(path, encoding), max_magnitude);
  if (std::find(kStbExtensions.begin(), kStbExtensions.end(), extension) != kStbExtensions.end())
    return checked_values(path, load_with_stb(path, encoding), max_magnitude);
  std::string known = "exr, pfm";
  for (const std::string_view name : kStbExtensions) known += ", " + std::string(name);
  fail(path,
       "unknown image extension \"" + path.extension().string() + "\" (expected one of: " + known + ")");
}

}  // namespace candela
