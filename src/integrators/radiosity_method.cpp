#include "integrators/radiosity_method.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "radiosity/delta_form_factors.h"
#include "radiosity/hemicube_form_factors.h"
#include "radiosity/ray_cast_form_factors.h"
#include "radiosity/solvers.h"
#include "radiosity/vertex_radiosity.h"
#include "raster/rasterizer.h"
#include "util/progress.h"

namespace candela {

namespace {

const char* solver_name(RadiositySolver solver) {
  switch (solver) {
    case RadiositySolver::progressive: return "progressive";
    case RadiositySolver::gauss_seidel: return "gauss-seidel";
    case RadiositySolver::gaussian: return "gaussian";
  }
  return "?";
}

double channel_sum(const Color& c) { return c.r + c.g + c.b; }

// Orients the hemicube around a surface's normal: its first edge (never along the normal).
Vec3 tangent_of(const RadiositySurface& surface) { return normalize(surface.corners[1] - surface.corners[0]); }

// Row sums of the hemicube rows (000 eq. 6-6: 1 in a closed scene), summarised.
struct RowSumSummary {
  double min = std::numeric_limits<double>::infinity(), max = 0, total = 0;
  std::size_t rows = 0;
  void add(double sum) {
    min = std::min(min, sum);
    max = std::max(max, sum);
    total += sum;
    ++rows;
  }
};

// Form factors from every surface's centroid to every target (a row per surface, F_i→j), in
// parallel: each row by one thread into its own matrix row (ray casting with a random stream per
// row), so the result does not depend on the thread count. A surface's row skips the target
// `skipped(i)` (its own patch). The targets are the triangles of `geometry`, one per target.
//   hemicube  000 §6.4: the row of a hemicube at the centroid over the targets;
//   ray-cast  per target, Lambert's exact unoccluded point-to-polygon form factor times the
//             fraction of ray_cast_samples² rays that reach it (radiosity/ray_cast_form_factors.h).
template <typename Skipped>
Eigen::MatrixXd form_factor_rows(const Scene& scene, const std::vector<RadiositySurface>& surfaces,
                                 const std::vector<RadiositySurface>& targets, const FormFactorGeometry& geometry,
                                 Skipped skipped, RowSumSummary& row_sums) {
  const RadiositySettings& settings = scene.radiosity;
  Eigen::MatrixXd matrix = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(surfaces.size()), static_cast<Eigen::Index>(targets.size()));
  if (settings.form_factors == RadiosityFormFactors::hemicube) {
    const auto table = std::make_shared<const DeltaFormFactors>(settings.hemicube_resolution);
    tbb::enumerable_thread_specific<std::unique_ptr<HemicubeFormFactors>> hemicubes;
    tbb::parallel_for(std::size_t(0), surfaces.size(), [&](std::size_t i) {
      auto& hemicube = hemicubes.local();
      if (!hemicube) hemicube = std::make_unique<HemicubeFormFactors>(table);
      thread_local std::vector<double> row;
      const RadiositySurface& surface = surfaces[i];
      hemicube->compute_row(geometry, surface.centroid, surface.normal, tangent_of(surface), static_cast<uint32_t>(skipped(i)), row);
      for (std::size_t j = 0; j < row.size(); ++j) matrix(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = row[j];
    });
  } else {
    std::vector<FormFactorElement> sources;
    sources.reserve(targets.size());
    for (const RadiositySurface& target : targets)
      sources.push_back(FormFactorElement::triangle(target.corners[0], target.corners[1], target.corners[2]));
    RayCastSettings ray_cast;
    ray_cast.source_samples_per_side = settings.ray_cast_samples;
    tbb::parallel_for(std::size_t(0), surfaces.size(), [&](std::size_t i) {
      Pcg32 random(scene.render.seed, i);  // one stream per row
      const RadiositySurface& surface = surfaces[i];
      for (std::size_t j = 0; j < sources.size(); ++j) {
        if (j == skipped(i)) continue;
        matrix(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = point_to_element_form_factor(
            surface.centroid, surface.normal, sources[j], &scene.accelerator(), ray_cast, random);
      }
    });
  }
  for (Eigen::Index i = 0; i < matrix.rows(); ++i) row_sums.add(matrix.row(i).sum());
  return matrix;
}

// 000 §6.6 with substructuring (000 §6.7.1): patches shoot, elements receive. See the header.
void solve_progressive(const Scene& scene, RadiositySolveResult& result, RowSumSummary& row_sums, bool quiet) {
  const RadiositySettings& settings = scene.radiosity;
  const RadiosityMesh& mesh = result.mesh;
  const std::size_t patch_count = mesh.patches.size(), element_count = mesh.elements.size();
  std::vector<Color> radiosity(element_count), unshot(patch_count);
  for (std::size_t q = 0; q < element_count; ++q) radiosity[q] = mesh.elements[q].emission;  // B = E
  double emitted_flux = 0, total_area = 0;
  for (std::size_t p = 0; p < patch_count; ++p) {
    unshot[p] = mesh.patches[p].emission;  // ΔB = E
    emitted_flux += channel_sum(unshot[p]) * mesh.patches[p].area;
    total_area += mesh.patches[p].area;
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

  // The gathering form factors F_qj from every element q to every patch j: a hemicube at each
  // element's centroid over the patches (000 §6.7.1), its own patch skipped. Each row sums to 1 in a
  // closed scene, so every element receives exactly its share (a hemicube at the shooter with
  // reciprocity, F_qj = F_jq A_j / A_q, misjudges elements near the shooter: ±17% in a furnace).
  const Eigen::MatrixXd element_to_patch = form_factor_rows(
      scene, mesh.elements, mesh.patches, mesh.patch_geometry,
      [&](std::size_t q) { return std::size_t{mesh.patch_of_element[q]}; }, row_sums);
  ProgressReporter progress("radiosity", 1000, "per mille of convergence", quiet);
  uint64_t progress_done = 0;
  std::size_t shooter = patch_count;
  double fraction = unshot_fraction(shooter);
  std::size_t steps = 0;
  while (fraction > settings.threshold && shooter < patch_count && steps < static_cast<std::size_t>(settings.max_steps)) {
    const Color shot = unshot[shooter];
    unshot[shooter] = Color();
    const auto column = element_to_patch.col(static_cast<Eigen::Index>(shooter));
    for (std::size_t q = 0; q < element_count; ++q) {
      const double form_factor = column(static_cast<Eigen::Index>(q));  // F_qj
      if (form_factor <= 0) continue;
      const RadiositySurface& element = mesh.elements[q];
      // 000 eqs. 6-12, 6-13: ΔRad = ρ_q ΔB_j F_qj.
      const Color gain = element.reflectance * shot * form_factor;
      radiosity[q] += gain;
      const uint32_t patch = mesh.patch_of_element[q];
      unshot[patch] += gain * (element.area / mesh.patches[patch].area);  // area-weighted mean
    }
    ++steps;
    fraction = unshot_fraction(shooter);
    const auto done = static_cast<uint64_t>(1000 * progressive_convergence_progress(fraction, settings.threshold));
    if (done > progress_done) progress.advance(done - progress_done), progress_done = done;
  }
  progress.finish();

  if (settings.ambient && total_area > 0) {
    // 000 §6.6.2: ρ_avg (eq. 6-14), R = 1 / (1 − ρ_avg) (eq. 6-15), B_amb = R Σ_i ΔB_i A_i / Σ A.
    Color average_reflectance, area_weighted_unshot;
    for (const RadiositySurface& element : mesh.elements) average_reflectance += element.reflectance * (element.area / total_area);
    for (std::size_t p = 0; p < patch_count; ++p) area_weighted_unshot += unshot[p] * (mesh.patches[p].area / total_area);
    Color ambient;
    for (int c = 0; c < 3; ++c) {
      // A channel where every surface reflects everything has no finite series; show no ambient.
      if (average_reflectance[c] < 1) ambient[c] = area_weighted_unshot[c] / (1 - average_reflectance[c]);
    }
    for (std::size_t q = 0; q < element_count; ++q) radiosity[q] += mesh.elements[q].reflectance * ambient;
  }
  result.element_radiosity = std::move(radiosity);
  result.steps = steps;
  result.unshot_fraction = fraction;
  result.converged = fraction <= settings.threshold;
  result.form_factor_rows = element_count;
}

// The patch system by Gauss-Seidel or Gaussian elimination (000 eq. 6-9), then the elements
// gathered from it (000 eq. 6-16).
void solve_direct(const Scene& scene, RadiositySolveResult& result, RowSumSummary& row_sums, double& reciprocity_error) {
  const RadiositySettings& settings = scene.radiosity;
  const RadiosityMesh& mesh = result.mesh;
  const RadiositySystem patches = mesh.patch_system();
  Eigen::MatrixXd patch_rows = form_factor_rows(
      scene, mesh.patches, mesh.patches, mesh.patch_geometry, [](std::size_t i) { return i; }, row_sums);
  // Reciprocity (000 eq. 6-5): the largest |A_i F_ij − A_j F_ji| relative to the largest A_i F_ij.
  double largest_transfer = 0, largest_mismatch = 0;
  for (Eigen::Index i = 0; i < patch_rows.rows(); ++i)
    for (Eigen::Index j = i + 1; j < patch_rows.cols(); ++j) {
      const double a = patches.areas[static_cast<std::size_t>(i)] * patch_rows(i, j);
      const double b = patches.areas[static_cast<std::size_t>(j)] * patch_rows(j, i);
      largest_transfer = std::max({largest_transfer, a, b});
      largest_mismatch = std::max(largest_mismatch, std::fabs(a - b));
    }
  reciprocity_error = largest_transfer > 0 ? largest_mismatch / largest_transfer : 0;
  const FormFactorSource patch_source(std::move(patch_rows));
  const RadiositySolution solution =
      settings.solver == RadiositySolver::gaussian
          ? solve_gaussian_elimination(patches, patch_source)
          : solve_gauss_seidel(patches, patch_source, settings.threshold, static_cast<std::size_t>(settings.max_steps));
  ElementSystem elements;
  for (std::size_t q = 0; q < mesh.elements.size(); ++q) {
    elements.patch.push_back(mesh.patch_of_element[q]);
    elements.areas.push_back(mesh.elements[q].area);
    elements.reflectance.push_back(mesh.elements[q].reflectance);
    elements.emission.push_back(mesh.elements[q].emission);
  }
  RowSumSummary element_row_sums;  // element → patch rows: not the shooting rows, kept apart
  const FormFactorSource element_to_patch(form_factor_rows(
      scene, mesh.elements, mesh.patches, mesh.patch_geometry,
      [&](std::size_t q) { return std::size_t{mesh.patch_of_element[q]}; }, element_row_sums));
  result.element_radiosity = gather_element_radiosities(elements, element_to_patch, solution.radiosity);
  result.steps = solution.iterations;
  result.converged = solution.converged;
  result.unshot_fraction = 0;
  result.form_factor_rows = mesh.patches.size() + mesh.elements.size();
}

RadiositySolveResult solve_with_statistics(const Scene& scene, bool quiet, nlohmann::json* statistics) {
  RadiositySolveResult result;
  const RadiositySettings& settings = scene.radiosity;
  Stopwatch mesh_time;
  RadiosityMeshSettings mesh_settings;
  mesh_settings.segments = settings.segments;
  mesh_settings.patch_size = settings.patch_size;
  mesh_settings.element_size = settings.element_size;
  result.mesh = build_radiosity_mesh(scene, mesh_settings);
  result.mesh_seconds = mesh_time.seconds();
  Stopwatch solve_time;
  RowSumSummary row_sums;
  double reciprocity_error = -1;  // measured by the direct solvers only
  if (settings.solver == RadiositySolver::progressive) {
    solve_progressive(scene, result, row_sums, quiet);
  } else {
    solve_direct(scene, result, row_sums, reciprocity_error);
  }
  result.solve_seconds = solve_time.seconds();
  if (statistics) {
    nlohmann::json& out = *statistics;
    out = {{"solver", solver_name(settings.solver)},
           {"form_factors", settings.form_factors == RadiosityFormFactors::hemicube ? "hemicube" : "ray-cast"},
           {"hemicube_resolution", settings.hemicube_resolution},
           {"patches", result.mesh.patches.size()},
           {"elements", result.mesh.elements.size()},
           {"patch_size", result.mesh.patch_size},
           {"element_size", result.mesh.element_size},
           {"steps", result.steps},
           {"converged", result.converged},
           {"unshot_fraction", result.unshot_fraction},
           {"form_factor_rows", result.form_factor_rows},
           {"mesh_seconds", result.mesh_seconds},
           {"solve_seconds", result.solve_seconds}};
    if (row_sums.rows > 0) {
      out["row_sum"] = {{"min", row_sums.min}, {"mean", row_sums.total / static_cast<double>(row_sums.rows)}, {"max", row_sums.max}};
    }
    if (reciprocity_error >= 0) out["reciprocity_error"] = reciprocity_error;
  }
  return result;
}

// 000 §6.5: the elements drawn as triangles through the scanline rasterizer with their vertex
// radiosities as colours, interpolated perspective-correctly (Gouraud); pixels no element covers
// show the background. Tiles of 32 × 32 pixels, each drawn by one thread from the same inputs with
// its own depth buffer, so the image does not depend on the thread count.
void display_gouraud(const Scene& scene, const RadiositySolveResult& solution, const PixelRect& region, Film& film) {
  const Camera& camera = *scene.camera;
  const std::vector<RadiositySurface>& elements = solution.mesh.elements;
  const VertexRadiosity vertices = compute_vertex_radiosity(elements, solution.element_radiosity);
  // Depth range: a box around the elements and the eye; near small enough for the closest element.
  Bounds3 bounds;
  bounds.extend(camera.eye_position());
  for (const RadiositySurface& element : elements)
    for (const Vec3& corner : element.corners) bounds.extend(corner);
  const double far = 2 * length(bounds.diagonal()) + 1;
  const Eigen::Matrix4d clip_from_world = camera.view_projection(far * 1e-8, far);
  std::vector<std::array<RasterVertex, 3>> triangles(elements.size());
  // The screen bounds of each triangle; unbounded when a corner is behind the near plane.
  std::vector<ScreenBounds> bounds_on_screen(elements.size());
  for (std::size_t q = 0; q < elements.size(); ++q) {
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec3& p = elements[q].corners[k];
      RasterVertex& vertex = triangles[q][k];
      vertex.clip = clip_from_world * Eigen::Vector4d(p.x, p.y, p.z, 1);
      const Color& b = vertices.radiosity[vertices.element_vertices[q][k]];
      vertex.varyings[0] = b.r, vertex.varyings[1] = b.g, vertex.varyings[2] = b.b;
    }
    bounds_on_screen[q] = screen_bounds(triangles[q][0].clip, triangles[q][1].clip, triangles[q][2].clip,
                                        camera.width(), camera.height());
  }
  const int tile = 32;
  const int tiles_x = (region.width() + tile - 1) / tile, tiles_y = (region.height() + tile - 1) / tile;
  tbb::parallel_for(0, tiles_x * tiles_y, [&](int index) {
    const int x0 = region.x0 + (index % tiles_x) * tile, y0 = region.y0 + (index / tiles_x) * tile;
    const int x1 = std::min(x0 + tile, region.x1), y1 = std::min(y0 + tile, region.y1);
    const int w = x1 - x0;
    Rasterizer rasterizer(camera.width(), camera.height());
    rasterizer.set_region(x0, y0, x1, y1);
    rasterizer.clear_depth();
    std::vector<Color> colors(std::size_t(w) * (y1 - y0));
    std::vector<bool> covered(colors.size(), false);
    for (std::size_t q = 0; q < elements.size(); ++q) {
      const ScreenBounds& box = bounds_on_screen[q];
      if (box.upper_x < x0 || box.lower_x > x1 || box.upper_y < y0 || box.lower_y > y1) continue;  // misses the tile
      rasterizer.draw_triangle(triangles[q][0], triangles[q][1], triangles[q][2], 3, [&](const Fragment& fragment) {
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
            covered[pixel] ? colors[pixel] : scene.background_along(camera.generate_ray(x + 0.5, y + 0.5).direction);
      }
  });
}

}  // namespace

RadiositySolveResult solve_radiosity(const Scene& scene, bool quiet) { return solve_with_statistics(scene, quiet, nullptr); }

void RadiosityMethod::render(const Scene& scene, const RenderRequest& request, Film& film,
                             RunStatistics& statistics) const {
  nlohmann::json facts;
  const RadiositySolveResult solution = solve_with_statistics(scene, request.quiet, &facts);
  const PixelRect region = request.region;
  const Camera& camera = *scene.camera;
  Stopwatch display_time;
  if (scene.radiosity.display == RadiosityDisplay::gouraud) {
    display_gouraud(scene, solution, region, film);
  } else {
    // Display: the radiosity of the element each pixel's ray hits (view independent: B itself).
    tbb::parallel_for(region.y0, region.y1, [&](int y) {
      for (int x = region.x0; x < region.x1; ++x) {
        const Ray ray = camera.generate_ray(x + 0.5, y + 0.5);
        Intersection hit;
        Color color;
        if (scene.intersect(ray, hit)) {
          const uint32_t element = solution.mesh.element_at(hit.primitive, hit.surface.position);
          color = element == UINT32_MAX ? Color() : solution.element_radiosity[element];
        } else {
          color = scene.background_along(ray.direction);
        }
        film.at(x - region.x0, y - region.y0) = color;
      }
    });
  }
  const auto pixel_count = static_cast<uint64_t>(region.width()) * region.height();
  if (scene.radiosity.display == RadiosityDisplay::flat) statistics.rays.primary += pixel_count;  // rasterized: none
  statistics.pixels += pixel_count;
  facts["display"] = scene.radiosity.display == RadiosityDisplay::gouraud ? "gouraud" : "flat";
  facts["display_seconds"] = display_time.seconds();
  statistics.extra["radiosity"] = std::move(facts);
}

}  // namespace candela
