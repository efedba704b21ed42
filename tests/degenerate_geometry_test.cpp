// Degenerate geometry (SPEC §15). NaN and Inf coordinates, zero-area and sliver
// triangles, coincident surfaces, and scenes at 1e-6 and 1e6 scale are rendered by every method
// without a crash and without a NaN or infinite pixel; what the loader skips it names in a
// warning, and what it refuses it refuses with a located InputError. docs/reliability.md lists
// every case and its outcome.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "integrators/scene_loading.h"
#include "render_support.h"
#include "scratch_directory.h"

namespace candela {
namespace {

const std::array<std::string, 6> kMethods = {"local", "whitted", "raster", "radiosity", "meshless", "path"};

// A number as JSON text, every digit kept.
std::string num(double value) {
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

std::string vec(double x, double y, double z, double scale = 1) {
  std::ostringstream out;
  out.precision(17);
  out << '[' << x * scale << ", " << y * scale << ", " << z * scale << ']';
  return out.str();
}

// Small settings for every method; lengths (patch size, site spacing) scaled with the scene.
std::string settings(double scale = 1) {
  return R"("radiosity": {"patch_size": )" + num(0.75 * scale) + R"(, "hemicube_resolution": 16},
    "meshless": {"spacing": )" +
         num(0.3 * scale) + R"(, "grid": 16, "rounds": 2},
    "path": {"spp": 4},
    "raster": {"segments": 8},)";
}

// An open room (floor, back and left walls, an emissive ceiling panel, a sphere) seen from the
// front, lit by a point light without attenuation, plus `extra` shapes; all lengths × scale.
std::string room(double scale, const std::string& extra = "") {
  const auto v = [scale](double x, double y, double z) { return vec(x, y, z, scale); };
  return R"({"format": "candela/1",
    "camera": {"eye": )" +
         v(0, 1, 3) + R"(, "target": )" + v(0, 0.8, 0) + R"(, "fov": 55, "width": 16, "height": 16},
    "ambient": 0.05,
    "lights": [{"type": "point", "position": )" +
         v(0.2, 1.5, 0.8) + R"(, "intensity": 0.8, "attenuation": "none"}],
    )" + settings(scale) +
         R"(
    "shapes": [
      {"type": "quad", "corner": )" +
         v(-1, 0, -1) + R"(, "edge_u": )" + v(0, 0, 2) + R"(, "edge_v": )" + v(2, 0, 0) + R"(,
       "material": {"kd": [0.6, 0.6, 0.6]}},
      {"type": "quad", "corner": )" +
         v(-1, 0, -1) + R"(, "edge_u": )" + v(2, 0, 0) + R"(, "edge_v": )" + v(0, 2, 0) + R"(,
       "material": {"kd": [0.5, 0.5, 0.7]}},
      {"type": "quad", "corner": )" +
         v(-1, 0, -1) + R"(, "edge_u": )" + v(0, 2, 0) + R"(, "edge_v": )" + v(0, 0, 2) + R"(,
       "material": {"kd": [0.7, 0.3, 0.3]}},
      {"type": "quad", "corner": )" +
         v(-0.5, 1.9, -0.5) + R"(, "edge_u": )" + v(1, 0, 0) + R"(, "edge_v": )" + v(0, 0, 1) + R"(,
       "material": {"kd": 0, "emission": 2}},
      {"type": "sphere", "center": )" +
         v(0.3, 0.4, -0.2) + R"(, "radius": )" + num(0.4 * scale) + R"(,
       "material": {"kd": [0.3, 0.6, 0.3], "ks": 0.3, "n": 20}})" +
         extra + R"(]})";
}

std::unique_ptr<Scene> load(const std::string& text, const std::string& base = ".") {
  return load_scene_text(text, "degenerate.json", base);
}

bool any_warning(const Scene& scene, const std::string& a, const std::string& b = "") {
  for (const std::string& w : scene.warnings)
    if (w.find(a) != std::string::npos && w.find(b) != std::string::npos) return true;
  return false;
}

std::string all_warnings(const Scene& scene) {
  std::string text;
  for (const std::string& w : scene.warnings) text += w + "\n";
  return text;
}

// Every pixel of every channel finite (and not negative).
void expect_finite(const Film& film, const std::string& label) {
  std::size_t bad = 0;
  for (const Color& c : film.pixels())
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(c[k]) || c[k] < 0) ++bad;
  EXPECT_EQ(bad, 0u) << label << ": non-finite or negative pixel channels";
}

