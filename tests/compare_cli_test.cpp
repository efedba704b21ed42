// `candela compare` end to end: the printed table, --json, --mask, --diff and the errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "camera/tone_map.h"
#include "io/false_color.h"
#include "io/image_writer.h"
#include "scratch_directory.h"
#include "shading/texture_image.h"

namespace candela {
namespace {

namespace fs = std::filesystem;

class CompareCli : public ::testing::Test {
 protected:
  // Runs candela in the scratch folder; returns the exit code, output gets stdout + stderr.
  int run(const std::string& arguments, std::string& output) {
    const fs::path log = directory_.path() / "log.txt";
    const std::string command = "cd '" + directory_.path().string() + "' && '" CANDELA_CLI "' " + arguments +
                                " > '" + log.string() + "' 2>&1";
    const int status = std::system(command.c_str());
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    output = text.str();
    fs::remove(log);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  void write(const Film& film, const std::string& name) {
    write_image(film, (directory_.path() / name).string(), DisplaySettings{});
  }
  bool exists(const std::string& name) const { return fs::exists(directory_.path() / name); }
  nlohmann::json read_json(const std::string& name) const {
    std::ifstream in(directory_.path() / name);
    return nlohmann::json::parse(in);
  }
  // A 2×2 pair: (1, 0) differs by 0.3 in G, (0, 1) by 0.1 in every channel (as in
  // image_comparison_test.cpp): RMSE 0.1, PSNR 20 dB, max error 0.3 at x 1, y 0, G.
  void write_pair() {
    Film a(2, 2), b(2, 2);
    for (Film* f : {&a, &b}) f->at(0, 0) = f->at(1, 1) = Color(1);
    a.at(1, 0) = Color(0.25, 0.5, 0.25);
    b.at(1, 0) = Color(0.25, 0.2, 0.25);
    a.at(0, 1) = Color(0);
    b.at(0, 1) = Color(0.125);
    write(a, "a.pfm");
    write(b, "b.pfm");
  }
  testing::ScratchDirectory directory_{"candela-compare-cli"};
};

TEST_F(CompareCli, PrintsTheMetricsAndWritesJson) {
  write_pair();
  std::string output;
  ASSERT_EQ(run("compare a.pfm b.pfm --json metrics.json", output), 0) << output;
  EXPECT_NE(output.find("linear as stored"), std::string::npos) << output;
  EXPECT_NE(output.find("RMSE"), std::string::npos) << output;
  EXPECT_NE(output.find("PSNR"), std::string::npos) << output;
  EXPECT_NE(output.find("B the reference"), std::string::npos) << output;
  EXPECT_NE(output.find("at x 1, y 0, G"), std::string::npos) << output;
  const nlohmann::json json = read_json("metrics.json");
  // PFM stores floats: 0.5, 0.25 and 0.125 are exact, 0.2 to float precision.
  const double squared = 0.3 * 0.3 + 3 * 0.125 * 0.125;
  const double rmse = std::sqrt(squared / 12);
  EXPECT_NEAR(json["rmse"].get<double>(), rmse, 1e-7);
  EXPECT_NEAR(json["psnr_db"].get<double>(), 20 * std::log10(1 / rmse), 1e-5);
  EXPECT_NEAR(json["relative_mse"].get<double>(),
              (0.09 / (0.04 + 0.01) + 3 * 0.125 * 0.125 / (0.125 * 0.125 + 0.01)) / 12, 1e-6);
  EXPECT_NEAR(json["max_absolute_error"].get<double>(), 0.3, 1e-6);
  EXPECT_EQ(json["max_absolute_error_at"]["x"], 1);
  EXPECT_EQ(json["max_absolute_error_at"]["y"], 0);
  EXPECT_EQ(json["max_absolute_error_at"]["channel"], 1);
  EXPECT_NEAR(json["mean_absolute_error"].get<double>(), (0.3 + 3 * 0.125) / 12, 1e-7);
  EXPECT_EQ(json["pixels_compared"], 4);
  EXPECT_EQ(json["relative_mse_epsilon"], 0.01);
  EXPECT_EQ(json["image"]["srgb_decoded"], false);
  EXPECT_TRUE(json["mask"].is_null());
  EXPECT_NEAR(json["luminance_ratio"].get<double>(),
              json["mean_luminance"].get<double>() / json["mean_luminance_reference"].get<double>(), 1e-12);
}

TEST_F(CompareCli, IdenticalImagesPrintInfinitePsnr) {
  write_pair();
  std::string output;
  ASSERT_EQ(run("compare b.pfm b.pfm --json m.json", output), 0) << output;
  EXPECT_NE(output.find("inf"), std::string::npos) << output;
  const nlohmann::json json = read_json("m.json");
  EXPECT_EQ(json["rmse"], 0.0);
  EXPECT_EQ(json["psnr_db"], "inf");
  EXPECT_EQ(json["luminance_ratio"], 1.0);
}

TEST_F(CompareCli, MaskLeavesPixelsOut) {
  write_pair();
  Film mask(2, 2);
  mask.at(1, 0) = mask.at(1, 1) = Color(1);  // the right column only
  write(mask, "mask.pfm");
  std::string output;
  ASSERT_EQ(run("compare a.pfm b.pfm --mask mask.pfm --json m.json", output), 0) << output;
  EXPECT_NE(output.find("2 of 4 pixels"), std::string::npos) << output;
  const nlohmann::json json = read_json("m.json");
  EXPECT_EQ(json["pixels_compared"], 2);
  EXPECT_NEAR(json["rmse"].get<double>(), std::sqrt(0.09 / 6), 1e-7);
  write(Film(2, 2), "black.pfm");
  EXPECT_EQ(run("compare a.pfm b.pfm --mask black.pfm", output), 2) << output;
  EXPECT_NE(output.find("excludes every pixel"), std::string::npos) << output;
  write(Film(3, 2), "wide.pfm");
  EXPECT_EQ(run("compare a.pfm b.pfm --mask wide.pfm", output), 2) << output;
}

TEST_F(CompareCli, DifferentSizesAreAnErrorNamingBoth) {
  write_pair();
  write(Film(3, 5), "c.pfm");
  std::string output;
  EXPECT_EQ(run("compare a.pfm c.pfm --json m.json --diff d.png", output), 2) << output;
  EXPECT_NE(output.find("2x2"), std::string::npos) << output;
  EXPECT_NE(output.find("3x5"), std::string::npos) << output;
  EXPECT_FALSE(exists("m.json"));
  EXPECT_FALSE(exists("d.png"));
}

TEST_F(CompareCli, MissingFileIsAnErrorAndNothingIsWritten) {
  write_pair();
  std::string output;
  EXPECT_EQ(run("compare a.pfm nothere.exr --json m.json --diff d.png", output), 2) << output;
  EXPECT_NE(output.find("nothere.exr"), std::string::npos) << output;
  EXPECT_FALSE(exists("m.json"));
  EXPECT_FALSE(exists("d.png"));
  std::ofstream(directory_.path() / "junk.png") << "not a png";
  EXPECT_EQ(run("compare junk.png a.pfm", output), 2) << output;
  EXPECT_NE(output.find("junk.png"), std::string::npos) << output;
  // Bad options are refused before anything is read.
  EXPECT_EQ(run("compare a.pfm b.pfm --diff-metric cubic", output), 2) << output;
  EXPECT_EQ(run("compare a.pfm b.pfm --diff-scale -1", output), 2) << output;
  EXPECT_EQ(run("compare a.pfm b.pfm --diff d.txt", output), 2) << output;
  EXPECT_EQ(run("compare a.pfm b.pfm --diff nowhere/d.png", output), 2) << output;
  EXPECT_FALSE(exists("d.png"));
}

TEST_F(CompareCli, DiffWritesAFalseColorPngWithItsBar) {
  Film a(8, 6), b(8, 6);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 8; ++x) {
      a.at(x, y) = Color(0.5);
      b.at(x, y) = Color(0.5 - 0.05 * x);  // |Y_A − Y_B| = 0.05·x: 0 .. 0.35
    }
  write(a, "a.pfm");
  write(b, "b.pfm");
  std::string output;
  ASSERT_EQ(run("compare a.pfm b.pfm --diff d.png --json m.json", output), 0) << output;
  EXPECT_NE(output.find("scale 0 .. 0.35"), std::string::npos) << output;
  const TextureImage png = TextureImage::load(directory_.path() / "d.png", ColorEncoding::linear);
  ASSERT_EQ(png.width(), 8);
  ASSERT_EQ(png.height(), 6 + color_bar_height(8, true));  // with the caption "|Y_A - Y_B|"
  const int top = png.height() - 1;                        // TextureImage rows count from the bottom
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(png.texel(0, top)[c], color_map_viridis(0)[c], 1.0 / 255);
    EXPECT_NEAR(png.texel(7, top)[c], color_map_viridis(1)[c], 1.0 / 255);
  }
  const nlohmann::json json = read_json("m.json");
  EXPECT_EQ(json["diff"]["metric"], "abs");
  EXPECT_NEAR(json["diff"]["high"].get<double>(), 0.35, 1e-6);
  // Signed, with a fixed scale: symmetric about 0, the blue-white-red map.
  ASSERT_EQ(
      run("compare a.pfm b.pfm --diff s.png --diff-metric signed --diff-scale 0.5 --json m.json", output), 0)
      << output;
  EXPECT_NE(output.find("scale -0.5 .. 0.5"), std::string::npos) << output;
  const TextureImage signed_png = TextureImage::load(directory_.path() / "s.png", ColorEncoding::linear);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(signed_png.texel(0, top)[c], 1.0, 1.0 / 255);  // 0: white
  EXPECT_EQ(read_json("m.json")["diff"]["color_map"], "diverging");
}

TEST_F(CompareCli, PngInputsAreDecodedFromSrgb) {
  Film a(4, 4), b(4, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) a.at(x, y) = b.at(x, y) = Color(0.2 * x);
  write(a, "a.png");
  write(b, "b.exr");
  std::string output;
  ASSERT_EQ(run("compare a.png b.exr --json m.json", output), 0) << output;
  EXPECT_NE(output.find("sRGB decoded to linear"), std::string::npos) << output;
  const nlohmann::json json = read_json("m.json");
  EXPECT_EQ(json["image"]["srgb_decoded"], true);
  EXPECT_EQ(json["reference"]["srgb_decoded"], false);
  // Only 8-bit quantisation separates them: well under one code step of linear value.
  EXPECT_LT(json["max_absolute_error"].get<double>(), 0.01);
}

}  // namespace
}  // namespace candela
