#include "meshless/meshless_settings.h"

namespace candela {

MeshlessSettings read_meshless_settings(const JsonNode& node) {
  MeshlessSettings settings;
  node.expect_object();
  settings.basis = node.enumeration("basis", settings.basis, kBasisNames);
  settings.kernel = node.enumeration("kernel", settings.kernel, kRadialKernelNames);
  settings.spacing = node.number("spacing", settings.spacing, Range::non_negative());
  settings.neighbours = node.integer("neighbours", settings.neighbours, {1, 1000, false, false});
  settings.grid = node.integer("grid", settings.grid, {1, 4096, false, false});
  settings.rounds = node.integer("rounds", settings.rounds, {0, 1000, false, false});
  settings.effective_area = node.enumeration("effective_area", settings.effective_area, kMeshlessAreaNames);
  settings.tolerance = node.number("tolerance", settings.tolerance, {0, 1, true, false});
  settings.max_iterations =
      node.integer("max_iterations", settings.max_iterations, {1, 1 << 20, false, false});
  settings.display = node.enumeration("display", settings.display, kMeshlessDisplayNames);
  settings.shepard_power = node.number("shepard_power", settings.shepard_power, {0, 16, false, false});
  settings.max_sites = node.integer("max_sites", settings.max_sites, {1, 1 << 22, false, false});
  settings.gather_rays = node.integer("gather_rays", settings.gather_rays, {1, 1 << 20, false, false});
  settings.near_field = node.number("near_field", settings.near_field, {0, 100, false, false});
  settings.transport = node.enumeration("transport", settings.transport, kMeshlessTransportNames);
  settings.cluster_angle = node.number("cluster_angle", settings.cluster_angle, {0, 10, false, false});
  settings.location = node.get("spacing") ? node.at("spacing").location() : node.location();
  node.finish();
  return settings;
}

}  // namespace candela
