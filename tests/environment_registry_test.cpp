// The environment registry (src/scene/environment_registry.*) building the environment maps of
// src/shading/: every JSON form from its example, the errors on the file and key they concern,
// and the image cache.
#include "scene/environment_registry.h"

#include <gtest/gtest.h>
#include <stb_image_write.h>  // the implementation is in candela_core (io/image_writer.cpp)

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "camera/film.h"
#include "io/image_writer.h"
#include "io/json_document.h"
#include "math/srgb.h"
#include "scratch_directory.h"
#include "shading/environment.h"
#include "util/error.h"

namespace candela {
namespace {

namespace fs = std::filesystem;

class EnvironmentRegistry : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(directory_ / "sky");
    // The files the entries' examples name.
    for (const char* face : {"px", "nx", "py", "ny", "pz", "nz"})
      write_png("sky/" + std::string(face) + ".png", 4, 4);
    Film panorama(8, 4);
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 8; ++x) panorama.at(x, y) = Color(x, y, 2.5);
    write_exr(panorama, (directory_ / "sky.exr").string(), 0);
    context_.base_directory = directory_;
  }

  void write_png(const std::string& name, int width, int height) const {
    std::vector<unsigned char> pixels(std::size_t(width) * height * 3, 128);
    std::vector<unsigned char> encoded;
    const auto append = [](void* context, void* data, int size) {
      auto* out = static_cast<std::vector<unsigned char>*>(context);
      out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
    };
    ASSERT_TRUE(stbi_write_png_to_func(append, &encoded, width, height, 3, pixels.data(), width * 3));
    std::ofstream out(directory_ / name, std::ios::binary);
    out.write(reinterpret_cast<const char*>(encoded.data()), static_cast<std::streamsize>(encoded.size()));
  }

  std::unique_ptr<Environment> read(const std::string& json) const {
    const JsonDocument document = JsonDocument::parse(json, "test.json");
    return read_environment(JsonNode(document, document.root(), ""), context_);
  }
  // The InputError that reading json gives.
  InputError read_error(const std::string& json) const {
    try {
      read(json);
    } catch (const InputError& e) {
      return e;
    }
    ADD_FAILURE() << "no error for " << json;
    return InputError({}, "");
  }
  static std::string cube_json(const std::string& plus_x = "sky/px.png",
                               const std::string& minus_y = "sky/ny.png") {
    return R"({"type": "cube", "faces": {"+x": ")" + plus_x +
           R"(", "-x": "sky/nx.png", "+y": "sky/py.png", "-y": ")" + minus_y +
           R"(", "+z": "sky/pz.png", "-z": "sky/nz.png"}})";
  }

  candela::testing::ScratchDirectory scratch_{"candela-environment"};
  const fs::path& directory_ = scratch_.path();
  LoadContext context_;
};

TEST_F(EnvironmentRegistry, EveryEntryFromItsExample) {
  ASSERT_EQ(environment_entries().size(), 4u);
  for (const EnvironmentEntry& entry : environment_entries()) {
    const auto environment = read(std::string(entry.example));
    ASSERT_NE(environment, nullptr) << entry.name;
    EXPECT_EQ(environment->type_name(), entry.name);
    EXPECT_EQ(find_environment(entry.name), &entry);
    EXPECT_FALSE(entry.description.empty());
  }
  EXPECT_EQ(find_environment("sphere"), nullptr);
  // The panorama's example is the linear EXR, read back as written: straight ahead is the
  // centre, between columns 3 and 4 and rows 1 and 2 (file rows run top first).
  const auto sky = read(std::string(find_environment("equirectangular")->example));
  EXPECT_EQ(sky->radiance({0, 0, -1}), Color(3.5, 1.5, 2.5));
  // 128 in an sRGB PNG.
  const auto cube = read(std::string(find_environment("cube")->example));
  EXPECT_FLOAT_EQ(static_cast<float>(cube->radiance({0, 1, 0}).g),
                  static_cast<float>(srgb_decode(128 / 255.0)));
}

TEST_F(EnvironmentRegistry, MultiplierAndEncodingAreRead) {
  const auto cube =
      read(R"({"type": "cube", "multiplier": [1, 2, 4], "encoding": "linear", )" + cube_json().substr(17));
  EXPECT_EQ(cube->radiance({0, 0, 1}), Color(1, 2, 4) * static_cast<float>(128 / 255.0));
  const auto constant = read(R"({"type": "constant", "color": 0.25})");
  EXPECT_EQ(constant->radiance({1, 0, 0}), Color(0.25));
}

TEST_F(EnvironmentRegistry, MissingFaceFileNamesTheJsonPathAndTheFile) {
  const InputError error = read_error(cube_json("sky/absent.png"));
  const std::string message = error.what();
  EXPECT_EQ(error.location().file, "test.json");
  EXPECT_EQ(error.location().json_path, "faces.+x");
  EXPECT_EQ(error.location().line, 1);
  EXPECT_GT(error.location().column, 1);
  EXPECT_NE(message.find("absent.png"), std::string::npos) << message;
  EXPECT_NE(message.find("no such file"), std::string::npos) << message;
}

