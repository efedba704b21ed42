#include "scene/json_transform.h"

#include <stdexcept>

#include "math/direction.h"

namespace candela {

namespace {

// One operation: {"translate": [x,y,z]}, {"scale": s or [sx,sy,sz]},
// {"rotate": {"angle": degrees, "axis": [x,y,z]}}, {"matrix": [16 numbers, row-major]}.
Transform read_transform_step(const JsonNode& step) {
  step.expect_object();
  if (step.json().size() != 1) step.fail("expected exactly one of translate, rotate, scale, matrix");
  Transform result;
  if (const auto translate = step.get("translate")) {
    result = Transform::translate(translate->as_vec3());
  } else if (const auto scale = step.get("scale")) {
    const Vec3 factors = scale->json().is_number() ? Vec3{1, 1, 1} * scale->as_number() : scale->as_vec3();
    if (factors.x == 0 || factors.y == 0 || factors.z == 0) scale->fail("scale factors must be non-zero");
    try {
      result = Transform::scale(factors);
    } catch (const std::invalid_argument& e) {
      scale->fail(e.what());
    }
  } else if (const auto rotate = step.get("rotate")) {
    const double angle = rotate->number("angle");
    const JsonNode axis = rotate->at("axis");
    const Vec3 a = axis.as_vec3();
    if (!direction_of(a)) axis.fail("must be non-zero");
    rotate->finish();
    result = Transform::rotate(angle, a);
  } else if (const auto matrix = step.get("matrix")) {
    if (matrix->size() != 16) matrix->fail("expected 16 numbers (a 4x4 matrix, row by row)");
    Eigen::Matrix4d m;
    for (int i = 0; i < 16; ++i) m(i / 4, i % 4) = matrix->element(i).as_number();
    try {
      result = Transform::from_matrix(m);
    } catch (const std::invalid_argument& e) {
      matrix->fail(e.what());
    }
  }
  step.finish();
  return result;
}

}  // namespace

Transform read_transform(const JsonNode& node) {
  Transform transform;
  if (node.json().is_object()) {
    transform = read_transform_step(node);
  } else {
    for (std::size_t i = 0; i < node.size(); ++i)
      transform = read_transform_step(node.element(i)) * transform;  // listed order
  }
  // Each step is legal, but their product may not be (25 x "scale 1e16" overflows).
  if (const std::string problem = transform_problem(transform); !problem.empty()) node.fail(problem);
  return transform;
}

}  // namespace candela
