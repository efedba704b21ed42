#include "validate/form_factor_validation.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "integrators/method_registry.h"
#include "integrators/scene_loading.h"
#include "math/constants.h"
#include "radiosity/configuration_factors.h"
#include "radiosity/form_factor_rows.h"
#include "radiosity/radiosity_mesh.h"
#include "scene/scene.h"
#include "util/atomic_file.h"
#include "validate/line_plot.h"

namespace candela {

std::vector<HowellCase> howell_cases() {
  const std::string grey = R"(, "material": "grey"})";
  const std::string sphere = R"({"type": "sphere", "center": [0, 0, 0], "radius": 1)" + grey;
  // A 0.01 square: a differential element at the origin's scale.
  const std::string point = R"({"type": "quad", "corner": [-0.005, -0.005, 0], "edge_u": [0.01, 0, 0], )"
                            R"("edge_v": [0, 0.01, 0])" +
                            grey;
  return {
      {"parallel squares", "C-11",
       R"({"type": "quad", "corner": [0, 0, 0], "edge_u": [1, 0, 0], "edge_v": [0, 1, 0])" + grey +
           R"(, {"type": "quad", "corner": [0, 0, 1], "edge_u": [0, 1, 0], "edge_v": [1, 0, 0])" + grey,
       0, parallel_rectangles(1, 1)},
      {"perpendicular squares", "C-14",
       R"({"type": "quad", "corner": [0, 0, 0], "edge_u": [1, 0, 0], "edge_v": [0, 1, 0])" + grey +
           R"(, {"type": "quad", "corner": [0, 0, 0], "edge_u": [0, 1, 0], "edge_v": [0, 0, 1])" + grey,
       0, perpendicular_rectangles(1, 1)},
      {"coaxial discs", "C-41",
       R"({"type": "disc", "center": [0, 0, 0], "normal": [0, 0, 1], "radius": 1)" + grey +
           R"(, {"type": "disc", "center": [0, 0, 1], "normal": [0, 0, -1], "radius": 1)" + grey,
       0, coaxial_discs(1, 1, 1)},
      {"point to disc", "",
       point + R"(, {"type": "disc", "center": [0, 0, 1], "normal": [0, 0, -1], "radius": 1)" + grey, 0,
       point_to_coaxial_disc(1, 1)},
      {"point to sphere", "",
       sphere +
           R"(, {"type": "quad", "corner": [-0.005, -0.005, 3], "edge_u": [0, 0.01, 0], )"
           R"("edge_v": [0.01, 0, 0])" +
           grey,
       1, point_to_sphere(1, 3)},
      {"sphere to disc", "",
       sphere + R"(, {"type": "disc", "center": [0, 0, 3], "normal": [0, 0, -1], "radius": 1.5)" + grey, 0,
       sphere_to_coaxial_disc(1.5, 3)},
  };
}

double radiosity_form_factor(const HowellCase& howell, RadiosityFormFactors method, int level) {
  const auto scene =
      load_scene_text(R"({"format": "candela/1", "camera": {"eye": [5, 0, 0], "target": [0, 0, 0], "width": 8,
        "height": 8}, "materials": {"grey": {"kd": 0.5}}, "shapes": [)" +
                          howell.shapes + "]}",
                      howell.name + ".json", ".");
  const double refinement = std::ldexp(1.0, level);
  RadiositySettings settings;
  settings.form_factors = method;
  settings.hemicube_resolution = static_cast<int>(settings.hemicube_resolution * refinement);
  settings.segments = static_cast<int>(settings.segments * refinement);
  RadiosityMeshSettings mesh_settings;
  mesh_settings.segments = settings.segments;
  // The defaults' patch size (the scene size / 8), then halved per level.
  mesh_settings.patch_size = length(scene->bounds().diagonal()) / 8 / refinement;
  const RadiosityMesh mesh = build_radiosity_mesh(*scene, mesh_settings);
  // The element rows F_qj the solvers gather with (000 §6.7.1), of the object's elements only.
  std::vector<uint32_t> elements;
  for (uint32_t q = 0; q < mesh.elements.size(); ++q)
    if (mesh.elements[q].object == howell.from) elements.push_back(q);
  ElementToPatch rows = ElementToPatch::Zero(static_cast<Eigen::Index>(mesh.elements.size()),
                                             static_cast<Eigen::Index>(mesh.patches.size()));
  std::vector<double> sums(mesh.elements.size());
  fill_element_form_factor_rows(settings, scene->render.seed, mesh, elements, rows, sums, nullptr);
  // 000 eq. 6-4: the area-weighted mean of the object's rows toward the other object.
  double weighted = 0, area = 0;
  for (const uint32_t q : elements) {
    double to_other = 0;
    for (Eigen::Index j = 0; j < rows.cols(); ++j)
      if (mesh.patches[static_cast<std::size_t>(j)].object != howell.from) to_other += rows(q, j);
    weighted += mesh.elements[q].area * to_other;
    area += mesh.elements[q].area;
  }
  return area > 0 ? weighted / area : 0.0;
}

