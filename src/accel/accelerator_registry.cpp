#include "accel/accelerator_registry.h"

#include <array>

#include "accel/primitive_list.h"
#include "accel/uniform_grid.h"
#include "accel/octree.h"
#include "accel/bvh.h"
#ifdef CANDELA_HAVE_EMBREE
#include "accel/embree_accelerator.h"
#endif

#include "util/registry.h"

namespace candela {

namespace {
const std::array kEntries = {
    AcceleratorEntry{"list", "brute force: every ray against every primitive",
                     [](const AcceleratorSettings& settings) -> std::unique_ptr<Accelerator> {
                       return std::make_unique<PrimitiveList>(settings.bounding_volume);
                     }},
    AcceleratorEntry{"grid", "uniform grid: L×M×N voxels from the object count, 3D-DDA traversal",
                     [](const AcceleratorSettings& settings) -> std::unique_ptr<Accelerator> {
                       return std::make_unique<UniformGrid>(settings.grid_density);
                     }},
    AcceleratorEntry{"octree", "octree: split while a voxel holds more than K objects, ordered traversal",
                     [](const AcceleratorSettings& settings) -> std::unique_ptr<Accelerator> {
                       return std::make_unique<Octree>(settings.octree_max_primitives, settings.octree_max_depth);
                     }},
    AcceleratorEntry{"bvh", "bounding volume hierarchy: binned SAH build, ordered traversal",
                     [](const AcceleratorSettings& settings) -> std::unique_ptr<Accelerator> {
                       return std::make_unique<Bvh>(settings);
                     }},
#ifdef CANDELA_HAVE_EMBREE
    AcceleratorEntry{"embree", "Embree's BVH over the primitives' bounds, hits from Candela's exact tests",
                     [](const AcceleratorSettings&) -> std::unique_ptr<Accelerator> {
                       return std::make_unique<EmbreeAccelerator>();
                     }},
#endif
};
}  // namespace

std::span<const AcceleratorEntry> accelerator_entries() { return kEntries; }

const AcceleratorEntry* find_accelerator(std::string_view name) { return find_entry<AcceleratorEntry>(kEntries, name); }

}  // namespace candela
