// What a render will hold, estimated before any work, and its refusal past the limit
// (SPEC §15: a valid scene must not exhaust the machine — meshless on the 10,584-sphere field grew
// past 24 GB in two minutes). Each method says what it holds (Method::memory_needed); the limit is
// render.memory_limit_mib, half the machine's memory by default (util/memory.h). Radiosity's
// form factors keep their own, finer checks (radiosity/form_factor_memory.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "integrators/method.h"

namespace candela {

// The bytes of `copies` films of the region's pixels.
uint64_t film_bytes(const PixelRect& region, int copies);
// A part held per pixel of the image (`what` names it): made smaller by the image's size.
MemoryPart image_memory_part(std::string what, uint64_t bytes);

// Throws InputError (bad input: exit 2, nothing written) when the parts of a render of the request
// (its region, and its seed and aa settings where it gives them) add up to more than the
// scene's render.memory_limit_mib allows: the message gives the total, the parts largest first, the
// largest part's setting and remedy, and render.memory_limit_mib; it is located at the largest
// part's setting (or at render.memory_limit_mib where the scene sets it).
void refuse_beyond_memory_limit(const Method& method, const Scene& scene, const RenderRequest& request);

}  // namespace candela
