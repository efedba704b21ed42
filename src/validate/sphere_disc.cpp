#include "validate/sphere_disc.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>
#include <stdexcept>

#include "camera/tone_map.h"
#include "integrators/meshless_method.h"
#include "integrators/scene_loading.h"
#include "io/image_writer.h"
#include "math/constants.h"
#include "util/atomic_file.h"
#include "validate/line_plot.h"

namespace candela {

namespace {

// F(p, q) = cos θ_p cos θ_q / (π d²) between the sphere point p at latitude α on the meridian
// τ = 0 and the disc point q at distance u from the centre and azimuth τ. The disc's normal is +z
// and p lies above it, so cos θ_q = p_z / d > 0; cos θ_p is clipped at 0.
double exchange_kernel(const SphereDiscScene& scene, double alpha, double u, double tau) {
  const double ca = std::cos(alpha), sa = std::sin(alpha);
  const double px = scene.sphere_radius * ca, pz = scene.height + scene.sphere_radius * sa;
  const double dx = u * std::cos(tau) - px, dy = u * std::sin(tau), dz = -pz;
  const double along_normal = dx * ca + dz * sa;  // d · n_p
  if (!(along_normal > 0)) return 0;
  const double d2 = dx * dx + dy * dy + dz * dz;
  return along_normal * pz / (kPi * d2 * d2);
}

void check(const SphereDiscScene& scene, const ReferenceSettings& settings) {
  if (!(scene.sphere_radius > 0) || !(scene.disc_radius > 0) || !(scene.height > scene.sphere_radius))
    throw std::invalid_argument("sphere-disc: need r > 0, R > 0 and h > r (the sphere above the disc)");
  if (settings.disc_rings < 1 || settings.sphere_rings < 1 || settings.azimuths < 1 ||
      settings.iterations < 0)
    throw std::invalid_argument("sphere-disc: n, m, k must be >= 1 and the iterations >= 0");
}

}  // namespace

double reference_disc_direct(const SphereDiscScene& scene, double u) {
  return u >= scene.sphere_radius && u <= scene.disc_radius ? scene.disc_albedo * scene.light : 0.0;
}

double reference_sphere_direct(const SphereDiscScene& scene, double alpha) {
  return std::max(0.0, scene.sphere_albedo * scene.light * std::sin(alpha));
}

ReferenceSolution::ReferenceSolution(const SphereDiscScene& scene, const ReferenceSettings& settings)
    : scene_(scene), settings_(settings) {
  check(scene, settings);
  const int n = settings.disc_rings, m = settings.sphere_rings, k = settings.azimuths;
  const double r = scene.sphere_radius, R = scene.disc_radius;
  const double su = R / n, sa = kPi / m, st = 2 * kPi / k;
  u.resize(n);
  alpha.resize(m);
  for (int j = 0; j < n; ++j) u[j] = (j + 0.5) * su;
  for (int i = 0; i < m; ++i) alpha[i] = (i + 0.5) * sa - kPi / 2;

  // What the rings send of the direct light: the area average over each ring's cell.
  std::vector<double> disc_star(n), sphere_star(m);
  for (int j = 0; j < n; ++j) {
    if (!settings.average_direct) {
      disc_star[j] = reference_disc_direct(scene, u[j]);
      continue;
    }
    const double a = u[j] - su / 2, b = u[j] + su / 2;
    const double lo = std::max(a, r), hi = std::min(b, R);
    disc_star[j] = hi > lo ? scene.disc_albedo * scene.light * (hi * hi - lo * lo) / (b * b - a * a) : 0.0;
  }
  for (int i = 0; i < m; ++i) {
    if (!settings.average_direct) {
      sphere_star[i] = reference_sphere_direct(scene, alpha[i]);
      continue;
    }
    const double a = alpha[i] - sa / 2, b = alpha[i] + sa / 2;
    const double lit = std::max(a, 0.0);  // ∫ sin α cos α dα over the lit part / ∫ cos α dα
    sphere_star[i] = b > 0 ? scene.sphere_albedo * scene.light *
                                 (std::pow(std::sin(b), 2) - std::pow(std::sin(lit), 2)) /
                                 (2 * (std::sin(b) - std::sin(a)))
                           : 0.0;
  }

  // K_ij = Σ_s F(p(α_i, 0), q(u_j, τ_s)) σ_τ — also Σ_s F(q(u_j, 0), p(α_i, τ_s)) σ_τ by symmetry.
  std::vector<double> K(static_cast<std::size_t>(m) * n);
  tbb::parallel_for(0, m, [&](int i) {
    for (int j = 0; j < n; ++j) {
      double sum = 0;
      for (int s = 0; s < k; ++s) sum += exchange_kernel(scene, alpha[i], u[j], (s + 0.5) * st);
      K[static_cast<std::size_t>(i) * n + j] = sum * st;
    }
  });

  // Jacobi: the indirect parts b (sphere) and d (disc), from 0 (λ = η).
  std::vector<double> b(m, 0.0), d(n, 0.0), nb(m), nd(n);
  double largest = 0;
  for (int i = 0; i < m; ++i) largest = std::max(largest, reference_sphere_direct(scene, alpha[i]));
  for (int j = 0; j < n; ++j) largest = std::max(largest, reference_disc_direct(scene, u[j]));
  for (int iteration = 0; iteration < settings.iterations; ++iteration) {
    for (int i = 0; i < m; ++i) {
      double sum = 0;
      for (int j = 0; j < n; ++j)
        sum += K[static_cast<std::size_t>(i) * n + j] * u[j] * su * (disc_star[j] + d[j]);
      nb[i] = scene.sphere_albedo * sum;
    }
    for (int j = 0; j < n; ++j) {
      double sum = 0;
      for (int i = 0; i < m; ++i)
        sum += K[static_cast<std::size_t>(i) * n + j] * r * r * std::cos(alpha[i]) * sa *
               (sphere_star[i] + b[i]);
      nd[j] = scene.disc_albedo * sum;
    }
    double change = 0;
    for (int i = 0; i < m; ++i) change = std::max(change, std::abs(nb[i] - b[i]));
    for (int j = 0; j < n; ++j) change = std::max(change, std::abs(nd[j] - d[j]));
    b.swap(nb);
    d.swap(nd);
    last_change = largest > 0 ? change / largest : change;
  }
  disc_sent_.resize(n);
  sphere_sent_.resize(m);
  for (int j = 0; j < n; ++j) disc_sent_[j] = disc_star[j] + d[j];
  for (int i = 0; i < m; ++i) sphere_sent_[i] = sphere_star[i] + b[i];
  disc_direct.resize(n);
  disc_total.resize(n);
  sphere_direct.resize(m);
  sphere_total.resize(m);
  for (int j = 0; j < n; ++j) {
    disc_direct[j] = reference_disc_direct(scene, u[j]);
    disc_total[j] = disc_direct[j] + d[j];
  }
  for (int i = 0; i < m; ++i) {
    sphere_direct[i] = reference_sphere_direct(scene, alpha[i]);
    sphere_total[i] = sphere_direct[i] + b[i];
  }
}

double ReferenceSolution::disc_indirect(double at_u) const {
  const int m = settings_.sphere_rings, k = settings_.azimuths;
  const double r = scene_.sphere_radius, sa = kPi / m, st = 2 * kPi / k;
  double sum = 0;
  for (int i = 0; i < m; ++i) {
    double ring = 0;
    for (int s = 0; s < k; ++s) ring += exchange_kernel(scene_, alpha[i], at_u, (s + 0.5) * st);
    sum += ring * st * r * r * std::cos(alpha[i]) * sa * sphere_sent_[i];
  }
  return scene_.disc_albedo * sum;
}

double ReferenceSolution::sphere_indirect(double at_alpha) const {
  const int n = settings_.disc_rings, k = settings_.azimuths;
  const double su = scene_.disc_radius / n, st = 2 * kPi / k;
  double sum = 0;
  for (int j = 0; j < n; ++j) {
    double ring = 0;
    for (int s = 0; s < k; ++s) ring += exchange_kernel(scene_, at_alpha, u[j], (s + 0.5) * st);
    sum += ring * st * u[j] * su * disc_sent_[j];
  }
  return scene_.sphere_albedo * sum;
}

double ReferenceSolution::disc_at(double at_u) const {
  return reference_disc_direct(scene_, at_u) + disc_indirect(at_u);
}

double ReferenceSolution::sphere_at(double at_alpha) const {
  return reference_sphere_direct(scene_, at_alpha) + sphere_indirect(at_alpha);
}

double ReferenceSolution::disc_to_sphere_factor(double at_u) const {
  const int m = settings_.sphere_rings, k = settings_.azimuths;
  const double r = scene_.sphere_radius, sa = kPi / m, st = 2 * kPi / k;
  double sum = 0;
  for (int i = 0; i < m; ++i)
    for (int s = 0; s < k; ++s)
      sum += exchange_kernel(scene_, alpha[i], at_u, (s + 0.5) * st) * st * r * r * std::cos(alpha[i]) * sa;
  return sum;
}

std::string sphere_disc_scene_json(const SphereDiscScene& scene, const FeSettings& settings) {
  const double window = scene.disc_radius * 1.05;
  return fmt::format(
      R"({{"format": "candela/1",
  "camera": {{"type": "orthographic", "eye": [0, {eye}, 0], "target": [0, 0, 0], "up": [0, 0, -1],
             "window": [{lo}, {hi}, {lo}, {hi}], "width": 64, "height": 64}},
  "render": {{"method": "meshless"}},
  "meshless": {{"basis": "{basis}", "spacing": {spacing}, "grid": {grid}, "rounds": {rounds}, "transport": "{transport}"}},
  "lights": [{{"type": "directional", "direction": [0, -1, 0], "intensity": {mu}}}],
  "shapes": [
    {{"type": "disc", "center": [0, 0, 0], "normal": [0, 1, 0], "radius": {R}, "material": {{"kd": {delta}}}}},
    {{"type": "sphere", "center": [0, {h}, 0], "radius": {r}, "material": {{"kd": {beta}}}}}
  ]}})",
      fmt::arg("eye", scene.height * 5), fmt::arg("lo", -window), fmt::arg("hi", window),
      fmt::arg("basis", kBasisNames.name(settings.basis)), fmt::arg("spacing", settings.spacing),
      fmt::arg("transport", settings.transport), fmt::arg("grid", settings.grid),
      fmt::arg("rounds", settings.rounds), fmt::arg("mu", scene.light), fmt::arg("R", scene.disc_radius),
      fmt::arg("delta", scene.disc_albedo), fmt::arg("h", scene.height), fmt::arg("r", scene.sphere_radius),
      fmt::arg("beta", scene.sphere_albedo));
}

