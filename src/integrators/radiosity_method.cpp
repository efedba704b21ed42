#include "integrators/radiosity_method.h"
#include "integrators/solution_field.h"
#include "radiosity/radiosity_checkpoint.h"
#include "util/error.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "distributed/cluster.h"
#include "distributed/task_farm.h"
#include "integrators/distributed_tiles.h"
#include "radiosity/delta_form_factors.h"
#include "radiosity/hemicube_form_factors.h"
#include "radiosity/ray_cast_form_factors.h"
#include "radiosity/solvers.h"
#include "radiosity/vertex_radiosity.h"
#include "raster/rasterizer.h"
#include "util/cancellation.h"
#include "util/progress.h"

namespace candela {

namespace {

// (Until the solve takes the method's settings: the scene's "radiosity" object, read again.)
RadiositySettings radiosity_settings_of(const Scene& scene) {
  return read_radiosity_settings(scene.plugin_settings.node("radiosity"));
}


double channel_sum(const Color& c) { return c.r + c.g + c.b; }

// Orients the hemicube around a surface's normal: its first edge (never along the normal).
Vec3 tangent_of(const RadiositySurface& surface) { return normalize(surface.corners[1] - surface.corners[0]); }

// Row sums of the form-factor rows (000 eq. 6-6: 1 in a closed scene), summarised. A row that
// sees nothing at all (a face lying on another, like a box's bottom on the floor, whose hemicube
// sees only the floor's back) is counted apart: it is hidden, not open.
constexpr double kHiddenRowSum = 1e-6;

struct RowSumSummary {
  double min = std::numeric_limits<double>::infinity(), max = 0, total = 0;
  std::size_t rows = 0, hidden_rows = 0;
  void add(double sum) {
    if (sum < kHiddenRowSum) {
      ++hidden_rows;
      return;
    }
    min = std::min(min, sum);
    max = std::max(max, sum);
    total += sum;
    ++rows;
  }
};

// The memory the stored form factors may take: radiosity.memory_limit_mib, or half the machine's.
uint64_t form_factor_memory_limit(const RadiositySettings& settings) {
  if (!(settings.memory_limit_mib > 0)) return default_gaussian_elimination_memory_limit();
  const double bytes = settings.memory_limit_mib * 1048576.0;
  // Saturated: beyond 2⁶⁴ bytes the conversion would be undefined.
  return bytes >= 18446744073709549568.0 ? UINT64_MAX : static_cast<uint64_t>(bytes);
}

// Refuses, before anything is allocated, form factors that would not fit (issue 7: "refused with a
// message naming the setting to change").
void check_form_factor_memory(uint64_t required, const RadiositySettings& settings, const std::string& what,
                              const std::string& remedy) {
  const uint64_t limit = form_factor_memory_limit(settings);
  if (required <= limit) return;
  throw SolverMemoryError(fmt::format("radiosity: {} needs {:.1f} MiB, more than the {:.1f} MiB allowed; {} "
                                      "(or raise radiosity.memory_limit_mib)",
                                      what, required / 1048576.0, limit / 1048576.0, remedy),
                          required, limit);
}

// Form factors from the centroids of surfaces[rows[k]] to every target (F_i→j), into row rows[k]
// of matrix (float: the element rows are the largest thing the solver keeps), in parallel: each
// row by one thread into its own place (ray casting with a random stream per row index), so the
// result does not depend on the thread count. A surface's row skips the target `skipped(i)`.
//   hemicube  000 §6.4: the row of a hemicube at the centroid over the targets;
//   ray-cast  per target, Lambert's exact unoccluded point-to-polygon form factor times the
//             fraction of ray_cast_samples² rays that reach it (radiosity/ray_cast_form_factors.h).
template <typename Sink, typename Skipped>
void compute_form_factor_rows(const Scene& scene, const std::vector<RadiositySurface>& surfaces,
                              std::span<const uint32_t> rows, const std::vector<RadiositySurface>& targets,
                              const FormFactorGeometry& geometry, Skipped skipped, Sink write, std::span<double> sums) {
  const RadiositySettings settings = radiosity_settings_of(scene);
  if (settings.form_factors == RadiosityFormFactors::hemicube) {
    const auto table = std::make_shared<const DeltaFormFactors>(settings.hemicube_resolution);
    tbb::enumerable_thread_specific<std::unique_ptr<HemicubeFormFactors>> hemicubes;
    tbb::parallel_for(std::size_t(0), rows.size(), [&](std::size_t k) {
      if (cancel_requested()) return;  // Ctrl-C: the rows not begun stay zero
      auto& hemicube = hemicubes.local();
      if (!hemicube) hemicube = std::make_unique<HemicubeFormFactors>(table);
      thread_local std::vector<double> row;
      const std::size_t i = rows[k];
      const RadiositySurface& surface = surfaces[i];
      hemicube->compute_row(geometry, surface.centroid, surface.normal, tangent_of(surface), static_cast<uint32_t>(skipped(i)), row);
      for (std::size_t j = 0; j < row.size(); ++j) write(k, j, row[j]);
      sums[k] = row_sum(row);
    });
  } else {
    std::vector<FormFactorElement> sources;
    sources.reserve(targets.size());
    for (const RadiositySurface& target : targets)
      sources.push_back(FormFactorElement::triangle(target.corners[0], target.corners[1], target.corners[2]));
    RayCastSettings ray_cast;
    ray_cast.source_samples_per_side = settings.ray_cast_samples;
    tbb::parallel_for(std::size_t(0), rows.size(), [&](std::size_t k) {
      if (cancel_requested()) return;
      const std::size_t i = rows[k];
      Pcg32 random(scene.render.seed, i);  // one stream per row
      const RadiositySurface& surface = surfaces[i];
      double sum = 0;
      for (std::size_t j = 0; j < sources.size(); ++j) {
        double form_factor = 0;
        if (j != skipped(i))
          form_factor = point_to_element_form_factor(surface.centroid, surface.normal, sources[j], &scene.accelerator(), ray_cast, random);
        write(k, j, form_factor);
        sum += form_factor;
      }
      sums[k] = sum;
    });
  }
}

// Form factors from the centroids of surfaces[rows[k]] to every target (F_i→j), into row rows[k]
// of matrix (float: the element rows are the largest thing the solver keeps), in parallel: each
// row by one thread into its own place (ray casting with a random stream per row index), so the
// result does not depend on the thread count. A surface's row skips the target `skipped(i)`.
//   hemicube  000 §6.4: the row of a hemicube at the centroid over the targets;
//   ray-cast  per target, Lambert's exact unoccluded point-to-polygon form factor times the
//             fraction of ray_cast_samples² rays that reach it (radiosity/ray_cast_form_factors.h).
// With several ranks (issue 11) the rows go out in chunks (dynamic scheduling) and every rank
// ends with every row, converted to the matrix's scalar where it was computed: the same values as
// one process, so every rank's solve — and its solution — is that of one process.
template <typename Matrix, typename Skipped>
void fill_form_factor_rows(const Scene& scene, const std::vector<RadiositySurface>& surfaces,
                           const std::vector<uint32_t>& rows, const std::vector<RadiositySurface>& targets,
                           const FormFactorGeometry& geometry, Skipped skipped, Matrix& matrix,
                           std::vector<double>& sums_by_row, Cluster* cluster) {
  using Scalar = typename Matrix::Scalar;
  std::vector<double> sums(rows.size());
  if (!cluster || !cluster->distributed()) {
    compute_form_factor_rows(scene, surfaces, rows, targets, geometry, skipped, [&](std::size_t k, std::size_t j, double value) {
      matrix(static_cast<Eigen::Index>(rows[k]), static_cast<Eigen::Index>(j)) = static_cast<Scalar>(value);
    }, sums);
  } else {
    // Chunks of about 8 a rank's worth of threads, at most 64 rows: enough to balance, few messages.
    const std::size_t chunk = std::clamp<std::size_t>(rows.size() / (std::size_t(cluster->size()) * 8), 1, 64);
    const std::size_t tasks = (rows.size() + chunk - 1) / chunk;
    const std::size_t columns = targets.size();
    // A chunk's rows and sums as bytes: what a rank sends, and what rank 0 rebuilds from the
    // matrix to pass on (it keeps no second copy of the rows).
    const auto chunk_bytes = [&](std::span<const Scalar> values, std::span<const double> chunk_sums) {
      ByteWriter writer;
      writer.put_array(values);
      writer.put_array(chunk_sums);
      return writer.take();
    };
    run_task_farm_everywhere(*cluster, tasks, [&](std::size_t task) {
      const std::size_t first = task * chunk, count = std::min(chunk, rows.size() - first);
      std::vector<Scalar> values(count * columns, Scalar(0));
      std::vector<double> chunk_sums(count);
      compute_form_factor_rows(scene, surfaces, std::span<const uint32_t>(rows).subspan(first, count), targets, geometry,
                               skipped, [&](std::size_t k, std::size_t j, double value) {
        values[k * columns + j] = static_cast<Scalar>(value);
      }, chunk_sums);
      return chunk_bytes(values, chunk_sums);
    }, [&](std::size_t task, std::span<const std::byte> result) {
      const std::size_t first = task * chunk;
      ByteReader reader(result);
      const std::vector<Scalar> values = reader.get_array<Scalar>();
      const std::vector<double> chunk_sums = reader.get_array<double>();
      for (std::size_t k = 0; k < chunk_sums.size(); ++k) {
        for (std::size_t j = 0; j < columns; ++j)
          matrix(static_cast<Eigen::Index>(rows[first + k]), static_cast<Eigen::Index>(j)) = values[k * columns + j];
        sums[first + k] = chunk_sums[k];
      }
    }, [&](std::size_t task) {
      const std::size_t first = task * chunk, count = std::min(chunk, rows.size() - first);
      std::vector<Scalar> values(count * columns);
      for (std::size_t k = 0; k < count; ++k)
        for (std::size_t j = 0; j < columns; ++j)
          values[k * columns + j] = matrix(static_cast<Eigen::Index>(rows[first + k]), static_cast<Eigen::Index>(j));
      return chunk_bytes(values, std::span<const double>(sums).subspan(first, count));
    });
  }
  for (std::size_t k = 0; k < rows.size(); ++k) sums_by_row[rows[k]] = sums[k];
}

std::vector<uint32_t> all_rows(std::size_t count) {
  std::vector<uint32_t> rows(count);
  for (std::size_t i = 0; i < count; ++i) rows[i] = static_cast<uint32_t>(i);
  return rows;
}

// Reciprocity (000 eq. 6-5) of patch form factors F_ij, measured over every pair: the
// transfer-weighted mean Σ|A_i F_ij − A_j F_ji| / Σ(A_i F_ij + A_j F_ji) and the largest
// mismatch relative to the largest transfer.
struct Reciprocity {
  bool measured = false;
  double mean_error = 0, max_error = 0;
};

template <typename Matrix>
Reciprocity measure_reciprocity(const std::vector<RadiositySurface>& patches, const Matrix& patch_rows) {
  double largest_transfer = 0, largest_mismatch = 0, mismatch_sum = 0, transfer_sum = 0;
  for (Eigen::Index i = 0; i < patch_rows.rows(); ++i)
    for (Eigen::Index j = i + 1; j < patch_rows.cols(); ++j) {
      const double a = patches[static_cast<std::size_t>(i)].area * patch_rows(i, j);
      const double b = patches[static_cast<std::size_t>(j)].area * patch_rows(j, i);
      largest_transfer = std::max({largest_transfer, a, b});
      largest_mismatch = std::max(largest_mismatch, std::fabs(a - b));
      mismatch_sum += std::fabs(a - b);
      transfer_sum += a + b;
    }
  Reciprocity result;
  result.measured = true;
  if (transfer_sum > 0) result.mean_error = mismatch_sum / transfer_sum;
  if (largest_transfer > 0) result.max_error = largest_mismatch / largest_transfer;
  return result;
}

// The element rows F_qj, q an element, j a patch (000 §6.7.1: elements receive from patches),
// kept for the whole solve; float (4 bytes a form factor).
using ElementToPatch = Eigen::MatrixXf;

uint64_t element_rows_bytes(std::size_t elements, std::size_t patches) {
  return static_cast<uint64_t>(elements) * patches * sizeof(float);
}

// What the elements' radiosities came to, before the ambient term.
struct ElementSolution {
  std::vector<Color> radiosity;  // B_q
  std::vector<Color> unshot;     // per patch (progressive), ΔB_j
  std::size_t steps = 0;
  double unshot_fraction = 0;
  bool converged = true;
};

// 000 §6.6 with substructuring (000 §6.7.1): patches shoot, elements receive. The patch j with
// the largest unshot flux ΔB_j·A_j shoots; every element q receives ΔRad_q = ρ_q ΔB_j F_qj
// (000 eqs. 6-12, 6-13) with F_qj from a hemicube at q over the patches — each such row sums to 1
// in a closed scene, which a hemicube at the shooter with reciprocity (F_qj = F_jq A_j / A_q) does
// not give elements near the shooter (a furnace then shows ±17%); B_q += ΔRad_q, and the unshot
// radiosity of q's patch grows by the area-weighted mean of its elements' gains.
// Checkpointing a progressive solution (issue 10): where its state goes every `interval`
// seconds and when the shooting ends (converged, out of steps or interrupted), and the state it
// starts from instead of B = E, ΔB = E.
struct ProgressiveRun {
  std::string checkpoint;
  const RadiosityCheckpoint* resume = nullptr;
  std::string fingerprint;
  double interval = 60;
  int checkpoints_written = 0;
};

ElementSolution shoot_progressively(const RadiosityMesh& mesh, const ElementToPatch& element_to_patch,
                                    const RadiositySettings& settings, ProgressReporter& progress,
                                    uint64_t& progress_done, ProgressiveRun* run, Cluster* cluster) {
  const std::size_t patch_count = mesh.patches.size(), element_count = mesh.elements.size();
  ElementSolution result;
  std::vector<Color>& radiosity = result.radiosity;
  std::vector<Color>& unshot = result.unshot;
  radiosity.resize(element_count);
  unshot.resize(patch_count);
  for (std::size_t q = 0; q < element_count; ++q) radiosity[q] = mesh.elements[q].emission;  // B = E
  double emitted_flux = 0;
  for (std::size_t p = 0; p < patch_count; ++p) {
    unshot[p] = mesh.patches[p].emission;  // ΔB = E
    emitted_flux += channel_sum(unshot[p]) * mesh.patches[p].area;
  }
  const auto unshot_fraction = [&](std::size_t& shooter) {
    double flux = 0, largest = 0;
    shooter = patch_count;
    for (std::size_t p = 0; p < patch_count; ++p) {
      const double patch_flux = channel_sum(unshot[p]) * mesh.patches[p].area;
      flux += patch_flux;
      if (patch_flux > largest) largest = patch_flux, shooter = p;
    }
    return emitted_flux > 0 ? flux / emitted_flux : 0.0;
  };
  std::size_t steps = 0;
  if (run && run->resume) {
    const RadiosityCheckpoint& state = *run->resume;
    if (state.radiosity.size() != element_count || state.unshot.size() != patch_count)
      throw std::invalid_argument(fmt::format("the checkpoint holds {} elements and {} patches, this mesh {} and {}",
                                              state.radiosity.size(), state.unshot.size(), element_count, patch_count));
    radiosity = state.radiosity;
    unshot = state.unshot;
    steps = static_cast<std::size_t>(state.steps);
  }
  Stopwatch since_checkpoint;
  const auto save = [&] {
    if (!run || run->checkpoint.empty()) return;  // (rank 0 alone is given a checkpoint path)
    write_radiosity_checkpoint(run->checkpoint, {run->fingerprint, steps, radiosity, unshot});
    ++run->checkpoints_written;
    since_checkpoint = Stopwatch();
  };
  std::size_t shooter = patch_count;
  double fraction = unshot_fraction(shooter);
  while (fraction > settings.threshold && shooter < patch_count && steps < static_cast<std::size_t>(settings.max_steps) &&
         !(cluster ? steps % 256 == 0 && cancelled_anywhere(*cluster) : cancel_requested())) {
    // Ctrl-C: the solution so far (several ranks agree every 256 shots, so they shoot alike; a
    // shot takes microseconds, an agreement between nodes tens of them)
    const Color shot = unshot[shooter];
    unshot[shooter] = Color();
    const float* column = element_to_patch.col(static_cast<Eigen::Index>(shooter)).data();  // contiguous
    for (std::size_t q = 0; q < element_count; ++q) {
      const double form_factor = column[q];  // F_qj
      if (form_factor <= 0) continue;
      const RadiositySurface& element = mesh.elements[q];
      const Color gain = element.reflectance * shot * form_factor;  // 000 eqs. 6-12, 6-13
      radiosity[q] += gain;
      const uint32_t patch = mesh.patch_of_element[q];
      unshot[patch] += gain * (element.area / mesh.patches[patch].area);  // area-weighted mean
    }
    ++steps;
    fraction = unshot_fraction(shooter);
    const auto done = static_cast<uint64_t>(1000 * progressive_convergence_progress(fraction, settings.threshold));
    progress.set_detail(fmt::format("unshot {:.3g}% after {} steps", 100 * fraction, steps));
    if (done > progress_done) progress.advance(done - progress_done), progress_done = done;
    if (run && !run->checkpoint.empty() && since_checkpoint.seconds() >= run->interval) save();
  }
  save();  // the final state: a later run goes on from it (after Ctrl-C, or with a lower threshold)
  result.steps = steps;
  result.unshot_fraction = fraction;
  result.converged = fraction <= settings.threshold;
  return result;
}

// 000 eq. 6-16: every element gathers from the patch solution, B_q = E_q + ρ_q Σ_j F_qj B_j.
std::vector<Color> gather_from_patches(const RadiosityMesh& mesh, const ElementToPatch& element_to_patch,
                                       const std::vector<Color>& patch_radiosity) {
  std::vector<Color> radiosity(mesh.elements.size());
  tbb::parallel_for(std::size_t(0), mesh.elements.size(), [&](std::size_t q) {
    Color gathered;
    for (std::size_t j = 0; j < patch_radiosity.size(); ++j)
      gathered += patch_radiosity[j] * static_cast<double>(element_to_patch(static_cast<Eigen::Index>(q), static_cast<Eigen::Index>(j)));
    radiosity[q] = mesh.elements[q].emission + mesh.elements[q].reflectance * gathered;
  });
  return radiosity;
}

// 000 §6.7.2: the elements to split — both of every pair of neighbours whose radiosities differ
// in some channel by more than threshold × the largest radiosity a reflecting element shows, as
// long as the element's longest edge exceeds min_size.
std::vector<bool> elements_to_split(const RadiosityMesh& mesh, const std::vector<Color>& radiosity,
                                    const std::vector<double>& row_sums, double threshold, double min_size) {
  // Hidden elements (lying against another surface) see nothing: their darkness is no gradient.
  const auto counted = [&](std::size_t q) { return mesh.elements[q].emission.is_black() && row_sums[q] >= kHiddenRowSum; };
  const std::size_t count = mesh.elements.size();
  double largest = 0;
  for (std::size_t q = 0; q < count; ++q)
    if (counted(q)) largest = std::max({largest, radiosity[q].r, radiosity[q].g, radiosity[q].b});
  std::vector<bool> split(count, false);
  if (!(largest > 0)) return split;
  const double limit = threshold * largest;
  const auto splittable = [&](std::size_t q) {
    const auto& c = mesh.elements[q].corners;
    return std::max({length(c[1] - c[0]), length(c[2] - c[1]), length(c[0] - c[2])}) > min_size;
  };
  const std::vector<std::vector<uint32_t>> neighbours = mesh.element_neighbours();
  for (std::size_t q = 0; q < count; ++q) {
    if (!counted(q)) continue;
    for (const uint32_t other : neighbours[q]) {
      if (!counted(other)) continue;
      const Color d = radiosity[q] - radiosity[other];
      if (std::max({std::fabs(d.r), std::fabs(d.g), std::fabs(d.b)}) > limit) {
        if (splittable(q)) split[q] = true;
        if (splittable(other)) split[other] = true;
      }
    }
  }
  return split;
}

RadiositySolveResult solve_with_statistics(const Scene& scene, bool quiet, nlohmann::json* statistics,
                                           ProgressiveRun* run = nullptr, Cluster* cluster = nullptr) {
  RadiositySolveResult result;
  const RadiositySettings settings = radiosity_settings_of(scene);
  Stopwatch mesh_time;
  RadiosityMeshSettings mesh_settings;
  mesh_settings.segments = settings.segments;
  mesh_settings.patch_size = settings.patch_size;
  mesh_settings.element_size = settings.element_size;
  mesh_settings.split_at_contacts = settings.split_at_contacts;
  const bool progressive = settings.solver == RadiositySolver::progressive;
  // Whether Ctrl-C arrived; with several ranks, whether it reached any (a collective), so that all
  // of them take the same branch.
  const auto stopped = [&] { return cancelled_anywhere(cluster); };
  const std::string fewer = "raise radiosity.patch_size or radiosity.element_size (fewer patches and elements)";
  {
    // Refused before the mesh is built (it can take gigabytes itself): the fewest patches and
    // elements these sizes can give, and what their form factors would take.
    const RadiosityMeshEstimate least = estimate_radiosity_mesh(scene, mesh_settings);
    const double element_bytes = least.elements * least.patches * sizeof(float);
    const double patch_bytes = progressive ? 0.0 : least.patches * least.patches * sizeof(double) * (settings.solver == RadiositySolver::gaussian ? 3 : 1);
    const double bytes = std::min(element_bytes + patch_bytes, 1.8e19);
    check_form_factor_memory(static_cast<uint64_t>(bytes), settings,
                             fmt::format("a mesh of at least {:.0f} patches and {:.0f} elements", least.patches, least.elements),
                             progressive ? fewer : "use radiosity.solver \"progressive\", or " + fewer);
  }
  result.mesh = build_radiosity_mesh(scene, mesh_settings);
  result.mesh_seconds = mesh_time.seconds();
  Stopwatch solve_time;
  double form_factor_seconds = 0;  // of solve_seconds, the time spent computing form factors
  RadiosityMesh& mesh = result.mesh;
  const std::size_t patch_count = mesh.patches.size();

  // The patch system first (direct solvers), its memory checked before anything is computed.
  std::vector<double> patch_sums;
  Reciprocity reciprocity;
  std::vector<Color> patch_radiosity;
  std::size_t patch_steps = 0;
  bool patch_converged = true;
  if (!progressive) {
    const uint64_t solver_bytes = settings.solver == RadiositySolver::gaussian ? gaussian_elimination_memory_bytes(patch_count) : 0;
    check_form_factor_memory(static_cast<uint64_t>(patch_count) * patch_count * sizeof(double) + solver_bytes +
                                 element_rows_bytes(mesh.elements.size(), patch_count),
                             settings, fmt::format("the full matrix of {} patches ({} elements)", patch_count, mesh.elements.size()),
                             "use radiosity.solver \"progressive\", or " + fewer);
    patch_sums.resize(patch_count);
    Eigen::MatrixXd patch_rows(static_cast<Eigen::Index>(patch_count), static_cast<Eigen::Index>(patch_count));
    {
      Stopwatch form_factor_time;
      fill_form_factor_rows(scene, mesh.patches, all_rows(patch_count), mesh.patches, mesh.patch_geometry,
                            [](std::size_t i) { return i; }, patch_rows, patch_sums, cluster);
      form_factor_seconds += form_factor_time.seconds();
    }
    reciprocity = measure_reciprocity(mesh.patches, patch_rows);
    if (stopped()) {  // Ctrl-C: not solved, B = E
      for (const RadiositySurface& patch : mesh.patches) patch_radiosity.push_back(patch.emission);
      patch_converged = false;
    } else {
      const RadiositySystem patches = mesh.patch_system();
      const FormFactorSource patch_source(std::move(patch_rows));
      const RadiositySolution solution =
          settings.solver == RadiositySolver::gaussian
              ? solve_gaussian_elimination(patches, patch_source, form_factor_memory_limit(settings))
              : solve_gauss_seidel(patches, patch_source, settings.threshold, static_cast<std::size_t>(settings.max_steps));
      patch_radiosity = solution.radiosity;
      patch_steps = solution.iterations;
      patch_converged = solution.converged;
    }
  }

  // The element rows, then solutions and adaptive subdivision (000 §6.7.2) until no neighbours
  // differ by more than the threshold.
  check_form_factor_memory(element_rows_bytes(mesh.elements.size(), patch_count), settings,
                           fmt::format("the form factors of {} elements to {} patches", mesh.elements.size(), patch_count), fewer);
  ElementToPatch element_to_patch(static_cast<Eigen::Index>(mesh.elements.size()), static_cast<Eigen::Index>(patch_count));
  const auto own_patch = [&](std::size_t q) { return std::size_t{mesh.patch_of_element[q]}; };
  std::vector<double> element_sums(mesh.elements.size());
  {
    Stopwatch form_factor_time;
    fill_form_factor_rows(scene, mesh.elements, all_rows(mesh.elements.size()), mesh.patches, mesh.patch_geometry,
                          own_patch, element_to_patch, element_sums, cluster);
    form_factor_seconds += form_factor_time.seconds();
  }
  // Ctrl-C before every row was computed: the rows not begun are zero.
  const bool form_factors_complete = !stopped();
  std::size_t form_factor_rows = (progressive ? 0 : patch_count) + mesh.elements.size();
  const double min_element_size = settings.min_element_size > 0 ? settings.min_element_size : mesh.element_size / 8;
  ProgressReporter progress("radiosity", 1000, "per mille of convergence", quiet);
  ElementSolution solution;
  for (;;) {
    uint64_t progress_done = 0;
    if (progressive) {
      solution = shoot_progressively(mesh, element_to_patch, settings, progress, progress_done, run, cluster);
    } else {
      solution.radiosity = gather_from_patches(mesh, element_to_patch, patch_radiosity);
      solution.steps = patch_steps;
      solution.converged = patch_converged;
    }
    if (!(settings.subdivision_threshold > 0) || stopped()) break;
    const std::vector<bool> split =
        elements_to_split(mesh, solution.radiosity, element_sums, settings.subdivision_threshold, min_element_size);
    const auto split_count = static_cast<std::size_t>(std::count(split.begin(), split.end(), true));
    if (split_count == 0) break;
    // The new elements' rows; the others keep theirs. Both matrices are held while copying.
    const std::size_t new_count = mesh.elements.size() + split_count;
    check_form_factor_memory(element_rows_bytes(mesh.elements.size(), patch_count) + element_rows_bytes(new_count, patch_count),
                             settings, fmt::format("adaptive subdivision to {} elements", new_count),
                             "raise radiosity.subdivision_threshold or radiosity.min_element_size");
    const std::vector<uint32_t> origin = mesh.split_elements(scene, split);
    ElementToPatch refined(static_cast<Eigen::Index>(mesh.elements.size()), static_cast<Eigen::Index>(patch_count));
    std::vector<uint32_t> new_rows;
    std::vector<double> refined_sums(mesh.elements.size());
    for (std::size_t q = 0; q < origin.size(); ++q) {
      if (split[origin[q]]) {
        new_rows.push_back(static_cast<uint32_t>(q));
      } else {
        refined.row(static_cast<Eigen::Index>(q)) = element_to_patch.row(origin[q]);
        refined_sums[q] = element_sums[origin[q]];
      }
    }
    element_to_patch = ElementToPatch();  // free before the new rows are computed
    {
      Stopwatch form_factor_time;
      fill_form_factor_rows(scene, mesh.elements, new_rows, mesh.patches, mesh.patch_geometry, own_patch, refined,
                            refined_sums, cluster);
      form_factor_seconds += form_factor_time.seconds();
    }
    element_sums = std::move(refined_sums);
    element_to_patch = std::move(refined);
    form_factor_rows += new_rows.size();
    ++result.subdivision_passes;
  }
  progress.finish();

  if (progressive && settings.ambient) {
    // 000 §6.6.2: ρ_avg (eq. 6-14), R = 1 / (1 − ρ_avg) (eq. 6-15), B_amb = R Σ_i ΔB_i A_i / Σ A.
    const double total_area = mesh.patch_area();
    Color average_reflectance, area_weighted_unshot;
    for (const RadiositySurface& element : mesh.elements) average_reflectance += element.reflectance * (element.area / total_area);
    for (std::size_t p = 0; p < patch_count; ++p) area_weighted_unshot += solution.unshot[p] * (mesh.patches[p].area / total_area);
    Color ambient;
    for (int c = 0; c < 3; ++c) {
      // A channel where every surface reflects everything has no finite series; show no ambient.
      if (average_reflectance[c] < 1) ambient[c] = area_weighted_unshot[c] / (1 - average_reflectance[c]);
    }
    for (std::size_t q = 0; q < mesh.elements.size(); ++q) solution.radiosity[q] += mesh.elements[q].reflectance * ambient;
  }
  if (progressive && patch_count <= 2048) {  // P² doubles: 32 MiB at most
    // Reciprocity of the substructured patch form factors F_ij = Σ_{q∈i} A_q F_qj / A_i (000 eq. 6-19).
    Eigen::MatrixXd patch_rows = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(patch_count), static_cast<Eigen::Index>(patch_count));
    for (std::size_t q = 0; q < mesh.elements.size(); ++q) {
      const uint32_t i = mesh.patch_of_element[q];
      const double weight = mesh.elements[q].area / mesh.patches[i].area;
      patch_rows.row(i) += element_to_patch.row(static_cast<Eigen::Index>(q)).cast<double>() * weight;
    }
    reciprocity = measure_reciprocity(mesh.patches, patch_rows);
  }
  result.element_radiosity = std::move(solution.radiosity);
  result.element_hidden.resize(mesh.elements.size());
  for (std::size_t q = 0; q < mesh.elements.size(); ++q) result.element_hidden[q] = element_sums[q] < kHiddenRowSum;
  result.steps = solution.steps;
  result.unshot_fraction = solution.unshot_fraction;
  result.converged = solution.converged;
  result.form_factor_rows = form_factor_rows;
  result.form_factors = (progressive ? 0 : patch_count * patch_count) + (form_factor_rows - (progressive ? 0 : patch_count)) * patch_count;
  result.form_factor_bytes = element_rows_bytes(mesh.elements.size(), patch_count);
  result.solve_seconds = solve_time.seconds();
  if (statistics) {
    nlohmann::json& out = *statistics;
    out = {{"solver", kRadiositySolverNames.name(settings.solver)},
           {"form_factors", kRadiosityFormFactorNames.name(settings.form_factors)},
           {"hemicube_resolution", settings.hemicube_resolution},
           {"patches", patch_count},
           {"elements", mesh.elements.size()},
           {"patch_size", mesh.patch_size},
           {"element_size", mesh.element_size},
           {"steps", result.steps},
           {"converged", result.converged},
           {"unshot_fraction", result.unshot_fraction},
           {"subdivision_passes", result.subdivision_passes},
           {"form_factor_rows", result.form_factor_rows},
           {"form_factors_computed", result.form_factors},
           {"form_factors_per_second", form_factor_seconds > 0 ? static_cast<double>(result.form_factors) / form_factor_seconds : 0.0},
           {"form_factor_memory_mib", static_cast<double>(result.form_factor_bytes) / 1048576.0},
           {"mesh_seconds", result.mesh_seconds},
           {"solve_seconds", result.solve_seconds},
           {"form_factor_seconds", form_factor_seconds}};
    if (reciprocity.measured) {  // progressive: up to 2,048 patches
      out["reciprocity_error"] = reciprocity.mean_error;
      out["reciprocity_error_max"] = reciprocity.max_error;
    }
    const auto summary = [](const std::vector<double>& row_sums) {
      RowSumSummary sums;
      for (const double sum : row_sums) sums.add(sum);
      nlohmann::json json = {{"rows", sums.rows}, {"hidden_rows", sums.hidden_rows}};
      if (sums.rows > 0) {
        json["min"] = sums.min;
        json["mean"] = sums.total / static_cast<double>(sums.rows);
        json["max"] = sums.max;
      }
      return json;
    };
    out["row_sum"] = summary(progressive ? element_sums : patch_sums);
    if (!progressive) out["element_row_sum"] = summary(element_sums);
    if (cancel_requested()) {
      out["interrupted"] = true;
      out["completed"] = !form_factors_complete ? std::string("form factors not finished")
                         : progressive ? fmt::format("{} shots, unshot {:.3g}%", result.steps, 100 * result.unshot_fraction)
                                       : fmt::format("{} sweeps", result.steps);
    }
  }
  return result;
}

// 000 §6.5: the elements drawn as triangles through the scanline rasterizer with their vertex
// radiosities as colours, interpolated perspective-correctly (Gouraud); pixels no element covers
// show the background. Tiles of 32 × 32 pixels, each drawn by one thread from the same inputs with
// its own depth buffer, so the image does not depend on the thread count. The elements are
// projected once, in the constructor; draw fills any region from them (tiles across ranks, issue
// 11, do not redo it).
class GouraudDisplay {
 public:
  GouraudDisplay(const Scene& scene, const RadiositySolveResult& solution);
  void draw(const PixelRect& region, Film& film) const;

