#include "radiosity/radiosity_settings.h"

namespace candela {

RadiositySettings read_radiosity_settings(const JsonNode& node) {
  RadiositySettings settings;
  node.expect_object();
  settings.solver = node.enumeration("solver", settings.solver, kRadiositySolverNames);
  settings.form_factors = node.enumeration("form_factors", settings.form_factors, kRadiosityFormFactorNames);
  settings.ray_cast_samples = node.integer("ray_cast_samples", 4, {1, 64, false, false});
  // 1024: 12 MiB of item buffers per thread; the error falls as 1/R² (000 §6.4), so more buys nothing.
  settings.hemicube_resolution = node.integer("hemicube_resolution", 100, {2, 1024, false, false});
  if (settings.hemicube_resolution % 2 != 0)
    node.at("hemicube_resolution").fail("hemicube_resolution must be even");
  settings.patch_size = node.number("patch_size", 0.0, Range::non_negative());
  settings.element_size = node.number("element_size", 0.0, Range::non_negative());
  if (settings.patch_size > 0 && settings.element_size > settings.patch_size)
    node.at("element_size").fail("element_size must not exceed patch_size");
  settings.segments = node.integer("segments", 16, {3, 4096, false, false});
  // 0: no threshold, max_steps shots or sweeps (the docs said [0, 1), the code refused 0).
  settings.threshold = node.number("threshold", 0.001, Range::unit());
  settings.max_steps = node.integer("max_steps", 100000, {1, 1 << 30, false, false});
  settings.ambient = node.boolean("ambient", true);
  settings.display = node.enumeration("display", settings.display, kRadiosityDisplayNames);
  settings.subdivision_threshold = node.number("subdivision_threshold", 0.0, Range::unit());
  // Hierarchical radiosity (the default) refines by its own oracle; a scene asking for the
  // classic solvers' adaptive subdivision is told so rather than have it ignored.
  if (settings.subdivision_threshold > 0 && settings.solver == RadiositySolver::hierarchical)
    node.at("subdivision_threshold")
        .fail(
            "subdivision_threshold is adaptive subdivision for the classic solvers: set radiosity.solver to "
            "\"progressive\", \"gauss-seidel\" or \"gaussian\" (the hierarchical solver, the default, "
            "refines "
            "by radiosity.refinement_tolerance)");
  settings.min_element_size = node.number("min_element_size", 0.0, Range::non_negative());
  // The element size the mesh will use when one is given (element_size, else patch_size / 2).
  const double element_size = settings.element_size > 0 ? settings.element_size : settings.patch_size / 2;
  if (settings.min_element_size > 0 && element_size > 0 && settings.min_element_size > element_size)
    node.at("min_element_size").fail("min_element_size must not exceed element_size");
  settings.refinement_tolerance =
      node.number("refinement_tolerance", settings.refinement_tolerance, {1e-9, 1, false, false});
  settings.memory_limit_mib = node.number("memory_limit_mib", 0.0, Range::non_negative());
  settings.split_at_contacts = node.boolean("split_at_contacts", false);
  settings.location = node.location();
  for (const char* size : {"min_element_size", "element_size", "patch_size"})
    if (const auto given = node.get(size)) {
      settings.location = given->location();
      break;
    }
  node.finish();
  return settings;
}

}  // namespace candela