FeCurves solve_fe(const SphereDiscScene& scene, const FeSettings& settings, const std::vector<double>& u,
                  const std::vector<double>& alpha) {
  const auto start = std::chrono::steady_clock::now();
  const auto loaded = load_scene_text(sphere_disc_scene_json(scene, settings), "sphere-disc.json", ".");
  nlohmann::json facts;
  const MeshlessSolution solution =
      solve_meshless(*loaded, read_meshless_settings(loaded->plugin_settings.node("meshless")), &facts);
  const SiteSet& set = solution.sites;
  const MeshlessBasis basis(set.sites, set.radius, settings.basis);
  FeCurves curves;
  curves.sites = set.sites.size();
  for (const Site& site : set.sites)
    (std::abs(site.position.y) < 1e-6 ? curves.disc_sites : curves.sphere_sites)++;
  curves.converged = solution.transfer.converged;
  curves.precompute_seconds = facts.value("sampling_seconds", 0.0) + facts.value("area_seconds", 0.0) +
                              facts.value("hierarchy_seconds", 0.0) + facts.value("transfer_seconds", 0.0);
  curves.entries = solution.matrix.entries();
  const int k = std::max(1, settings.azimuths);
  // One ring: (mean, meridian, direct mean, uncovered points) of L = Σ λ_i φ_i at k azimuths.
  struct Ring {
    double mean = 0, meridian = 0, direct = 0;
    std::size_t uncovered = 0;
  };
  auto ring = [&](auto&& site_at) {
    std::vector<std::pair<uint32_t, double>> weights;
    Ring result;
    auto value = [&](double tau, double& direct) {
      basis.evaluate(site_at(tau), weights);
      double global = 0;
      direct = 0;
      for (const auto& [i, phi] : weights) {
        global += solution.transfer.lambda[i].g * phi;
        direct += solution.eta[i].g * phi;
      }
      if (weights.empty()) ++result.uncovered;
      return global;
    };
    for (int s = 0; s < k; ++s) {
      double direct = 0;
      result.mean += value((s + 0.5) * 2 * kPi / k, direct) / k;
      result.direct += direct / k;
    }
    double ignored = 0;
    result.meridian = value(0, ignored);
    return result;
  };
  const double r = scene.sphere_radius, h = scene.height;
  std::vector<Ring> disc(u.size()), sphere(alpha.size());
  tbb::parallel_for(std::size_t(0), u.size(), [&](std::size_t j) {
    disc[j] = ring([&](double tau) {
      return Site{{u[j] * std::cos(tau), 0, u[j] * std::sin(tau)}, {0, 1, 0}};
    });
  });
  tbb::parallel_for(std::size_t(0), alpha.size(), [&](std::size_t i) {
    const double ca = std::cos(alpha[i]), sa = std::sin(alpha[i]);
    sphere[i] = ring([&](double tau) {
      const Vec3 normal{ca * std::cos(tau), sa, ca * std::sin(tau)};
      return Site{Vec3{0, h, 0} + normal * r, normal};
    });
  });
  for (const Ring& x : disc) {
    curves.disc_mean.push_back(x.mean);
    curves.disc_meridian.push_back(x.meridian);
    curves.disc_direct_mean.push_back(x.direct);
    curves.uncovered += x.uncovered;
  }
  for (const Ring& x : sphere) {
    curves.sphere_mean.push_back(x.mean);
    curves.sphere_meridian.push_back(x.meridian);
    curves.sphere_direct_mean.push_back(x.direct);
    curves.uncovered += x.uncovered;
  }
  curves.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return curves;
}