// Renders the scene with every method; returns the films in kMethods' order.
std::vector<Film> render_every_method(const Scene& scene, const std::string& label, std::size_t threads = 2) {
  std::vector<Film> films;
  for (const std::string& method : kMethods) {
    SCOPED_TRACE(label + ", " + method);
    try {
      films.push_back(testing::render_scene(scene, method, threads));
    } catch (const std::exception& e) {
      ADD_FAILURE() << label << ", " << method << " threw: " << e.what();
      films.emplace_back(scene.camera->width(), scene.camera->height());
    }
    expect_finite(films.back(), label + ", " + method);
  }
  return films;
}

double mean_channel_average(const Film& film) {
  double sum = 0;
  for (const Color& c : film.pixels()) sum += c.average();
  return sum / static_cast<double>(film.pixels().size());
}

// Mean absolute difference of two films, relative to the first one's mean.
double relative_difference(const Film& a, const Film& b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.pixels().size(); ++i)
    for (int k = 0; k < 3; ++k) sum += std::fabs(a.pixels()[i][k] - b.pixels()[i][k]) / 3;
  return sum / static_cast<double>(a.pixels().size()) / std::max(1e-12, mean_channel_average(a));
}

std::string write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path.string();
}

// The message of the InputError the text's loading throws ("" and a failure when it loads).
std::string load_error(const std::string& text, const std::string& base = ".") {
  try {
    load(text, base);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an InputError";
  return "";
}

// --- 1. NaN and Inf ---------------------------------------------------------------------------

TEST(DegenerateGeometry, MeshWithNanOrInfVertexIsRefusedNamingTheFileAndVertex) {
  testing::ScratchDirectory scratch("candela-degenerate");
  for (const char* bad : {"nan", "inf", "-inf", "1e400"}) {
    SCOPED_TRACE(bad);
    write_file(scratch.path() / "bad.obj",
               std::string("v 0 0 0\nv 1 0 0\nv ") + bad + " 1 0\nv 0 1 0\nf 1 2 4\nf 1 2 3\n");
    const std::string message =
        load_error(room(1, R"(, {"type": "mesh", "file": "bad.obj", "material": {"kd": 0.5}})"),
                   scratch.path().string());
    EXPECT_NE(message.find("bad.obj"), std::string::npos) << message;
    EXPECT_NE(message.find("shapes[5]"), std::string::npos) << message;
    EXPECT_NE(message.find("vertex 3"), std::string::npos) << message;
    EXPECT_NE(message.find("non-finite"), std::string::npos) << message;
  }
}

TEST(DegenerateGeometry, MeshWithHugeVertexIsRefusedNamingTheFileAndVertex) {
  // Finite but beyond the scene file's 1e16 limit on any number.
  testing::ScratchDirectory scratch("candela-degenerate");
  write_file(scratch.path() / "huge.obj", "v 0 0 0\nv 1e30 0 0\nv 0 1e30 0\nf 1 2 3\n");
  const std::string message = load_error(
      room(1, R"(, {"type": "mesh", "file": "huge.obj", "material": {"kd": 0.5}})"), scratch.path().string());
  EXPECT_NE(message.find("shapes[5]"), std::string::npos) << message;
  EXPECT_NE(message.find("vertex 2: magnitude above 1e16"), std::string::npos) << message;
}

TEST(DegenerateGeometry, JsonOverflowingNumberIsRefusedWithItsLocation) {
  // JSON has no NaN or Inf literal; 1e400 overflows a double and is refused where it stands.
  const std::string message =
      load_error(room(1, R"(, {"type": "sphere", "center": [0, 1e400, 0], "radius": 1})"));
  EXPECT_NE(message.find("degenerate.json:"), std::string::npos) << message;
  EXPECT_NE(message.find("1e400"), std::string::npos) << message;
  for (const char* literal : {"NaN", "Infinity", "-Infinity"}) {
    const std::string refused =
        load_error(room(1, R"(, {"type": "sphere", "center": [0, )" + std::string(literal) + R"(, 0]})"));
    EXPECT_NE(refused.find("degenerate.json:"), std::string::npos) << refused;
  }
}

TEST(DegenerateGeometry, AnalyticShapesWithOverflowingParametersAreRefusedOrSkipped) {
  // Finite in the file, overflowing once squared or crossed: radius², |edge_u × edge_v|.
  const std::vector<std::string> shapes = {
      R"({"type": "sphere", "center": [0, 1, 0], "radius": 1e300})",
      R"({"type": "sphere", "center": [1e300, 0, 0], "radius": 1})",
      R"({"type": "quad", "corner": [0, 0, 0], "edge_u": [1e200, 0, 0], "edge_v": [0, 1e200, 0]})",
      R"({"type": "disc", "center": [0, 0, 0], "normal": [0, 1, 0], "radius": 1e300})",
      R"({"type": "triangle", "vertices": [[0, 0, 0], [1e300, 0, 0], [0, 1e300, 0]]})",
      R"({"type": "box", "min": [-1e308, 0, 0], "max": [1e308, 1, 1]})",
      R"({"type": "cylinder", "base": [0, 0, 0], "cap": [0, 1e300, 0], "radius": 1})",
      R"({"type": "torus", "center": [0, 0, 0], "major_radius": 1e300, "minor_radius": 1})",
  };
  for (const std::string& shape : shapes) {
    SCOPED_TRACE(shape);
    std::unique_ptr<Scene> scene;
    try {
      scene = load(room(1, ", " + shape));
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("shapes[5]"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("magnitude above 1e16"), std::string::npos) << e.what();
      continue;
    }
    EXPECT_TRUE(any_warning(*scene, "shapes[5]", "skipped")) << all_warnings(*scene);
    render_every_method(*scene, shape);
  }
}

// --- 2. Zero-area and sliver triangles ----------------------------------------------------------

TEST(DegenerateGeometry, ZeroAreaTrianglesInAMeshAreSkippedWithAWarning) {
  testing::ScratchDirectory scratch("candela-degenerate");
  write_file(scratch.path() / "mixed.obj",
             "v -0.8 0.1 0\nv 0.8 0.1 0\nv 0 1.2 0\nv 0.4 0.1 0\nv 1e-12 1.2 0\n"
             "f 1 2 3\n"    // a good triangle
             "f 1 1 2\n"    // a repeated vertex
             "f 1 4 2\n"    // collinear
             "f 3 5 1\n");  // a sliver 1e-12 wide at the top: kept
  const auto scene = load(room(1, R"(, {"type": "mesh", "file": "mixed.obj", "material": {"kd": 0.5}})"),
                          scratch.path().string());
  EXPECT_TRUE(any_warning(*scene, "shapes[5]", "skipped 2 degenerate triangle(s)")) << all_warnings(*scene);
  EXPECT_EQ(scene->objects[5].primitive_count, 2u);
  render_every_method(*scene, "zero-area mesh");

  write_file(scratch.path() / "all-bad.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 1\n");
  const std::string message =
      load_error(room(1, R"(, {"type": "mesh", "file": "all-bad.obj", "material": {"kd": 0.5}})"),
                 scratch.path().string());
  EXPECT_NE(message.find("all-bad.obj"), std::string::npos) << message;
  EXPECT_NE(message.find("degenerate"), std::string::npos) << message;
}

TEST(DegenerateGeometry, ZeroAreaTriangleShapesAreSkippedWithAWarning) {
  const auto scene = load(room(1, R"(,
      {"type": "triangle", "vertices": [[0, 0.5, 0], [0, 0.5, 0], [1, 1, 0]]},
      {"type": "triangle", "vertices": [[0, 0.5, 0], [0.5, 0.75, 0], [1, 1, 0]]},
      {"type": "triangle", "vertices": [[-0.5, 0.2, 0.5], [0.5, 0.2, 0.5], [0, 1.5, 0.5]], "material": {"kd": 0.8}})"));
  EXPECT_TRUE(any_warning(*scene, "shapes[5]", "skipped")) << all_warnings(*scene);
  EXPECT_TRUE(any_warning(*scene, "shapes[6]", "skipped")) << all_warnings(*scene);
  EXPECT_FALSE(any_warning(*scene, "shapes[7]")) << all_warnings(*scene);
  EXPECT_EQ(scene->objects[5].primitive_count, 0u);
  EXPECT_EQ(scene->objects[7].primitive_count, 1u);
  render_every_method(*scene, "zero-area triangles");
}

TEST(DegenerateGeometry, SliverTrianglesRenderWithoutNan) {
  // 1e-12 wide and 2 long, across the view, and one spanning the whole room: kept (they have
  // area), never a NaN normal, nothing to mesh into empty elements.
  const auto scene = load(room(1, R"(,
      {"type": "triangle", "vertices": [[-1, 0.5, 0.5], [1, 0.5, 0.5], [1, 0.5, 0.500000000001]], "material": {"kd": 0.9}},
      {"type": "triangle", "vertices": [[-1, 0.2, 0.3], [1, 1.6, 0.3], [1, 1.600000000001, 0.3]], "material": {"kd": 0.9}},
      {"type": "triangle", "vertices": [[0, 1, 0], [1e-12, 1, 0], [0.5, 1.5, 0]], "material": {"kd": 0.9}})"));
  EXPECT_TRUE(scene->warnings.empty()) << all_warnings(*scene);
  EXPECT_EQ(scene->objects[5].primitive_count, 1u);
  render_every_method(*scene, "slivers");
}

// --- 3. Coincident surfaces ---------------------------------------------------------------------

TEST(DegenerateGeometry, CoincidentQuadsAreDeterministicAndTheFirstWins) {
  // Two identical quads, red then blue, in front of the back wall: the accelerators' tie rule
  // (equal t: the lower primitive index) shows the red one, whatever the thread count.
  const std::string quads = R"(,
      {"type": "quad", "corner": [-0.6, 0.3, 0], "edge_u": [1.2, 0, 0], "edge_v": [0, 1.2, 0], "material": {"kd": [0.9, 0, 0]}},
      {"type": "quad", "corner": [-0.6, 0.3, 0], "edge_u": [1.2, 0, 0], "edge_v": [0, 1.2, 0], "material": {"kd": [0, 0, 0.9]}})";
  for (const char* accelerator : {"list", "bvh", "grid", "octree"}) {
    SCOPED_TRACE(accelerator);
    const std::string text = room(1, quads);
    const auto scene = load(text.substr(0, text.size() - 1) + R"(, "render": {"accelerator": ")" +
                            std::string(accelerator) + R"("}})");
    const std::vector<Film> one =
        render_every_method(*scene, std::string("coincident, 1 thread, ") + accelerator, 1);
    const std::vector<Film> two =
        render_every_method(*scene, std::string("coincident, 2 threads, ") + accelerator, 2);
    for (std::size_t m = 0; m < kMethods.size(); ++m) {
      if (kMethods[m] == "meshless") continue;  // its site placement is not thread-count exact
      EXPECT_EQ(one[m].pixels(), two[m].pixels()) << kMethods[m] << ": differs between 1 and 2 threads";
    }
    // The red quad alone gives the same image: the blue one is never seen (the methods that
    // trace or rasterize; radiosity and meshless mesh both quads).
    const std::string red = room(1, quads.substr(0, quads.find("},\n") + 1));
    const auto red_only = load(red.substr(0, red.size() - 1) + R"(, "render": {"accelerator": ")" +
                               std::string(accelerator) + R"("}})");
    for (std::size_t m : {0u, 1u, 2u, 5u}) {
      const Film expected = testing::render_scene(*red_only, kMethods[m], 1);
      EXPECT_EQ(one[m].pixels(), expected.pixels()) << kMethods[m] << ": the second coincident quad shows";
    }
  }
}

