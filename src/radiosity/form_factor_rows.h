// The form-factor rows a radiosity solve keeps (SPEC §10), every one taken from a surface's
// centroid (the seed's point approximation), by radiosity.form_factors:
//   hemicube  000 §6.4: the row of a hemicube at the centroid over the targets;
//   ray-cast  per target, Lambert's exact unoccluded point-to-polygon form factor times the
//             fraction of ray_cast_samples² rays that reach it (radiosity/ray_cast_form_factors.h).
// The rows are computed in parallel, each by one thread into its own place (ray casting with a
// random stream per row index), so the result does not depend on the thread count. With several
// ranks the rows go out in chunks (dynamic scheduling) and every rank ends with every
// row, converted to the matrix's scalar where it was computed: the same values as one process,
// so every rank's solve — and its solution — is that of one process. Ctrl-C leaves the rows not
// begun zero. Unless quiet, a progress bar counts the rows (rank 0's, for all ranks).
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "radiosity/radiosity_mesh.h"
#include "radiosity/radiosity_settings.h"
#include "radiosity/radiosity_system.h"

namespace candela {

class Cluster;

// The element rows a solve keeps (000 §6.7.1: elements receive from patches), with each row's
// sum (000 eq. 6-6: 1 in a closed scene; below kHiddenRowSum for a hidden element).
struct ElementRows {
  std::shared_ptr<ElementToPatch> form_factors;
  std::vector<double> sums;
};

// 0, 1, …, count − 1: every row.
std::vector<uint32_t> all_rows(std::size_t count);

// The patch rows F_ij of the direct solvers (i, j patches; F_ii not computed, 0) into rows
// (patches × patches), and their sums into sums (one per patch). seed: the ray-cast streams.
// Visibility is the patches' own: the hemicube draws them, ray casting tests them.
void fill_patch_form_factor_rows(const RadiositySettings& settings, uint64_t seed, const RadiosityMesh& mesh,
                                 Eigen::MatrixXd& rows, std::vector<double>& sums, Cluster* cluster,
                                 bool quiet = true);

// The element rows F_qj of the elements `elements` (a form factor to every patch; none to the
// element's own patch) into those rows of matrix (elements × patches) and of sums; the other rows
// are left as they are.
void fill_element_form_factor_rows(const RadiositySettings& settings, uint64_t seed,
                                   const RadiosityMesh& mesh, const std::vector<uint32_t>& elements,
                                   ElementToPatch& matrix, std::vector<double>& sums, Cluster* cluster,
                                   bool quiet = true);

}  // namespace candela