 private:
  const Scene& scene_;
  std::vector<std::array<RasterVertex, 3>> triangles_;
  // The screen bounds of each triangle; unbounded when a corner is behind the near plane.
  std::vector<ScreenBounds> bounds_on_screen_;
};

GouraudDisplay::GouraudDisplay(const Scene& scene, const RadiositySolveResult& solution)
    : scene_(scene) {
  const Camera& camera = *scene.camera;
  const std::vector<RadiositySurface>& elements = solution.mesh.elements;
  const VertexRadiosity vertices =
      compute_vertex_radiosity(solution.mesh.elements, solution.element_radiosity, solution.element_hidden);
  // Depth range: a box around the elements and the eye; near small enough for the closest element.
  Bounds3 bounds;
  bounds.extend(camera.eye_position());
  for (const RadiositySurface& element : elements)
    for (const Vec3& corner : element.corners) bounds.extend(corner);
  const double far = 2 * length(bounds.diagonal()) + 1;
  const Eigen::Matrix4d clip_from_world = camera.view_projection(far * 1e-8, far);
  triangles_.resize(elements.size());
  bounds_on_screen_.resize(elements.size());
  for (std::size_t q = 0; q < elements.size(); ++q) {
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec3& p = elements[q].corners[k];
      RasterVertex& vertex = triangles_[q][k];
      vertex.clip = clip_from_world * Eigen::Vector4d(p.x, p.y, p.z, 1);
      const Color& b = vertices.radiosity[vertices.element_vertices[q][k]];
      vertex.varyings[0] = b.r, vertex.varyings[1] = b.g, vertex.varyings[2] = b.b;
    }
    bounds_on_screen_[q] = screen_bounds(triangles_[q][0].clip, triangles_[q][1].clip, triangles_[q][2].clip,
                                         camera.width(), camera.height());
  }
}

