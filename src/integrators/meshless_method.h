// The `meshless` method (SPEC §11; seed 002, after Lehtinen et al. 2008): the solution of
// meshless/meshless_solve.h — sites, basis, effective areas, transfer matrix, then per light set-up
// η and λ ← η + Rλ — drawn as meshless/meshless_display.h says, the geometry kept between renders
// of one scene (other views, --relight), the sites drawn on request (seed 002 Figure 4.7).
#pragma once

#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>

#include "integrators/method.h"
#include "meshless/meshless_solve.h"
#include "util/error.h"

namespace candela {

struct MeshlessSolution {
  SiteSet sites;
  std::vector<Color> eta;     // η: emitted and directly reflected
  TransferSolution transfer;  // λ
  TransferMatrix matrix;      // S
  std::vector<double> areas;  // A_k, the effective areas
};

// Samples, builds and solves with the scene's render.seed; fills facts for --stats when given.
// Throws InputError before any work past render.memory_limit_mib.
MeshlessSolution solve_meshless(const Scene& scene, const MeshlessSettings& settings,
                                nlohmann::json* facts = nullptr);

// Keeps the last scene's geometry (recognised by Scene::unique_id, the settings that shape it and
// the render's seed) and reuses it when called again for the same scene: other views, or other
// lights (candela render --relight, which swaps the scene's lights between renders).
class MeshlessMethod final : public Method {
 public:
  explicit MeshlessMethod(const MeshlessSettings& settings = {}) : settings_(settings) {}
  std::string_view name() const override { return "meshless"; }
  const MeshlessSettings& settings() const { return settings_; }
  RenderResult render(const Scene& scene, const RenderRequest& request) const override;
  // The image, the sites and, with integrated effective areas, the tessellated surfaces.
  std::vector<MemoryPart> memory_needed(const Scene& scene, const RenderRequest& request) const override;
  // The global display's field, gathered over the hemisphere (integrators/probe.h).
  std::unique_ptr<PointProbe> point_probe(const Scene& scene, const ProbeSettings& settings) const override;
  // The sites (positions, normals) with their λ, η, effective areas and objects, and the facts.
  StandaloneSolution solve_alone(const Scene& scene, bool quiet) const override;

 private:
  std::shared_ptr<const MeshlessGeometry> geometry_for(const Scene& scene, uint64_t seed, bool& reused,
                                                       Cluster* cluster, bool quiet) const;
  MeshlessSettings settings_;
  mutable std::mutex cache_mutex_;
  mutable std::shared_ptr<const MeshlessGeometry> cached_;
  mutable std::string cached_key_;
};

}  // namespace candela
