// A radiosity solution's elements as CSV (SPEC §10), for a spreadsheet: one header line
// then one line per element (id = element index), the columns in this order:
//   id,patch,area,cx,cy,cz,nx,ny,nz,e_r,e_g,e_b,rho_r,rho_g,rho_b,b_r,b_g,b_b
// (c = centroid, n = unit normal, e = emitted exitance E, rho = reflectance ρ, b = displayed
// radiosity B), numbers written so that they read back to the same double (shortest round trip).
// Plain data in, so that io/ needs nothing of radiosity/ (radiosity/solution_export.h converts).
#pragma once

#include <cstdint>
#include <iosfwd>
#include <span>

#include "math/vector.h"

namespace candela {

struct SolutionElementRow {
  uint32_t patch = 0;
  double area = 0;
  Vec3 centroid, normal;
  Color emission, reflectance, radiosity;
};

void write_solution_csv(std::span<const SolutionElementRow> elements, std::ostream& out);

}  // namespace candela