void GouraudDisplay::draw(const PixelRect& region, Film& film) const {
  const Camera& camera = *scene_.camera;
  const int tile = 32;
  const int tiles_x = (region.width() + tile - 1) / tile, tiles_y = (region.height() + tile - 1) / tile;
  tbb::parallel_for(0, tiles_x * tiles_y, [&](int index) {
    const int x0 = region.x0 + (index % tiles_x) * tile, y0 = region.y0 + (index / tiles_x) * tile;
    const int x1 = std::min(x0 + tile, region.x1), y1 = std::min(y0 + tile, region.y1);
    const int w = x1 - x0;
    Rasterizer rasterizer(camera.width(), camera.height(), x0, y0, x1, y1);  // cleared
    std::vector<Color> colors(std::size_t(w) * (y1 - y0));
    std::vector<bool> covered(colors.size(), false);
    for (std::size_t q = 0; q < triangles_.size(); ++q) {
      const ScreenBounds& box = bounds_on_screen_[q];
      if (box.upper_x < x0 || box.lower_x > x1 || box.upper_y < y0 || box.lower_y > y1) continue;  // misses the tile
      rasterizer.draw_triangle(triangles_[q][0], triangles_[q][1], triangles_[q][2], 3, [&](const Fragment& fragment) {
        const std::size_t pixel = std::size_t(fragment.y - y0) * w + (fragment.x - x0);
        colors[pixel] = {fragment.varyings[0], fragment.varyings[1], fragment.varyings[2]};
        covered[pixel] = true;
        return true;
      });
    }
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const std::size_t pixel = std::size_t(y - y0) * w + (x - x0);
        film.at(x - region.x0, y - region.y0) =
            covered[pixel] ? colors[pixel] : scene_.background_along(camera.generate_ray(x + 0.5, y + 0.5).direction);
      }
  });
}

