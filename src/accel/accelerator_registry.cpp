#include "accel/accelerator_registry.h"

#include <array>

#include "accel/bvh.h"
#include "accel/octree.h"
#include "accel/primitive_list.h"
#include "accel/uniform_grid.h"
#ifdef CANDELA_HAVE_EMBREE
#include "accel/embree_accelerator.h"
#endif

#include "util/registry.h"

namespace candela {

namespace {

template <typename Made>
std::unique_ptr<Accelerator> finished(const JsonNode& settings, std::unique_ptr<Made> accelerator) {
  settings.finish();  // unknown keys refused, naming the valid ones
  return accelerator;
}

// The "bvh" and "bvh-fast" objects (the same keys).
BvhSettings read_bvh_settings(const JsonNode& settings, bool exact) {
  settings.expect_object();
  BvhSettings bvh;
  // 0: automatic (8 for a mesh-only scene, 4 with other shapes)
  bvh.max_leaf_primitives = settings.integer("max_leaf_primitives", 0, {0, 64, false, false});
  bvh.bins = settings.integer("bins", BvhSettings{}.bins, {2, 256, false, false});
  // the traversal's instruction set: auto = the widest this CPU supports
  bvh.isa = settings.enumeration("isa", BvhIsa::automatic, kBvhIsaNames);
  if (static_cast<int>(bvh.isa) > static_cast<int>(widest_bvh_isa()))
    settings.at("isa").fail("this CPU does not support " + std::string(kBvhIsaNames.name(bvh.isa)) +
                            " (the widest it supports is " +
                            std::string(kBvhIsaNames.name(widest_bvh_isa())) + ")");
  bvh.exact = exact;
  return bvh;
}

const std::array kAcceleratorEntries = {
    AcceleratorEntry{
        "list", "brute force: every ray against every primitive",
        [](const JsonNode& settings, BoundingVolumeKind object_volume) -> std::unique_ptr<Accelerator> {
          settings.expect_object();
          return finished(settings, std::make_unique<PrimitiveList>(object_volume));
        }},
    AcceleratorEntry{"grid", "uniform grid: L×M×N voxels from the object count, 3D-DDA traversal",
                     [](const JsonNode& settings, BoundingVolumeKind) -> std::unique_ptr<Accelerator> {
                       settings.expect_object();
                       // voxels ≈ density × primitives (Cleary & Wyvill; Woo)
                       const double density = settings.number("density", 3.0, {0, 1000, true, false});
                       return finished(settings, std::make_unique<UniformGrid>(density));
                     }},
    AcceleratorEntry{
        "octree", "octree: split while a voxel holds more than K objects, ordered traversal",
        [](const JsonNode& settings, BoundingVolumeKind) -> std::unique_ptr<Accelerator> {
          settings.expect_object();
          // K: subdivide a voxel holding more; D: the depth at most (000 §5.7.2)
          const int max_primitives = settings.integer("max_primitives", 8, {1, 1 << 20, false, false});
          const int max_depth = settings.integer("max_depth", 10, {0, 32, false, false});
          return finished(settings, std::make_unique<Octree>(max_primitives, max_depth));
        }},
    AcceleratorEntry{"bvh", "bounding volume hierarchy: binned SAH build, ordered traversal",
                     [](const JsonNode& settings, BoundingVolumeKind) -> std::unique_ptr<Accelerator> {
                       return finished(settings, std::make_unique<Bvh>(read_bvh_settings(settings, true)));
                     }},
    // The BVH with float Möller–Trumbore leaf tests, outside the exact contract.
    AcceleratorEntry{"bvh-fast",
                     "the bvh with Embree-like float triangle tests: faster, not exact (hits differ from the "
                     "list's in float's last bits, edges are not watertight)",
                     [](const JsonNode& settings, BoundingVolumeKind) -> std::unique_ptr<Accelerator> {
                       return finished(settings, std::make_unique<Bvh>(read_bvh_settings(settings, false)));
                     },
                     false},
#ifdef CANDELA_HAVE_EMBREE
    AcceleratorEntry{"embree", "Embree's BVH over the primitives' bounds, hits from Candela's exact tests",
                     [](const JsonNode& settings, BoundingVolumeKind) -> std::unique_ptr<Accelerator> {
                       settings.expect_object();
                       return finished(settings, std::make_unique<EmbreeAccelerator>());
                     }},
#endif
};

}  // namespace

std::span<const AcceleratorEntry> accelerator_entries() {
  return kAcceleratorEntries;
}

const AcceleratorEntry* find_accelerator(std::string_view name) {
  return find_entry<AcceleratorEntry>(kAcceleratorEntries, name);
}

std::unique_ptr<Accelerator> create_default_accelerator(const AcceleratorEntry& entry,
                                                        BoundingVolumeKind object_volume) {
  const JsonDocument defaults = JsonDocument::parse("{}", "<defaults>");
  return entry.create(JsonNode(defaults, defaults.root(), std::string(entry.name)), object_volume);
}

}  // namespace candela
