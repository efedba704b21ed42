#include "io/obj_import.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <future>
#include <random>
#include <sstream>
#include <string>

#include "geometry/triangle_mesh.h"
#include "math/constants.h"
#include "util/input_file.h"

namespace candela {
namespace {

namespace fs = std::filesystem;

// A fresh directory under the system temporary directory, removed with its contents at the end.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::random_device random;
    path_ = fs::temp_directory_path() / ("candela_obj_" + std::string(info ? info->name() : "test") + "_" +
                                         std::to_string(random()) + std::to_string(random()));
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  // Writes text to name inside the directory and returns the full path.
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path file = path_ / name;
    std::ofstream out(file, std::ios::binary);
    out << text;
    return file.string();
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

SourceLocation scene_location() {
  SourceLocation location;
  location.file = "scene.json";
  location.line = 12;
  location.column = 7;
  location.json_path = "shapes[2].file";
  return location;
}

// Runs import_obj expecting an InputError; returns its message (empty when nothing was thrown).
std::string import_error(const std::string& path) {
  try {
    import_obj(path, scene_location());
  } catch (const InputError& error) {
    EXPECT_EQ(error.location().file, "scene.json");
    EXPECT_EQ(error.location().line, 12);
    EXPECT_EQ(error.location().json_path, "shapes[2].file");
    return error.message();
  }
  ADD_FAILURE() << "no InputError for " << path;
  return {};
}

bool any_contains(const std::vector<std::string>& lines, const std::string& needle) {
  for (const auto& line : lines)
    if (line.find(needle) != std::string::npos) return true;
  return false;
}

const char* const kCubeObj = R"(# unit cube [0,1]^3, quads counter-clockwise from outside
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
)";

TEST(ObjImport, CubeCountsAndGeometry) {
  const TempDir dir;
  const ObjImport result = import_obj(dir.write("cube.obj", kCubeObj), scene_location());
  ASSERT_TRUE(result.mesh);
  EXPECT_EQ(result.mesh->positions.size(), 8u);
  EXPECT_EQ(result.mesh->triangles.size(), 12u);
  EXPECT_TRUE(result.mesh->corner_normals.empty());
  EXPECT_TRUE(result.mesh->corner_uvs.empty());
  EXPECT_TRUE(result.materials.empty());
  ASSERT_EQ(result.triangle_material.size(), 12u);
  for (int m : result.triangle_material) EXPECT_EQ(m, -1);
  EXPECT_TRUE(result.warnings.empty());
  // Counter-clockwise quads stay outward after triangulation.
  const Vec3 centre{0.5, 0.5, 0.5};
  for (std::size_t t = 0; t < result.mesh->triangles.size(); ++t) {
    EXPECT_FALSE(result.mesh->is_degenerate(t));
    EXPECT_GT(dot(result.mesh->face_cross(t), result.mesh->triangle_bounds(t).center() - centre), 0);
  }
  // Usable as shapes: a ray down the z axis enters through the top face at z = 1.
  const auto shapes = make_triangles(result.mesh);
  ASSERT_EQ(shapes.size(), 12u);
  const Ray ray{{0.3, 0.6, 3}, {0, 0, -1}};
  double nearest = kInfinity;
  for (const auto& shape : shapes) {
    SurfaceHit hit;
    if (shape->intersect(ray, hit)) nearest = std::min(nearest, hit.t);
  }
  EXPECT_DOUBLE_EQ(nearest, 2.0);
}

TEST(ObjImport, NegativeIndicesAndSeveralObjects) {
  const TempDir dir;
  const std::string obj = R"(o first
v 0 0 0
v 1 0 0
v 0 1 0
f -3 -2 -1
o second
v 0 0 1
v 1 0 1
v 0 1 1
v 1 1 1
f 4 5 6
f 5 7 6
)";
  const ObjImport result = import_obj(dir.write("two.obj", obj), scene_location());
  ASSERT_EQ(result.mesh->triangles.size(), 3u);
  EXPECT_EQ(result.mesh->triangles[0], (std::array<uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(result.mesh->triangles[1], (std::array<uint32_t, 3>{3, 4, 5}));
  EXPECT_EQ(result.mesh->triangles[2], (std::array<uint32_t, 3>{4, 6, 5}));
}

TEST(ObjImport, MaterialsMapFromMtl) {
  const TempDir dir;
  dir.write("materials.mtl", R"(newmtl red
Ka 0.1 0.2 0.3
Kd 0.8 0.1 0.05
Ks 0.3 0.6 0.9
Ns 50
d 0.25
Ni 1.5

newmtl glass
Kd 0 0 0
Tr 0.9
Ke 4 3 2
)");
  const std::string obj = R"(mtllib materials.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
f 1 2 3
usemtl red
f 1 3 4
usemtl glass
f 1 2 3 4
usemtl red
f 4 3 2
)";
  const ObjImport result = import_obj(dir.write("scene.obj", obj), scene_location());
  EXPECT_TRUE(result.warnings.empty()) << (result.warnings.empty() ? "" : result.warnings[0]);
  ASSERT_EQ(result.materials.size(), 2u);
  const ImportedMaterial& red = result.materials[0];
  EXPECT_EQ(red.name, "red");
  EXPECT_NEAR(red.ka.r, 0.1, 1e-6);
  EXPECT_NEAR(red.ka.g, 0.2, 1e-6);
  EXPECT_NEAR(red.ka.b, 0.3, 1e-6);
  EXPECT_NEAR(red.kd.r, 0.8, 1e-6);
  EXPECT_NEAR(red.kd.g, 0.1, 1e-6);
  EXPECT_NEAR(red.kd.b, 0.05, 1e-6);
  EXPECT_NEAR(red.ks, 0.6, 1e-6);
  EXPECT_NEAR(red.shininess, 50, 1e-6);
  EXPECT_NEAR(red.kt, 0.75, 1e-6);
  EXPECT_NEAR(red.ior, 1.5, 1e-6);
  EXPECT_TRUE(red.ke.is_black());
  const ImportedMaterial& glass = result.materials[1];
  EXPECT_EQ(glass.name, "glass");
  EXPECT_NEAR(glass.kt, 0.9, 1e-6);  // Tr is the transparency itself
  EXPECT_NEAR(glass.ior, 1.0, 0);    // no Ni
  EXPECT_NEAR(glass.ks, 0.0, 0);
  EXPECT_NEAR(glass.ke.r, 4, 1e-6);
  EXPECT_NEAR(glass.ke.b, 2, 1e-6);
  // The face before any usemtl has none; the quad became two triangles.
  const std::vector<int> expected{-1, 0, 1, 1, 0};
  EXPECT_EQ(result.triangle_material, expected);
  EXPECT_EQ(result.mesh->triangles.size(), 5u);
}

TEST(ObjImport, NormalsAndTextureCoordinates) {
  const TempDir dir;
  const std::string obj = R"(v 0 0 0
v 1 0 0
v 0 1 0
vn 0 0 2
vn 1 0 1
vn 0 1 1
vt 0.5 0.25
vt 1 0
vt 0 1
f 1/1/1 2/2/2 3/3/3
)";
  const ObjImport result = import_obj(dir.write("smooth.obj", obj), scene_location());
  const TriangleMesh& mesh = *result.mesh;
  ASSERT_EQ(mesh.corner_normals.size(), 1u);
  ASSERT_EQ(mesh.corner_uvs.size(), 1u);
  EXPECT_NEAR(mesh.corner_normals[0][0].z, 1.0, 1e-15);  // normalised
  EXPECT_NEAR(mesh.corner_normals[0][1].x, std::sqrt(0.5), 1e-7);
  EXPECT_NEAR(mesh.corner_normals[0][2].y, std::sqrt(0.5), 1e-7);
  EXPECT_NEAR(mesh.corner_uvs[0][0].x, 0.5, 1e-7);
  EXPECT_NEAR(mesh.corner_uvs[0][0].y, 0.25, 1e-7);
  EXPECT_NEAR(mesh.corner_uvs[0][2].y, 1.0, 1e-7);