CurveErrors curve_errors(const std::vector<double>& disc_fe, const std::vector<double>& disc_reference,
                         const std::vector<double>& sphere_fe, const std::vector<double>& sphere_reference) {
  if (disc_fe.size() != disc_reference.size() || sphere_fe.size() != sphere_reference.size())
    throw std::invalid_argument("curve_errors: mismatched sizes");
  CurveErrors e;
  double squares = 0, largest = 0;
  auto add = [&](const std::vector<double>& fe, const std::vector<double>& reference) {
    for (std::size_t i = 0; i < fe.size(); ++i) {
      const double difference = fe[i] - reference[i];
      squares += difference * difference;
      e.max = std::max(e.max, std::abs(difference));
      largest = std::max(largest, std::abs(reference[i]));
    }
  };
  add(disc_fe, disc_reference);
  add(sphere_fe, sphere_reference);
  const std::size_t count = disc_fe.size() + sphere_fe.size();
  e.rms = count ? std::sqrt(squares / static_cast<double>(count)) : 0.0;
  e.rms_relative = largest > 0 ? e.rms / largest : 0.0;
  e.max_relative = largest > 0 ? e.max / largest : 0.0;
  return e;
}

namespace {

nlohmann::json to_json(const CurveErrors& e) {
  return {{"rms", e.rms}, {"max", e.max}, {"rms_relative", e.rms_relative}, {"max_relative", e.max_relative}};
}

std::string csv(const char* header, const std::vector<double>& x,
                const std::vector<const std::vector<double>*>& columns) {
  std::string text = std::string(header) + "\n";
  for (std::size_t i = 0; i < x.size(); ++i) {
    text += fmt::format("{:.9g}", x[i]);
    for (const auto* c : columns) text += fmt::format(",{:.9g}", (*c)[i]);
    text += "\n";
  }
  return text;
}

void write_plot(const std::filesystem::path& path, const std::vector<PlotPanel>& panels) {
  write_line_plot_png(path.string(), panels, 600, 420);
}

const Color kReferenceTotal(0, 0, 0), kReferenceDirect(0.6, 0.6, 0.6);
Color basis_color(BasisKind kind) {
  switch (kind) {
    case BasisKind::radial:
      return Color(0.85, 0.15, 0.1);
    case BasisKind::normalized:
      return Color(0.1, 0.3, 0.9);
    case BasisKind::shepard:
      return Color(0.1, 0.65, 0.2);
  }
  return Color(0.5);
}
Color lighter(const Color& c) {
  return c * 0.45 + Color(0.55);
}

std::vector<double> degrees(const std::vector<double>& radians) {
  std::vector<double> out;
  for (const double a : radians) out.push_back(a * 180 / kPi);
  return out;
}

const BasisKind kComparedBases[] = {BasisKind::radial, BasisKind::normalized, BasisKind::shepard};
const double kComparedSpacings[] = {3, 1};

// What the steps of the validation share: the run's options, the folder its files go to, where its
// progress lines go, the scene with its reference solution, and the axes of every plot.
struct SphereDiscReport {
  SphereDiscReport(const SphereDiscRun& run, const std::filesystem::path& out, std::ostream* log,
                   const SphereDiscScene& scene, const ReferenceSolution& reference)
      : run(run),
        out(out),
        log(log),
        scene(scene),
        reference(reference),
        alpha_degrees(degrees(reference.alpha)),
        // Every panel titled, both axes named, every curve named in the legend.
        disc_axes{{},
                  0,
                  scene.disc_radius,
                  0,
                  0,
                  5,
                  0,
                  "disc: radiosity along a radius",
                  "distance u from the disc's centre",
                  "radiosity B"},
        sphere_axes{{},
                    -90,
                    90,
                    0,
                    0,
                    30,
                    0,
                    "sphere: radiosity along a meridian",
                    "angle α from the equator (degrees; 90: top)",
                    "radiosity B"} {}

