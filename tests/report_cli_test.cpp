// `candela report` end to end (SPEC §13 "Cross-method"): a tiny box room rendered by whitted,
// radiosity, meshless and path, the HTML page, report.json, the images, and the page opened in
// headless Chromium to check that every image loads. Chromium is a dependency of the tests
// (scripts/install-deps.sh): without it the browser test fails, it is not skipped.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>

namespace candela {
namespace {

namespace fs = std::filesystem;

// A 4 × 3 × 4 room of diffuse walls (every wall faces in) lit only by a 2 × 2 emissive quad in
// the centre of the ceiling, out of the camera's view (its edges would make the path tracer's
// few samples per pixel noisy). Whitted shows emission but lets it light nothing (an emissive
// surface is not a light source for it), so its image is black where the reference is lit; the
// other methods converge to the reference.
const char* kRoom = R"({
  "format": "candela/1",
  "camera": {"type": "perspective", "eye": [2, 1.5, 3.9], "target": [2, 0.9, 0], "up": [0, 1, 0], "fov": 60,
             "width": 24, "height": 18},
  "background": [0, 0, 0],
  "render": {"method": "whitted", "seed": 7},
  "radiosity": {"patch_size": 2, "element_size": 1, "hemicube_resolution": 24, "threshold": 0.01},
  "meshless": {"spacing": 0.6, "grid": 12, "rounds": 2},
  "path": {"spp": 4},
  "materials": {
    "white": {"kd": [0.7, 0.7, 0.7]},
    "red": {"kd": [0.7, 0.2, 0.15]},
    "green": {"kd": [0.2, 0.65, 0.2]},
    "lamp": {"kd": 0, "emission": [6, 6, 6]}
  },
  "shapes": [
    {"name": "floor", "type": "quad", "corner": [0, 0, 0], "edge_u": [0, 0, 4], "edge_v": [4, 0, 0], "material": "white"},
    {"name": "ceiling front", "type": "quad", "corner": [0, 3, 0], "edge_u": [4, 0, 0], "edge_v": [0, 0, 1], "material": "white"},
    {"name": "ceiling back", "type": "quad", "corner": [0, 3, 3], "edge_u": [4, 0, 0], "edge_v": [0, 0, 1], "material": "white"},
    {"name": "ceiling left", "type": "quad", "corner": [0, 3, 1], "edge_u": [1, 0, 0], "edge_v": [0, 0, 2], "material": "white"},
    {"name": "ceiling right", "type": "quad", "corner": [3, 3, 1], "edge_u": [1, 0, 0], "edge_v": [0, 0, 2], "material": "white"},
    {"name": "lamp", "type": "quad", "corner": [1, 3, 1], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2], "material": "lamp"},
    {"name": "left wall", "type": "quad", "corner": [0, 0, 0], "edge_u": [0, 3, 0], "edge_v": [0, 0, 4], "material": "red"},
    {"name": "right wall", "type": "quad", "corner": [4, 0, 0], "edge_u": [0, 0, 4], "edge_v": [0, 3, 0], "material": "green"},
    {"name": "back wall", "type": "quad", "corner": [0, 0, 0], "edge_u": [4, 0, 0], "edge_v": [0, 3, 0], "material": "white"},
    {"name": "front wall", "type": "quad", "corner": [0, 0, 4], "edge_u": [0, 3, 0], "edge_v": [4, 0, 0], "material": "white"}
  ]
})";