// 000 §6.5 and SPEC §10 "a ray-traced view that looks the value up at each hit": a ray through
// each pixel centre; at its hit, the element under the hit point, and the vertex radiosities of
// that element interpolated at the point's barycentric coordinates (the same field the Gouraud
// display shows, without its screen-space interpolation).
// Barycentric coordinates (weights of corners 0, 1, 2) of a point projected on a triangle's
// plane, clamped to the triangle.
std::array<double, 3> barycentric(const std::array<Vec3, 3>& corners, const Vec3& point) {
  const Vec3 e1 = corners[1] - corners[0], e2 = corners[2] - corners[0], d = point - corners[0];
  const double d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2), d1 = dot(d, e1), d2 = dot(d, e2);
  const double denominator = d11 * d22 - d12 * d12;
  double v = denominator > 0 ? (d22 * d1 - d12 * d2) / denominator : 0;
  double w = denominator > 0 ? (d11 * d2 - d12 * d1) / denominator : 0;
  v = std::clamp(v, 0.0, 1.0);
  w = std::clamp(w, 0.0, 1.0 - v);
  return {1 - v - w, v, w};
}

Color ray_traced_radiosity(const RadiositySolveResult& solution, const VertexRadiosity& vertices,
                           uint32_t element, const Intersection& hit) {
  const auto weights = barycentric(solution.mesh.elements[element].corners, hit.surface.position);
  const auto& ids = vertices.element_vertices[element];
  return vertices.radiosity[ids[0]] * weights[0] + vertices.radiosity[ids[1]] * weights[1] +
         vertices.radiosity[ids[2]] * weights[2];
}