  const SphereDiscRun& run;
  const std::filesystem::path& out;
  std::ostream* log;
  const SphereDiscScene& scene;
  const ReferenceSolution& reference;
  const std::vector<double> alpha_degrees;
  const PlotPanel disc_axes, sphere_axes;

  void say(const std::string& line) const {
    if (log) *log << line << std::endl;
  }

  // The refined reference evaluated at this one's nodes (Nyström): how far from converged it is.
  nlohmann::json refine_reference() const {
    const ReferenceSettings& settings = reference.settings();
    ReferenceSettings fine = settings;
    fine.disc_rings = fine.sphere_rings = fine.azimuths = 4 * settings.disc_rings;
    const auto start = std::chrono::steady_clock::now();
    const ReferenceSolution refined(scene, fine);
    std::vector<double> disc_fine(reference.u.size()), sphere_fine(reference.alpha.size());
    tbb::parallel_for(std::size_t(0), reference.u.size(),
                      [&](std::size_t j) { disc_fine[j] = refined.disc_at(reference.u[j]); });
    tbb::parallel_for(std::size_t(0), reference.alpha.size(),
                      [&](std::size_t i) { sphere_fine[i] = refined.sphere_at(reference.alpha[i]); });
    // Pointwise direct at the shadow edge node is the same convention in both; compare the totals.
    const CurveErrors difference =
        curve_errors(reference.disc_total, disc_fine, reference.sphere_total, sphere_fine);
    // And the thesis's own pointwise direct term in the rings' exchange, for comparison.
    ReferenceSettings pointwise = settings;
    pointwise.average_direct = false;
    const ReferenceSolution thesis(scene, pointwise);
    const CurveErrors thesis_difference =
        curve_errors(thesis.disc_total, disc_fine, thesis.sphere_total, sphere_fine);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    say(
        fmt::format("refined reference n = m = k = {}: largest difference {:.3g} ({:.3g} % of the largest), "
                    "{:.3g} % with the thesis's pointwise direct term; {:.1f} s",
                    fine.disc_rings, difference.max, 100 * difference.max_relative,
                    100 * thesis_difference.max_relative, seconds));
    return {{"n", fine.disc_rings},
            {"difference", to_json(difference)},
            {"pointwise_direct_difference", to_json(thesis_difference)},
            {"seconds", seconds}};
  }