class ReportCli : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ =
        fs::temp_directory_path() /
        ("candela-report-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
         "-" + std::to_string(::getpid()));  // two suites at once (two checkouts) must not share a folder
    fs::remove_all(directory_);
    fs::create_directories(directory_);
    std::ofstream(directory_ / "room.json") << kRoom;
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(directory_);  // kept for a look when a test fails
  }

  // Runs a shell command in the test's folder; returns the exit code, output = stdout + stderr.
  int shell(const std::string& command, std::string& output) {
    const fs::path log = directory_ / "log.txt";
    const std::string line =
        "cd '" + directory_.string() + "' && " + command + " > '" + log.string() + "' 2>&1";
    const int status = std::system(line.c_str());
    output = read(log);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  int candela(const std::string& arguments, std::string& output) {
    return shell("'" CANDELA_CLI "' " + arguments, output);
  }
  static std::string read(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
  fs::path directory_;
};

const char* kFourMethods =
    "report room.json --methods whitted,radiosity,meshless,path --reference-spp 16 --threads 2";

TEST_F(ReportCli, WritesThePageTheJsonAndEveryImage) {
  std::string output;
  ASSERT_EQ(candela(std::string(kFourMethods) + " --equal-time -q -o out", output), 0) << output;
  EXPECT_TRUE(output.empty()) << output;  // -q
  const fs::path out = directory_ / "out";
  ASSERT_TRUE(fs::is_regular_file(out / "index.html"));
  ASSERT_TRUE(fs::is_regular_file(out / "report.json"));
  for (const char* file : {"reference.png", "reference.exr"})
    EXPECT_TRUE(fs::is_regular_file(out / file)) << file;

  std::ifstream json_file(out / "report.json");
  const nlohmann::json report = nlohmann::json::parse(json_file);
  EXPECT_EQ(report["scene_name"], "room");
  EXPECT_EQ(report["width"], 24);
  EXPECT_EQ(report["height"], 18);
  EXPECT_EQ(report["reference"]["spp"], 16);
  EXPECT_EQ(report["reference"]["statistics"]["path"]["spp"], 16);
  ASSERT_EQ(report["methods"].size(), 7u);  // four methods, then path at each other method's time
  std::map<std::string, double> rmse;
  for (const nlohmann::json& entry : report["methods"]) {
    const std::string key = entry["key"];
    for (const char* kind : {"png", "exr", "diff"}) {
      const std::string file = entry["images"][kind];
      EXPECT_TRUE(fs::is_regular_file(out / file)) << file;
    }
    ASSERT_TRUE(entry["errors"]["rmse"].is_number()) << key;
    const double value = entry["errors"]["rmse"];
    EXPECT_TRUE(std::isfinite(value)) << key;
    EXPECT_GE(value, 0) << key;
    EXPECT_GT(entry["seconds"].get<double>(), 0) << key;
    rmse[key] = value;
  }
  for (const char* key : {"whitted", "radiosity", "meshless", "path", "path-equal-time-whitted",
                          "path-equal-time-radiosity", "path-equal-time-meshless"})
    EXPECT_TRUE(rmse.count(key)) << key;
  // Whitted sees the lamp's direct light but none of what the walls pass on; 4 samples
  // of the path tracer only add noise.
  EXPECT_LT(rmse["path"], rmse["whitted"]);
  EXPECT_LT(rmse["path"], 0.75 * rmse["whitted"]);                  // about 0.62 with seed 0
  EXPECT_EQ(report["methods"][3]["statistics"]["path"]["spp"], 4);  // the scene's path.spp
  EXPECT_EQ(report["methods"][4]["equal_time_to"], "whitted");
  EXPECT_GT(report["difference"]["high"].get<double>(), 0);
  EXPECT_EQ(report["settings"]["path"]["spp"], 4);
  EXPECT_TRUE(report["settings"]["whitted"].is_null());  // defaults

  const std::string html = read(out / "index.html");
  EXPECT_NE(html.find("<title>Cross-method report: room</title>"), std::string::npos);
  EXPECT_EQ(html.find("http://"), std::string::npos);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  // Every <img> names a file that exists, by a relative path.
  const std::regex image_source("<img src=\"([^\"]+)\"");
  int images = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), image_source); it != std::sregex_iterator();
       ++it) {
    ++images;
    const std::string file = (*it)[1];
    EXPECT_TRUE(fs::path(file).is_relative()) << file;
    EXPECT_TRUE(fs::is_regular_file(out / file)) << file;
  }
  EXPECT_EQ(images, 2 + 2 * 7);  // the reference, each entry's image and difference, the chart

  // Every method's error against time — a row per step, the image's last — on one chart.
  std::map<std::string, std::vector<std::string>> units;
  std::istringstream csv(read(out / "convergence.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "method,unit,work,seconds,image_seconds,time_to_image,rmse,relative_mse,unshot_fraction");
  while (std::getline(csv, line))
    units[line.substr(0, line.find(','))].push_back(line.substr(line.find(',') + 1));
  ASSERT_EQ(units["whitted"].size(), 1u);
  EXPECT_EQ(units["whitted"][0].rfind("final,", 0), 0u);
  ASSERT_EQ(units["path"].size(), 5u);  // 4 passes and the image
  EXPECT_EQ(units["path"][3].rfind("passes,4,", 0), 0u);
  EXPECT_GE(units["radiosity"].size(), 2u);
  EXPECT_EQ(units["radiosity"][0].rfind("iterations,", 0), 0u);  // hierarchical: Jacobi iterations
  EXPECT_EQ(units["meshless"][0].rfind("iterations,1,", 0), 0u);
  EXPECT_EQ(units["path (equal time: whitted)"].back().rfind("final,", 0), 0u);
  const std::string chart = read(out / "convergence.svg");
  EXPECT_EQ(chart.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0), 0u);
  for (const char* label :
       {">whitted<", ">radiosity<", ">meshless<", ">path<", ">path at radiosity&#39;s time<",
        ">RMSE against the reference<", ">time to the image (s)<"})
    EXPECT_NE(chart.find(label), std::string::npos) << label;

  // The browser: the page's script sets data-images-loaded="loaded/total" once it has loaded.
  std::string dom;
  const std::string chromium =
      "(timeout 60 chromium --headless --no-sandbox --disable-gpu --virtual-time-budget=5000 "
      "--user-data-dir='" +
      (directory_ / "chromium-profile").string() + "' --dump-dom 'file://" + (out / "index.html").string() +
      "' > dom.html 2> chromium-log.txt)";
  const int status = shell(chromium, dom);
  ASSERT_EQ(status, 0) << "headless chromium failed (is it installed? scripts/install-deps.sh installs it):\n"
                       << read(directory_ / "chromium-log.txt");
  dom = read(directory_ / "dom.html");
  std::smatch match;
  ASSERT_TRUE(std::regex_search(dom, match, std::regex("data-images-loaded=\"(\\d+)/(\\d+)\"")))
      << dom.substr(0, 2000);
  const int loaded = std::stoi(match[1].str()), total = std::stoi(match[2].str());
  EXPECT_EQ(total, images);
  EXPECT_EQ(loaded, total);
  EXPECT_GT(total, 0);
}

