// Renders a whole scene with a method by name, on at most `threads` threads (the tests that
// compare images across methods and thread counts).
#pragma once

#include <tbb/global_control.h>

#include <string>

#include "integrators/method_registry.h"
#include "scene/scene.h"

namespace candela::testing {

// A render in the tests' usual shape: the image into film, the statistics added to statistics.
inline void render_into(const Method& method, const Scene& scene, const RenderRequest& request, Film& film,
                        RunStatistics& statistics) {
  RenderResult result = method.render(scene, request);
  film = std::move(result.film);
  statistics.absorb(std::move(result.statistics));
}

inline Film render_scene(const Scene& scene, const std::string& method_name, std::size_t threads,
                         RunStatistics& statistics) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  const auto method = create_method(*find_method(method_name), scene);
  Film film(scene.camera->width(), scene.camera->height());
  render_into(*method, scene, {{0, 0, film.width(), film.height()}, true}, film, statistics);
  return film;
}

inline Film render_scene(const Scene& scene, const std::string& method_name, std::size_t threads = 2) {
  RunStatistics statistics;
  return render_scene(scene, method_name, threads, statistics);
}

}  // namespace candela::testing