  // The hit interpolates them.
  const MeshTriangle triangle(result.mesh, 0);
  SurfaceHit hit;
  ASSERT_TRUE(triangle.intersect(Ray{{0, 0.5, 1}, {0, 0, -1}}, hit));  // b0 = b2 = 0.5
  EXPECT_NEAR(hit.uv.x, 0.25, 1e-7);
  EXPECT_NEAR(hit.uv.y, 0.625, 1e-7);
  EXPECT_NEAR(hit.shading_normal.x, 0, 1e-12);
  EXPECT_GT(hit.shading_normal.y, 0.3);
}

TEST(ObjImport, PartialNormalsGiveFlatShadingAndAWarning) {
  const TempDir dir;
  const std::string obj = R"(v 0 0 0
v 1 0 0
v 0 1 0
v 1 1 0
vn 0 0 1
f 1//1 2//1 3//1
f 2 4 3
)";
  const ObjImport result = import_obj(dir.write("partial.obj", obj), scene_location());
  EXPECT_TRUE(result.mesh->corner_normals.empty());
  EXPECT_TRUE(any_contains(result.warnings, "normals"));
}

TEST(ObjImport, MissingFileNamesThePath) {
  const TempDir dir;
  const std::string path = (dir.path() / "nowhere.obj").string();
  const std::string message = import_error(path);
  EXPECT_NE(message.find(path), std::string::npos) << message;
  // A directory is not a mesh either.
  EXPECT_NE(import_error(dir.path().string()).find(dir.path().string()), std::string::npos);
}

