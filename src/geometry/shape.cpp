#include "geometry/shape.h"

#include <stdexcept>
#include <string>

namespace candela {

void Shape::tessellate(const TessellationSettings&, TriangleMesh&) const {
  throw std::logic_error("shape \"" + std::string(type_name()) + "\" cannot be tessellated");
}

}  // namespace candela
