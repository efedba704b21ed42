// The Python module `candela`: scenes loaded with the command line's overrides, rendered
// by any method into NumPy arrays, written, compared and probed — what a researcher's notebook
// needs (Mitsuba 3's load_file / render). The arrays are what `candela render -o x.pfm` writes:
// linear RGB after the scene's film.exposure, float32, H × W × 3, row 0 at the top.
//
// Bad input raises candela.InputError (a ValueError) with the command line's message
// ("file:line:column: json.path: what was expected") and its parts as attributes. A render runs
// on a worker thread with the GIL released; the calling thread looks at Python's signals every
// 50 ms, so Ctrl-C stops the method at its next coarse point (util/cancellation.h) and raises
// KeyboardInterrupt once it has stopped. No function writes to a Scene, so several Python
// threads may render (probe, solve) one Scene at once, each getting what the same call alone gives.
#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <tbb/global_control.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "camera/tone_map.h"
#include "integrators/antialiasing_support.h"
#include "integrators/memory_estimate.h"
#include "integrators/method_registry.h"
#include "integrators/probe.h"
#include "integrators/scene_loading.h"
#include "io/image_reader.h"
#include "io/image_writer.h"
#include "math/direction.h"
#include "util/cancellation.h"
#include "util/error.h"
#include "validate/image_comparison.h"

namespace py = pybind11;

namespace candela {
namespace {

// Arrays as the functions take them: any sequence of numbers NumPy can convert (lists too).
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
using BoolArray = py::array_t<bool, py::array::c_style | py::array::forcecast>;

// candela.InputError, made when the module is imported.
PyObject* input_error_type = nullptr;

// Keyword arguments as the command line's --set assignments: each value as JSON (Python's json
// module), so 64 is a number, "bvh" a string and [1, 2, 3] an array.
std::vector<std::string> overrides_from(const py::kwargs& overrides) {
  std::vector<std::string> assignments;
  const py::object dumps = py::module_::import("json").attr("dumps");
  for (const auto& [key, value] : overrides)
    assignments.push_back(py::str(key).cast<std::string>() + "=" + dumps(value).cast<std::string>());
  return assignments;
}

// The runs in progress (run_interruptibly), from every Python thread; read and written with the
// GIL held.
int runs_in_progress = 0;

// Runs work() on a worker thread while this (Python's) thread, without the GIL, looks at its
// signals every 50 ms: on Ctrl-C the run is asked to stop (request_cancellation) and, once it has,
// KeyboardInterrupt is raised instead of its result. The cancellation flag is one for the
// process, so with runs from several Python threads at once it is cleared only when none is in
// progress (a run starting does not undo another's Ctrl-C), and a run it cut short raises
// KeyboardInterrupt too rather than return a part of its image.
template <class Result, class Work>
Result run_interruptibly(Work&& work) {
  // Counted for the whole call, whatever leaves it (a thread that cannot start included).
  struct RunInProgress {
    RunInProgress() {
      if (runs_in_progress++ == 0) reset_cancellation();
    }
    ~RunInProgress() {
      if (--runs_in_progress == 0) reset_cancellation();
    }
    RunInProgress(const RunInProgress&) = delete;
    RunInProgress& operator=(const RunInProgress&) = delete;
  } counted;
  std::optional<Result> result;
  std::exception_ptr error;
  std::mutex mutex;
  std::condition_variable finished;
  bool done = false;
  std::thread worker([&] {
    try {
      result.emplace(work());
    } catch (...) {
      error = std::current_exception();
    }
    const std::lock_guard lock(mutex);
    done = true;
    finished.notify_all();
  });
  bool interrupted = false;
  for (;;) {
    bool stopped = false;
    {
      const py::gil_scoped_release release;
      std::unique_lock lock(mutex);
      stopped = finished.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; });
    }
    if (stopped) break;
    if (!interrupted && PyErr_CheckSignals() != 0) {  // the KeyboardInterrupt is now pending
      interrupted = true;
      request_cancellation();
    }
  }
  worker.join();
  const bool cut_short = cancel_requested();
  if (interrupted) throw py::error_already_set();
  if (error) std::rethrow_exception(error);
  if (cut_short) {  // another thread's Ctrl-C
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
  }
  return std::move(*result);
}

