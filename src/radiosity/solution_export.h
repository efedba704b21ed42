// Exports of a radiosity solution (issue 7, SPEC §10): one row per element to CSV, and the
// element mesh with vertex colours (the vertex radiosities of radiosity/vertex_radiosity.h) to
// PLY and glTF 2.0, so that a solution can be inspected in a spreadsheet, MeshLab or Blender.
//
// CSV columns, in this order, one header line then one line per element (id = element index):
//   id,patch,area,cx,cy,cz,nx,ny,nz,e_r,e_g,e_b,rho_r,rho_g,rho_b,b_r,b_g,b_b
// (c = centroid, n = unit normal, e = emitted exitance E, rho = reflectance ρ, b = displayed
// radiosity B), numbers written so that they read back to the same double (shortest round trip).
//
// PLY (binary little endian) and glTF (.gltf, one JSON file with its buffer embedded as a base64
// data URI): the vertices of compute_vertex_radiosity with their radiosity as colour, one triangle
// per element. Colours: PLY carries both the display colour (uchar red/green/blue: exposure, then
// the display's out-of-range rule and sRGB as the PNG output) and the linear radiosity (float
// b_r/b_g/b_b); glTF's COLOR_0 is linear float RGB after exposure, clamped to [0, 1] as the glTF
// specification requires.
#pragma once

#include <iosfwd>
#include <string>

#include "camera/tone_map.h"
#include "radiosity/radiosity_solve_result.h"

namespace candela {

enum class SolutionFormat { csv, ply, gltf };

// The format for a path's extension (.csv, .ply, .gltf; case-insensitive); false for any other.
bool solution_format_for_path(const std::string& path, SolutionFormat& format);

void write_solution_csv(const RadiositySolveResult& solution, std::ostream& out);
void write_solution_ply(const RadiositySolveResult& solution, const DisplaySettings& display, std::ostream& out);
void write_solution_gltf(const RadiositySolveResult& solution, const DisplaySettings& display, std::ostream& out);

// Writes the solution to path in the format of its extension, through a temporary file renamed
// into place (no half-written file). Throws std::runtime_error naming the path when the
// extension is unknown or the file cannot be written.
void export_solution(const RadiositySolveResult& solution, const std::string& path, const DisplaySettings& display);

}  // namespace candela