TEST_F(ReportCli, ReusesAReferenceImage) {
  std::string output;
  ASSERT_EQ(candela("report room.json --methods whitted --reference-spp 8 --threads 2 -q -o first", output),
            0)
      << output;
  ASSERT_EQ(candela("report room.json --methods whitted --reference first/reference.exr -o second", output),
            0)
      << output;
  EXPECT_NE(output.find("second/index.html"), std::string::npos) << output;  // the summary
  std::ifstream first_file(directory_ / "first" / "report.json"),
      second_file(directory_ / "second" / "report.json");
  const nlohmann::json first = nlohmann::json::parse(first_file), second = nlohmann::json::parse(second_file);
  EXPECT_EQ(second["reference"]["rendered"], false);
  EXPECT_EQ(second["reference"]["file"], "first/reference.exr");
  // The same whitted image against the same reference (stored as 32-bit floats).
  const double a = first["methods"][0]["errors"]["rmse"], b = second["methods"][0]["errors"]["rmse"];
  EXPECT_NEAR(a, b, 1e-5 * a);
  EXPECT_TRUE(fs::is_regular_file(directory_ / "second" / "reference.png"));
  // --luminance measures in cd/m², 179/π × each image's Rec. 709 luminance.
  ASSERT_EQ(
      candela("report room.json --methods whitted --reference first/reference.exr --luminance -q -o lum",
              output),
      0)
      << output;
  std::ifstream lum_file(directory_ / "lum" / "report.json");
  const nlohmann::json lum = nlohmann::json::parse(lum_file);
  EXPECT_EQ(second["units"], "linear");
  EXPECT_EQ(lum["units"], "cd/m2");
  const double linear_mean = second["methods"][0]["errors"]["mean_luminance"];
  EXPECT_NEAR(lum["methods"][0]["errors"]["mean_luminance"].get<double>(),
              179 / 3.14159265358979 * linear_mean, 1e-6 * linear_mean * 179);
  // The wrong size is refused.
  EXPECT_EQ(
      candela(
          "report room.json --methods whitted --set camera.width=12 --reference first/reference.exr -o third",
          output),
      2);
  EXPECT_NE(output.find("24x18"), std::string::npos) << output;
  EXPECT_FALSE(fs::exists(directory_ / "third" / "index.html"));
}

