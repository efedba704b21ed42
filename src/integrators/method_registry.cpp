#include "integrators/method_registry.h"

#include <array>
#include <string>

#include "integrators/local.h"
#include "integrators/meshless_method.h"
#include "integrators/path_tracer.h"
#include "integrators/radiosity_method.h"
#include "integrators/raster_method.h"
#include "integrators/whitted.h"

#include "util/registry.h"

namespace candela {

namespace {
const std::array kEntries = {
    MethodEntry{"local", "ray casting with the local model only (001, 000 §2)",
                []() -> std::unique_ptr<Method> { return std::make_unique<LocalMethod>(); }},
    MethodEntry{"whitted", "recursive Whitted ray tracing (000 §5, 001)",
                []() -> std::unique_ptr<Method> { return std::make_unique<WhittedMethod>(); }},
    MethodEntry{"raster", "scanline z-buffer rasterizer, flat / Gouraud / Phong / dot-product shading (000 §3)",
                []() -> std::unique_ptr<Method> { return std::make_unique<RasterMethod>(); }},
    MethodEntry{"radiosity", "classic radiosity: hemicube form factors, progressive refinement with substructuring (000 §6)",
                []() -> std::unique_ptr<Method> { return std::make_unique<RadiosityMethod>(); }},
    MethodEntry{"meshless", "meshless finite-element radiosity: sites, radial / normalized / Shepard bases (002)",
                []() -> std::unique_ptr<Method> { return std::make_unique<MeshlessMethod>(); }},
    MethodEntry{"path", "path-traced reference: next-event estimation, MIS, Russian roulette, progressive passes (SPEC §12)",
                []() -> std::unique_ptr<Method> { return std::make_unique<PathMethod>(); }},
};
}  // namespace

std::span<const MethodEntry> method_entries() { return kEntries; }

const MethodEntry* find_method(std::string_view name) { return find_entry<MethodEntry>(kEntries, name); }

std::string method_names() { return entry_names<MethodEntry>(kEntries); }

}  // namespace candela
