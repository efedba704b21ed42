// A triangle mesh as occluders: a BVH over its triangles, what radiosity's visibility rays are
// traced against (the surfaces radiosity models, not the scene's analytic shapes, whose
// true surface a tessellated sphere's triangles lie inside).
#pragma once

#include <memory>
#include <vector>

#include "accel/accelerator.h"
#include "accel/accelerator_registry.h"
#include "geometry/triangle_mesh.h"

namespace candela {

class TriangleOccluders {
 public:
  explicit TriangleOccluders(const TriangleMesh& mesh)
      : mesh_(std::make_shared<const TriangleMesh>(mesh)),
        triangles_(make_triangles(mesh_)),
        accelerator_(create_default_accelerator(*find_accelerator("bvh"))) {
    primitives_.reserve(triangles_.size());
    for (const auto& triangle : triangles_) primitives_.push_back({triangle.get(), 0, 0});
    accelerator_->build(primitives_);
  }
  const Accelerator& accelerator() const { return *accelerator_; }

 private:
  std::shared_ptr<const TriangleMesh> mesh_;
  std::vector<std::unique_ptr<Shape>> triangles_;
  std::vector<Primitive> primitives_;
  std::unique_ptr<Accelerator> accelerator_;
};

}  // namespace candela