  void write_reference() const {
    write_text_atomically(out / "reference_disc.csv", csv("u,direct,total", reference.u,
                                                          {&reference.disc_direct, &reference.disc_total}));
    write_text_atomically(
        out / "reference_sphere.csv",
        csv("alpha_deg,direct,total", alpha_degrees, {&reference.sphere_direct, &reference.sphere_total}));
    PlotPanel disc = disc_axes, sphere = sphere_axes;
    disc.curves = {
        {reference.u, reference.disc_direct, kReferenceDirect, 2, false, false, "reference, direct"},
        {reference.u, reference.disc_total, kReferenceTotal, 2, false, false, "reference, total"}};
    sphere.curves = {{alpha_degrees, reference.sphere_direct, kReferenceDirect, 2, false, false, {}},
                     {alpha_degrees, reference.sphere_total, kReferenceTotal, 2, false, false, {}}};
    write_plot(out / "reference.png", {disc, sphere});
  }

  // One FE solve's settings; quick: a coarser camera grid and fewer azimuths.
  FeSettings fe_settings(BasisKind kind, double spacing, const std::string& transport) const {
    FeSettings fe;
    fe.basis = kind;
    fe.spacing = spacing;
    fe.transport = transport;
    if (run.quick) {
      fe.grid = 64;
      fe.azimuths = 16;
    }
    return fe;
  }

