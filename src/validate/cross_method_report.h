// The cross-method report (SPEC §13 "Cross-method"; `candela report`, docs/report.md): one scene
// rendered by several methods, each image measured against a path-traced reference.
//
// run_cross_method_report renders, in order: the reference (method "path" with path.spp =
// reference_spp, path.time = 0 and its own seed, render.seed XOR kReferenceSeedMix, so that its
// passes are independent of the "path" entry's — with the same seed its first passes would BE the
// entry's and hide the entry's noise), unless a reference image is given; then each method of the
// list over the whole image; then, with equal_time, "path" once for each other method, limited to
// that method's measured render time (path.time = t, path.spp = 0). Every image is written as it
// is done to DIR/<key>.png (sRGB, the scene's display settings) and DIR/<key>.exr (written as
// `candela render -o x.exr` writes it: linear, display.exposure applied); then each image is
// compared with the reference (validate/image_comparison.h), the difference pictures
// DIR/<key>-diff.png are drawn on ONE scale, 0 to the 99th percentile of |Y − Y_ref| over all of
// them (larger values take the top color), and
// DIR/report.json and last DIR/index.html are written (each atomically). A page and report.json
// left in DIR by an earlier run are removed first; a method that fails stops the run with an
// error naming it: no page is written (images already written stay).
//
// Every method's image is in the same units (π × radiance), so the images compare directly.
#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "camera/film.h"
#include "validate/convergence_log.h"
#include "validate/image_comparison.h"

namespace candela {

class Scene;

// The reference's seed is render.seed XOR this ("REFERENC" in ASCII).
inline constexpr uint64_t kReferenceSeedMix = 0x5245464552454e43ULL;

struct CrossMethodOptions {
  std::vector<std::string> methods;  // registered method names, each once
  std::string output_directory;      // must exist
  int reference_spp = 1024;
  // A reference image to use instead of rendering one (the scene's image size, linear values in
  // the units the methods' Films hold, i.e. with display.exposure already undone), and its file.
  std::optional<Film> reference_image;
  std::string reference_file;
  std::optional<int> path_spp;  // the "path" entry's spp (default: the scene's path.spp)
  bool equal_time = false;
  bool quiet = false;  // passed on to the methods (no progress output)
  // Scene description for the page.
  std::string scene_path;
  std::string scene_text;              // the scene file's text (its method objects are shown)
  std::vector<std::string> overrides;  // --set key=value, shown on the page
  int threads = 0;                     // worker threads the run may use
  // > 0 measures the errors in luminance, cd/m² (validate/image_comparison.h's
  // luminance_film at this efficacy, lm/W); 0: on the linear RGB the methods render.
  double luminance_efficacy = 0;
  // The pixels the convergence chart measures (image_comparison.h's mask: the scene's
  // width·height bytes, row by row from the top); empty: every pixel.
  std::vector<uint8_t> convergence_mask;
  // Told one line per step ("rendering radiosity"); may be empty.
  std::function<void(const std::string&)> log;
};

// One image of the report: a method's, or the reference.
struct CrossMethodEntry {
  std::string label;          // "whitted", "path (equal time: radiosity)", "reference"
  std::string method;         // the registered method name ("" for a reference read from a file)
  std::string key;            // file stem: "whitted", "path-equal-time-radiosity", "reference"
  std::string equal_time_to;  // the method whose time limited this path run, or ""
  double seconds = -1;        // render time; < 0: unknown (a reference read from a file)
  nlohmann::json statistics = nlohmann::json::object();    // RunStatistics::to_json()
  std::vector<std::pair<std::string, std::string>> facts;  // a few key facts, name → value
  ImageComparison errors;  // against the reference (not set for the reference itself)
  Film image{0, 0};
  // The error (linear RGB) against the reference at each step of the method and at its
  // image (validate/convergence_log.h); empty for the reference. `seconds` leaves out the log's
  // own time (making and measuring the step images).
  std::vector<ConvergenceRow> convergence;
};

struct CrossMethodReport {
  std::string scene_name;  // the scene file's stem
  std::string scene_path;
  int width = 0, height = 0;
  CrossMethodEntry reference;
  bool reference_rendered = true;  // false: read from reference_file
  std::string reference_file;
  int reference_spp = 0;
  uint64_t reference_seed = 0;
  std::vector<CrossMethodEntry> entries;  // the methods in the order asked, then the equal-time runs
  double difference_scale = 1;            // the top of every difference picture's scale
  double luminance_efficacy = 0;          // > 0: errors and differences in cd/m² (the options')
  // Each method's object of the scene file ("whitted", "radiosity", ...) or null (defaults).
  nlohmann::json settings = nlohmann::json::object();
  std::vector<std::string> overrides;
  int threads = 0;
  unsigned hardware_threads = 0;
  std::string cpu;   // the CPU model, "" when unknown
  std::string date;  // UTC, ISO 8601
};

// Each method's error (RMSE, linear RGB) against the reference as it converged, from its
// convergence log — every method on one log-log chart, the equal-time path runs as hollow markers —
// DIR/convergence.svg, with its data in DIR/convergence.csv.
std::string convergence_chart(const CrossMethodReport& report);

// Renders, compares and writes everything (see the top of this file). The scene's render.method,
// render.seed and path settings are changed while it runs and restored at the end. Throws
// std::runtime_error naming the method when one fails, InputError as it comes from a method.
CrossMethodReport run_cross_method_report(Scene& scene, const CrossMethodOptions& options);

// The pieces, for tests.
std::string html_escape(std::string_view text);
// A script that sets <body data-images-loaded="loaded/total"> once the page has loaded, and the text
// of an element with id image-status: what the headless checks of our pages read.
const char* page_load_check_script();

// The names of every file a run with these options may write in its directory (index.html,
// report.json, reference.*, each entry's .png, .exr and -diff.png): what must not be one of its
// inputs.
std::vector<std::string> cross_method_report_files(const CrossMethodOptions& options);
// A few facts from a method's statistics: spp for path, patches and elements for radiosity, sites
// for meshless, rays for the ray tracers ...
std::vector<std::pair<std::string, std::string>> key_facts(const std::string& method,
                                                           const nlohmann::json& statistics);
// Each method's object of the scene text (JSON, comments allowed), null where absent.
nlohmann::json method_settings(const std::string& scene_text, const std::vector<std::string>& methods);
std::string cross_method_html(const CrossMethodReport& report);
nlohmann::json cross_method_json(const CrossMethodReport& report);

}  // namespace candela