TEST_F(EnvironmentRegistry, CorruptImageReportsTheReasonOnTheFileNode) {
  std::ofstream(directory_ / "broken.png") << "not a png";
  const InputError error = read_error(R"({"type": "equirectangular", "file": "broken.png"})");
  EXPECT_EQ(error.location().json_path, "file");
  EXPECT_NE(error.message().find("broken.png"), std::string::npos) << error.what();
  EXPECT_NE(error.message().find("stb_image"), std::string::npos) << error.what();
}

TEST_F(EnvironmentRegistry, NonSquareOrMismatchedFacesAreRefused) {
  write_png("wide.png", 8, 4);
  const InputError wide = read_error(cube_json("sky/px.png", "wide.png"));
  EXPECT_EQ(wide.location().json_path, "faces.-y");
  EXPECT_NE(wide.message().find("square"), std::string::npos) << wide.what();
  write_png("big.png", 8, 8);
  const InputError big = read_error(cube_json("sky/px.png", "big.png"));
  EXPECT_EQ(big.location().json_path, "faces.-y");
  EXPECT_NE(big.message().find("same size"), std::string::npos) << big.what();
}

TEST_F(EnvironmentRegistry, BadTypesKeysAndValuesAreLocated) {
  const InputError type = read_error(R"({"type": "sphere"})");
  EXPECT_EQ(type.location().json_path, "type");
  EXPECT_NE(type.message().find("constant, cube, equirectangular"), std::string::npos) << type.what();
  EXPECT_EQ(read_error(R"({"color": 1})").location().json_path, "");  // no type
  EXPECT_EQ(read_error(R"({"type": "constant", "colour": 1, "color": 1})").location().json_path,
            "colour");  // British spelling: unknown
  EXPECT_EQ(read_error(R"({"type": "constant"})").message(), "missing required key \"color\"");
  EXPECT_EQ(read_error(R"({"type": "constant", "color": -1})").location().json_path, "color");
  std::string extra_face = cube_json();
  extra_face.insert(extra_face.find("\"+x\""), R"("+w": "sky/px.png", )");
  EXPECT_EQ(read_error(extra_face).location().json_path, "faces.+w");
  EXPECT_EQ(read_error(R"({"type": "equirectangular", "file": "sky.exr", "encoding": "gamma"})")
                .location()
                .json_path,
            "encoding");
  EXPECT_EQ(read_error(R"({"type": "equirectangular", "file": "sky.exr", "forward": [0, 2, 0]})")
                .location()
                .json_path,
            "forward");
  EXPECT_EQ(
      read_error(R"({"type": "equirectangular", "file": "sky.exr", "up": [0, 0, 0]})").location().json_path,
      "up");
  EXPECT_EQ(read_error(R"({"type": "equirectangular", "file": 3})").location().json_path, "file");
  EXPECT_EQ(read_error(R"({"type": "equirectangular", "file": "sky.exr", "multiplier": [1, -1, 1]})")
                .location()
                .json_path,
            "multiplier[1]");
  EXPECT_EQ(read_error(R"([1, 2])").location().json_path, "");
}

TEST_F(EnvironmentRegistry, WrapAndEncodingReaders) {
  const JsonDocument document = JsonDocument::parse(
      R"({"a": {}, "b": {"wrap": "clamp", "encoding": "srgb"}, "c": {"wrap": "mirror", "encoding": "linear"},
          "d": {"wrap": "tile"}})",
      "test.json");
  const JsonNode root(document, document.root(), "");
  EXPECT_EQ(read_wrap_mode(root.at("a")), WrapMode::repeat);
  EXPECT_EQ(read_color_encoding(root.at("a")), ColorEncoding::automatic);
  EXPECT_EQ(read_wrap_mode(root.at("b")), WrapMode::clamp);
  EXPECT_EQ(read_color_encoding(root.at("b")), ColorEncoding::srgb);
  EXPECT_EQ(read_wrap_mode(root.at("c")), WrapMode::mirror);
  EXPECT_EQ(read_color_encoding(root.at("c")), ColorEncoding::linear);
  try {
    read_wrap_mode(root.at("d"));
    ADD_FAILURE() << "no error for wrap \"tile\"";
  } catch (const InputError& e) {
    EXPECT_EQ(e.location().json_path, "d.wrap");
    EXPECT_NE(e.message().find("repeat, clamp, mirror"), std::string::npos) << e.what();
  }
}

TEST_F(EnvironmentRegistry, TheSameFileIsReadOnceWhileInUse) {
  const JsonDocument document =
      JsonDocument::parse(R"({"a": "sky/px.png", "b": "sky/../sky/px.png", "c": "sky/py.png"})", "test.json");
  const JsonNode root(document, document.root(), "");
  const auto first = load_texture_image(root.at("a"), context_, ColorEncoding::automatic);
  // The same canonical file and encoding: shared.
  EXPECT_EQ(load_texture_image(root.at("b"), context_, ColorEncoding::automatic), first);
  // Another encoding or another file: a separate image.
  EXPECT_NE(load_texture_image(root.at("a"), context_, ColorEncoding::linear), first);
  EXPECT_NE(load_texture_image(root.at("c"), context_, ColorEncoding::automatic), first);
  // A changed file is read again.
  write_png("sky/px.png", 2, 2);
  const auto changed = load_texture_image(root.at("a"), context_, ColorEncoding::automatic);
  EXPECT_NE(changed, first);
  EXPECT_EQ(changed->width(), 2);
}

}  // namespace
}  // namespace candela