TEST(DegenerateGeometry, QuadLyingInABoxFaceRendersWithoutNan) {
  const auto scene = load(room(1, R"(,
      {"type": "box", "min": [-0.9, 0, 0.2], "max": [-0.3, 0.6, 0.8], "material": {"kd": [0.2, 0.2, 0.8]}},
      {"type": "quad", "corner": [-0.8, 0.6, 0.3], "edge_u": [0, 0, 0.4], "edge_v": [0.4, 0, 0], "material": {"kd": [0.9, 0.9, 0.1]}},
      {"type": "quad", "corner": [-0.8, 0.1, 0.8], "edge_u": [0.4, 0, 0], "edge_v": [0, 0.4, 0], "material": {"kd": [0.9, 0.1, 0.9]}})"));
  const std::vector<Film> one = render_every_method(*scene, "quad in box face, 1 thread", 1);
  const std::vector<Film> two = render_every_method(*scene, "quad in box face, 2 threads", 2);
  for (std::size_t m = 0; m < kMethods.size(); ++m) {
    if (kMethods[m] == "meshless") continue;
    EXPECT_EQ(one[m].pixels(), two[m].pixels()) << kMethods[m];
  }
}

// --- 4. Scale -----------------------------------------------------------------------------------

class DegenerateScale : public ::testing::TestWithParam<double> {};

TEST_P(DegenerateScale, RoomRendersAsAtUnitScale) {
  const double scale = GetParam();
  const auto unit = load(room(1));
  const auto scaled = load(room(scale));
  const std::vector<Film> reference = render_every_method(*unit, "unit scale");
  const std::vector<Film> films = render_every_method(*scaled, "scale " + num(scale));
  for (std::size_t m = 0; m < kMethods.size(); ++m) {
    const double difference = relative_difference(reference[m], films[m]);
    // Local, Whitted and the path tracer see exactly the same scene scaled (no attenuation):
    // the same image up to rounding, no acne. The others mesh and place sites by lengths that
    // are scaled too, so they are close as well.
    const double bound = kMethods[m] == "meshless" ? 0.1 : 0.02;
    EXPECT_LT(difference, bound) << kMethods[m] << " at scale " << scale << ": mean "
                                 << mean_channel_average(films[m]) << " vs "
                                 << mean_channel_average(reference[m]);
  }
}

INSTANTIATE_TEST_SUITE_P(Scales, DegenerateScale, ::testing::Values(1e-6, 1e6),
                         [](const ::testing::TestParamInfo<double>& info) {
                           return info.param < 1 ? std::string("Micro") : std::string("Mega");
                         });

}  // namespace
}  // namespace candela