// float32 H × W × 3 of the film's pixels after 2^exposure, as the PFM and EXR writers store them.
py::array_t<float> array_of(const Film& film, double exposure) {
  const std::vector<Color> pixels = expose(film, exposure);
  py::array_t<float> array({py::ssize_t(film.height()), py::ssize_t(film.width()), py::ssize_t(3)});
  auto view = array.mutable_unchecked<3>();
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x)
      for (int c = 0; c < 3; ++c)
        view(y, x, c) = static_cast<float>(pixels[std::size_t(y) * film.width() + x][c]);
  return array;
}

// An H × W × 3 (or H × W, grey) array of numbers as a film.
Film film_of(const DoubleArray& values, const char* name) {
  if ((values.ndim() != 3 && values.ndim() != 2) || (values.ndim() == 3 && values.shape(2) != 3))
    throw py::value_error(std::string(name) +
                          ": expected an array of shape (height, width, 3) or (height, width)");
  const int height = int(values.shape(0)), width = int(values.shape(1));
  if (width < 1 || height < 1) throw py::value_error(std::string(name) + ": the image is empty");
  Film film(width, height);
  const double* data = values.data();
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t i = std::size_t(y) * width + x;
      film.at(x, y) =
          values.ndim() == 3 ? Color(data[3 * i], data[3 * i + 1], data[3 * i + 2]) : Color(data[i]);
    }
  return film;
}

py::array_t<double> rows_of(const std::vector<Color>& colors) {
  py::array_t<double> array({py::ssize_t(colors.size()), py::ssize_t(3)});
  auto view = array.mutable_unchecked<2>();
  for (std::size_t i = 0; i < colors.size(); ++i)
    for (int c = 0; c < 3; ++c) view(py::ssize_t(i), c) = colors[i][c];
  return array;
}

std::vector<Vec3> vectors_of(const DoubleArray& values, const char* name) {
  if (values.ndim() != 2 || values.shape(1) != 3)
    throw py::value_error(std::string(name) + ": expected an array of shape (n, 3)");
  std::vector<Vec3> vectors;
  for (py::ssize_t i = 0; i < values.shape(0); ++i)
    vectors.push_back({values.at(i, 0), values.at(i, 1), values.at(i, 2)});
  return vectors;
}

std::shared_ptr<Scene> load_file(const std::string& path, const py::kwargs& overrides) {
  return load_scene_file(path, overrides_from(overrides));
}

// The scene is only read — this render's seed and anti-aliasing samples go down in the
// RenderRequest — so that renders of one Scene from several Python threads (the GIL is released
// while they run) are each what the same render alone gives, and the Scene stays as it was.
py::array_t<float> render(const Scene& scene, std::optional<std::string> method_name, std::optional<int> spp,
                          int threads, std::optional<uint64_t> seed) {
  const std::string name = method_name.value_or(scene.render.method);
  const MethodEntry* entry = find_method(name);
  if (!entry)
    throw py::value_error("unknown method '" + name + "' (expected one of: " + method_names() + ")");
  if (threads < 0) throw py::value_error("threads must be >= 0 (0: all cores)");
  // spp: the path tracer's passes; every other method's n×n anti-aliasing samples, as --spp.
  std::vector<std::string> settings;
  std::optional<AntialiasingSettings> antialiasing;
  bool choose_mode = false;
  if (spp && entry->capabilities.progressive_passes) {
    if (*spp < 1) throw py::value_error("spp must be >= 1");
    settings.push_back("spp=" + std::to_string(*spp));
  } else if (spp) {
    antialiasing = scene.antialiasing;
    try {
      choose_mode = set_samples_per_pixel(*antialiasing, entry->name, *spp);
    } catch (const std::invalid_argument& e) {
      throw py::value_error(std::string("spp ") + e.what());
    }
  }
  const std::unique_ptr<Method> method =
      create_method(*entry, scene, settings, antialiasing ? *antialiasing : scene.antialiasing);
  if (choose_mode) choose_jittered_where_possible(*antialiasing, scene, *method);
  RenderRequest request;
  request.region = {0, 0, scene.camera->width(), scene.camera->height()};
  request.quiet = true;
  request.seed = seed;
  request.antialiasing = antialiasing;
  std::optional<tbb::global_control> thread_limit;
  if (threads > 0) thread_limit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  Film film = run_interruptibly<Film>([&] {
    // Refused before any work, as the CLI; without the GIL (it counts triangles).
    refuse_beyond_memory_limit(*method, scene, request);
    return std::move(method->render(scene, request).film);
  });
  return array_of(film, scene.display.exposure);
}

