// Exports of a radiosity solution (SPEC §10): one row per element to CSV, and the
// element mesh with vertex colors (the vertex radiosities of radiosity/vertex_radiosity.h) to
// PLY and glTF 2.0, so that a solution can be inspected in a spreadsheet, MeshLab or Blender.
// The formats are io/'s (io/solution_csv.h: the columns; io/solution_mesh_formats.h: the
// vertices, colors and indices); this is the conversion of a RadiositySolveResult to their plain
// data, and the choice of format by extension.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "camera/tone_map.h"
#include "io/solution_csv.h"
#include "io/solution_mesh_formats.h"
#include "radiosity/radiosity_solve_result.h"

namespace candela {

enum class SolutionFormat { csv, ply, gltf };

// The format for a path's extension (.csv, .ply, .gltf; case-insensitive); false for any other.
bool solution_format_for_path(const std::string& path, SolutionFormat& format);

// What the formats write. Both throw std::invalid_argument when the solution's element arrays
// (elements, radiosities, patch indices) differ in length.
std::vector<SolutionElementRow> solution_element_rows(const RadiositySolveResult& solution);
// The display's vertex radiosities (hidden elements kept apart), one triangle per element.
SolutionMesh solution_mesh(const RadiositySolveResult& solution);

void write_solution_csv(const RadiositySolveResult& solution, std::ostream& out);
void write_solution_ply(const RadiositySolveResult& solution, const DisplaySettings& display,
                        std::ostream& out);
void write_solution_gltf(const RadiositySolveResult& solution, const DisplaySettings& display,
                         std::ostream& out);

// Writes the solution to path in the format of its extension, through a temporary file renamed
// into place (no half-written file). Throws std::runtime_error naming the path when the
// extension is unknown or the file cannot be written.
void export_solution(const RadiositySolveResult& solution, const std::string& path,
                     const DisplaySettings& display);

}  // namespace candela
