// Form factors (000 §6.2–6.4.1, SPEC §10): delta form factors, the hemicube, ray casting and
// the analytic polygon formula, against closed forms from J. R. Howell, "A Catalog of Radiation
// Heat Transfer Configuration Factors" (3rd ed., 2010; entries named by title below, with the
// catalogue's numbers where they are the well-known ones).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "accel/bvh.h"
#include "geometry/triangle_mesh.h"
#include "math/constants.h"
#include "math/pcg32.h"
#include "radiosity/configuration_factors.h"
#include "radiosity/delta_form_factors.h"
#include "radiosity/hemicube_form_factors.h"
#include "radiosity/ray_cast_form_factors.h"

namespace candela {
namespace {

// ---------------------------------------------------------------------------------------------
// Closed forms (Howell's catalogue)

// "Plane element to plane parallel rectangle; normal to element passes through a corner of the
// rectangle", rectangle a × b at distance c, A = a/c, B = b/c:
// F = (1/2π) [ A/√(1+A²) atan(B/√(1+A²)) + B/√(1+B²) atan(A/√(1+B²)) ].
double point_to_parallel_rectangle_corner(double a, double b, double c) {
  const double A = a / c, B = b / c;
  return (A / std::sqrt(1 + A * A) * std::atan(B / std::sqrt(1 + A * A)) +
          B / std::sqrt(1 + B * B) * std::atan(A / std::sqrt(1 + B * B))) /
         (2 * kPi);
}

// "Plane element to a perpendicular rectangle, the element on the normal to the rectangle
// through one of the corners of its edge in the element's plane": the rectangle w wide (along
// the element's plane) and h high, at distance c; X = h/w, Y = c/w:
// F = (1/2π) [ atan(1/Y) − Y/√(X²+Y²) atan(1/√(X²+Y²)) ].
double point_to_perpendicular_rectangle(double w, double h, double c) {
  const double X = h / w, Y = c / w;
  return (std::atan(1 / Y) - Y / std::sqrt(X * X + Y * Y) * std::atan(1 / std::sqrt(X * X + Y * Y))) /
         (2 * kPi);
}

// The centre of a unit square facing a parallel unit square at distance 1 (four corner rectangles).
const double kPointToSquare = 4 * point_to_parallel_rectangle_corner(0.5, 0.5, 1);  // 0.23946
const double kParallelSquares = parallel_rectangles(1, 1);                          // 0.19982
const double kPerpendicularSquares = perpendicular_rectangles(1, 1);                // 0.20004

double relative_error(double value, double expected) {
  return std::fabs(value - expected) / std::fabs(expected);
}

// A measured value, kept in the test report (--gtest_output=xml) rather than printed.
void record_measurement(const std::string& key, double value) {
  std::ostringstream text;
  text << value;
  ::testing::Test::RecordProperty(key, text.str());
}

// ---------------------------------------------------------------------------------------------
// Scenes

// Appends a planar quad p0 p1 p2 p3 (two triangles) belonging to `element`.
void add_quad(FormFactorGeometry& geometry, const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3,
              uint32_t element) {
  const auto base = static_cast<uint32_t>(geometry.mesh.positions.size());
  for (const Vec3& p : {p0, p1, p2, p3}) geometry.mesh.positions.push_back(p);
  geometry.mesh.triangles.push_back({base, base + 1, base + 2});
  geometry.mesh.triangles.push_back({base, base + 2, base + 3});
  geometry.element_of_triangle.push_back(element);
  geometry.element_of_triangle.push_back(element);
  geometry.element_count = std::max(geometry.element_count, element + 1);
}

// A regular polygon of `sides` corners around centre in the plane z = centre.z (a disc), as a fan.
std::vector<Vec3> disc_polygon(const Vec3& centre, double radius, int sides) {
  std::vector<Vec3> corners;
  for (int k = 0; k < sides; ++k) {
    const double phi = 2 * kPi * k / sides;
    corners.push_back(centre + Vec3{radius * std::cos(phi), radius * std::sin(phi), 0});
  }
  return corners;
}

void add_fan(FormFactorGeometry& geometry, const Vec3& centre, const std::vector<Vec3>& corners,
             uint32_t element) {
  const auto base = static_cast<uint32_t>(geometry.mesh.positions.size());
  geometry.mesh.positions.push_back(centre);
  for (const Vec3& p : corners) geometry.mesh.positions.push_back(p);
  const auto count = static_cast<uint32_t>(corners.size());
  for (uint32_t k = 0; k < count; ++k) {
    geometry.mesh.triangles.push_back({base, base + 1 + k, base + 1 + (k + 1) % count});
    geometry.element_of_triangle.push_back(element);
  }
  geometry.element_count = std::max(geometry.element_count, element + 1);
}

// Two unit squares: element 0 in z = 0 ([0,1]², facing +z), element 1 in z = 1 facing it.
FormFactorGeometry parallel_squares() {
  FormFactorGeometry geometry;
  add_quad(geometry, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 0);
  add_quad(geometry, {0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}, 1);
  return geometry;
}

// Element 0: [0,w] × [0,1] in z = 0 facing +z; element 1: x = 0, y ∈ [0,1], z ∈ [0,h] facing +x;
// the common edge is the y axis from 0 to 1.
FormFactorGeometry perpendicular_rectangles_geometry(double w, double h) {
  FormFactorGeometry geometry;
  add_quad(geometry, {0, 0, 0}, {w, 0, 0}, {w, 1, 0}, {0, 1, 0}, 0);
  add_quad(geometry, {0, 0, 0}, {0, 1, 0}, {0, 1, h}, {0, 0, h}, 1);
  return geometry;
}

// The substructured F_ij (000 eq. 6-19) from the unit square [0,1]² in z = 0 (facing +z): the mean
// of hemicube rows from the centres of a grid × grid subdivision (equal areas A_k).
double substructured_from_unit_square(HemicubeFormFactors& hemicube, const FormFactorGeometry& geometry,
                                      int grid, uint32_t target, const Vec3& tangent = {1, 0, 0}) {
  std::vector<double> row;
  double sum = 0;
  for (int i = 0; i < grid; ++i)
    for (int j = 0; j < grid; ++j) {
      hemicube.compute_row(geometry, {(i + 0.5) / grid, (j + 0.5) / grid, 0}, {0, 0, 1}, tangent, 0, row);
      sum += row[target];
    }
  return sum / (grid * grid);
}

// A BVH over a mesh's triangles, for visibility.
struct Occluders {
  explicit Occluders(const TriangleMesh& triangles) : mesh(std::make_shared<TriangleMesh>(triangles)) {
    shapes = make_triangles(mesh);
    for (const auto& shape : shapes) primitives.push_back({shape.get(), 0, 0});
    bvh.build(primitives);
  }
  std::shared_ptr<const TriangleMesh> mesh;
  std::vector<std::unique_ptr<Shape>> shapes;
  std::vector<Primitive> primitives;
  Bvh bvh;
};

// ---------------------------------------------------------------------------------------------
// Delta form factors (000 §6.4.1)

TEST(DeltaFormFactors, SumOverTheHemicubeIsOneAndConverges) {
  const double error_100 = std::fabs(DeltaFormFactors(100).total() - 1);
  EXPECT_LT(error_100, 1e-3);  // measured 5.4e-5
  record_measurement("sum_error_R100", error_100);
  // The midpoint rule's error falls with the resolution, as 1/R².
  double previous_error = 1;
  for (const int resolution : {4, 10, 20, 50, 100, 200, 400}) {
    const double error = std::fabs(DeltaFormFactors(resolution).total() - 1);
    EXPECT_LT(error, previous_error) << "R = " << resolution;
    previous_error = error;
  }
  EXPECT_LT(previous_error, 1e-5);                   // R = 400: measured 3.4e-6
  EXPECT_NEAR(error_100 / previous_error, 16, 0.5);  // four times the resolution: 1/16 of the error
}

TEST(DeltaFormFactors, SymmetricLookupsEqualDirectEvaluation) {
  for (const int resolution : {2, 6, 100}) {
    const DeltaFormFactors delta(resolution);
    std::vector<double> expanded(static_cast<std::size_t>(resolution));
    int mismatches = 0;
    for (const HemicubeFace face : kHemicubeFaces) {
      for (int row = 0; row < resolution; ++row) {
        delta.expand_row(face, row, expanded.data());
        for (int column = 0; column < resolution; ++column) {
          const double direct = DeltaFormFactors::evaluate(resolution, face, column, row);
          // Bit-identical: the tables hold the direct values, found through the symmetries.
          mismatches += delta.at(face, column, row) != direct;
          mismatches += expanded[column] != direct;
          if (face == HemicubeFace::top) {
            mismatches += delta.top(column, row) != direct;
            mismatches += delta.top(row, column) != direct;  // x ↔ y
            mismatches +=
                delta.top(resolution - 1 - column, resolution - 1 - row) != direct;  // x, y → −x, −y
          } else if (row < delta.side_rows()) {
            mismatches += delta.side(column, row) != direct;
            mismatches += delta.side(resolution - 1 - column, row) != direct;  // y → −y
            // The side face's formula is z times the top face's at the same (y, z) lattice point.
            const double z = (resolution - 2.0 * row - 1) / resolution;
            EXPECT_NEAR(direct, z * delta.top(column, row), 1e-15 * direct);
          } else {
            mismatches += direct != 0.0;  // below the surface
          }
        }
      }
    }
    EXPECT_EQ(mismatches, 0) << "R = " << resolution;
  }
  // The centre cells of the top face: ΔA/(π(1 + 2(1/R)²)²) with ΔA = (2/R)².
  const DeltaFormFactors delta(100);
  EXPECT_NEAR(delta.top(50, 50), 4e-4 / (kPi * std::pow(1 + 2e-4, 2)), 1e-18);
}

TEST(DeltaFormFactors, StoresOneEighthOfTheCells) {
  for (const int resolution : {2, 100, 400}) {
    const DeltaFormFactors delta(resolution);
    const std::size_t half = resolution / 2;
    // An octant of the top face, a quarter of a side face (half its columns, the upper rows).
    EXPECT_EQ(delta.stored_values(), half * (half + 1) / 2 + half * half);
    EXPECT_EQ(delta.memory_bytes(), delta.stored_values() * sizeof(double));
    // 3R² cells above the surface (R² on top, 4 × R²/2 on the sides): 3R²/8 + R/4 stored.
    const std::size_t cells = 3 * static_cast<std::size_t>(resolution) * resolution;
    EXPECT_EQ(8 * delta.stored_values(), cells + 2 * static_cast<std::size_t>(resolution));
  }
}

TEST(DeltaFormFactors, RejectsBadResolutionsAndCells) {
  EXPECT_THROW(DeltaFormFactors(0), std::invalid_argument);
  EXPECT_THROW(DeltaFormFactors(7), std::invalid_argument);
  EXPECT_THROW(DeltaFormFactors(-4), std::invalid_argument);
  const DeltaFormFactors delta(8);
  EXPECT_THROW(delta.at(HemicubeFace::top, 8, 0), std::out_of_range);
  EXPECT_THROW(delta.at(HemicubeFace::left, 0, -1), std::out_of_range);
  EXPECT_EQ(delta.at(HemicubeFace::left, 3, 4), 0.0);  // first row below the surface
  EXPECT_GT(delta.at(HemicubeFace::left, 3, 3), 0.0);  // last row above it
}

// ---------------------------------------------------------------------------------------------
// Closed forms and the analytic polygon formula

TEST(FormFactorAnalytic, HowellClosedFormsGiveTheCatalogueValues) {
  EXPECT_NEAR(kParallelSquares, 0.19982, 5e-6);
  EXPECT_NEAR(kPerpendicularSquares, 0.20004, 5e-6);
  EXPECT_NEAR(kPointToSquare, 0.2395, 5e-5);
  EXPECT_NEAR(coaxial_discs(1, 1, 1), (3 - std::sqrt(5.0)) / 2, 1e-15);  // 0.38197
  // Reciprocity of the closed forms themselves: A_1 F_12 = A_2 F_21 (000 eq. 6-5).
  EXPECT_NEAR(1 * perpendicular_rectangles(1, 2), 2 * perpendicular_rectangles(2, 1), 1e-14);
  EXPECT_NEAR(1 * 1 * coaxial_discs(1, 0.5, 0.7), 0.5 * 0.5 * coaxial_discs(0.5, 1, 0.7), 1e-14);
}

TEST(FormFactorAnalytic, PointToPolygonIsExactForRectangles) {
  const Vec3 up{0, 0, 1};
  // Normal through a corner: [0,a] × [0,b] at height c, any normal length. One-sided: wound
  // clockwise seen from above, the rectangle faces down to the point; the other winding faces
  // away and passes nothing.
  for (const auto& [a, b, c] :
       {std::array{1.0, 1.0, 1.0}, std::array{0.3, 2.0, 0.7}, std::array{5.0, 0.1, 2.0}}) {
    const std::vector<Vec3> facing_down{{0, 0, c}, {0, b, c}, {a, b, c}, {a, 0, c}};
    const std::vector<Vec3> facing_up(facing_down.rbegin(), facing_down.rend());
    const double expected = point_to_parallel_rectangle_corner(a, b, c);
    EXPECT_NEAR(point_to_polygon_form_factor({0, 0, 0}, up, facing_down), expected, 1e-12);
    EXPECT_NEAR(point_to_polygon_form_factor({0, 0, 0}, up * 3, facing_down), expected, 1e-12);
    EXPECT_EQ(point_to_polygon_form_factor({0, 0, 0}, up, facing_up), 0.0);
  }
  // The centre of a unit square facing a parallel unit square at distance 1: 0.2395.
  const std::vector<Vec3> square{{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}};
  EXPECT_NEAR(point_to_polygon_form_factor({0.5, 0.5, 0}, up, square), kPointToSquare, 1e-12);
  // An off-centre point: four corner rectangles of different sizes.
  const Vec3 x{0.2, 0.65, 0};
  const double four_corners =
      point_to_parallel_rectangle_corner(0.2, 0.65, 1) + point_to_parallel_rectangle_corner(0.8, 0.65, 1) +
      point_to_parallel_rectangle_corner(0.2, 0.35, 1) + point_to_parallel_rectangle_corner(0.8, 0.35, 1);
  EXPECT_NEAR(point_to_polygon_form_factor(x, up, square), four_corners, 1e-12);
  // Perpendicular rectangle: the wall y = c, x ∈ [0, w], z ∈ [0, h], seen from the origin.
  for (const auto& [w, h, c] :
       {std::array{1.0, 1.0, 1.0}, std::array{2.0, 0.5, 0.3}, std::array{0.4, 3.0, 1.5}}) {
    const std::vector<Vec3> wall{{0, c, 0}, {w, c, 0}, {w, c, h}, {0, c, h}};
    EXPECT_NEAR(point_to_polygon_form_factor({0, 0, 0}, up, wall), point_to_perpendicular_rectangle(w, h, c),
                1e-12);
  }
}

TEST(FormFactorAnalytic, PointToPolygonClipsAtTheHorizon) {
  const Vec3 up{0, 0, 1};
  // A wall reaching below the plane counts only its upper part.
  const std::vector<Vec3> wall{{0, 0.5, -2}, {1.5, 0.5, -2}, {1.5, 0.5, 0.8}, {0, 0.5, 0.8}};
  EXPECT_NEAR(point_to_polygon_form_factor({0, 0, 0}, up, wall),
              point_to_perpendicular_rectangle(1.5, 0.8, 0.5), 1e-12);
  // On or below the plane: nothing.
  const std::vector<Vec3> floor{{1, 1, 0}, {2, 1, 0}, {2, 2, 0}, {1, 2, 0}};
  EXPECT_EQ(point_to_polygon_form_factor({0, 0, 0}, up, floor), 0.0);
  EXPECT_EQ(point_to_polygon_form_factor({1.5, 1.5, 0}, up, floor), 0.0);  // a point on the polygon
  const std::vector<Vec3> below{{0, 0, -1}, {1, 0, -1}, {1, 1, -1}};
  EXPECT_EQ(point_to_polygon_form_factor({0, 0, 0}, up, below), 0.0);
  // A fine regular polygon tends to the coaxial disc's r²/(h² + r²) (inscribed: slightly below).
  const std::vector<Vec3> ring = disc_polygon({0, 0, 0.8}, 1.3, 4096);
  const double disc =
      point_to_polygon_form_factor({0, 0, 0}, up, std::vector<Vec3>(ring.rbegin(), ring.rend()));
  EXPECT_NEAR(disc, point_to_coaxial_disc(1.3, 0.8), 1e-6);
  EXPECT_LT(disc, point_to_coaxial_disc(1.3, 0.8));
  EXPECT_THROW(point_to_polygon_form_factor({0, 0, 0}, Vec3{}, floor), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// The hemicube (000 §6.4)

TEST(HemicubeFormFactors, PointFacingAParallelSquare) {
  const FormFactorGeometry geometry = parallel_squares();
  geometry.validate();
  // The hemicube turned by 0.3 rad around the normal, so that the square's edges cross the cells.
  const Vec3 tangent{std::cos(0.3), std::sin(0.3), 0};
  HemicubeFormFactors hemicube(100);
  const std::vector<double> row = hemicube.row(geometry, {0.5, 0.5, 0}, {0, 0, 1}, tangent, 0);
  ASSERT_EQ(row.size(), 2u);
  EXPECT_EQ(row[0], 0.0);  // the source itself
  const double error = relative_error(row[1], kPointToSquare);
  EXPECT_LT(error, 0.01);
  record_measurement("relative_error_R100", error);
  // The error (the aliasing of the edges, which depends on how they cross the cells) falls with
  // the resolution: its mean over eight turns of the hemicube, measured 4.9e-2, 8.1e-3, 8.9e-4
  // and 7.6e-5 at R = 10, 30, 100, 400.
  std::vector<double> mean_errors;
  for (const int resolution : {10, 30, 100, 400}) {
    HemicubeFormFactors turned(resolution);
    double mean = 0;
    for (int k = 0; k < 8; ++k) {
      const double turn = 0.1 + 0.7 * k;
      const Vec3 turned_tangent{std::cos(turn), std::sin(turn), 0};
      mean += relative_error(turned.row(geometry, {0.5, 0.5, 0}, {0, 0, 1}, turned_tangent, 0)[1],
                             kPointToSquare) /
              8;
    }
    mean_errors.push_back(mean);
  }
  for (std::size_t k = 1; k < mean_errors.size(); ++k)
    EXPECT_LT(mean_errors[k], mean_errors[k - 1]) << "step " << k;
  EXPECT_LT(mean_errors[2], 0.01);  // R = 100
}

TEST(HemicubeFormFactors, ClosedBoxRowSumsToOne) {
  // The box [0,2] × [0,1] × [0,1.5], one element per face.
  FormFactorGeometry box;
  const double X = 2, Y = 1, Z = 1.5;
  add_quad(box, {0, 0, 0}, {X, 0, 0}, {X, Y, 0}, {0, Y, 0}, 0);  // floor
  add_quad(box, {0, 0, Z}, {0, Y, Z}, {X, Y, Z}, {X, 0, Z}, 1);  // ceiling
  add_quad(box, {0, 0, 0}, {0, 0, Z}, {X, 0, Z}, {X, 0, 0}, 2);  // y = 0
  add_quad(box, {0, Y, 0}, {X, Y, 0}, {X, Y, Z}, {0, Y, Z}, 3);  // y = Y
  add_quad(box, {0, 0, 0}, {0, Y, 0}, {0, Y, Z}, {0, 0, Z}, 4);  // x = 0
  add_quad(box, {X, 0, 0}, {X, 0, Z}, {X, Y, Z}, {X, Y, 0}, 5);  // x = X
  box.validate();
  HemicubeFormFactors hemicube(100);
  Pcg32 random(7, 1);
  double largest_error = 0;
  for (int trial = 0; trial < 4; ++trial) {
    // A point inside the floor, a random turn of the hemicube.
    const Vec3 point{0.1 + 1.8 * random.next_double(), 0.1 + 0.8 * random.next_double(), 0};
    const double turn = 2 * kPi * random.next_double();
    const std::vector<double> row =
        hemicube.row(box, point, {0, 0, 1}, {std::cos(turn), std::sin(turn), 0}, 0);
    // 000 eq. 6-6: every cell sees a face, so Σ − 1 is the delta form factors' own deficit.
    EXPECT_NEAR(row_sum(row), 1, 0.01);
    EXPECT_NEAR(row_sum(row), hemicube.delta_form_factors().total(), 1e-12);
    EXPECT_EQ(row[0], 0.0);
    // Every face against the exact polygon formula (nothing occludes inside a convex box): the
    // hemicube's aliasing at R = 100 stays within 3% of a face (measured at most 2.2%).
    for (uint32_t face = 1; face < 6; ++face) {
      const auto first = box.mesh.triangles[2 * face][0];
      const std::vector<Vec3> quad{box.mesh.positions[first], box.mesh.positions[first + 1],
                                   box.mesh.positions[first + 2], box.mesh.positions[first + 3]};
      const double exact = point_to_polygon_form_factor(point, {0, 0, 1}, quad);
      EXPECT_LT(relative_error(row[face], exact), 0.03) << "face " << face << " from " << point;
      largest_error = std::max(largest_error, relative_error(row[face], exact));
    }
  }
  record_measurement("largest_face_error", largest_error);
}

TEST(HemicubeFormFactors, SubstructuredParallelSquares) {
  // 000 eq. 6-19 with 8 × 8 elements on the source, R = 100: 0.19982 (Howell C-11).
  HemicubeFormFactors hemicube(100);
  const double f =
      substructured_from_unit_square(hemicube, parallel_squares(), 8, 1, {std::cos(0.3), std::sin(0.3), 0});
  EXPECT_LT(relative_error(f, kParallelSquares), 0.01);
  record_measurement("relative_error", relative_error(f, kParallelSquares));
}

TEST(HemicubeFormFactors, SubstructuredPerpendicularSquares) {
  // Edge-sharing squares, 16 × 16 elements on the source, R = 100: 0.20004 (Howell C-14).
  HemicubeFormFactors hemicube(100);
  const double f = substructured_from_unit_square(hemicube, perpendicular_rectangles_geometry(1, 1), 16, 1);
  EXPECT_LT(relative_error(f, kPerpendicularSquares), 0.01);
  record_measurement("relative_error", relative_error(f, kPerpendicularSquares));
}

TEST(HemicubeFormFactors, SubstructuredCoaxialDiscs) {
  // Discs of radii 1 (source, z = 0) and 0.6 (z = 0.8) as 256-gons; points on the source at the
  // centres of 8 equal-area rings × 32 sectors (000 eq. 6-19 with equal A_k).
  const double r1 = 1, r2 = 0.6, h = 0.8;
  FormFactorGeometry geometry;
  add_fan(geometry, {0, 0, 0}, disc_polygon({0, 0, 0}, r1, 256), 0);
  const std::vector<Vec3> upper = disc_polygon({0, 0, h}, r2, 256);
  add_fan(geometry, {0, 0, h}, std::vector<Vec3>(upper.rbegin(), upper.rend()), 1);  // facing down
  HemicubeFormFactors hemicube(100);
  std::vector<double> row;
  const int rings = 8, sectors = 32;
  double sum = 0;
  for (int ring = 0; ring < rings; ++ring)
    for (int sector = 0; sector < sectors; ++sector) {
      const double radius = r1 * std::sqrt((ring + 0.5) / rings), phi = 2 * kPi * (sector + 0.5) / sectors;
      hemicube.compute_row(geometry, {radius * std::cos(phi), radius * std::sin(phi), 0}, {0, 0, 1},
                           {1, 0, 0}, 0, row);
      sum += row[1];
    }
  EXPECT_LT(relative_error(sum / (rings * sectors), coaxial_discs(r1, r2, h)), 0.01);
  record_measurement("area_to_area_error", relative_error(sum / (rings * sectors), coaxial_discs(r1, r2, h)));
  // From the centre: the point-to-disc closed form.
  hemicube.compute_row(geometry, {0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 0, row);
  EXPECT_LT(relative_error(row[1], point_to_coaxial_disc(r2, h)), 0.01);
  record_measurement("point_to_disc_error", relative_error(row[1], point_to_coaxial_disc(r2, h)));
}

TEST(HemicubeFormFactors, BackFacesHideButPassNothing) {
  // Surfaces are one-sided: a square above the point facing away from it (its back toward the
  // point, like a lamp's back toward the ceiling) receives nothing and hides the target above.
  FormFactorGeometry geometry = parallel_squares();  // element 1 at z = 1, facing down
  add_quad(geometry, {-1, -1, 0.5}, {2, -1, 0.5}, {2, 2, 0.5}, {-1, 2, 0.5}, 2);  // faces up
  geometry.validate();
  HemicubeFormFactors hemicube(50);
  const std::vector<double> row = hemicube.row(geometry, {0.5, 0.5, 0}, {0, 0, 1}, {1, 0, 0}, 0);
  EXPECT_EQ(row[2], 0.0);
  EXPECT_EQ(row[1], 0.0);
  EXPECT_LT(row_sum(row), 1e-12);
  // Turned around, the same square faces the point and takes its full share.
  FormFactorGeometry facing = parallel_squares();
  add_quad(facing, {-1, -1, 0.5}, {-1, 2, 0.5}, {2, 2, 0.5}, {2, -1, 0.5}, 2);
  const std::vector<double> seen = hemicube.row(facing, {0.5, 0.5, 0}, {0, 0, 1}, {1, 0, 0}, 0);
  EXPECT_EQ(seen[1], 0.0);
  EXPECT_NEAR(
      seen[2],
      point_to_polygon_form_factor({0.5, 0.5, 0}, {0, 0, 1},
                                   std::vector<Vec3>{{-1, -1, 0.5}, {-1, 2, 0.5}, {2, 2, 0.5}, {2, -1, 0.5}}),
      0.01);
}

TEST(FormFactorRayCast, BackFacingSourcesSendNothing) {
  // The sampled integrand and the exact polygon formula agree that a source seen from behind
  // gives 0, and that the same source turned around gives the catalogue's 0.2395.
  const FormFactorElement facing = FormFactorElement::quad({0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1});
  const FormFactorElement away = FormFactorElement::quad({0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1});
  RayCastSettings settings;
  settings.source_samples_per_side = 16;
  for (const InnerIntegral inner : {InnerIntegral::sampled, InnerIntegral::analytic_visibility}) {
    settings.inner_integral = inner;
    Pcg32 random(3, 4);
    EXPECT_NEAR(point_to_element_form_factor({0.5, 0.5, 0}, {0, 0, 1}, facing, nullptr, settings, random),
                kPointToSquare, 0.003);
    EXPECT_EQ(point_to_element_form_factor({0.5, 0.5, 0}, {0, 0, 1}, away, nullptr, settings, random), 0.0);
  }
}

TEST(HemicubeFormFactors, SkipsTheSourceAndReusesItsBuffers) {
  // The source element also owns a triangle above the point, which would hide the target.
  FormFactorGeometry geometry = parallel_squares();
  const auto base = static_cast<uint32_t>(geometry.mesh.positions.size());
  for (const Vec3& p : {Vec3{-1, -1, 0.5}, Vec3{3, -1, 0.5}, Vec3{0.5, 3, 0.5}})
    geometry.mesh.positions.push_back(p);
  geometry.mesh.triangles.push_back({base, base + 2, base + 1});  // facing down, to the point
  geometry.element_of_triangle.push_back(0);
  geometry.validate();
  HemicubeFormFactors hemicube(50);
  const std::vector<double> first = hemicube.row(geometry, {0.5, 0.5, 0}, {0, 0, 1}, {1, 0, 0}, 0);
  EXPECT_EQ(first[0], 0.0);
  EXPECT_LT(relative_error(first[1], kPointToSquare), 0.01);
  // Without skipping, the triangle hides the target.
  const std::vector<double> unskipped =
      hemicube.row(geometry, {0.5, 0.5, 0}, {0, 0, 1}, {1, 0, 0}, kNoElement);
  EXPECT_GT(unskipped[0], 0.5);
  EXPECT_EQ(unskipped[1], 0.0);
  // The same row again, from reused buffers, bit for bit.
  std::vector<double> again{9, 9, 9, 9};
  hemicube.compute_row(geometry, {0.5, 0.5, 0}, {0, 0, 1}, {1, 0, 0}, 0, again);
  EXPECT_EQ(again, first);
  EXPECT_GT(hemicube.triangles_drawn(), 0u);
  // Bad input.
  FormFactorGeometry bad = geometry;
  bad.element_of_triangle.back() = 7;
  EXPECT_THROW(bad.validate(), std::invalid_argument);
  EXPECT_THROW(hemicube.row(bad, {0.5, 0.5, 0}, {0, 0, 1}, {1, 0, 0}, 0), std::invalid_argument);
  EXPECT_THROW(hemicube.row(geometry, {0.5, 0.5, 0}, Vec3{}, {1, 0, 0}, 0), std::invalid_argument);
  EXPECT_THROW(HemicubeFormFactors(9), std::invalid_argument);
  EXPECT_THROW(HemicubeFormFactors(10, 0.0), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Ray casting (SPEC §10)

FormFactorElement unit_square_at(double z, bool facing_up) {
  return facing_up ? FormFactorElement::quad({0, 0, z}, {1, 0, z}, {1, 1, z}, {0, 1, z})
                   : FormFactorElement::quad({0, 0, z}, {0, 1, z}, {1, 1, z}, {1, 0, z});
}

TEST(FormFactorRayCast, PointToSquare) {
  const FormFactorElement target = unit_square_at(1, false);
  RayCastSettings settings;
  settings.inner_integral = InnerIntegral::sampled;
  settings.source_samples_per_side = 16;  // N = 256
  Pcg32 random(1, 2);
  const double sampled =
      point_to_element_form_factor({0.5, 0.5, 0}, {0, 0, 1}, target, nullptr, settings, random);
  EXPECT_LT(relative_error(sampled, kPointToSquare), 0.01);
  record_measurement("sampled_error", relative_error(sampled, kPointToSquare));
  // The analytic inner integral without occluders is the polygon formula itself.
  settings.inner_integral = InnerIntegral::analytic_visibility;
  EXPECT_NEAR(point_to_element_form_factor({0.5, 0.5, 0}, {0, 0, 1}, target, nullptr, settings, random),
              kPointToSquare, 1e-12);
}

TEST(FormFactorRayCast, ParallelSquares) {
  // Plain sampling, M = N = 8 × 8: 0.19982 (Howell C-11).
  const FormFactorElement from = unit_square_at(0, true), to = unit_square_at(1, false);
  RayCastSettings settings;
  settings.inner_integral = InnerIntegral::sampled;
  settings.source_samples_per_side = 8;
  settings.receiver_samples_per_side = 8;
  Pcg32 random(3, 4);
  const double unoccluded = element_to_element_form_factor(from, to, nullptr, settings, random);
  EXPECT_LT(relative_error(unoccluded, kParallelSquares), 0.01);
  record_measurement("sampled_error", relative_error(unoccluded, kParallelSquares));
  // Through the BVH of the two squares themselves: nothing occludes (the offsets keep the
  // endpoints' own surfaces out), so the same seed gives the same value bit for bit.
  const Occluders occluders(parallel_squares().mesh);
  Pcg32 same(3, 4);
  EXPECT_EQ(element_to_element_form_factor(from, to, &occluders.bvh, settings, same), unoccluded);
  // The analytic inner integral: only the outer average is sampled.
  settings.inner_integral = InnerIntegral::analytic_visibility;
  const double analytic = element_to_element_form_factor(from, to, &occluders.bvh, settings, random);
  EXPECT_LT(relative_error(analytic, kParallelSquares), 0.01);
  record_measurement("analytic_error", relative_error(analytic, kParallelSquares));
}

TEST(FormFactorRayCast, PerpendicularRectanglesAreReciprocal) {
  // Unequal areas: i = [0,1] × [0,1] in z = 0 (A = 1), j = x = 0, z ∈ [0,2] (A = 2), common edge
  // along y. Howell C-14: F_ij with W = 1, H = 2; F_ji with W = 2, H = 1.
  const FormFactorElement i = FormFactorElement::quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
  const FormFactorElement j = FormFactorElement::quad({0, 0, 0}, {0, 1, 0}, {0, 1, 2}, {0, 0, 2});
  const Occluders occluders(perpendicular_rectangles_geometry(1, 2).mesh);
  // The analytic inner integral: M = 32² points, N = 4² visibility samples each; 1%.
  // Plain sampling: M = N = 32²; its error near the shared edge falls slowly (see the next
  // test), so 3%.
  for (const InnerIntegral inner : {InnerIntegral::analytic_visibility, InnerIntegral::sampled}) {
    SCOPED_TRACE(inner == InnerIntegral::sampled ? "sampled" : "analytic_visibility");
    RayCastSettings settings;
    settings.inner_integral = inner;
    settings.receiver_samples_per_side = 32;
    settings.source_samples_per_side = inner == InnerIntegral::sampled ? 32 : 4;
    const double tolerance = inner == InnerIntegral::sampled ? 0.03 : 0.01;
    Pcg32 random(5, 6);
    const double f_ij = element_to_element_form_factor(i, j, &occluders.bvh, settings, random);
    const double f_ji = element_to_element_form_factor(j, i, &occluders.bvh, settings, random);
    EXPECT_LT(relative_error(f_ij, perpendicular_rectangles(1, 2)), tolerance);
    EXPECT_LT(relative_error(f_ji, perpendicular_rectangles(2, 1)), tolerance);
    // 000 eq. 6-5: A_i F_ij = A_j F_ji.
    const double reciprocity_error = relative_error(i.area() * f_ij, j.area() * f_ji);
    EXPECT_LT(reciprocity_error, tolerance);
    record_measurement(
        inner == InnerIntegral::sampled ? "sampled_reciprocity_error" : "analytic_reciprocity_error",
        reciprocity_error);
  }
}

TEST(FormFactorRayCast, EdgeSharingErrorFallsLikeOneOverN) {
  // Perpendicular unit squares sharing an edge (Howell C-14, 0.20004): the mean error over 8
  // seeds for M = n² points on the receiving square, n = 2, 4, 8, 16, 32.
  // - Analytic inner integral (no occluders: exact per point): only the outer average over the
  //   receiving square is sampled; F(x) is bounded (→ ½ at the shared edge), and the stratified
  //   error falls as 1/M (measured slope −0.95; 9.5e-4 at M = 1024).
  // - Plain sampling with N = M source samples: the integrand's 1/r² singularity at the shared
  //   edge has unbounded variance, so the error falls more slowly (measured slope −0.6 in N;
  //   8e-3 at M = N = 1024) and the close-pair guard biases it slightly low.
  const FormFactorElement i = FormFactorElement::quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
  const FormFactorElement j = FormFactorElement::quad({0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1});
  for (const InnerIntegral inner : {InnerIntegral::analytic_visibility, InnerIntegral::sampled}) {
    std::vector<double> errors;
    const std::vector<int> sides{2, 4, 8, 16, 32};
    for (const int side : sides) {
      RayCastSettings settings;
      settings.inner_integral = inner;
      settings.receiver_samples_per_side = side;
      settings.source_samples_per_side = inner == InnerIntegral::sampled ? side : 1;
      double error = 0;
      for (uint64_t seed = 0; seed < 8; ++seed) {
        Pcg32 random(seed, 11);
        error += std::fabs(element_to_element_form_factor(i, j, nullptr, settings, random) -
                           kPerpendicularSquares);
      }
      errors.push_back(error / 8 / kPerpendicularSquares);
    }
    // A least-squares slope of log error against log N (N = side²): about −1.
    double mean_x = 0, mean_y = 0;
    for (std::size_t k = 0; k < sides.size(); ++k) {
      mean_x += std::log(double(sides[k]) * sides[k]) / sides.size();
      mean_y += std::log(errors[k]) / sides.size();
    }
    double sxy = 0, sxx = 0;
    for (std::size_t k = 0; k < sides.size(); ++k) {
      const double dx = std::log(double(sides[k]) * sides[k]) - mean_x;
      sxy += dx * (std::log(errors[k]) - mean_y);
      sxx += dx * dx;
    }
    const double slope = sxy / sxx;
    if (inner == InnerIntegral::analytic_visibility) {
      EXPECT_LT(slope, -0.75);
      EXPECT_GT(slope, -1.3);
      EXPECT_LT(errors.back(), 0.003);
      record_measurement("analytic_slope", slope);
    } else {
      EXPECT_LT(slope, -0.4);
      EXPECT_GT(slope, -1.3);
      EXPECT_LT(errors.back(), 0.02);
      record_measurement("sampled_slope", slope);
    }
  }
}

TEST(FormFactorRayCast, ElementsSampleTheirArea) {
  // A trapezoid (not a parallelogram: the bilinear map's density varies) and a triangle.
  const FormFactorElement trapezoid = FormFactorElement::quad({0, 0, 1}, {0, 2, 1}, {1, 1.5, 1}, {1, 0.5, 1});
  const FormFactorElement triangle =
      FormFactorElement::triangle({-1, 0, 2}, {0, 1, 2}, {0.5, -1, 2});  // faces down
  EXPECT_NEAR(trapezoid.area(), 1.5, 1e-15);
  EXPECT_NEAR(triangle.area(), 0.5 * length(cross(Vec3{1.5, -1, 0}, Vec3{1, 1, 0})), 1e-15);
  EXPECT_NEAR(trapezoid.normal().z, -1, 1e-15);  // clockwise seen from above: faces down
  Pcg32 random(8, 9);
  for (const FormFactorElement* element : {&trapezoid, &triangle}) {
    // The mean area density is the area.
    double density_sum = 0;
    for (int k = 0; k < 4096; ++k) {
      double density = 0;
      element->point_at(random.next_double(), random.next_double(), density);
      density_sum += density;
    }
    EXPECT_NEAR(density_sum / 4096, element->area(), 0.01 * element->area());
    // The sampled F against the exact polygon formula.
    RayCastSettings settings;
    settings.inner_integral = InnerIntegral::sampled;
    settings.source_samples_per_side = 32;
    const Vec3 x{0.3, 0.2, 0};
    EXPECT_LT(relative_error(point_to_element_form_factor(x, {0, 0, 1}, *element, nullptr, settings, random),
                             point_to_polygon_form_factor(x, {0, 0, 1}, element->corners())),
              0.01);
  }
  EXPECT_THROW(FormFactorElement::quad({0, 0, 0}, {1, 0, 0}, {0.2, 0.2, 0}, {0, 1, 0}),
               std::invalid_argument);
  EXPECT_THROW(FormFactorElement::quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0.1}, {0, 1, 0}), std::invalid_argument);
  EXPECT_THROW(FormFactorElement::triangle({0, 0, 0}, {1, 1, 1}, {2, 2, 2}), std::invalid_argument);
  RayCastSettings no_samples;
  no_samples.source_samples_per_side = 0;
  EXPECT_THROW(point_to_element_form_factor({0, 0, 0}, {0, 0, 1}, triangle, nullptr, no_samples, random),
               std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Cross-checks

TEST(FormFactorCrossCheck, BlockerBetweenParallelSquares) {
  // A 0.5 × 0.5 blocker halfway between the parallel unit squares (element 2).
  FormFactorGeometry geometry = parallel_squares();
  add_quad(geometry, {0.25, 0.25, 0.5}, {0.75, 0.25, 0.5}, {0.75, 0.75, 0.5}, {0.25, 0.75, 0.5}, 2);
  HemicubeFormFactors hemicube(100);
  const double by_hemicube =
      substructured_from_unit_square(hemicube, geometry, 8, 1, {std::cos(0.3), std::sin(0.3), 0});
  const Occluders occluders(geometry.mesh);
  RayCastSettings settings;  // analytic inner integral × visible fraction
  settings.source_samples_per_side = 16;
  settings.receiver_samples_per_side = 8;
  Pcg32 random(12, 13);
  const double by_rays = element_to_element_form_factor(unit_square_at(0, true), unit_square_at(1, false),
                                                        &occluders.bvh, settings, random);
  settings.inner_integral = InnerIntegral::sampled;
  const double by_sampled_rays = element_to_element_form_factor(
      unit_square_at(0, true), unit_square_at(1, false), &occluders.bvh, settings, random);
  EXPECT_LT(by_hemicube, 0.8 * kParallelSquares);
  EXPECT_LT(by_rays, 0.8 * kParallelSquares);
  EXPECT_LT(relative_error(by_rays, by_hemicube), 0.03);
  EXPECT_LT(relative_error(by_sampled_rays, by_hemicube), 0.03);
  record_measurement("hemicube", by_hemicube);
  record_measurement("rays_analytic", by_rays);
  record_measurement("rays_sampled", by_sampled_rays);
}

}  // namespace
}  // namespace candela