void write_image_file(const std::string& path, const DoubleArray& image) {
  ImageFormat format;
  if (!image_format_for_path(path, format))
    throw py::value_error("cannot write '" + path + "': the extension is not " + kImageExtensions);
  const Film film = film_of(image, "image");
  const DisplaySettings display;
  if (const std::string problem = non_finite_image_problem(film, format, display.exposure); !problem.empty())
    throw py::value_error(problem);
  write_image(film, path, display);
}

// A pixel no image file holds — not finite, or beyond the largest float (3.4e38), whose
// square overflows the metrics' sums (±1e308) — is refused naming the array, the pixel and the
// value, as `candela compare` refuses such a file (read_linear_image), rather than metrics of NaN
// and a max error of −1. The first such pixel, row by row.
void refuse_values_beyond_float(const Film& film, const char* name) {
  const double largest = static_cast<double>(std::numeric_limits<float>::max());
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x)
      for (int c = 0; c < 3; ++c) {
        const double value = film.at(x, y)[c];
        if (std::isfinite(value) && std::abs(value) <= largest) continue;
        throw py::value_error(fmt::format(
            "{}: pixel ({}, {}) channel {} is {:g}: compare takes finite values within the float range "
            "(|v| <= 3.4e38), as image files hold them",
            name, x, y, c, value));
      }
}

// The metrics of `candela compare` (validate/image_comparison.h), with its JSON's names; infinite
// values (psnr_db of identical images, luminance_ratio against black) as float infinities.
py::dict compare(const DoubleArray& image, const DoubleArray& reference,
                 const std::optional<BoolArray>& mask) {
  const Film a = film_of(image, "image"), b = film_of(reference, "reference");
  refuse_values_beyond_float(a, "image");
  refuse_values_beyond_float(b, "reference");
  std::optional<std::vector<uint8_t>> included;
  if (mask) {
    if (mask->ndim() != 2 || mask->shape(0) != b.height() || mask->shape(1) != b.width())
      throw py::value_error("mask: expected a boolean array of the images' (height, width)");
    included.emplace(mask->data(), mask->data() + mask->size());
  }
  const ImageComparison result = compare_images(a, b, included ? &*included : nullptr);
  // to_json's names and values, but infinities as floats (its JSON writes them as text).
  py::dict metrics = py::module_::import("json").attr("loads")(result.to_json().dump());
  metrics["psnr_db"] = result.psnr;
  metrics["luminance_ratio"] = result.luminance_ratio;
  return metrics;
}