// The element mesh (000 Figure 65): each element flat, its edges drawn dark about a pixel wide —
// where the hit lies closer to an edge than pixel_footprint (the width a pixel covers there).
Color element_outline(const RadiositySolveResult& solution, uint32_t element, const Intersection& hit,
                      double pixel_footprint) {
  const RadiositySurface& surface = solution.mesh.elements[element];
  const auto weights = barycentric(surface.corners, hit.surface.position);
  for (int k = 0; k < 3; ++k) {
    // Weight k is the distance to the opposite edge over the triangle's height there, 2A/|edge|.
    const double edge = length(surface.corners[(k + 2) % 3] - surface.corners[(k + 1) % 3]);
    if (edge > 0 && weights[static_cast<std::size_t>(k)] * 2 * surface.area / edge < 0.6 * pixel_footprint)
      return solution.element_radiosity[element] * 0.15;
  }
  return solution.element_radiosity[element];
}

}  // namespace

RadiositySolveResult solve_radiosity(const Scene& scene, bool quiet) { return solve_with_statistics(scene, quiet, nullptr); }

namespace {

// What a solution depends on besides the scene object: its radiosity settings (all but the
// display) and the seed of the ray-cast form factors.
std::string solution_key(const Scene& scene) {
  const RadiositySettings r = radiosity_settings_of(scene);
  return fmt::format("{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}", scene.unique_id, static_cast<int>(r.solver),
                     static_cast<int>(r.form_factors), r.hemicube_resolution, r.ray_cast_samples, r.patch_size,
                     r.element_size, r.segments, r.threshold, r.max_steps, r.ambient, r.subdivision_threshold,
                     r.min_element_size, r.memory_limit_mib, r.split_at_contacts, scene.render.seed);
}

}  // namespace

