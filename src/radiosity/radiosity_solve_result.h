// A scene's radiosity solution as the `radiosity` method computes it (SPEC §10): the mesh of
// patches and elements and one displayed radiosity per element, with what the solve measured.
// It does not depend on a camera, so one solution serves every view (and the exports of
// radiosity/solution_export.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "radiosity/radiosity_mesh.h"

namespace candela {

struct RadiositySolveResult {
  RadiosityMesh mesh;
  std::vector<Color> element_radiosity;  // B_q (+ ρ_q B_amb with the ambient term)
  // 1 for an element whose form factors sum to ≈ 0: it sees nothing (it lies against another
  // surface, like the floor under a box) and receives nothing; its radiosity says nothing about
  // its visible neighbours', so the display leaves it out of their vertex radiosities.
  std::vector<uint8_t> element_hidden;
  std::size_t steps = 0;       // shots or sweeps (1 for gaussian)
  double unshot_fraction = 0;  // progressive: on return; 0 for the direct solvers
  bool converged = true;
  std::size_t form_factor_rows = 0;    // form-factor rows computed
  std::size_t form_factors = 0;        // form factors computed (rows × their length)
  std::size_t subdivision_passes = 0;  // adaptive subdivision passes that split elements
  double solve_seconds = 0, mesh_seconds = 0;
  std::size_t form_factor_bytes = 0;  // memory held by the stored form factors
};

}  // namespace candela
