// A radiosity solution's element mesh with vertex colors (SPEC §10) as PLY and glTF
// 2.0, so that a solution can be inspected in MeshLab or Blender: the vertices with their
// radiosity as color, one triangle per element. Plain data in, so that io/ needs nothing of
// radiosity/ (radiosity/solution_export.h computes the vertex radiosities and converts).
//
// PLY (binary little endian) carries both the display color (uchar red/green/blue: exposure,
// then the display's out-of-range rule and sRGB as the PNG output) and the linear radiosity
// (float b_r/b_g/b_b). glTF (.gltf, one JSON file with its buffer embedded as a base64 data URI):
// COLOR_0 is linear float RGB after exposure, clamped to [0, 1] as the glTF specification
// requires, and _RADIOSITY the linear radiosity.
#pragma once

#include <array>
#include <cstdint>
#include <iosfwd>
#include <vector>

#include "camera/tone_map.h"
#include "math/vector.h"

namespace candela {

struct SolutionMesh {
  std::vector<Vec3> positions;
  std::vector<Color> radiosity;                    // B at each vertex (one per position)
  std::vector<std::array<uint32_t, 3>> triangles;  // vertex indices, counter-clockwise
};

// Both throw std::invalid_argument when positions and radiosity differ in size, and
// std::length_error when there are too many vertices for the formats' 32-bit signed indices.
void write_solution_ply(const SolutionMesh& mesh, const DisplaySettings& display, std::ostream& out);
void write_solution_gltf(const SolutionMesh& mesh, const DisplaySettings& display, std::ostream& out);

}  // namespace candela