std::shared_ptr<const RadiosityMethod::Solved> RadiosityMethod::solution_for(const Scene& scene,
                                                                            const RenderRequest& request,
                                                                            bool& reused) const {
  const std::string key = solution_key(scene);
  Cluster* cluster = several_ranks(request);
  std::lock_guard lock(cache_mutex_);
  // A checkpoint to write or resume from asks for this run's own solve.
  const bool checkpointing = !request.checkpoint.empty() || !request.resume.empty();
  reused = !checkpointing && cached_ && cached_key_ == key;
  if (reused) return cached_;
  auto solved = std::make_shared<Solved>();
  ProgressiveRun run;
  RadiosityCheckpoint resumed;
  if (checkpointing) {
    const SourceLocation where{!request.resume.empty() ? request.resume : request.checkpoint, 0, 0, {}};
    if (radiosity_settings_of(scene).solver != RadiositySolver::progressive || radiosity_settings_of(scene).subdivision_threshold > 0)
      throw InputError(where, "checkpoints are for radiosity.solver \"progressive\" without adaptive subdivision "
                              "(radiosity.subdivision_threshold 0)");
    run.checkpoint = request.checkpoint;
    // Every setting that shapes the mesh, the form factors or the display — not threshold,
    // max_steps or memory_limit_mib, which only say how far to go (a resumed run may go further).
    const RadiositySettings r = radiosity_settings_of(scene);
    run.fingerprint = fmt::format("{}|radiosity {} {} {} {} {} {} {} {} {}", request.fingerprint,
                                  static_cast<int>(r.form_factors), r.hemicube_resolution, r.ray_cast_samples,
                                  r.patch_size, r.element_size, r.segments, r.ambient, r.split_at_contacts,
                                  scene.render.seed);
    if (request.checkpoint_interval > 0) run.interval = request.checkpoint_interval;
    // Every rank shoots the same way from the same state; rank 0 alone reads the checkpoint and
    // sends it to the others, and alone writes checkpoints.
    const bool root = !cluster || cluster->root();
    if (!root) run.checkpoint.clear();
    if (!request.resume.empty()) {
      std::exception_ptr error;
      try {
        if (root) {
          resumed = read_radiosity_checkpoint(request.resume);
          if (resumed.fingerprint != run.fingerprint)
            throw InputError(where, "the checkpoint was made for another scene or other settings (" +
                                        resumed.fingerprint + "), not this one (" + run.fingerprint + ")");
        }
      } catch (...) {
        if (!cluster) throw;
        error = std::current_exception();
      }
      if (cluster) {
        settle_root_outcome(*cluster, error);
        ByteWriter writer;
        if (root) {
          writer.put<uint64_t>(resumed.steps);
          writer.put_array(resumed.radiosity);
          writer.put_array(resumed.unshot);
        }
        Bytes state = writer.take();
        cluster->broadcast(state);
        ByteReader reader(state);
        resumed.fingerprint = run.fingerprint;
        resumed.steps = reader.get<uint64_t>();
        resumed.radiosity = reader.get_array<Color>();
        resumed.unshot = reader.get_array<Color>();
      }
      run.resume = &resumed;
    }
  }
  try {
    solved->result = solve_with_statistics(scene, request.quiet || (cluster && !cluster->root()), &solved->facts,
                                           checkpointing ? &run : nullptr, cluster);
  } catch (const std::invalid_argument& e) {
    if (!run.resume) throw;
    throw InputError({request.resume, 0, 0, {}}, e.what());
  }
  if (checkpointing) {
    solved->facts["checkpoints_written"] = run.checkpoints_written;
    if (run.resume) solved->facts["resumed_from_shots"] = resumed.steps;
  }
  if (checkpointing) return solved;  // not kept: the next render may resume from elsewhere
  if (solved->facts.contains("interrupted")) return solved;  // Ctrl-C: not a solution to keep
  cached_ = solved;
  cached_key_ = key;
  return solved;
}

