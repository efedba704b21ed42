#include "validate/cross_method_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <thread>

#include "integrators/memory_estimate.h"
#include "integrators/method_registry.h"
#include "io/false_color.h"
#include "io/image_writer.h"
#include "scene/scene.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/statistics.h"
#include "validate/convergence_chart.h"

namespace candela {

namespace {

// The file stem of the path tracer's run at another method's time.
std::string equal_time_key(const std::string& other_method) {
  return "path-equal-time-" + other_method;
}

namespace fs = std::filesystem;

std::string number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return fmt::format("{:.4g}", value);
}

std::string fact_text(const nlohmann::json& value) {
  if (value.is_string()) return value.get<std::string>();
  if (value.is_boolean()) return value.get<bool>() ? "yes" : "no";
  if (value.is_number_integer() || value.is_number_unsigned()) return value.dump();
  if (value.is_number()) return number(value.get<double>());
  return value.dump();
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm parts{};
  gmtime_r(&now, &parts);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &parts);
  return text;
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) != 0) continue;
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    const std::size_t start = line.find_first_not_of(" \t", colon + 1);
    return start == std::string::npos ? std::string() : line.substr(start);
  }
  return {};
}

// The scene's settings as they were before the run, put back however it ends.
class SettingsGuard {
 public:
  explicit SettingsGuard(Scene& scene)
      : scene_(scene), method_(scene.render.method), seed_(scene.render.seed) {}
  ~SettingsGuard() {
    scene_.render.method = method_;
    scene_.render.seed = seed_;
  }
  SettingsGuard(const SettingsGuard&) = delete;
  SettingsGuard& operator=(const SettingsGuard&) = delete;

 private:
  Scene& scene_;
  std::string method_;
  uint64_t seed_;
};

// Renders the whole image with the scene's current settings, the method's settings object changed
// by `settings` ("spp=16"), and writes DIR/<key>.png and .exr.
// With a reference, the method's convergence against it is logged (CrossMethodEntry::convergence).
CrossMethodEntry render_entry(Scene& scene, const CrossMethodOptions& options, const std::string& method_name,
                              const std::string& label, const std::string& key,
                              const std::vector<std::string>& settings = {},
                              const Film* reference = nullptr) {
  const MethodEntry* registered = find_method(method_name);
  if (!registered)
    throw std::invalid_argument("unknown method \"" + method_name + "\" (expected one of: " + method_names() +
                                ")");
  scene.render.method = method_name;
  if (options.log) options.log("rendering " + label);
  const int width = scene.camera->width(), height = scene.camera->height();
  CrossMethodEntry entry;
  entry.label = label;
  entry.method = method_name;
  entry.key = key;
  RunStatistics statistics;
  statistics.threads = options.threads;
  RenderRequest request;
  request.region = {0, 0, width, height};
  request.quiet = options.quiet;
  std::optional<ConvergenceLog> log;
  if (reference) log.emplace(label, *reference, options.convergence_mask);
  Stopwatch timer;
  try {
    const std::unique_ptr<Method> method = create_method(*registered, scene, settings);
    if (log) {
      log->start();
      request.on_progress = log->observer();
    }
    RenderResult result = method->render(scene, request);
    entry.image = std::move(result.film);
    if (log) {
      log->finish(entry.image);
      entry.convergence = log->rows();
    }
    statistics.absorb(std::move(result.statistics));
  } catch (const InputError& e) {
    throw InputError(e.location(), "method " + label + ": " + e.message());
  } catch (const std::exception& e) {
    throw std::runtime_error("method " + label + " failed: " + e.what());
  }
  entry.seconds = timer.seconds() - (log ? log->overhead_seconds() : 0.0);
  statistics.add_phase("render", entry.seconds);
  statistics.extra["method"] = method_name;
  statistics.extra["emitters"] = emitter_facts(scene, *registered);
  entry.statistics = statistics.to_json();
  entry.facts = key_facts(method_name, entry.statistics);
  const fs::path directory(options.output_directory);
  write_image(entry.image, (directory / (key + ".png")).string(), scene.display);
  write_image(entry.image, (directory / (key + ".exr")).string(), scene.display);
  return entry;
}

