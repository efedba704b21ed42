// A "transform" value of the scene format: one operation or a list applied in the order
// listed — {"translate": [x,y,z]}, {"scale": s or [sx,sy,sz]},
// {"rotate": {"angle": degrees, "axis": [x,y,z]}}, {"matrix": [16 numbers, row-major]}.
// Used by shapes (object to world) and solid textures (texture placement in object space).
#pragma once

#include "io/json_node.h"
#include "math/transform.h"

namespace candela {

Transform read_transform(const JsonNode& node);

}  // namespace candela