py::dict probe_points(const Scene& scene, const DoubleArray& points, const DoubleArray& normals,
                      const std::string& method, int samples, std::optional<uint64_t> seed, int threads) {
  const std::vector<Vec3> positions = vectors_of(points, "points"),
                          directions = vectors_of(normals, "normals");
  if (positions.size() != directions.size())
    throw py::value_error("points and normals: " + std::to_string(positions.size()) + " points but " +
                          std::to_string(directions.size()) + " normals");
  // As `candela probe --points` reads its file (read_probe_points): every value finite
  // (a NaN point gave zeros), and a normal any non-zero vector, normalised by direction_of (a huge
  // but finite one too).
  std::vector<ProbePoint> sensors;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (!is_finite(positions[i]))
      throw py::value_error(fmt::format("points[{}]: ({:g}, {:g}, {:g}): every value must be finite", i,
                                        positions[i].x, positions[i].y, positions[i].z));
    if (!is_finite(directions[i]))
      throw py::value_error(fmt::format("normals[{}]: ({:g}, {:g}, {:g}): every value must be finite", i,
                                        directions[i].x, directions[i].y, directions[i].z));
    const std::optional<Vec3> normal = direction_of(directions[i]);
    if (!normal) throw py::value_error(fmt::format("normals[{}]: the normal must not be zero", i));
    sensors.push_back({positions[i], *normal});
  }
  ProbeSettings settings;
  settings.method = method;
  settings.samples = samples;
  settings.seed = seed.value_or(scene.render.seed);  // as candela probe's --seed
  if (threads < 0) throw py::value_error("threads must be >= 0 (0: all cores)");
  std::optional<tbb::global_control> thread_limit;
  if (threads > 0) thread_limit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  const std::vector<ProbeResult> results =
      run_interruptibly<std::vector<ProbeResult>>([&] { return probe(scene, sensors, settings); });
  std::vector<Color> irradiance, radiance;
  py::array_t<double> error(py::ssize_t(results.size()));
  for (std::size_t i = 0; i < results.size(); ++i) {
    irradiance.push_back(results[i].irradiance);
    radiance.push_back(results[i].radiance);
    error.mutable_at(py::ssize_t(i)) = results[i].irradiance_error;
  }
  py::dict out;
  out["irradiance"] = rows_of(irradiance);
  out["radiance"] = rows_of(radiance);
  out["irradiance_standard_error"] = error;
  return out;
}

// A method's view-independent solution of the scene (Method::solve_alone), made from the scene's
// settings as render makes the method: its arrays by name — one column flat, indices as uint32 —
// and under "facts" what the solve measured (the method's facts of render --stats).
py::dict solution(const Scene& scene, const std::string& method_name, int threads) {
  const MethodEntry* entry = find_method(method_name);
  if (!entry || !entry->capabilities.standalone_solution)
    throw py::value_error(
        fmt::format("method '{}' has no view-independent solution (expected one of: {})", method_name,
                    fmt::join(method_names_with(&MethodCapabilities::standalone_solution), ", ")));
  if (threads < 0) throw py::value_error("threads must be >= 0 (0: all cores)");
  const std::unique_ptr<Method> method = create_method(*entry, scene);
  std::optional<tbb::global_control> thread_limit;
  if (threads > 0) thread_limit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  const StandaloneSolution solved =
      run_interruptibly<StandaloneSolution>([&] { return method->solve_alone(scene, true); });
  py::dict out;
  for (const StandaloneSolution::Array& array : solved.arrays) {
    std::vector<py::ssize_t> shape{py::ssize_t(array.rows())};
    if (array.columns > 1) shape.push_back(py::ssize_t(array.columns));
    if (array.indices) {
      py::array_t<uint32_t> values(shape);
      uint32_t* data = values.mutable_data();
      for (std::size_t i = 0; i < array.values.size(); ++i) data[i] = static_cast<uint32_t>(array.values[i]);
      out[py::str(array.name)] = values;
    } else {
      py::array_t<double> values(shape);
      std::copy(array.values.begin(), array.values.end(), values.mutable_data());
      out[py::str(array.name)] = values;
    }
  }
  out["facts"] = py::module_::import("json").attr("loads")(solved.facts.dump());
  return out;
}

}  // namespace
}  // namespace candela

