// Image files to linear RGB (SPEC §7: image textures, PNG/JPG/EXR): decoded values against the
// sRGB formula, the bottom-row-first convention, and the errors a bad file gives (the fuzz-found
// ones included).
#include "io/image_reader.h"

#include <gtest/gtest.h>
#include <stb_image_write.h>  // the implementation is in candela_core (io/image_writer.cpp)
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "camera/film.h"
#include "io/image_writer.h"
#include "scratch_directory.h"

namespace candela {
namespace {

namespace fs = std::filesystem;

// The sRGB EOTF written out independently of the code under test (IEC 61966-2-1).
double srgb_to_linear(int byte) {
  const double c = byte / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// A fresh folder per test and process.
class TextureImageFiles : public ::testing::Test {
 protected:
  fs::path path(const std::string& name) const { return directory_ / name; }

  static void write_bytes(const fs::path& file, const void* data, std::size_t size) {
    std::ofstream out(file, std::ios::binary);
    out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
    ASSERT_TRUE(out.good()) << file;
  }
  static void append(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(context);
    out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
  }
  // candela_core builds stb_image_write without stdio: encode to memory, then write.
  fs::path write_png(const std::string& name, int width, int height, int channels,
                     const std::vector<unsigned char>& pixels) const {
    std::vector<unsigned char> encoded;
    EXPECT_TRUE(
        stbi_write_png_to_func(append, &encoded, width, height, channels, pixels.data(), width * channels));
    write_bytes(path(name), encoded.data(), encoded.size());
    return path(name);
  }
  static std::vector<unsigned char> encode_jpg(int width, int height, const std::vector<unsigned char>& rgb) {
    std::vector<unsigned char> encoded;
    EXPECT_TRUE(stbi_write_jpg_to_func(append, &encoded, width, height, 3, rgb.data(), 100));
    return encoded;
  }
  fs::path write_jpg(const std::string& name, int width, int height,
                     const std::vector<unsigned char>& rgb) const {
    const std::vector<unsigned char> encoded = encode_jpg(width, height, rgb);
    write_bytes(path(name), encoded.data(), encoded.size());
    return path(name);
  }

  candela::testing::ScratchDirectory scratch_{"candela-texture-image"};
  const fs::path& directory_ = scratch_.path();
};

// The message of the std::runtime_error that loading `file` throws.
std::string load_error(const fs::path& file) {
  try {
    read_image(file);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for " << file;
  return "";
}

// 4×2 RGB bytes, file order (top row first); every channel of every pixel different.
const std::vector<unsigned char> kPixels4x2 = {
    0,   10,  20,  30,  40,  50,  60,  70,  80,  90,  100, 110,  // top row
    120, 130, 140, 150, 160, 170, 200, 220, 240, 255, 1,   5,    // bottom row
};

TEST_F(TextureImageFiles, PngBytesDecodeWithTheSrgbCurveBottomRowFirst) {
  const RgbImage image = read_image(write_png("rgb.png", 4, 2, 3, kPixels4x2), ColorEncoding::automatic);
  ASSERT_EQ(image.width(), 4);
  ASSERT_EQ(image.height(), 2);
  for (int file_row = 0; file_row < 2; ++file_row)
    for (int x = 0; x < 4; ++x) {
      // The file's first (top) row is y = 1; its last (bottom) row y = 0.
      const Color c = image.texel(x, 1 - file_row);
      for (int channel = 0; channel < 3; ++channel)
        EXPECT_NEAR(c[channel], srgb_to_linear(kPixels4x2[std::size_t(file_row * 12 + x * 3 + channel)]),
                    1e-7)
            << "x " << x << " file row " << file_row << " channel " << channel;
    }
  // Spot values: byte 255 → 1, byte 0 → 0, byte 10 below the 0.04045 threshold is linear.
  EXPECT_FLOAT_EQ(image.texel(3, 0).r, 1.0f);
  EXPECT_FLOAT_EQ(image.texel(0, 1).r, 0.0f);
  EXPECT_FLOAT_EQ(image.texel(0, 1).g, static_cast<float>(10 / 255.0 / 12.92));
  // Explicit srgb is what automatic means for a PNG.
  const RgbImage srgb = read_image(path("rgb.png"), ColorEncoding::srgb);
  EXPECT_EQ(srgb.rgb(), image.rgb());
}

TEST_F(TextureImageFiles, LinearEncodingKeepsPngBytesDividedBy255) {
  const RgbImage image = read_image(write_png("rgb.png", 4, 2, 3, kPixels4x2), ColorEncoding::linear);
  EXPECT_FLOAT_EQ(image.texel(2, 1).g, static_cast<float>(70 / 255.0));
  EXPECT_FLOAT_EQ(image.texel(3, 0).b, static_cast<float>(5 / 255.0));
}

TEST_F(TextureImageFiles, GreyAndGreyAlphaBecomeEqualChannels) {
  const RgbImage grey = read_image(write_png("grey.png", 2, 1, 1, {64, 200}));
  EXPECT_EQ(grey.texel(0, 0), Color(static_cast<float>(srgb_to_linear(64))));
  EXPECT_EQ(grey.texel(1, 0), Color(static_cast<float>(srgb_to_linear(200))));
  // Grey + alpha: alpha is ignored, not multiplied in.
  const RgbImage grey_alpha = read_image(write_png("grey-alpha.png", 2, 1, 2, {64, 0, 200, 17}));
  EXPECT_EQ(grey_alpha.rgb(), grey.rgb());
}

TEST_F(TextureImageFiles, RgbaDropsAlpha) {
  const RgbImage image = read_image(write_png("rgba.png", 1, 1, 4, {255, 128, 0, 0}));
  EXPECT_EQ(image.texel(0, 0), Color(1.0, static_cast<float>(srgb_to_linear(128)), 0.0));
}

// A 16-bit PNG built by hand (stb_image_write writes only 8 bits): IHDR, one IDAT holding an
// uncompressed ("stored") deflate block, IEND; CRC-32 and Adler-32 as PNG and zlib define them.
std::string sixteen_bit_png(int width, int height, int color_type, const std::vector<int>& samples) {
  const auto crc32 = [](const std::string& bytes) {
    uint32_t crc = 0xffffffffu;
    for (const unsigned char byte : bytes) {
      crc ^= byte;
      for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    return ~crc;
  };
  const auto big_endian = [](uint32_t value, int bytes) {
    std::string out;
    for (int i = bytes - 1; i >= 0; --i) out += static_cast<char>((value >> (8 * i)) & 0xff);
    return out;
  };
  const auto chunk = [&](const std::string& type, const std::string& data) {
    return big_endian(static_cast<uint32_t>(data.size()), 4) + type + data +
           big_endian(crc32(type + data), 4);
  };
  const int channels = color_type == 2 ? 3 : 1;
  std::string raw;  // each row: filter type 0, then big-endian samples
  for (int y = 0; y < height; ++y) {
    raw += '\0';
    for (int i = 0; i < width * channels; ++i)
      raw += big_endian(static_cast<uint32_t>(samples[std::size_t(y * width * channels + i)]), 2);
  }
  uint32_t a = 1, b = 0;  // Adler-32
  for (const unsigned char byte : raw) {
    a = (a + byte) % 65521;
    b = (b + a) % 65521;
  }
  const uint16_t length = static_cast<uint16_t>(raw.size());
  std::string zlib = "\x78\x01";
  zlib += '\x01';  // final block, stored
  zlib += static_cast<char>(length & 0xff);
  zlib += static_cast<char>(length >> 8);
  zlib += static_cast<char>(~length & 0xff);
  zlib += static_cast<char>((~length >> 8) & 0xff);
  zlib += raw + big_endian((b << 16) | a, 4);
  const std::string header = big_endian(static_cast<uint32_t>(width), 4) +
                             big_endian(static_cast<uint32_t>(height), 4) + static_cast<char>(16) +
                             static_cast<char>(color_type) + std::string(3, '\0');
  return std::string("\x89PNG\r\n\x1a\n") + chunk("IHDR", header) + chunk("IDAT", zlib) + chunk("IEND", "");
}

TEST_F(TextureImageFiles, SixteenBitPngKeepsItsPrecision) {
  const std::string rgb = sixteen_bit_png(2, 1, 2, {1000, 40000, 65535, 0, 257, 12345});
  write_bytes(path("deep.png"), rgb.data(), rgb.size());
  const RgbImage linear = read_image(path("deep.png"), ColorEncoding::linear);
  EXPECT_EQ(linear.texel(0, 0),
            Color(static_cast<float>(1000 / 65535.0), static_cast<float>(40000 / 65535.0), 1.0));
  EXPECT_EQ(linear.texel(1, 0),
            Color(0.0, static_cast<float>(257 / 65535.0), static_cast<float>(12345 / 65535.0)));
  const RgbImage srgb = read_image(path("deep.png"));
  EXPECT_FLOAT_EQ(srgb.texel(0, 0).g, static_cast<float>(std::pow((40000 / 65535.0 + 0.055) / 1.055, 2.4)));
  // 1000/65535 is no multiple of 1/255: eight bits would have lost it.
  EXPECT_FLOAT_EQ(srgb.texel(0, 0).r, static_cast<float>(1000 / 65535.0 / 12.92));
  // 16-bit grey becomes equal channels.
  const std::string grey = sixteen_bit_png(2, 1, 0, {1000, 40000});
  write_bytes(path("deep-grey.png"), grey.data(), grey.size());
  const RgbImage grey_image = read_image(path("deep-grey.png"), ColorEncoding::linear);
  EXPECT_EQ(grey_image.texel(0, 0), Color(static_cast<float>(1000 / 65535.0)));
  EXPECT_EQ(grey_image.texel(1, 0), Color(static_cast<float>(40000 / 65535.0)));
}

TEST_F(TextureImageFiles, EightBitPnmIsReadSixteenBitRefused) {
  const std::string ppm = std::string("P6\n2 1\n255\n") + '\x00' + '\x80' + '\xff' + '\x10' + '\x20' + '\x30';
  write_bytes(path("small.ppm"), ppm.data(), ppm.size());
  const RgbImage image = read_image(path("small.ppm"), ColorEncoding::linear);
  EXPECT_EQ(image.texel(0, 0), Color(0.0, static_cast<float>(128 / 255.0), 1.0));
  // stb_image 2.27 swaps the bytes of 16-bit PNM samples: refused, not read wrong.
  const std::string pgm = std::string("P5\n1 1\n65535\n") + '\x03' + '\xe8';
  write_bytes(path("deep.pgm"), pgm.data(), pgm.size());
  const std::string message = load_error(path("deep.pgm"));
  EXPECT_NE(message.find("deep.pgm"), std::string::npos) << message;
  EXPECT_NE(message.find("16-bit PNM"), std::string::npos) << message;
}

TEST_F(TextureImageFiles, JpegRoundTripsWithinCompressionError) {
  // Smooth content at quality 100 (no chroma subsampling): JPEG's error stays within 3 codes.
  constexpr int kSize = 16;
  std::vector<unsigned char> rgb;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      for (const int value : {40 + 8 * x, 200 - 4 * y, 128}) rgb.push_back(static_cast<unsigned char>(value));
  const RgbImage image = read_image(write_jpg("smooth.jpg", kSize, kSize, rgb));
  ASSERT_EQ(image.width(), kSize);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const Color c = image.texel(x, kSize - 1 - y);
      for (int channel = 0; channel < 3; ++channel) {
        const int code = rgb[std::size_t((y * kSize + x) * 3 + channel)];
        EXPECT_GE(c[channel], srgb_to_linear(code - 3)) << x << ", " << y << " channel " << channel;
        EXPECT_LE(c[channel], srgb_to_linear(code + 3)) << x << ", " << y << " channel " << channel;
      }
    }
}

Film float_film() {
  Film film(3, 2);  // rows top first
  film.at(0, 0) = {1.5, 2.25, 1000.125};
  film.at(1, 0) = {0.1, 0.2, 0.3};
  film.at(2, 0) = {0, 65504.5, 1e-4};
  film.at(0, 1) = {3.75, 0, 42};
  film.at(1, 1) = {0.333, 0.666, 0.999};
  film.at(2, 1) = {7, 8, 9};
  return film;
}

void expect_film_exactly(const RgbImage& image, const Film& film) {
  ASSERT_EQ(image.width(), film.width());
  ASSERT_EQ(image.height(), film.height());
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) {
      const Color stored = film.at(x, film.height() - 1 - y);
      const Color read = image.texel(x, y);
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(read[c], static_cast<float>(stored[c])) << x << ", " << y << " channel " << c;
    }
}

TEST_F(TextureImageFiles, ExrFromTheImageWriterReadsBackExactlyAndLinear) {
  const Film film = float_film();
  write_exr(film, path("float.exr").string(), 0);
  expect_film_exactly(read_image(path("float.exr")), film);  // values > 1 kept, no curve applied
  expect_film_exactly(read_image(path("float.exr"), ColorEncoding::linear), film);
  const RgbImage srgb = read_image(path("float.exr"), ColorEncoding::srgb);
  EXPECT_FLOAT_EQ(srgb.texel(1, 0).g, static_cast<float>(std::pow((0.666f + 0.055) / 1.055, 2.4)));
}

TEST_F(TextureImageFiles, PfmReadsBackExactlyAndLinear) {
  const Film film = float_film();
  write_pfm(film, path("float.pfm").string(), 0);
  expect_film_exactly(read_image(path("float.pfm")), film);
}

TEST_F(TextureImageFiles, RadianceHdrIsLinear) {
  // One RGBE pixel written by hand (byte for byte, independent of io/image_writer.h): shared
  // exponent 133 means mantissa · 2^(133 − 136), so (4, 16, 128) is (0.5, 2, 16) exactly.
  const std::string hdr =
      std::string("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 1\n") + '\x04' + '\x10' + '\x80' + '\x85';
  write_bytes(path("sky.hdr"), hdr.data(), hdr.size());
  EXPECT_EQ(read_image(path("sky.hdr")).texel(0, 0), Color(0.5, 2, 16));
  const RgbImage srgb = read_image(path("sky.hdr"), ColorEncoding::srgb);
  EXPECT_FLOAT_EQ(srgb.texel(0, 0).r, static_cast<float>(std::pow(0.555 / 1.055, 2.4)));
}

TEST_F(TextureImageFiles, UpperCaseExtensionIsAccepted) {
  write_png("rgb.png", 4, 2, 3, kPixels4x2);
  fs::rename(path("rgb.png"), path("RGB.PNG"));
  EXPECT_EQ(read_image(path("RGB.PNG")).width(), 4);
}

TEST_F(TextureImageFiles, MissingFileNamesTheFile) {
  const std::string message = load_error(path("absent.png"));
  EXPECT_NE(message.find("absent.png"), std::string::npos) << message;
  EXPECT_NE(message.find("no such file"), std::string::npos) << message;
}

TEST_F(TextureImageFiles, GarbageBytesNameTheFileAndStbsReason) {
  const std::string garbage = "this is not a PNG file at all, just text";
  write_bytes(path("garbage.png"), garbage.data(), garbage.size());
  const std::string message = load_error(path("garbage.png"));
  EXPECT_NE(message.find("garbage.png"), std::string::npos) << message;
  EXPECT_NE(message.find("stb_image: "), std::string::npos) << message;
  // A PNG cut short after its header.
  std::vector<unsigned char> encoded;
  ASSERT_TRUE(stbi_write_png_to_func(append, &encoded, 4, 2, 3, kPixels4x2.data(), 12));
  write_bytes(path("truncated.png"), encoded.data(), 40);
  EXPECT_NE(load_error(path("truncated.png")).find("truncated.png"), std::string::npos);
}

TEST_F(TextureImageFiles, GarbageExrAndPfmNameTheFile) {
  const std::string garbage = "garbage";
  write_bytes(path("garbage.exr"), garbage.data(), garbage.size());
  const std::string exr = load_error(path("garbage.exr"));
  EXPECT_NE(exr.find("garbage.exr"), std::string::npos) << exr;
  EXPECT_NE(exr.find("OpenEXR"), std::string::npos) << exr;
  write_bytes(path("garbage.pfm"), garbage.data(), garbage.size());
  const std::string pfm = load_error(path("garbage.pfm"));
  EXPECT_NE(pfm.find("garbage.pfm"), std::string::npos) << pfm;
  EXPECT_NE(pfm.find("not a PFM file"), std::string::npos) << pfm;
  const std::string truncated = "PF\n2 2\n-1.0\n0123";
  write_bytes(path("truncated.pfm"), truncated.data(), truncated.size());
  EXPECT_NE(load_error(path("truncated.pfm")).find("truncated PFM data"), std::string::npos);
}

TEST_F(TextureImageFiles, UnknownExtensionNamesTheFileAndTheKnownOnes) {
  write_png("picture.png", 4, 2, 3, kPixels4x2);
  fs::copy_file(path("picture.png"), path("picture.webp"));
  const std::string message = load_error(path("picture.webp"));
  EXPECT_NE(message.find("picture.webp"), std::string::npos) << message;
  EXPECT_NE(message.find("\".webp\""), std::string::npos) << message;
  EXPECT_NE(message.find("png, jpg"), std::string::npos) << message;
  fs::copy_file(path("picture.png"), path("no-extension"));
  EXPECT_NE(load_error(path("no-extension")).find("no-extension"), std::string::npos);
}

TEST_F(TextureImageFiles, EmptyFilesAndFoldersAreRefused) {
  write_bytes(path("empty.png"), "", 0);
  EXPECT_NE(load_error(path("empty.png")).find("empty"), std::string::npos);
  fs::create_directories(path("folder.png"));
  EXPECT_NE(load_error(path("folder.png")).find("directory"), std::string::npos);
}

TEST_F(TextureImageFiles, ImagesOverTwoToThe28PixelsAreRefusedBeforeDecoding) {
  // A PFM header announcing 20000 × 20000 pixels (400 M > 2^28) and no data: refused from the
  // header, without allocating the 4.8 GB it announces.
  const std::string huge = "PF\n20000 20000\n-1.0\n";
  write_bytes(path("huge.pfm"), huge.data(), huge.size());
  const std::string message = load_error(path("huge.pfm"));
  EXPECT_NE(message.find("huge.pfm"), std::string::npos) << message;
  EXPECT_NE(message.find("2^28"), std::string::npos) << message;
  const std::string zero = "PF\n0 4\n-1.0\n";
  write_bytes(path("zero.pfm"), zero.data(), zero.size());
  EXPECT_NE(load_error(path("zero.pfm")).find("no pixels"), std::string::npos);
}

// Fuzzing regression (fuzz/image_fuzzer): a PFM header within the 2^28-pixel limit but with no
// data made read_pfm allocate what the header announced (16384 × 16384 × 3 floats, 3 GiB)
// before finding the file truncated. It must refuse from the file size, naming the file.
TEST_F(TextureImageFiles, FuzzPfmHeaderLargerThanTheFileIsRefusedBeforeAllocating) {
  const std::string header_only = "PF\n16384 16384\n-1.0\n";
  write_bytes(path("header-only.pfm"), header_only.data(), header_only.size());
  const std::string message = load_error(path("header-only.pfm"));
  EXPECT_NE(message.find("header-only.pfm"), std::string::npos) << message;
  EXPECT_NE(message.find("truncated PFM data"), std::string::npos) << message;
  // read_pfm on its own (no 2^28 check in front): 2^31-1 squared announced in a 30-byte file.
  const std::string absurd = "Pf\n2147483647 2147483647\n1\n";
  write_bytes(path("absurd.pfm"), absurd.data(), absurd.size());
  try {
    (void)read_pfm(path("absurd.pfm").string());
    ADD_FAILURE() << "read_pfm accepted a header larger than the file";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("truncated PFM data"), std::string::npos) << e.what();
  }
}

// Fuzzing regression (fuzz/image_fuzzer): a 54-byte BMP header announcing 16384 × 16384
// pixels (exactly 2^28, within the limit) and no pixel data was decoded by stb_image as 4 GiB
// of zeros. A header announcing far more pixels than the file could hold is refused.
TEST_F(TextureImageFiles, FuzzTinyFileAnnouncingAHugeImageIsRefused) {
  const std::string bmp(
      "BM\x36\0\0\0\0\0\0\0\x36\0\0\0"              // file header, 54 bytes
      "\x28\0\0\0\0\x40\0\0\0\x40\0\0\x01\0\x18\0"  // 40, 16384, 16384, 1 plane, 24 bits
      "\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0",
      54);
  write_bytes(path("huge.bmp"), bmp.data(), bmp.size());
  const std::string message = load_error(path("huge.bmp"));
  EXPECT_NE(message.find("huge.bmp"), std::string::npos) << message;
  EXPECT_NE(message.find("16384×16384"), std::string::npos) << message;
  EXPECT_NE(message.find("corrupt or truncated"), std::string::npos) << message;
}

// Fuzzing regression (fuzz/image_fuzzer): a JPEG whose Huffman table (DHT) declares 512 codes
// made stb_image 2.27 write past its 257-entry size table (UBSan: index 257 out of bounds).
TEST_F(TextureImageFiles, FuzzJpegHuffmanTableWithOver256CodesIsRefused) {
  const std::string jpeg = std::string("\xFF\xD8\xFF\xC4\x00\x13\x00", 7) + std::string(16, '\x20');
  write_bytes(path("bad-dht.jpg"), jpeg.data(), jpeg.size());
  const std::string message = load_error(path("bad-dht.jpg"));
  EXPECT_NE(message.find("bad-dht.jpg"), std::string::npos) << message;
  EXPECT_NE(message.find("Huffman table (DHT) declares 512 codes"), std::string::npos) << message;
  // The same table cut short by the end of the file (stb reads the missing counts as 0).
  const std::string cut = std::string("\xFF\xD8\xFF\xC4\x00\x13\x00\x20\x20\x20\x01\xFF\xD8", 13);
  write_bytes(path("cut-dht.jpg"), cut.data(), cut.size());
  EXPECT_NE(load_error(path("cut-dht.jpg")).find("declares 568 codes"), std::string::npos);
  // stb takes 0xFF fill bytes before the start-of-image marker: FF FF … FF D8 is a JPEG too.
  const std::string filled =
      std::string(9, '\xFF') + std::string("\xD8\xFF\xC4\x00\x13\x00\x20\x20\x20\x01\xFF\xD8", 12);
  write_bytes(path("filled-dht.jpg"), filled.data(), filled.size());
  EXPECT_NE(load_error(path("filled-dht.jpg")).find("Huffman table (DHT) declares"), std::string::npos);
}

// Where the first segment with this marker starts (its 0xFF) in a JPEG written by stb_image_write,
// whose segments follow each other without fill bytes up to the scan.
std::size_t jpeg_segment(const std::vector<unsigned char>& jpeg, unsigned char marker) {
  std::size_t at = 2;
  while (at + 3 < jpeg.size() && jpeg[at + 1] != marker)
    at += 2 + ((std::size_t(jpeg[at + 2]) << 8) | jpeg[at + 3]);
  EXPECT_LT(at + 3, jpeg.size()) << "no marker " << int(marker);
  return at;
}

// 8×8 pixels of a gradient, as stb_image_write encodes them: quantisation tables 0 (luma) and 1
// (chroma), Huffman tables 0 and 1 of each class, one interleaved baseline scan.
std::vector<unsigned char> gradient_rgb_8x8() {
  std::vector<unsigned char> rgb;
  for (int i = 0; i < 64; ++i)
    for (const int value : {4 * i, 200 - i, 128}) rgb.push_back(static_cast<unsigned char>(value));
  return rgb;
}

// Found by valgrind and UBSan (a conditional jump on an uninitialised value in stb_image; signed
// overflow at stb_image.h:2197): a JPEG whose frame gives a component quantisation table 2, which
// no DQT segment defines, was decoded by stb_image 2.27 with whatever memory its table held. It
// is refused before stb decodes it, naming the file, the component and the table.
TEST_F(TextureImageFiles, JpegUsingAnUndefinedQuantisationTableIsRefused) {
  std::vector<unsigned char> jpeg = encode_jpg(8, 8, gradient_rgb_8x8());
  write_bytes(path("good.jpg"), jpeg.data(), jpeg.size());
  EXPECT_EQ(read_image(path("good.jpg")).width(), 8);
  jpeg[jpeg_segment(jpeg, 0xC0) + 12] =
      2;  // FF C0, length, precision, height, width, count, id, sampling: Tq
  write_bytes(path("undefined-dqt.jpg"), jpeg.data(), jpeg.size());
  const std::string message = load_error(path("undefined-dqt.jpg"));
  EXPECT_NE(message.find("undefined-dqt.jpg"), std::string::npos) << message;
  EXPECT_NE(message.find("component 0 (id 1) uses quantisation table 2, which no DQT segment defines"),
            std::string::npos)
      << message;
}

// The same for Huffman tables: a scan naming DC and AC table 2, which no DHT segment defines,
// made stb_image 2.27 decode with uninitialised code tables (valgrind: stbi__jpeg_huff_decode).
TEST_F(TextureImageFiles, JpegUsingAnUndefinedHuffmanTableIsRefused) {
  std::vector<unsigned char> jpeg = encode_jpg(8, 8, gradient_rgb_8x8());
  jpeg[jpeg_segment(jpeg, 0xDA) + 6] = 0x22;  // FF DA, length, count, id: Td and Ta
  write_bytes(path("undefined-dht.jpg"), jpeg.data(), jpeg.size());
  const std::string message = load_error(path("undefined-dht.jpg"));
  EXPECT_NE(message.find("undefined-dht.jpg"), std::string::npos) << message;
  EXPECT_NE(message.find("component 0 (id 1) uses DC Huffman table 2, which no DHT segment defines"),
            std::string::npos)
      << message;
}

// stb_image 2.27 leaves the plane of a component that no scan codes as it was allocated: a JPEG
// that ends after its tables, or whose one scan codes only the first of three components, gave
// pixels made of leftover memory (valgrind: stbi__YCbCr_to_RGB_simd).
TEST_F(TextureImageFiles, JpegWithAComponentNoScanCodesIsRefused) {
  const std::vector<unsigned char> jpeg = encode_jpg(8, 8, gradient_rgb_8x8());
  const std::size_t scan = jpeg_segment(jpeg, 0xDA);
  std::vector<unsigned char> no_scan(jpeg.begin(), jpeg.begin() + static_cast<std::ptrdiff_t>(scan));
  no_scan.insert(no_scan.end(), {0xFF, 0xD9});
  write_bytes(path("no-scan.jpg"), no_scan.data(), no_scan.size());
  std::string message = load_error(path("no-scan.jpg"));
  EXPECT_NE(message.find("no-scan.jpg"), std::string::npos) << message;
  EXPECT_NE(message.find("no scan codes component 0 (id 1)"), std::string::npos) << message;
  // One scan of the luma only (a 10-byte scan header), then the rest of the file.
  std::vector<unsigned char> luma_only(jpeg.begin(), jpeg.begin() + static_cast<std::ptrdiff_t>(scan));
  luma_only.insert(luma_only.end(), {0xFF, 0xDA, 0x00, 0x08, 0x01, 0x01, 0x00, 0x00, 0x3F, 0x00});
  luma_only.insert(luma_only.end(), jpeg.begin() + static_cast<std::ptrdiff_t>(scan + 14), jpeg.end());
  write_bytes(path("luma-only.jpg"), luma_only.data(), luma_only.size());
  message = load_error(path("luma-only.jpg"));
  EXPECT_NE(message.find("no scan codes component 1 (id 2)"), std::string::npos) << message;
}

// fuzz/image_fuzzer: a 2 KB TGA announcing 4112 × 4112 pixels, which stb decodes as garbage; TGA
// packs at most 256 pixels into a byte. An honest small TGA still loads.
TEST_F(TextureImageFiles, FuzzSmallTgaAnnouncingAHugeImageIsRefused) {
  std::string tga(18, '\0');
  tga[2] = 2;                      // uncompressed true-color
  tga[12] = 0x10, tga[13] = 0x10;  // width 4112
  tga[14] = 0x10, tga[15] = 0x10;  // height 4112
  tga[16] = 24;                    // bits per pixel
  tga += std::string(2000, '\x7f');
  write_bytes(path("huge.tga"), tga.data(), tga.size());
  const std::string message = load_error(path("huge.tga"));
  EXPECT_NE(message.find("announces 4112×4112 pixels"), std::string::npos) << message;
  std::string small(18, '\0');
  small[2] = 2, small[12] = 2, small[14] = 2, small[16] = 24;
  small += std::string(12, '\x40');
  write_bytes(path("small.tga"), small.data(), small.size());
  EXPECT_EQ(read_image(path("small.tga")).width(), 2);
}

// fuzz/image_fuzzer: stb 2.27 overflows an int reading a binary PNM's width of many digits.
TEST_F(TextureImageFiles, FuzzPnmHeaderWithAHugeNumberIsRefused) {
  const std::string pnm = "P6\n" + std::string(60, '7') + " 3:\n255\n";
  write_bytes(path("huge.ppm"), pnm.data(), pnm.size());
  const std::string message = load_error(path("huge.ppm"));
  EXPECT_NE(message.find("huge.ppm"), std::string::npos) << message;
  EXPECT_NE(message.find("corrupt PNM header: a number of 60 digits"), std::string::npos) << message;
}

}  // namespace
}  // namespace candela