TEST(ObjImport, MalformedFaceGivesTheLine) {
  const TempDir dir;
  const std::string path = dir.write("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
  const std::string message = import_error(path);
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("line 4"), std::string::npos) << message;
}

TEST(ObjImport, OutOfRangeIndexIsAnError) {
  const TempDir dir;
  const std::string triangle = dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  EXPECT_NE(import_error(triangle).find("out of range"), std::string::npos);
  // tinyobjloader silently drops a quad with a bad index; it is still an error.
  const std::string quad = dir.write("quad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 3 12\n");
  EXPECT_NE(import_error(quad).find("out of range"), std::string::npos);
  const std::string normal =
      dir.write("normal.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//4\n");
  EXPECT_NE(import_error(normal).find("out of range"), std::string::npos);
  const std::string relative = dir.write("relative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -5\n");
  EXPECT_NE(import_error(relative).find("out of range"), std::string::npos);
}

// tinyobjloader reads an index with atoi, which saturates: 99999999999999999999
// became -1, "the last vertex", and the face loaded without a word.
TEST(ObjImport, IndexBeyondTheIntegerRangeIsALocatedError) {
  const TempDir dir;
  const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  for (const std::string face : {"f 1 2 99999999999999999999", "f 1 2 -99999999999999999999",
                                 "f 1 2 2147483648", "f 1/99999999999 2 3", "l 1 99999999999999"}) {
    const std::string message = import_error(dir.write("overflow.obj", head + "\n" + face + "\n"));
    EXPECT_NE(message.find("line 5"), std::string::npos) << face << ": " << message;
    EXPECT_NE(message.find("beyond the 32-bit integer range"), std::string::npos) << face << ": " << message;
  }
  // A relative index reaching before the first vertex, with the line.
  const std::string message = import_error(dir.write("back.obj", head + "f 1 2 -4\n"));
  EXPECT_NE(message.find("line 4"), std::string::npos) << message;
  EXPECT_NE(message.find("out of range"), std::string::npos) << message;
  // The largest index that fits is an ordinary out-of-range index, located too.
  const std::string large = import_error(dir.write("large.obj", head + "f 1 2 2147483647\n"));
  EXPECT_NE(large.find("line 4"), std::string::npos) << large;
  EXPECT_NE(large.find("out of range"), std::string::npos) << large;
}

std::string regular_polygon_obj(int corners, double radius) {
  std::string obj;
  obj.reserve(static_cast<std::size_t>(corners) * 40);
  char buffer[96];
  for (int k = 0; k < corners; ++k) {
    const double angle = 2 * kPi * k / corners;
    std::snprintf(buffer, sizeof buffer, "v %.9g %.9g 0\n", radius * std::cos(angle),
                  radius * std::sin(angle));
    obj += buffer;
  }
  obj += "f";
  for (int k = 1; k <= corners; ++k) {
    obj += ' ';
    obj += std::to_string(k);
  }
  return obj + "\n";
}

double total_area(const TriangleMesh& mesh) {
  double area = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) area += 0.5 * length(mesh.face_cross(t));
  return area;
}

