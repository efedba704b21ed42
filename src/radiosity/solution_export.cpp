#include "radiosity/solution_export.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "radiosity/vertex_radiosity.h"
#include "util/atomic_file.h"
#include "util/file_extension.h"

namespace candela {

namespace {

// Every writer reads element i's patch and radiosity by index, so the arrays must line up.
void require_consistent(const RadiositySolveResult& solution) {
  const std::size_t elements = solution.mesh.elements.size();
  if (solution.element_radiosity.size() != elements || solution.mesh.patch_of_element.size() != elements)
    throw std::invalid_argument("radiosity solution export: " + std::to_string(elements) + " elements but " +
                                std::to_string(solution.element_radiosity.size()) + " radiosities and " +
                                std::to_string(solution.mesh.patch_of_element.size()) + " patch indices");
}

}  // namespace

bool solution_format_for_path(const std::string& path, SolutionFormat& format) {
  const std::string extension = lower_case_extension(path);
  if (extension == ".csv")
    format = SolutionFormat::csv;
  else if (extension == ".ply")
    format = SolutionFormat::ply;
  else if (extension == ".gltf")
    format = SolutionFormat::gltf;
  else
    return false;
  return true;
}

std::vector<SolutionElementRow> solution_element_rows(const RadiositySolveResult& solution) {
  require_consistent(solution);
  const auto& elements = solution.mesh.elements;
  std::vector<SolutionElementRow> rows(elements.size());
  for (std::size_t id = 0; id < elements.size(); ++id) {
    const RadiositySurface& element = elements[id];
    rows[id] = {solution.mesh.patch_of_element[id],
                element.area,
                element.centroid,
                element.normal,
                element.emission,
                element.reflectance,
                solution.element_radiosity[id]};
  }
  return rows;
}

SolutionMesh solution_mesh(const RadiositySolveResult& solution) {
  require_consistent(solution);
  VertexRadiosity vertices =
      compute_vertex_radiosity(solution.mesh.elements, solution.element_radiosity, solution.element_hidden);
  return {std::move(vertices.positions), std::move(vertices.radiosity), std::move(vertices.element_vertices)};
}

void write_solution_csv(const RadiositySolveResult& solution, std::ostream& out) {
  write_solution_csv(solution_element_rows(solution), out);
}

void write_solution_ply(const RadiositySolveResult& solution, const DisplaySettings& display,
                        std::ostream& out) {
  write_solution_ply(solution_mesh(solution), display, out);
}

void write_solution_gltf(const RadiositySolveResult& solution, const DisplaySettings& display,
                         std::ostream& out) {
  write_solution_gltf(solution_mesh(solution), display, out);
}

void export_solution(const RadiositySolveResult& solution, const std::string& path,
                     const DisplaySettings& display) {
  SolutionFormat format;
  if (!solution_format_for_path(path, format))
    throw std::runtime_error("unsupported solution export extension: " + path +
                             " (expected .csv, .ply or .gltf)");
  write_atomically(path, [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    if (!out) throw std::runtime_error("cannot write " + path + ": cannot create " + temporary);
    switch (format) {
      case SolutionFormat::csv:
        write_solution_csv(solution, out);
        break;
      case SolutionFormat::ply:
        write_solution_ply(solution, display, out);
        break;
      case SolutionFormat::gltf:
        write_solution_gltf(solution, display, out);
        break;
    }
    out.close();
    if (!out) throw std::runtime_error("cannot write " + path);
  });
}

}  // namespace candela