RenderResult RadiosityMethod::render(const Scene& scene, const RenderRequest& request) const {
  RenderResult output(request.region);
  Film& film = output.film;
  RunStatistics& statistics = output.statistics;
  bool reused = false;
  const std::shared_ptr<const Solved> solved = solution_for(scene, request, reused);
  const RadiositySolveResult& solution = solved->result;
  nlohmann::json facts = solved->facts;
  facts["solution_reused"] = reused;
  if (facts.contains("interrupted")) {  // Ctrl-C: the solution so far is displayed
    statistics.extra["interrupted"] = true;
    statistics.extra["completed"] = facts["completed"];
  }
  // The same solution serves every view: the caller may export it (candela render --export-solution).
  output.solution = std::shared_ptr<const RadiositySolveResult>(solved, &solved->result);
  const PixelRect region = request.region;
  const Camera& camera = *scene.camera;
  Stopwatch display_time;
  const RadiosityDisplay display = radiosity_settings_of(scene).display;
  const VertexRadiosity vertices =
      display == RadiosityDisplay::ray_traced
          ? compute_vertex_radiosity(solution.mesh.elements, solution.element_radiosity, solution.element_hidden)
          : VertexRadiosity();
  std::optional<GouraudDisplay> gouraud;
  if (display == RadiosityDisplay::gouraud) gouraud.emplace(scene, solution);
  // The pixels of area into target (area-sized).
  const auto draw = [&](const PixelRect& area, Film& target) {
    if (gouraud) return gouraud->draw(area, target);
    // Display by ray casting: the radiosity (view independent: B itself) where each pixel's ray hits.
    tbb::parallel_for(area.y0, area.y1, [&](int y) {
      for (int x = area.x0; x < area.x1; ++x) {
        const Ray ray = camera.generate_ray(x + 0.5, y + 0.5);
        Intersection hit;
        Color color;
        const uint32_t element =
            scene.intersect(ray, hit) ? solution.mesh.element_at(hit.primitive, hit.surface.position) : UINT32_MAX;
        if (element == UINT32_MAX) {
          color = scene.background_along(ray.direction);  // a miss, or off the mesh (as the Gouraud display)
        } else if (display == RadiosityDisplay::ray_traced) {
          color = ray_traced_radiosity(solution, vertices, element, hit);
        } else if (display == RadiosityDisplay::elements) {
          const Vec3 next = camera.generate_ray(x + 1.5, y + 0.5).direction;
          color = element_outline(solution, element, hit, length(hit.surface.position - ray.origin) *
                                                              length(normalize(next) - normalize(ray.direction)));
        } else {
          color = solution.element_radiosity[element];
        }
        target.at(x - area.x0, y - area.y0) = color;
      }
    });
  };
  draw_across_ranks(request.cluster, region, draw, film, statistics);  // issue 11: every rank holds the same solution
  const auto pixel_count = static_cast<uint64_t>(region.width()) * region.height();
  if (display != RadiosityDisplay::gouraud) statistics.rays.primary += pixel_count;  // rasterized: none
  statistics.pixels += pixel_count;
  facts["display"] = kRadiosityDisplayNames.name(display);
  facts["display_seconds"] = display_time.seconds();
  statistics.extra["radiosity"] = std::move(facts);
  return output;
}