  // The three bases at each spacing (flat transport) against the reference: result's "bases", and
  // per spacing the one of least RMS error, "least_rms".
  void compare_bases(nlohmann::json& result) const {
    nlohmann::json bases = nlohmann::json::object();
    std::map<double, std::vector<std::pair<BasisKind, FeCurves>>> by_spacing;
    for (const BasisKind kind : kComparedBases) {
      for (const double spacing : kComparedSpacings) {
        const FeCurves curves =
            solve_fe(scene, fe_settings(kind, spacing, "flat"), reference.u, reference.alpha);
        bases[std::string(kBasisNames.name(kind))][fmt::format("delta{}", spacing)] =
            compare_basis(kind, spacing, curves);
        by_spacing[spacing].emplace_back(kind, curves);
      }
    }
    result["bases"] = bases;
    nlohmann::json best = nlohmann::json::object();
    for (const double spacing : kComparedSpacings) {
      const std::string key = fmt::format("delta{}", spacing);
      std::string winner;
      double least = 0;
      for (const BasisKind kind : kComparedBases) {
        const nlohmann::json& rms = bases[std::string(kBasisNames.name(kind))][key]["rms"];
        if (!rms.is_number() || !std::isfinite(rms.get<double>())) continue;
        if (winner.empty() || rms.get<double>() < least)
          winner = std::string(kBasisNames.name(kind)), least = rms.get<double>();
      }
      best[key] = winner;
      plot_bases_together(spacing, key, by_spacing[spacing]);
    }
    result["least_rms"] = best;
  }

  // One basis at one spacing: its curves written, its errors against the reference (returned as
  // its entry of "bases"), its line of the log and its plot.
  nlohmann::json compare_basis(BasisKind kind, double spacing, const FeCurves& curves) const {
    const std::string name = fmt::format("fe_{}_delta{}", std::string(kBasisNames.name(kind)), spacing);
    write_text_atomically(out / (name + "_disc.csv"),
                          csv("u,direct,total,total_meridian", reference.u,
                              {&curves.disc_direct_mean, &curves.disc_mean, &curves.disc_meridian}));
    write_text_atomically(out / (name + "_sphere.csv"),
                          csv("alpha_deg,direct,total,total_meridian", alpha_degrees,
                              {&curves.sphere_direct_mean, &curves.sphere_mean, &curves.sphere_meridian}));
    const CurveErrors mean =
        curve_errors(curves.disc_mean, reference.disc_total, curves.sphere_mean, reference.sphere_total);
    const CurveErrors meridian = curve_errors(curves.disc_meridian, reference.disc_total,
                                              curves.sphere_meridian, reference.sphere_total);
    const CurveErrors direct = curve_errors(curves.disc_direct_mean, reference.disc_direct,
                                            curves.sphere_direct_mean, reference.sphere_direct);
    const CurveErrors indirect = indirect_errors(curves);
    nlohmann::json entry = to_json(mean);
    entry["spacing"] = spacing;
    entry["meridian"] = to_json(meridian);
    entry["direct"] = to_json(direct);
    entry["indirect"] = to_json(indirect);
    entry["sites"] = curves.sites;
    entry["disc_sites"] = curves.disc_sites;
    entry["sphere_sites"] = curves.sphere_sites;
    entry["uncovered_points"] = curves.uncovered;
    entry["converged"] = curves.converged;         // as solve_transfer reports it
    entry["diverged"] = !std::isfinite(mean.rms);  // JSON has no infinity: the errors are then null
    entry["seconds"] = curves.seconds;
    say(fmt::format(
        "{:<10} delta {}: {:>5} sites, RMS {:.4g} ({:.3g} %), max {:.4g} ({:.3g} %), indirect "
        "RMS {:.4g}; {:.1f} s",
        std::string(kBasisNames.name(kind)), spacing, curves.sites, mean.rms, 100 * mean.rms_relative,
        mean.max, 100 * mean.max_relative, indirect.rms, curves.seconds));
    plot_basis(kind, spacing, curves, name);
    return entry;
  }

