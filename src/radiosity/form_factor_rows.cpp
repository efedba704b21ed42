#include "radiosity/form_factor_rows.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <memory>
#include <span>

#include "accel/accelerator_registry.h"
#include "distributed/cluster.h"
#include "distributed/task_farm.h"
#include "io/byte_stream.h"
#include "math/constants.h"
#include "math/pcg32.h"
#include "radiosity/delta_form_factors.h"
#include "radiosity/hemicube_form_factors.h"
#include "radiosity/ray_cast_form_factors.h"
#include "radiosity/triangle_occluders.h"
#include "util/cancellation.h"
#include "util/progress.h"

namespace candela {
namespace {

// Orients the hemicube around a surface's normal: its first edge (never along the normal).
Vec3 tangent_of(const RadiositySurface& surface) {
  return normalize(surface.corners[1] - surface.corners[0]);
}

// Form factors from the centroids of surfaces[rows[k]] to every target (F_i→j), written as
// write(k, j, F), in parallel; row k's sum into sums[k]. A surface's row skips the target
// `skipped(i)`.
template <typename Sink, typename Skipped>
void compute_form_factor_rows(const Accelerator* occluders, const RadiositySettings& settings, uint64_t seed,
                              const std::vector<RadiositySurface>& surfaces, std::span<const uint32_t> rows,
                              const std::vector<RadiositySurface>& targets,
                              const FormFactorGeometry& geometry, Skipped skipped, Sink write,
                              std::span<double> sums, ProgressReporter* progress) {
  RayCastSettings ray_cast;
  ray_cast.source_samples_per_side = settings.ray_cast_samples;
  if (settings.form_factors == RadiosityFormFactors::hemicube) {
    const auto table = std::make_shared<const DeltaFormFactors>(settings.hemicube_resolution);
    tbb::enumerable_thread_specific<std::unique_ptr<HemicubeFormFactors>> hemicubes;
    // An emitter that covers few cells of the hemicube aliases — a small lamp's light
    // on the walls came out 2–10 % off at resolution 100. Its factor is taken instead as the
    // ray-cast one (the exact unoccluded point-to-polygon factor times the visible fraction of its
    // samples) wherever the unoccluded factor is worth fewer than kSmallOnHemicube cells of the
    // top face's centre (ΔF = 4 / (π R²) each).
    constexpr double kSmallOnHemicube = 2000;
    const double resolution = settings.hemicube_resolution;
    const double small_factor = kSmallOnHemicube * 4 / (kPi * resolution * resolution);
    std::vector<uint32_t> emitters;
    std::vector<FormFactorElement> emitter_elements;
    if (occluders)
      for (uint32_t j = 0; j < targets.size(); ++j)
        if (!targets[j].emission.is_black()) {
          emitters.push_back(j);
          emitter_elements.push_back(FormFactorElement::triangle(targets[j].corners[0], targets[j].corners[1],
                                                                 targets[j].corners[2]));
        }
    tbb::parallel_for(std::size_t(0), rows.size(), [&](std::size_t k) {
      if (cancel_requested()) return;  // Ctrl-C: the rows not begun stay zero
      auto& hemicube = hemicubes.local();
      if (!hemicube) hemicube = std::make_unique<HemicubeFormFactors>(table);
      thread_local std::vector<double> row;
      const std::size_t i = rows[k];
      const RadiositySurface& surface = surfaces[i];
      hemicube->compute_row(geometry, surface.centroid, surface.normal, tangent_of(surface),
                            static_cast<uint32_t>(skipped(i)), row);
      Pcg32 random(seed, i);  // one stream per row
      for (std::size_t e = 0; e < emitters.size(); ++e) {
        const uint32_t j = emitters[e];
        if (j == skipped(i)) continue;
        const double unoccluded =
            point_to_polygon_form_factor(surface.centroid, surface.normal, emitter_elements[e].corners());
        if (unoccluded > 0 && unoccluded < small_factor)
          row[j] = point_to_element_form_factor(surface.centroid, surface.normal, emitter_elements[e],
                                                occluders, ray_cast, random);
      }
      for (std::size_t j = 0; j < row.size(); ++j) write(k, j, row[j]);
      sums[k] = row_sum(row);
      if (progress) progress->advance();
    });
  } else {
    std::vector<FormFactorElement> sources;
    sources.reserve(targets.size());
    for (const RadiositySurface& target : targets)
      sources.push_back(FormFactorElement::triangle(target.corners[0], target.corners[1], target.corners[2]));
    tbb::parallel_for(std::size_t(0), rows.size(), [&](std::size_t k) {
      if (cancel_requested()) return;
      const std::size_t i = rows[k];
      Pcg32 random(seed, i);  // one stream per row
      const RadiositySurface& surface = surfaces[i];
      double sum = 0;
      for (std::size_t j = 0; j < sources.size(); ++j) {
        double form_factor = 0;
        if (j != skipped(i))
          form_factor = point_to_element_form_factor(surface.centroid, surface.normal, sources[j], occluders,
                                                     ray_cast, random);
        write(k, j, form_factor);
        sum += form_factor;
      }
      sums[k] = sum;
      if (progress) progress->advance();
    });
  }
}

// The rows `rows` of matrix (and of sums_by_row), on this process or farmed out across the ranks.
template <typename Matrix, typename Skipped>
void fill_form_factor_rows(const RadiositySettings& settings, uint64_t seed,
                           const std::vector<RadiositySurface>& surfaces, const std::vector<uint32_t>& rows,
                           const std::vector<RadiositySurface>& targets, const FormFactorGeometry& geometry,
                           Skipped skipped, Matrix& matrix, std::vector<double>& sums_by_row,
                           Cluster* cluster, bool quiet) {
  using Scalar = typename Matrix::Scalar;
  std::vector<double> sums(rows.size());
  // The rows take half a minute on large meshes; rank 0 shows them (every rank's rows
  // come back to it).
  ProgressReporter progress("form factors", rows.size(), "rows", quiet || (cluster && !cluster->root()));
  // Ray-cast visibility is decided against the targets themselves — the surfaces
  // radiosity models, which the hemicube draws too — not the scene's analytic shapes: the elements
  // of a tessellated sphere or cylinder lie inside the analytic surface, which would block every
  // ray they send.
  // The hemicube needs them for the emitters small on it (below).
  std::unique_ptr<TriangleOccluders> occluders;
  const bool any_emitter = std::any_of(targets.begin(), targets.end(), [](const RadiositySurface& target) {
    return !target.emission.is_black();
  });
  if (settings.form_factors == RadiosityFormFactors::ray_cast || any_emitter)
    occluders = std::make_unique<TriangleOccluders>(geometry.mesh);
  const Accelerator* visibility = occluders ? &occluders->accelerator() : nullptr;
  if (!cluster || !cluster->distributed()) {
    compute_form_factor_rows(
        visibility, settings, seed, surfaces, rows, targets, geometry, skipped,
        [&](std::size_t k, std::size_t j, double value) {
          matrix(static_cast<Eigen::Index>(rows[k]), static_cast<Eigen::Index>(j)) =
              static_cast<Scalar>(value);
        },
        sums, &progress);
  } else {
    // Chunks of about 8 a rank's worth of threads, at most 64 rows: enough to balance, few messages.
    const std::size_t chunk =
        std::clamp<std::size_t>(rows.size() / (std::size_t(cluster->size()) * 8), 1, 64);
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
    run_task_farm_everywhere(
        *cluster, tasks,
        [&](std::size_t task) {
          const std::size_t first = task * chunk, count = std::min(chunk, rows.size() - first);
          std::vector<Scalar> values(count * columns, Scalar(0));
          std::vector<double> chunk_sums(count);
          compute_form_factor_rows(
              visibility, settings, seed, surfaces, std::span<const uint32_t>(rows).subspan(first, count),
              targets, geometry, skipped,
              [&](std::size_t k, std::size_t j, double value) {
                values[k * columns + j] = static_cast<Scalar>(value);
              },
              chunk_sums, nullptr);
          return chunk_bytes(values, chunk_sums);
        },
        [&](std::size_t task, std::span<const std::byte> result) {
          const std::size_t first = task * chunk;
          ByteReader reader(result);
          const std::vector<Scalar> values = reader.get_array<Scalar>();
          const std::vector<double> chunk_sums = reader.get_array<double>();
          for (std::size_t k = 0; k < chunk_sums.size(); ++k) {
            for (std::size_t j = 0; j < columns; ++j)
              matrix(static_cast<Eigen::Index>(rows[first + k]), static_cast<Eigen::Index>(j)) =
                  values[k * columns + j];
            sums[first + k] = chunk_sums[k];
          }
          progress.advance(chunk_sums.size());
        },
        [&](std::size_t task) {
          const std::size_t first = task * chunk, count = std::min(chunk, rows.size() - first);
          std::vector<Scalar> values(count * columns);
          for (std::size_t k = 0; k < count; ++k)
            for (std::size_t j = 0; j < columns; ++j)
              values[k * columns + j] =
                  matrix(static_cast<Eigen::Index>(rows[first + k]), static_cast<Eigen::Index>(j));
          return chunk_bytes(values, std::span<const double>(sums).subspan(first, count));
        });
  }
  progress.finish();
  for (std::size_t k = 0; k < rows.size(); ++k) sums_by_row[rows[k]] = sums[k];
}

}  // namespace

std::vector<uint32_t> all_rows(std::size_t count) {
  std::vector<uint32_t> rows(count);
  for (std::size_t i = 0; i < count; ++i) rows[i] = static_cast<uint32_t>(i);
  return rows;
}

void fill_patch_form_factor_rows(const RadiositySettings& settings, uint64_t seed, const RadiosityMesh& mesh,
                                 Eigen::MatrixXd& rows, std::vector<double>& sums, Cluster* cluster,
                                 bool quiet) {
  fill_form_factor_rows(
      settings, seed, mesh.patches, all_rows(mesh.patches.size()), mesh.patches, mesh.patch_geometry,
      [](std::size_t i) { return i; }, rows, sums, cluster, quiet);
}

void fill_element_form_factor_rows(const RadiositySettings& settings, uint64_t seed,
                                   const RadiosityMesh& mesh, const std::vector<uint32_t>& elements,
                                   ElementToPatch& matrix, std::vector<double>& sums, Cluster* cluster,
                                   bool quiet) {
  fill_form_factor_rows(
      settings, seed, mesh.elements, elements, mesh.patches, mesh.patch_geometry,
      [&](std::size_t q) { return std::size_t{mesh.patch_of_element[q]}; }, matrix, sums, cluster, quiet);
}

}  // namespace candela