// tinyobjloader's ear clipping is quadratic: a convex face of 10⁵ corners took 36 s.
TEST(ObjImport, AHugeConvexFaceIsHalvedInLinearTime) {
  const TempDir dir;
  constexpr int kCorners = 100000;
  const std::string path = dir.write("disc.obj", regular_polygon_obj(kCorners, 1.0));
  const auto start = std::chrono::steady_clock::now();
  const ObjImport result = import_obj(path, scene_location());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 5.0);  // 0.1 s here; sanitizers are slower
  ASSERT_EQ(result.mesh->triangles.size(), static_cast<std::size_t>(kCorners - 2));
  const double expected = 0.5 * kCorners * std::sin(2 * kPi / kCorners);  // the polygon's area
  EXPECT_NEAR(total_area(*result.mesh), expected, 1e-6);
  for (std::size_t t = 0; t < result.mesh->triangles.size(); ++t)
    ASSERT_GE(result.mesh->face_cross(t).z, -1e-9)
        << t;  // counter-clockwise as the face (slivers: within rounding)
  // Halved, not fanned: few triangles meet at any one corner (a fan: all 99,998 at corner 0).
  std::size_t at_corner_zero = 0;
  for (const auto& t : result.mesh->triangles) at_corner_zero += std::count(t.begin(), t.end(), 0u);
  EXPECT_LE(at_corner_zero, 40u);
}

// A non-convex face: ear-clipped up to kMaxNonConvexFaceCorners corners, refused beyond with the
// face's line and the limit.
TEST(ObjImport, NonConvexFacesAreEarClippedUpToTheLimit) {
  const TempDir dir;
  // An L of area 3 (concave at its fourth corner).
  const ObjImport l_shape =
      import_obj(dir.write("l.obj", "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nf 1 2 3 4 5 6\n"),
                 scene_location());
  ASSERT_EQ(l_shape.mesh->triangles.size(), 4u);
  EXPECT_NEAR(total_area(*l_shape.mesh), 3.0, 1e-12);
  const auto star = [](int points) {
    std::string obj;
    char buffer[96];
    for (int k = 0; k < 2 * points; ++k) {
      const double angle = kPi * k / points, radius = k % 2 ? 0.5 : 1.0;
      std::snprintf(buffer, sizeof buffer, "v %.9g %.9g 0\n", radius * std::cos(angle),
                    radius * std::sin(angle));
      obj += buffer;
    }
    obj += "f";
    for (int k = 1; k <= 2 * points; ++k) {
      obj += ' ';
      obj += std::to_string(k);
    }
    return obj + "\n";
  };
  const ObjImport small = import_obj(dir.write("star.obj", star(50)), scene_location());
  EXPECT_EQ(small.mesh->triangles.size(), 98u);
  const double star_area = 100 * 0.5 * 1.0 * 0.5 * std::sin(kPi / 50);
  EXPECT_NEAR(total_area(*small.mesh), star_area, 1e-6);  // the vertices are floats
  const auto start = std::chrono::steady_clock::now();
  const std::string message = import_error(dir.write("big-star.obj", star(2000)));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  EXPECT_NE(message.find("line 4001"), std::string::npos) << message;
  EXPECT_NE(message.find("4000 corners"), std::string::npos) << message;
  EXPECT_NE(message.find(std::to_string(kMaxNonConvexFaceCorners)), std::string::npos) << message;
}

// tinyobjloader opened the MTL files itself: a FIFO blocked in open() forever, and
// /dev/zero was read until memory ran out. Each is refused, naming the file and the problem.
TEST(ObjImport, MtlFilesMustBeRegularFilesOfBoundedSize) {
  const TempDir dir;
  const std::string fifo = (dir.path() / "pipe.mtl").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const std::string path = dir.write("pipe.obj", "mtllib pipe.mtl\n" + obj);
  auto pending = std::async(std::launch::async, [&] { return import_error(path); });
  if (pending.wait_for(std::chrono::seconds(20)) != std::future_status::ready) {
    ADD_FAILURE() << "import_obj blocked on the FIFO";
    // A writer lets the blocked open() return, so that the test can end.
    const int writer = ::open(fifo.c_str(), O_WRONLY);
    if (writer >= 0) ::close(writer);
  }
  const std::string message = pending.get();
  EXPECT_NE(message.find("FIFO"), std::string::npos) << message;
  EXPECT_NE(message.find(fifo), std::string::npos) << message;

  std::filesystem::create_directory(dir.path() / "folder.mtl");
  const std::string folder = import_error(dir.write("folder.obj", "mtllib folder.mtl\n" + obj));
  EXPECT_NE(folder.find("is a directory"), std::string::npos) << folder;

  // Larger than the limit (a sparse file: nothing is written, nothing may be read).
  const std::filesystem::path huge = dir.path() / "huge.mtl";
  std::ofstream(huge).put('\n');
  std::filesystem::resize_file(huge, kLargeInputLimit + 1);
  const std::string big = import_error(dir.write("huge.obj", "mtllib huge.mtl\n" + obj));
  EXPECT_NE(big.find("more than the " + std::to_string(kLargeInputLimit) + " bytes"), std::string::npos)
      << big;
}

