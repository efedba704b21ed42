// Adaptive subdivision (000 §6.7.2, setting radiosity.subdivision_threshold): after a solution,
// the elements whose radiosity differs too much from a neighbour's are split and the scene solved
// again, until no neighbours differ by more or the elements reach radiosity.min_element_size.
#pragma once

#include <cstdint>
#include <vector>

#include "math/vector.h"
#include "radiosity/form_factor_rows.h"
#include "radiosity/radiosity_mesh.h"
#include "radiosity/radiosity_settings.h"

namespace candela {

class Scene;

// The elements to split — both of every pair of neighbours whose radiosities differ in some
// channel by more than threshold × the largest radiosity a reflecting element shows, as long as
// the element's longest edge exceeds min_size. Emitters and hidden elements (row sum below
// kHiddenRowSum: lying against another surface, their darkness is no gradient) are not compared.
std::vector<bool> elements_to_split(const RadiosityMesh& mesh, const std::vector<Color>& radiosity,
                                    const std::vector<double>& row_sums, double threshold, double min_size);

// Splits the elements `split` marks (RadiosityMesh::split_elements) and carries the rows and row
// sums of the others over; returns the new elements, whose rows are left to compute
// (fill_element_form_factor_rows). The old rows are freed before it returns. Refuses
// (SolverMemoryError) before splitting when the old and the new rows, held together while
// copying, would exceed radiosity.memory_limit_mib.
std::vector<uint32_t> split_elements_keeping_rows(const Scene& scene, const RadiositySettings& settings,
                                                  const std::vector<bool>& split, RadiosityMesh& mesh,
                                                  ElementRows& rows);

}  // namespace candela