RadiositySolveResult solve_radiosity(const Scene& scene, bool quiet, nlohmann::json* facts) { return solve_with_statistics(scene, quiet, facts); }

namespace {

// The ray-traced display's field: the vertex radiosities interpolated over the element hit.
class RadiosityField final : public SolutionField {
 public:
  explicit RadiosityField(RadiositySolveResult solution)
      : solution_(std::move(solution)),
        vertices_(compute_vertex_radiosity(solution_.mesh.elements, solution_.element_radiosity,
                                           solution_.element_hidden)) {}
  bool exitance(const Ray& ray, const Intersection& hit, Color& exitance) const override {
    const uint32_t element = solution_.mesh.element_at(hit.primitive, hit.surface.position);
    if (element == UINT32_MAX) return false;
    // Patches are one-sided (000 §6): nothing leaves a patch's back.
    if (dot(ray.direction, solution_.mesh.elements[element].normal) > 0) {
      exitance = Color();
      return true;
    }
    exitance = ray_traced_radiosity(solution_, vertices_, element, hit);
    return true;
  }
  Color direct_irradiance(const Vec3&, const Vec3&) const override { return {}; }  // emissive surfaces only (000 §6)

 private:
  RadiositySolveResult solution_;
  VertexRadiosity vertices_;
};

}  // namespace

std::unique_ptr<SolutionField> make_radiosity_field(const Scene& scene, bool quiet) {
  return std::make_unique<RadiosityField>(solve_radiosity(scene, quiet));
}

}  // namespace candela