TEST(ObjImport, NonFiniteCoordinateIsAnError) {
  const TempDir dir;
  const std::string path = dir.write("huge.obj", "v 0 0 0\nv 1e300 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string message = import_error(path);
  EXPECT_NE(message.find("non-finite"), std::string::npos) << message;
  EXPECT_NE(message.find(path), std::string::npos) << message;
}

TEST(ObjImport, NoTrianglesIsAnError) {
  const TempDir dir;
  EXPECT_NE(import_error(dir.write("points.obj", "v 0 0 0\nv 1 0 0\n")).find("no triangles"),
            std::string::npos);
  EXPECT_NE(import_error(dir.write("empty.obj", "")).find("no triangles"), std::string::npos);
  EXPECT_NE(import_error(dir.write("lines.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n")).find("no triangles"),
            std::string::npos);
}

TEST(ObjImport, MissingMtlIsAWarning) {
  const TempDir dir;
  const std::string obj = "mtllib nothere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n";
  const std::string path = dir.write("lonely.obj", obj);
  const ObjImport result = import_obj(path, scene_location());
  EXPECT_EQ(result.mesh->triangles.size(), 1u);
  EXPECT_TRUE(result.materials.empty());
  EXPECT_EQ(result.triangle_material, std::vector<int>{-1});
  EXPECT_TRUE(any_contains(result.warnings, "nothere.mtl"));
  for (const auto& warning : result.warnings) EXPECT_EQ(warning.rfind(path, 0), 0u) << warning;
}

TEST(ObjImport, DegenerateFacesAreKeptForTheLoaderToSkip) {
  const TempDir dir;
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n";
  const ObjImport result = import_obj(dir.write("flat.obj", obj), scene_location());
  ASSERT_EQ(result.mesh->triangles.size(), 2u);
  std::size_t skipped = 0;
  EXPECT_EQ(make_triangles(result.mesh, &skipped).size(), 1u);
  EXPECT_EQ(skipped, 1u);
}

TEST(ObjImport, WeldedSmoothingOfADuplicatedVertexCube) {
  // Each face with its own four vertices, as exporters write it: smoothing at 180 degrees must
  // still average across faces, 30 degrees must keep them flat.
  const TempDir dir;
  std::string obj;
  const int faces[6][4] = {{1, 4, 3, 2}, {5, 6, 7, 8}, {1, 2, 6, 5},
                           {2, 3, 7, 6}, {3, 4, 8, 7}, {4, 1, 5, 8}};
  const double corners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  int next = 1;
  std::string face_lines;
  for (const auto& face : faces) {
    face_lines += "f";
    for (int corner : face) {
      const double* c = corners[corner - 1];
      std::ostringstream vertex;
      vertex << "v " << c[0] << ' ' << c[1] << ' ' << c[2] << '\n';
      obj += vertex.str();
      face_lines += ' ';
      face_lines += std::to_string(next++);
    }
    face_lines += "\n";
  }
  ObjImport result = import_obj(dir.write("split.obj", obj + face_lines), scene_location());
  ASSERT_EQ(result.mesh->positions.size(), 24u);
  ASSERT_EQ(result.mesh->triangles.size(), 12u);
  compute_corner_normals(*result.mesh, 180);
  for (std::size_t t = 0; t < 12; ++t) {
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = result.mesh->positions[result.mesh->triangles[t][k]] - Vec3{0.5, 0.5, 0.5};
      EXPECT_GT(dot(result.mesh->corner_normals[t][k], normalize(p)), 0.9);
    }
  }
  compute_corner_normals(*result.mesh, 30);
  for (std::size_t t = 0; t < 12; ++t) {
    const Vec3 face = normalize(result.mesh->face_cross(t));
    for (const Vec3& n : result.mesh->corner_normals[t]) EXPECT_NEAR(dot(n, face), 1.0, 1e-15);
  }
}

}  // namespace
}  // namespace candela