  // The indirect light alone (total − direct): smooth, no shadow edge to interpolate.
  CurveErrors indirect_errors(const FeCurves& curves) const {
    std::vector<double> fe_disc_indirect, ref_disc_indirect, fe_sphere_indirect, ref_sphere_indirect;
    for (std::size_t j = 0; j < reference.u.size(); ++j) {
      fe_disc_indirect.push_back(curves.disc_mean[j] - curves.disc_direct_mean[j]);
      ref_disc_indirect.push_back(reference.disc_total[j] - reference.disc_direct[j]);
    }
    for (std::size_t i = 0; i < reference.alpha.size(); ++i) {
      fe_sphere_indirect.push_back(curves.sphere_mean[i] - curves.sphere_direct_mean[i]);
      ref_sphere_indirect.push_back(reference.sphere_total[i] - reference.sphere_direct[i]);
    }
    return curve_errors(fe_disc_indirect, ref_disc_indirect, fe_sphere_indirect, ref_sphere_indirect);
  }

  void plot_basis(BasisKind kind, double spacing, const FeCurves& curves, const std::string& name) const {
    const Color color = basis_color(kind);
    const std::string basis(kBasisNames.name(kind));
    PlotPanel disc = disc_axes, sphere = sphere_axes;
    disc.title += fmt::format(", {} basis, Δ = {}", basis, spacing);
    sphere.title += fmt::format(", Δ = {}", spacing);
    disc.curves = {
        {reference.u, reference.disc_direct, kReferenceDirect, 2, false, false, "reference, direct"},
        {reference.u, reference.disc_total, kReferenceTotal, 2, false, false, "reference, total"},
        {reference.u, curves.disc_direct_mean, lighter(color), 2, true, false, basis + ", direct"},
        {reference.u, curves.disc_mean, color, 3, false, false, basis + ", total (azimuth mean)"},
        {reference.u, curves.disc_meridian, color, 1, false, false, basis + ", total (one meridian)"}};
    sphere.curves = {{alpha_degrees, reference.sphere_direct, kReferenceDirect, 2, false, false, {}},
                     {alpha_degrees, reference.sphere_total, kReferenceTotal, 2, false, false, {}},
                     {alpha_degrees, curves.sphere_direct_mean, lighter(color), 2, true, false, {}},
                     {alpha_degrees, curves.sphere_mean, color, 3, false, false, {}},
                     {alpha_degrees, curves.sphere_meridian, color, 1, false, false, {}}};
    write_plot(out / (name + ".png"), {disc, sphere});
  }

  // All three bases against the reference's total.
  void plot_bases_together(double spacing, const std::string& key,
                           const std::vector<std::pair<BasisKind, FeCurves>>& solved) const {
    PlotPanel disc = disc_axes, sphere = sphere_axes;
    disc.title = fmt::format("disc, Δ = {}: each basis's total", spacing);
    sphere.title = fmt::format("sphere, Δ = {}", spacing);
    disc.curves = {{reference.u, reference.disc_total, kReferenceTotal, 2, false, false, "reference, total"}};
    sphere.curves = {{alpha_degrees, reference.sphere_total, kReferenceTotal, 2, false, false, {}}};
    for (const auto& [kind, curves] : solved) {
      disc.curves.push_back({reference.u, curves.disc_mean, basis_color(kind), 2, false, false,
                             std::string(kBasisNames.name(kind))});
      sphere.curves.push_back({alpha_degrees, curves.sphere_mean, basis_color(kind), 2, false, false, {}});
    }
    write_plot(out / fmt::format("compare_{}.png", key), {disc, sphere});
  }

