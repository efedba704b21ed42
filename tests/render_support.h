// Renders a whole scene with a method by name, on at most `threads` threads (the tests that
// compare images across methods and thread counts).
#pragma once

#include <tbb/global_control.h>

#include <string>

#include "integrators/method_registry.h"
#include "scene/scene.h"

namespace candela::testing {

inline Film render_scene(const Scene& scene, const std::string& method_name, std::size_t threads,
                         RunStatistics& statistics) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  const auto method = find_method(method_name)->create();
  Film film(scene.camera->width(), scene.camera->height());
  method->render(scene, {{0, 0, film.width(), film.height()}, true}, film, statistics);
  return film;
}

inline Film render_scene(const Scene& scene, const std::string& method_name, std::size_t threads = 2) {
  RunStatistics statistics;
  return render_scene(scene, method_name, threads, statistics);
}

}  // namespace candela::testing