std::vector<std::string> furnace_methods() {
  return {"radiosity-hemicube", "radiosity-ray-cast", "meshless-normalized",
          "meshless-shepard",   "meshless-radial",    "path"};
}

FurnaceResult run_furnace(const std::string& method, double albedo, bool quick) {
  // The method's name and its settings object, as a scene file gives them.
  std::string name, settings;
  if (method == "radiosity-hemicube" || method == "radiosity-ray-cast") {
    name = "radiosity";
    // Gauss–Seidel to a tight tolerance: what is measured is the form factors, not the stopping.
    // Quick: patches of the box's half side (the rows still sum to 1).
    settings = fmt::format(R"("radiosity": {{"solver": "gauss-seidel", "threshold": 1e-7, "max_steps": 100000,
      "form_factors": "{}"{}}},)",
                           method == "radiosity-hemicube" ? "hemicube" : "ray-cast",
                           quick ? R"(, "patch_size": 1, "element_size": 1)" : "");
  } else if (method.starts_with("meshless-")) {
    name = "meshless";
    settings = fmt::format(
        R"("meshless": {{"basis": "{}", "spacing": {}, "grid": 32, "rounds": 6, "tolerance": 1e-6}},)",
        method.substr(9), quick ? 0.25 : 0.15);
  } else if (method == "path") {
    name = "path";
    // Long paths at ρ = 0.95: Russian roulette's variance needs many samples.
    settings = fmt::format(R"("path": {{"spp": {}, "max_depth": 1000}},)", quick ? 64 : 1024);
  } else {
    throw std::invalid_argument("furnace: unknown method '" + method + "'");
  }
  const std::string wall = fmt::format(R"(, "material": {{"kd": {}, "emission": 1}}}})", albedo);
  const std::string text = fmt::format(R"({{"format": "candela/1",
    "camera": {{"eye": [1, 1.1, 1.7], "target": [0.9, 0.8, 0], "fov": 80, "width": 16, "height": 16}},
    "render": {{"method": "{}"}}, {}
    "shapes": [
      {{"type": "quad", "corner": [0, 0, 0], "edge_u": [0, 0, 2], "edge_v": [2, 0, 0]{},
      {{"type": "quad", "corner": [0, 2, 0], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2]{},
      {{"type": "quad", "corner": [0, 0, 0], "edge_u": [0, 2, 0], "edge_v": [0, 0, 2]{},
      {{"type": "quad", "corner": [2, 0, 0], "edge_u": [0, 0, 2], "edge_v": [0, 2, 0]{},
      {{"type": "quad", "corner": [0, 0, 0], "edge_u": [2, 0, 0], "edge_v": [0, 2, 0]{},
      {{"type": "quad", "corner": [0, 0, 2], "edge_u": [0, 2, 0], "edge_v": [2, 0, 0]{}]}})",
                                       name, settings, wall, wall, wall, wall, wall, wall);
  const auto scene = load_scene_text(text, "furnace.json", ".");
  const auto start = std::chrono::steady_clock::now();
  const auto renderer = create_method(*find_method(name), *scene);
  RenderRequest request;
  request.region = {0, 0, scene->camera->width(), scene->camera->height()};
  request.quiet = true;
  const RenderResult rendered = renderer->render(*scene, request);
  FurnaceResult result;
  result.method = method;
  result.albedo = albedo;
  result.expected = 1 / (1 - albedo);
  double sum = 0;
  for (const Color& pixel : rendered.film.pixels()) {
    sum += pixel.g;
    result.largest_error =
        std::max(result.largest_error, std::fabs(pixel.g - result.expected) / result.expected);
  }
  result.mean = sum / static_cast<double>(rendered.film.pixels().size());
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

nlohmann::json run_form_factor_validation(const std::string& out_dir, const FormFactorRun& run,
                                          std::ostream* log) {
  namespace fs = std::filesystem;
  const fs::path out(out_dir);
  const std::vector<HowellCase> cases = howell_cases();
  // Refinements per case: the squares three (their meshes stay small), the discs and spheres two
  // (at 128 segments and patches of 1/32 the element rows take hours); one fewer each when quick.
  const auto levels_of = [&](const HowellCase& howell) {
    return (howell.name.ends_with("squares") ? 3 : 2) - (run.quick ? 1 : 0);
  };
  const RadiosityFormFactors methods[] = {RadiosityFormFactors::hemicube, RadiosityFormFactors::ray_cast};
  const RadiositySettings defaults;
  nlohmann::json results;
  std::string csv =
      "case,catalogue,method,level,patch_size_fraction,segments,hemicube_resolution,computed,"
      "expected,relative_error\n";
  // Per case and method, (log10 of the patch size relative to the scene, log10 |error|).
  std::map<std::pair<std::size_t, RadiosityFormFactors>, PlotCurve> curves;
  for (std::size_t c = 0; c < cases.size(); ++c)
    for (const RadiosityFormFactors method : methods)
      for (int level = 0; level < levels_of(cases[c]); ++level) {
        const std::string method_name(kRadiosityFormFactorNames.name(method));
        const HowellCase& howell = cases[c];
        const double computed = radiosity_form_factor(howell, method, level);
        const double error = computed / howell.expected - 1;
        const double refinement = std::ldexp(1.0, level);
        csv += fmt::format(
            "{},{},{},{},{:.6g},{},{},{:.9g},{:.9g},{:.6g}\n", howell.name, howell.catalogue, method_name,
            level, 1 / (8 * refinement), static_cast<int>(defaults.segments * refinement),
            static_cast<int>(defaults.hemicube_resolution * refinement), computed, howell.expected, error);
        results["form_factors"][howell.name][method_name].push_back({{"level", level},
                                                                     {"computed", computed},
                                                                     {"expected", howell.expected},
                                                                     {"relative_error", error}});
        PlotCurve& curve = curves[{c, method}];
        curve.x.push_back(std::log10(1 / (8 * refinement)));
        curve.y.push_back(std::log10(std::max(std::fabs(error), 1e-7)));
        if (log)
          *log << fmt::format("{:<22} {:<9} level {}: F = {:.6f} (Howell {:.6f}, {:+.3f} %)\n", howell.name,
                              method_name, level, computed, howell.expected, 100 * error);
      }
  // The observed order between the last two levels: log2 of the ratio of the errors.
  for (std::size_t c = 0; c < cases.size(); ++c)
    for (const RadiosityFormFactors method : methods) {
      const std::string method_name(kRadiosityFormFactorNames.name(method));
      const auto& entries = results["form_factors"][cases[c].name][method_name];
      const std::size_t count = entries.size();
      if (count < 2) {
        results["order"][cases[c].name][method_name] = nullptr;
        continue;
      }
      const double coarse = std::fabs(entries[count - 2]["relative_error"].get<double>()),
                   fine = std::fabs(entries[count - 1]["relative_error"].get<double>());
      results["order"][cases[c].name][method_name] = fine > 0 && coarse > 0 ? std::log2(coarse / fine) : 0.0;
    }
  write_text_atomically((out / "form_factors.csv").string(), csv);
  // Two plots of three panels (flat, curved): log10 |relative error| against log10 of the patch
  // size over the scene's size, hemicube blue, ray cast red; a dashed grey slope of −2 for scale.
  for (const auto& [file, first] : {std::pair<std::string, std::size_t>{"convergence_flat.png", 0},
                                    std::pair<std::string, std::size_t>{"convergence_curved.png", 3}}) {
    std::vector<PlotPanel> panels;
    for (std::size_t c = first; c < first + 3 && c < cases.size(); ++c) {
      PlotPanel panel;
      panel.x_min = std::log10(1.0 / 32) - 0.1;
      panel.x_max = std::log10(1.0 / 8) + 0.1;
      panel.y_min = -5;
      panel.y_max = 0;
      panel.x_tick = 0.3;
      panel.y_tick = 1;
      // Each panel named by its case, both axes named, every curve in the legend.
      panel.title = cases[c].name;
      panel.x_label = "log10 (patch size / scene size)";
      panel.y_label = "log10 |relative error|";
      PlotCurve hemicube = curves[{c, RadiosityFormFactors::hemicube}];
      hemicube.color = Color(0.1, 0.3, 0.9);
      hemicube.width = 2;
      hemicube.label = "hemicube";
      PlotCurve ray_cast = curves[{c, RadiosityFormFactors::ray_cast}];
      ray_cast.color = Color(0.9, 0.15, 0.1);
      ray_cast.width = 2;
      ray_cast.label = "ray cast";
      PlotCurve slope;
      slope.label = "slope −2";
      slope.x = {panel.x_max - 0.1, panel.x_min + 0.1};
      slope.y = {-1, -1 - 2 * (slope.x[0] - slope.x[1])};
      slope.color = Color(0.6, 0.6, 0.6);
      slope.dashed = true;
      panel.curves = {hemicube, ray_cast, slope};
      panels.push_back(panel);
    }
    write_line_plot_png((out / file).string(), panels);
  }
  // The furnace for every method at three reflectances.
  std::string furnace_csv = "method,albedo,expected,mean,mean_relative_error,largest_pixel_error,seconds\n";
  for (const std::string& method : furnace_methods())
    for (const double albedo : {0.5, 0.9, 0.95}) {
      const FurnaceResult f = run_furnace(method, albedo, run.quick);
      furnace_csv += fmt::format("{},{},{:.9g},{:.9g},{:.6g},{:.6g},{:.3f}\n", f.method, f.albedo, f.expected,
                                 f.mean, f.mean / f.expected - 1, f.largest_error, f.seconds);
      results["furnace"][method].push_back({{"albedo", albedo},
                                            {"expected", f.expected},
                                            {"mean", f.mean},
                                            {"mean_relative_error", f.mean / f.expected - 1},
                                            {"largest_pixel_error", f.largest_error},
                                            {"seconds", f.seconds}});
      if (log)
        *log << fmt::format(
            "furnace {:<20} rho {:<4}: mean {:.5f} (E/(1 - rho) = {:.5f}, {:+.3f} %), worst pixel "
            "{:.3f} %, {:.1f} s\n",
            method, albedo, f.mean, f.expected, 100 * (f.mean / f.expected - 1), 100 * f.largest_error,
            f.seconds);
    }
  write_text_atomically((out / "furnace.csv").string(), furnace_csv);
  results["quick"] = run.quick;
  write_text_atomically((out / "results.json").string(), results.dump(2) + "\n");
  return results;
}

}  // namespace candela