TEST_F(ReportCli, RefusesBadArguments) {
  std::string output;
  EXPECT_EQ(candela("report room.json --methods whitted,nosuch -o out", output), 2);
  EXPECT_NE(output.find("nosuch"), std::string::npos) << output;
  EXPECT_NE(output.find("radiosity"), std::string::npos) << output;  // the valid names listed
  EXPECT_FALSE(fs::exists(directory_ / "out"));
  EXPECT_EQ(candela("report room.json --methods path,path -o out", output), 2);
  std::ofstream(directory_ / "a-file") << "x";
  EXPECT_EQ(candela("report room.json --methods whitted -o a-file", output), 2);
  EXPECT_NE(output.find("a-file"), std::string::npos) << output;
  EXPECT_EQ(candela("report room.json --methods whitted --reference-spp 0 -o out", output), 2);
  EXPECT_EQ(candela("report missing.json -o out", output), 2);
  EXPECT_EQ(candela("report room.json --methods whitted --reference room.json -o out", output), 2);
}

// A report writes DIR/<method>.png and the rest; one of them may be a texture the scene
// reads (or the scene, or the reference): refused before any work, the input untouched.
TEST_F(ReportCli, RefusesToWriteOverItsInputs) {
  std::string output;
  ASSERT_EQ(candela("render room.json -q --set camera.width=4 --set camera.height=3 -o whitted.png", output),
            0)
      << output;
  const std::string texture = read(directory_ / "whitted.png");
  std::string scene = kRoom;
  const std::string white = R"("white": {"kd": [0.7, 0.7, 0.7]})";
  scene.replace(scene.find(white), white.size(),
                R"("white": {"kd": {"type": "image", "file": "whitted.png"}})");
  std::ofstream(directory_ / "textured.json") << scene;
  EXPECT_EQ(candela("report textured.json --methods whitted --reference-spp 2 -q -o .", output), 2) << output;
  EXPECT_NE(output.find("whitted.png, an input of this run"), std::string::npos) << output;
  EXPECT_EQ(read(directory_ / "whitted.png"), texture);
  EXPECT_FALSE(fs::exists(directory_ / "index.html"));
  // The reference given is read; the report writes DIR/reference.exr.
  ASSERT_EQ(candela("render room.json -q -o reference.exr", output), 0) << output;
  const std::string reference = read(directory_ / "reference.exr");
  EXPECT_EQ(candela("report room.json --methods whitted -q --reference reference.exr -o .", output), 2)
      << output;
  EXPECT_NE(output.find("reference.exr, an input of this run"), std::string::npos) << output;
  EXPECT_EQ(read(directory_ / "reference.exr"), reference);
}