// The methods whose scene-file objects the page shows: those rendered, and "aa", whose sampling
// and reconstruction filter every method's pixels go through (or which it refuses).
std::vector<std::string> settings_keys(const CrossMethodReport& report) {
  std::vector<std::string> keys;
  const auto add = [&](const std::string& key) {
    if (!key.empty() && std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
  };
  for (const CrossMethodEntry& entry : report.entries) {
    add(entry.method);
    add("aa");
  }
  if (report.reference_rendered) add("path");
  return keys;
}

const char* kStyle = R"(
body { font-family: system-ui, sans-serif; margin: 1.5em; color: #222; background: #fff; }
h1 { font-size: 1.5em; } h2 { font-size: 1.2em; margin-top: 1.6em; } h3 { font-size: 1em; margin-bottom: 0.2em; }
table { border-collapse: collapse; }
th, td { border: 1px solid #bbb; padding: 0.25em 0.6em; text-align: right; vertical-align: top; }
th { background: #eee; } td.name, td.facts { text-align: left; }
tr.reference td { background: #f6f6f6; }
.gallery .row { display: flex; flex-wrap: wrap; gap: 1em; margin-bottom: 1.2em; }
figure { margin: 0; } figcaption { font-size: 0.85em; max-width: 40em; }
img { image-rendering: pixelated; max-width: 100%; height: auto; border: 1px solid #888; }
pre { background: #f4f4f4; padding: 0.5em; display: inline-block; margin: 0; }
.note { font-size: 0.85em; color: #555; max-width: 60em; }
)";

// Sets <body data-images-loaded="loaded/total"> once the page has loaded, for headless checks.
const char* kScript = R"(
window.addEventListener('load', function () {
  var images = document.getElementsByTagName('img');
  var loaded = 0;
  for (var i = 0; i < images.length; ++i)
    if (images[i].complete && images[i].naturalWidth > 0) ++loaded;
  document.body.setAttribute('data-images-loaded', loaded + '/' + images.length);
  var status = document.getElementById('image-status');
  if (status) status.textContent = loaded + ' of ' + images.length + ' images loaded.';
});
)";

}  // namespace

const char* page_load_check_script() {
  return kScript;
}

namespace {

std::string seconds_text(double seconds) {
  return seconds < 0 ? "&mdash;" : fmt::format("{:.3f}", seconds);
}

std::string facts_html(const std::vector<std::pair<std::string, std::string>>& facts) {
  std::string text;
  for (const auto& [name, value] : facts) {
    if (!text.empty()) text += ", ";
    text += html_escape(name) + " " + html_escape(value);
  }
  return text.empty() ? "&mdash;" : text;
}

}  // namespace

std::string html_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

namespace {

// "2 point, 1 area, emissive lamp, environment constant" from emitter_facts.
std::string emitters_text(const nlohmann::json& emitters) {
  std::string text;
  const auto add = [&](const std::string& part) { text += (text.empty() ? "" : ", ") + part; };
  if (emitters.contains("lights") && emitters.at("lights").is_object())
    for (const auto& [type, count] : emitters.at("lights").items()) add(fact_text(count) + " " + type);
  if (emitters.contains("emissive_surfaces") && emitters.at("emissive_surfaces").is_array())
    for (const auto& name : emitters.at("emissive_surfaces"))
      if (name.is_string()) add("emissive " + name.get<std::string>());
  if (emitters.contains("environment") && emitters.at("environment").is_string())
    add("environment " + emitters.at("environment").get<std::string>());
  return text.empty() ? std::string("none") : text;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> key_facts(const std::string& method,
                                                           const nlohmann::json& statistics) {
  std::vector<std::pair<std::string, std::string>> facts;
  const auto take = [&](const nlohmann::json& object, const char* key, const char* name) {
    if (object.is_object() && object.contains(key)) facts.emplace_back(name, fact_text(object.at(key)));
  };
  const nlohmann::json empty = nlohmann::json::object();
  const nlohmann::json& own = statistics.contains(method) ? statistics.at(method) : empty;
  if (method == "path") {
    take(own, "spp", "spp");
    if (own.contains("max_depth") && own.at("max_depth").is_number())
      facts.emplace_back("max depth", own.at("max_depth").get<double>() > 0 ? fact_text(own.at("max_depth"))
                                                                            : std::string("unlimited"));
  } else if (method == "radiosity") {
    take(own, "patches", "patches");
    take(own, "elements", "elements");
    take(own, "solver", "solver");
    take(own, "steps", "steps");
  } else if (method == "meshless") {
    take(own, "sites", "sites");
    take(own, "basis", "basis");
    take(own, "iterations", "iterations");
  } else if (method == "raster") {
    take(own, "shading", "shading");
  } else {
    take(statistics, "antialiasing", "aa");
  }
  // Which of the scene's emitters the method accounted for (every one, each its own way).
  if (statistics.contains("emitters") && statistics.at("emitters").is_object())
    facts.emplace_back("emitters", emitters_text(statistics.at("emitters")));
  if (statistics.contains("rays") && statistics.at("rays").contains("total")) {
    const nlohmann::json& total = statistics.at("rays").at("total");
    if (total.is_number() && total.get<double>() > 0) facts.emplace_back("rays", fact_text(total));
  }
  return facts;
}

nlohmann::json method_settings(const std::string& scene_text, const std::vector<std::string>& methods) {
  nlohmann::json root;
  try {
    root = nlohmann::json::parse(scene_text, nullptr, true, /*ignore_comments=*/true);
  } catch (const nlohmann::json::exception&) {
    root = nlohmann::json::object();
  }
  nlohmann::json settings = nlohmann::json::object();
  for (const std::string& method : methods)
    settings[method] = root.is_object() && root.contains(method) ? root.at(method) : nlohmann::json(nullptr);
  return settings;
}

CrossMethodReport run_cross_method_report(Scene& scene, const CrossMethodOptions& options) {
  if (options.methods.empty()) throw std::invalid_argument("no methods to compare");
  if (options.reference_spp < 1) throw std::invalid_argument("the reference needs spp >= 1");
  if (options.path_spp && *options.path_spp < 1) throw std::invalid_argument("the path entry needs spp >= 1");
  const int width = scene.camera->width(), height = scene.camera->height();
  if (options.reference_image &&
      (options.reference_image->width() != width || options.reference_image->height() != height))
    throw std::invalid_argument(fmt::format("the reference image is {}x{}, the scene's image {}x{}",
                                            options.reference_image->width(),
                                            options.reference_image->height(), width, height));
  const SettingsGuard guard(scene);
  const uint64_t seed = scene.render.seed;
  const fs::path directory(options.output_directory);
  // Every method the report renders is held to render.memory_limit_mib before the first
  // renders and writes anything.
  RenderRequest whole_image;
  whole_image.region = {0, 0, width, height};
  std::vector<std::string> checked = options.methods;
  if (!options.reference_image) checked.push_back("path");
  for (const std::string& method_name : checked)
    if (const MethodEntry* registered = find_method(method_name)) try {
        refuse_beyond_memory_limit(*create_method(*registered, scene), scene, whole_image);
      } catch (const InputError& e) {
        throw InputError(e.location(), "method " + method_name + ": " + e.message());
      }
  // A page left from an earlier report would describe images this run is about to replace: it
  // goes first, so that a run that fails leaves no page at all.
  std::error_code ignored;
  fs::remove(directory / "index.html", ignored);
  fs::remove(directory / "report.json", ignored);

  CrossMethodReport report;
  report.scene_path = options.scene_path;
  report.scene_name = fs::path(options.scene_path).stem().string();
  report.width = width;
  report.height = height;
  report.overrides = options.overrides;
  report.threads = options.threads;
  report.hardware_threads = std::thread::hardware_concurrency();
  report.cpu = cpu_model();
  report.date = utc_now();

  // The reference: path traced with its own seed, or read from a file.
  report.reference_seed = seed ^ kReferenceSeedMix;
  if (options.reference_image) {
    report.reference_rendered = false;
    report.reference_file = options.reference_file;
    report.reference.label = "reference";
    report.reference.key = "reference";
    report.reference.image = *options.reference_image;
    write_image(report.reference.image, (directory / "reference.png").string(), scene.display);
    write_image(report.reference.image, (directory / "reference.exr").string(), scene.display);
  } else {
    report.reference_spp = options.reference_spp;
    scene.render.seed = report.reference_seed;
    report.reference = render_entry(scene, options, "path", "reference", "reference",
                                    {"spp=" + std::to_string(options.reference_spp), "time=0"});
    report.reference.facts.emplace_back("seed", std::to_string(report.reference_seed));
    scene.render.seed = seed;
  }

  // Each method, then path at each other method's time.
  for (const std::string& method : options.methods) {
    std::vector<std::string> settings;
    if (method == "path" && options.path_spp) settings.push_back("spp=" + std::to_string(*options.path_spp));
    report.entries.push_back(
        render_entry(scene, options, method, method, method, settings, &report.reference.image));
  }
  if (options.equal_time) {
    const std::size_t count = report.entries.size();
    for (std::size_t i = 0; i < count; ++i) {
      const CrossMethodEntry& other = report.entries[i];
      if (other.method == "path") continue;
      const std::string other_method = other.method;
      const double seconds = std::max(other.seconds, 1e-6);
      CrossMethodEntry entry = render_entry(
          scene, options, "path", "path (equal time: " + other_method + ")", equal_time_key(other_method),
          {"spp=0", fmt::format("time={:.17g}", seconds)}, &report.reference.image);
      entry.equal_time_to = other_method;
      entry.facts.emplace_back("time limit (s)", fmt::format("{:.3g}", seconds));
      report.entries.push_back(std::move(entry));
    }
  }

  // Errors and the difference pictures, all on one scale.
  if (options.log) options.log("comparing with the reference");
  std::vector<std::vector<double>> differences;
  std::vector<double> all;
  report.luminance_efficacy = options.luminance_efficacy;
  const bool photometric = options.luminance_efficacy > 0;
  const Film reference_measured = photometric
                                      ? luminance_film(report.reference.image, options.luminance_efficacy)
                                      : report.reference.image;
  for (CrossMethodEntry& entry : report.entries) {
    const Film measured = photometric ? luminance_film(entry.image, options.luminance_efficacy) : entry.image;
    entry.errors = compare_images(measured, reference_measured);
    differences.push_back(difference_values(measured, reference_measured, DifferenceMetric::absolute));
    for (const double value : differences.back())
      if (std::isfinite(value)) all.push_back(value);
  }
  // The 99th percentile of every difference: a few pixels along the lamp's edges (10× the rest)
  // would otherwise leave every picture dark; larger values take the top color.
  double scale = 0;
  if (!all.empty()) {
    const auto at = all.begin() + static_cast<std::ptrdiff_t>(0.99 * double(all.size() - 1));
    std::nth_element(all.begin(), at, all.end());
    scale = *at;
  }
  report.difference_scale = scale > 0 ? scale : 1.0;  // identical images: 0 .. 1
  for (std::size_t i = 0; i < report.entries.size(); ++i) {
    const Film picture =
        false_color_image(differences[i], width, height,
                          false_color_scale(report.difference_scale, {0.0, report.difference_scale}, false, 0,
                                            photometric ? "cd/m²" : "", "|Y − Y_ref|"),
                          ColorMap::viridis);
    write_image(picture, (directory / (report.entries[i].key + "-diff.png")).string(), DisplaySettings{});
  }

  std::vector<ConvergenceRow> all_rows;
  for (const CrossMethodEntry& entry : report.entries)
    all_rows.insert(all_rows.end(), entry.convergence.begin(), entry.convergence.end());
  write_text_atomically((directory / "convergence.csv").string(), convergence_csv(all_rows));
  write_text_atomically((directory / "convergence.svg").string(), convergence_chart(report));
  report.settings = method_settings(options.scene_text, settings_keys(report));
  write_text_atomically((directory / "report.json").string(), cross_method_json(report).dump(2) + "\n");
  write_text_atomically((directory / "index.html").string(), cross_method_html(report));
  return report;
}

std::string convergence_chart(const CrossMethodReport& report) {
  std::vector<std::vector<ConvergenceRow>> logs;
  for (const CrossMethodEntry& entry : report.entries)
    if (entry.equal_time_to.empty()) logs.push_back(entry.convergence);
  std::vector<ChartSeries> series = convergence_series(logs);
  // The equal-time path runs: hollow points in the path curve's colour.
  std::string path_color = "#404040";
  for (const ChartSeries& s : series)
    if (s.label == "path") path_color = s.color;
  for (const CrossMethodEntry& entry : report.entries) {
    if (entry.equal_time_to.empty() || entry.convergence.empty()) continue;
    const ConvergenceRow& last = entry.convergence.back();
    series.push_back({"path at " + entry.equal_time_to + "'s time",
                      path_color,
                      {{last.time_to_image(), last.rmse}},
                      false,
                      true});
  }
  ChartAxes axes;
  axes.title = report.scene_name + ": error against time";
  axes.x_label = "time to the image (s)";
  axes.y_label = "RMSE against the reference";
  return log_log_chart_svg(series, axes);
}

nlohmann::json cross_method_json(const CrossMethodReport& report) {
  const auto images = [](const CrossMethodEntry& entry, bool diff) {
    nlohmann::json files = {{"png", entry.key + ".png"}, {"exr", entry.key + ".exr"}};
    if (diff) files["diff"] = entry.key + "-diff.png";
    return files;
  };
  const auto facts = [](const CrossMethodEntry& entry) {
    nlohmann::json object = nlohmann::json::object();
    for (const auto& [name, value] : entry.facts) object[name] = value;
    return object;
  };
  nlohmann::json reference = {{"rendered", report.reference_rendered},
                              {"images", images(report.reference, false)}};
  if (report.reference_rendered) {
    reference["method"] = "path";
    reference["spp"] = report.reference_spp;
    reference["seed"] = report.reference_seed;
    reference["seconds"] = report.reference.seconds;
    reference["statistics"] = report.reference.statistics;
  } else {
    reference["file"] = report.reference_file;
  }
  nlohmann::json methods = nlohmann::json::array();
  for (const CrossMethodEntry& entry : report.entries) {
    methods.push_back({{"label", entry.label},
                       {"method", entry.method},
                       {"key", entry.key},
                       {"equal_time_to", entry.equal_time_to.empty() ? nlohmann::json(nullptr)
                                                                     : nlohmann::json(entry.equal_time_to)},
                       {"seconds", entry.seconds},
                       {"images", images(entry, true)},
                       {"facts", facts(entry)},
                       {"errors", entry.errors.to_json()},
                       {"statistics", entry.statistics}});
  }
  return {{"scene", report.scene_path},
          {"scene_name", report.scene_name},
          {"width", report.width},
          {"height", report.height},
          {"reference", reference},
          {"methods", methods},
          {"units", report.luminance_efficacy > 0 ? "cd/m2" : "linear"},
          {"luminous_efficacy",
           report.luminance_efficacy > 0 ? nlohmann::json(report.luminance_efficacy) : nlohmann::json()},
          {"difference",
           {{"metric", "absolute luminance difference |Y - Y_ref| (Rec. 709)"},
            {"color_map", "viridis"},
            {"low", 0.0},
            {"high", report.difference_scale}}},
          {"settings", report.settings},
          {"overrides", report.overrides},
          {"machine",
           {{"hardware_threads", report.hardware_threads}, {"threads", report.threads}, {"cpu", report.cpu}}},
          {"date", report.date}};
}

std::string cross_method_html(const CrossMethodReport& report) {
  const std::string name = html_escape(report.scene_name);
  // Small images are shown enlarged (pixelated) to about 320 pixels wide.
  const int scale = std::max(1, 320 / std::max(1, report.width));
  const int shown_width = report.width * scale;
  const auto image = [&](const std::string& file, const std::string& alt) {
    return fmt::format("<img src=\"{}\" width=\"{}\" alt=\"{}\">", html_escape(file), shown_width,
                       html_escape(alt));
  };
  std::string html;
  html += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  html += "<title>Cross-method report: " + name + "</title>\n";
  html += "<style>" + std::string(kStyle) + "</style>\n";
  html += "<script>" + std::string(kScript) + "</script>\n</head>\n";
  html += "<body data-images-loaded=\"pending\">\n";
  html += "<h1>Cross-method report: " + name + "</h1>\n";
  html += fmt::format("<p>Scene <code>{}</code>, {}&times;{} pixels. ", html_escape(report.scene_path),
                      report.width, report.height);
  if (report.reference_rendered)
    html += fmt::format("Reference: method path, {} samples per pixel (seed {}), {} s.</p>\n",
                        report.reference_spp, report.reference_seed, seconds_text(report.reference.seconds));
  else
    html += "Reference: the image <code>" + html_escape(report.reference_file) + "</code>.</p>\n";

  // The table.
  html += "<h2>Errors against the reference</h2>\n<table>\n";
  html +=
      "<tr><th>method</th><th>time (s)</th><th>samples and other facts</th><th>RMSE</th><th>relative MSE</th>"
      "<th>PSNR (dB)</th><th>max error</th><th>mean luminance ratio</th></tr>\n";
  html += fmt::format(
      "<tr class=\"reference\"><td class=\"name\">reference</td><td>{}</td><td class=\"facts\">{}</td>"
      "<td colspan=\"5\">&mdash;</td></tr>\n",
      seconds_text(report.reference.seconds),
      report.reference_rendered ? facts_html(report.reference.facts)
                                : "file " + html_escape(report.reference_file));
  for (const CrossMethodEntry& entry : report.entries) {
    const ImageComparison& e = entry.errors;
    html += fmt::format(
        "<tr><td class=\"name\">{}</td><td>{}</td><td class=\"facts\">{}</td><td>{}</td><td>{}</td>"
        "<td>{}</td><td>{}</td><td>{}</td></tr>\n",
        html_escape(entry.label), seconds_text(entry.seconds), facts_html(entry.facts), number(e.rmse),
        number(e.relative_mse), number(e.psnr), number(e.max_absolute_error), number(e.luminance_ratio));
  }
  html += "</table>\n";
  html += fmt::format(
      "<p class=\"note\">Images are linear RGB in the same units for every method (&pi; &times; radiance). "
      "<b>time</b>: the method's render call (meshing, solving and display included). "
      "<b>RMSE</b>: &radic;(mean (a &minus; b)&sup2;) over pixels and channels, b the reference. "
      "<b>relative MSE</b>: mean (a &minus; b)&sup2; / (b&sup2; + {}). "
      "<b>PSNR</b>: 20 log<sub>10</sub>(peak / RMSE), peak the reference's largest value. "
      "<b>max error</b>: the largest |a &minus; b|. "
      "<b>mean luminance ratio</b>: mean Rec. 709 luminance of the image over the reference's (1: the same "
      "overall brightness).{}</p>\n",
      kRelativeMseEpsilon,
      std::any_of(report.entries.begin(), report.entries.end(),
                  [](const CrossMethodEntry& entry) { return !entry.equal_time_to.empty(); })
          ? " <b>path (equal time: M)</b>: the path tracer given the time method M took (passes until it is "
            "up)."
          : "");

  // Error against time, every method on one chart.
  html +=
      "<h2>Error against time</h2>\n<p><img src=\"convergence.svg\" alt=\"RMSE against time, log-log, one "
      "curve per method\"></p>\n<p class=\"note\">Each method's RMSE (linear RGB) against the reference at "
      "every step of its way — the path tracer's passes, progressive radiosity's shots (every 50), "
      "Gauss-Seidel's sweeps, meshless iterations — plotted at the time a run stopped there would have had "
      "its image (the solve so far and its display); a method without steps is one point; hollow points are "
      "the equal-time path runs. Data: <a href=\"convergence.csv\">convergence.csv</a>.</p>\n";

  // The gallery.
  html += "<h2>Images</h2>\n";
  html += fmt::format(
      "<p class=\"note\">Difference pictures show |Y &minus; Y<sub>ref</sub>| (Rec. 709 luminance) in the "
      "viridis "
      "color map, all on one scale: <b>0 to {}{}</b> (dark violet 0, yellow {}), drawn as a bar beneath "
      "each.</p>\n",
      format_scale_value(report.difference_scale), report.luminance_efficacy > 0 ? " cd/m²" : "",
      format_scale_value(report.difference_scale));
  if (report.luminance_efficacy > 0)
    html += fmt::format(
        "<p class=\"note\">Errors in <b>luminance, cd/m²</b>: {} lm/W × Y / &pi; of each image and of the "
        "reference.</p>\n",
        report.luminance_efficacy);
  html += "<div class=\"gallery\">\n<div class=\"row\">\n<figure>" + image("reference.png", "reference") +
          "<figcaption>reference" +
          (report.reference_rendered ? fmt::format(": path, {} spp, {} s", report.reference_spp,
                                                   seconds_text(report.reference.seconds))
                                     : ": " + html_escape(report.reference_file)) +
          " (<a href=\"reference.exr\">EXR</a>)</figcaption></figure>\n</div>\n";
  for (const CrossMethodEntry& entry : report.entries) {
    const std::string label = html_escape(entry.label);
    html += "<div class=\"row\">\n<figure>" + image(entry.key + ".png", entry.label) + "<figcaption>" +
            label + ", " + seconds_text(entry.seconds) + " s (<a href=\"" + html_escape(entry.key) +
            ".exr\">EXR</a>)</figcaption></figure>\n";
    html += "<figure>" + image(entry.key + "-diff.png", entry.label + " difference") + "<figcaption>|" +
            label + " &minus; reference|: RMSE " + number(entry.errors.rmse) + ", PSNR " +
            number(entry.errors.psnr) + " dB</figcaption></figure>\n</div>\n";
  }
  html += "</div>\n";

  // The settings.
  html +=
      "<h2>Settings</h2>\n<p class=\"note\">The scene file's object for each method (defaults where it has "
      "none)";
  html += report.overrides.empty() ? std::string(".") : std::string(", before these overrides:");
  html += "</p>\n";
  if (!report.overrides.empty()) {
    html += "<ul>\n";
    for (const std::string& o : report.overrides)
      html += "<li><code>--set " + html_escape(o) + "</code></li>\n";
    html += "</ul>\n";
  }
  for (auto it = report.settings.begin(); it != report.settings.end(); ++it) {
    const nlohmann::json& value = it.value();
    html += "<h3>" + html_escape(it.key()) + "</h3>\n";
    html += value.is_null() ? std::string("<p>defaults</p>\n")
                            : "<pre>" + html_escape(value.dump(2)) + "</pre>\n";
  }

  // The machine.
  html += "<h2>Machine</h2>\n<p>";
  html += fmt::format("{} hardware threads", report.hardware_threads);
  if (report.threads > 0) html += fmt::format(", {} used", report.threads);
  if (!report.cpu.empty()) html += ", " + html_escape(report.cpu);
  html += ". Generated " + html_escape(report.date) + " by <code>candela report</code>.</p>\n";
  html += "<p id=\"image-status\" class=\"note\"></p>\n</body>\n</html>\n";
  return html;
}

std::vector<std::string> cross_method_report_files(const CrossMethodOptions& options) {
  std::vector<std::string> keys{"reference"};
  for (const std::string& method : options.methods) {
    keys.push_back(method);
    if (options.equal_time && method != "path") keys.push_back(equal_time_key(method));
  }
  std::vector<std::string> files{"index.html", "report.json", "convergence.svg", "convergence.csv"};
  for (const std::string& key : keys)
    for (const char* ending : {".png", ".exr", "-diff.png"}) files.push_back(key + ending);
  return files;
}

}  // namespace candela