PYBIND11_MODULE(candela, module) {
  using namespace candela;
  module.doc() =
      "Candela's renderer from Python: load_file, render (NumPy arrays, linear RGB), write_image, "
      "read_image, compare, probe, solution.\n\n"
      "Thread safety: no function changes a Scene (render's method, spp and seed are that render's "
      "alone), and the GIL is released while one runs, so several Python threads may render, probe or "
      "solve one Scene at once; each result equals the same call made alone.";
  static py::exception<InputError> input_error(module, "InputError", PyExc_ValueError);
  input_error_type = input_error.ptr();
  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const InputError& e) {
      py::object exception = py::reinterpret_borrow<py::object>(input_error_type)(e.what());
      exception.attr("file") = e.location().file;
      exception.attr("line") = e.location().line;
      exception.attr("column") = e.location().column;
      exception.attr("json_path") = e.location().json_path;
      exception.attr("message") = e.message();
      PyErr_SetObject(input_error_type, exception.ptr());
    }
  });

  py::class_<Scene, std::shared_ptr<Scene>>(module, "Scene", "A loaded scene (candela/1 JSON).")
      .def_property_readonly("width", [](const Scene& scene) { return scene.camera->width(); })
      .def_property_readonly("height", [](const Scene& scene) { return scene.camera->height(); })
      .def_property_readonly(
          "method", [](const Scene& scene) { return scene.render.method; },
          "The scene's own method (render.method).")
      .def_property_readonly("source", [](const Scene& scene) { return scene.source; })
      .def("__repr__", [](const Scene& scene) {
        return "<candela.Scene " + scene.source + " " + std::to_string(scene.camera->width()) + "x" +
               std::to_string(scene.camera->height()) + ">";
      });

  module.def("load_file", &load_file, py::arg("path"),
             "Loads a scene file; keyword arguments are --set overrides with dots spelled out: "
             "load_file(path, **{'camera.width': 64}).");
  module.def(
      "render", &render, py::arg("scene"), py::kw_only(), py::arg("method") = py::none(),
      py::arg("spp") = py::none(), py::arg("threads") = 0, py::arg("seed") = py::none(),
      "Renders the scene by a method (default: the scene's) into a float32 array (height, width, 3) of "
      "linear RGB, what `candela render -o image.pfm` writes. spp: passes of the path tracer, n×n "
      "anti-aliasing samples of the others (as --spp); threads: 0 for "
      "all cores; seed: this render's (default render.seed). The Scene is not changed: renders of one "
      "Scene from several threads at once are thread-safe, each the image the same render alone gives.");
  module.def("write_image", &write_image_file, py::arg("path"), py::arg("image"),
             "Writes an array (height, width, 3) to .exr or .pfm (linear) or .png (tone-mapped sRGB).");
  module.def(
      "read_image",
      [](const std::string& path) {
        const LinearImage image = read_linear_image(path);
        return array_of(image.film, 0);
      },
      py::arg("path"), "Reads an .exr, .pfm or .hdr file (or an 8-bit image, decoded to linear) as float32.");
  module.def("compare", &compare, py::arg("image"), py::arg("reference"), py::arg("mask") = py::none(),
             "The metrics of `candela compare` (rmse, relative_mse, psnr, ...) as a dict; mask: a boolean "
             "(height, width) array of the pixels that count. A value that is not finite or beyond the "
             "float range (3.4e38) raises ValueError naming the array, the pixel and the value.");
  module.def("solution", &solution, py::arg("scene"), py::arg("method"), py::kw_only(),
             py::arg("threads") = 0,
             "A method's view-independent solution of the scene, made from its settings: its arrays by name "
             "((n,) or (n, 3); indices uint32; docs/python.md lists each method's) and 'facts' (what the "
             "solve measured, as render --stats). A method without one raises ValueError naming those "
             "with one.");
  module.def("probe", &probe_points, py::arg("scene"), py::arg("points"), py::arg("normals"), py::kw_only(),
             py::arg("method") = std::string(kReferenceMethod), py::arg("samples") = 256,
             py::arg("seed") = py::none(), py::arg("threads") = 0,
             "Irradiance (n, 3), radiance (n, 3) and the irradiance's standard error (n) at sensor points "
             "(n, 3) facing normals (n, 3), as `candela probe`. A point or normal that is not finite, or a "
             "zero normal, raises ValueError naming its index.");
}