TEST_F(ReportCli, AFailingMethodWritesNoPage) {
  std::string output;
  // Meshless refuses more sites than meshless.max_sites when it renders.
  const int code = candela(
      "report room.json --methods whitted,meshless --reference-spp 4 --threads 2 -q "
      "--set meshless.max_sites=2 -o out",
      output);
  EXPECT_NE(code, 0) << output;
  EXPECT_NE(output.find("meshless"), std::string::npos) << output;
  EXPECT_FALSE(fs::exists(directory_ / "out" / "index.html"));
  EXPECT_FALSE(fs::exists(directory_ / "out" / "report.json"));

  // A good report, then a failing run into the same folder: the old page would describe the new
  // reference it did not measure, so it must be gone.
  ASSERT_EQ(candela("report room.json --methods whitted --reference-spp 4 --threads 2 -q -o again", output),
            0)
      << output;
  ASSERT_TRUE(fs::exists(directory_ / "again" / "index.html"));
  EXPECT_NE(candela("report room.json --methods whitted,meshless --reference-spp 2 --threads 2 -q "
                    "--set meshless.max_sites=2 -o again",
                    output),
            0);
  EXPECT_FALSE(fs::exists(directory_ / "again" / "index.html"));
  EXPECT_FALSE(fs::exists(directory_ / "again" / "report.json"));
}

// The relighting page — every frame written (the scene's own lights first), each
// image loads in headless Chromium, page.html#2 opens at the third frame; refused without --relight
// or with an image a browser cannot show.
TEST_F(ReportCli, RelightPageShowsEveryFrameWithASlider) {
  std::ofstream(directory_ / "frames.json") << R"({"frames": [
    {"name": "low", "lights": [{"type": "point", "position": [1, 0.5, 2], "intensity": 2}]},
    {"name": "green-floor", "lights": [{"type": "point", "position": [2, 2.5, 2], "intensity": 2}],
     "materials": {"white": {"kd": [0.2, 0.7, 0.2]}}}]})";
  fs::create_directories(directory_ / "frames");
  fs::create_directories(directory_ / "page");
  std::string output;
  ASSERT_EQ(
      candela(
          "render room.json --method meshless --set meshless.transport=hierarchical --relight frames.json "
          "-q -o frames/room.png --relight-page page/relight.html",
          output),
      0)
      << output;
  const std::string page = read(directory_ / "page" / "relight.html");
  for (const char* image : {"../frames/room.png", "../frames/room-low.png", "../frames/room-green-floor.png"})
    EXPECT_NE(page.find(image), std::string::npos) << image;
  EXPECT_NE(page.find("hierarchical ("), std::string::npos);
  std::string dom;
  const int status = shell(
      "(timeout 60 chromium --headless --no-sandbox --disable-gpu --virtual-time-budget=5000 "
      "--user-data-dir='" +
          (directory_ / "chromium-profile").string() + "' --dump-dom 'file://" +
          (directory_ / "page" / "relight.html").string() + "#2' > dom.html 2> chromium-log.txt)",
      dom);
  ASSERT_EQ(status, 0) << read(directory_ / "chromium-log.txt");
  dom = read(directory_ / "dom.html");
  EXPECT_NE(dom.find("data-images-loaded=\"4/4\""), std::string::npos)
      << dom.substr(0, 3000);  // frame + 3 thumbs
  EXPECT_NE(dom.find("data-frame=\"green-floor\""), std::string::npos) << dom.substr(0, 3000);
  EXPECT_NE(dom.find("Frame 3 of 3: green-floor"), std::string::npos);
  // Refusals, before any work.
  EXPECT_EQ(candela("render room.json --method meshless -q -o x.png --relight-page p.html", output), 2);
  EXPECT_NE(output.find("--relight-page needs --relight"), std::string::npos) << output;
  EXPECT_EQ(
      candela("render room.json --method meshless --relight frames.json -q -o x.pfm --relight-page p.html",
              output),
      2);
  EXPECT_NE(output.find("-o must name a .png"), std::string::npos) << output;
  EXPECT_FALSE(fs::exists(directory_ / "x.pfm"));
  EXPECT_FALSE(fs::exists(directory_ / "p.html"));
}

}  // namespace
}  // namespace candela