  // The flat and the hierarchical transport (normalized basis) at several spacings, each
  // with its precomputation time: which is more accurate for the same time.
  nlohmann::json compare_transports() const {
    std::string table = "transport,spacing,sites,entries,precompute_seconds,rms,rms_relative\n";
    nlohmann::json runs = nlohmann::json::array();
    const std::vector<std::pair<std::string, std::vector<double>>> plan =
        run.quick
            ? std::vector<std::pair<std::string, std::vector<double>>>{{"flat", {3}}, {"hierarchical", {3}}}
            : std::vector<std::pair<std::string, std::vector<double>>>{
                  {"flat", {3, 2, 1.5, 1.2, 1, 0.8, 0.7}}, {"hierarchical", {3, 2, 1.5, 1.2, 1, 0.8, 0.7}}};
    for (const auto& [transport, spacings_of_run] : plan)
      for (const double spacing : spacings_of_run) {
        const FeCurves curves = solve_fe(scene, fe_settings(BasisKind::normalized, spacing, transport),
                                         reference.u, reference.alpha);
        const CurveErrors mean =
            curve_errors(curves.disc_mean, reference.disc_total, curves.sphere_mean, reference.sphere_total);
        nlohmann::json entry = to_json(mean);
        entry["transport"] = transport;
        entry["spacing"] = spacing;
        entry["sites"] = curves.sites;
        entry["entries"] = curves.entries;
        entry["precompute_seconds"] = curves.precompute_seconds;
        runs.push_back(entry);
        table += fmt::format("{},{},{},{},{:.3f},{:.6g},{:.6g}\n", transport, spacing, curves.sites,
                             curves.entries, curves.precompute_seconds, mean.rms, mean.rms_relative);
        say(fmt::format(
            "{:<12} delta {}: {:>5} sites, {:>9} entries, precomputed in {:.2f} s, RMS {:.4g} ({:.3g} %)",
            transport, spacing, curves.sites, curves.entries, curves.precompute_seconds, mean.rms,
            100 * mean.rms_relative));
      }
    write_text_atomically(out / "transport.csv", table);
    return runs;
  }
};

}  // namespace

nlohmann::json run_sphere_disc_validation(const std::string& directory, const SphereDiscRun& run,
                                          std::ostream* log) {
  namespace fs = std::filesystem;
  const fs::path out(directory);
  std::error_code error;
  fs::create_directories(out, error);
  if (error || !fs::is_directory(out)) throw std::runtime_error("cannot create the directory " + directory);
  SphereDiscScene scene;
  ReferenceSettings settings;
  if (run.quick) {  // a disc of radius 15 (a seventh of the sites), a coarser reference
    scene.disc_radius = 15;
    settings.disc_rings = settings.sphere_rings = settings.azimuths = 30;
  }
  const auto start = std::chrono::steady_clock::now();
  const ReferenceSolution reference(scene, settings);
  const double reference_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const SphereDiscReport report(run, out, log, scene, reference);
  report.say(fmt::format("reference: n = m = k = {}, {} iterations, last change {:.3g}, {:.2f} s",
                         settings.disc_rings, settings.iterations, reference.last_change, reference_seconds));

  nlohmann::json result;
  result["quick"] = run.quick;
  result["scene"] = {{"sphere_radius", scene.sphere_radius},
                     {"disc_radius", scene.disc_radius},
                     {"height", scene.height},
                     {"sphere_albedo", scene.sphere_albedo},
                     {"disc_albedo", scene.disc_albedo},
                     {"light", scene.light},
                     {"units", "radiosity (exitance) B; radiance is B/pi"}};
  double reference_largest = 0;
  for (const double v : reference.disc_total) reference_largest = std::max(reference_largest, v);
  for (const double v : reference.sphere_total) reference_largest = std::max(reference_largest, v);
  result["reference"] = {{"n", settings.disc_rings},
                         {"m", settings.sphere_rings},
                         {"k", settings.azimuths},
                         {"iterations", settings.iterations},
                         {"last_change", reference.last_change},
                         {"average_direct", settings.average_direct},
                         {"largest_total", reference_largest},
                         {"seconds", reference_seconds}};
  if (run.refine) result["reference"]["refinement"] = report.refine_reference();
  report.write_reference();
  report.compare_bases(result);
  result["transport"] = report.compare_transports();
  result["error_definition"] =
      "FE azimuth mean (or meridian) minus reference total at the reference's n disc nodes and m sphere "
      "nodes "
      "together, each node once; relative: over the reference's largest total";
  write_text_atomically(out / "errors.json", result.dump(2) + "\n");
  return result;
}

}  // namespace candela
