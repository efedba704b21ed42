#include "util/statistics.h"

#include <fmt/format.h>
#include <sys/resource.h>

#include <algorithm>

namespace candela {

void RunStatistics::absorb(RunStatistics&& other) {
  for (auto& phase : other.phases) phases.push_back(std::move(phase));
  rays += other.rays;
  pixels += other.pixels;
  primary_per_pixel = std::move(other.primary_per_pixel);
  samples_per_pixel = std::move(other.samples_per_pixel);
  for (auto& [key, value] : other.extra.items()) extra[key] = std::move(value);
}

nlohmann::json RunStatistics::to_json() const {
  nlohmann::json out = extra;
  nlohmann::json phase_list = nlohmann::json::object();
  double total = 0;
  for (const auto& [name, seconds] : phases) {
    phase_list[name] = seconds;
    total += seconds;
  }
  out["phases_seconds"] = phase_list;
  out["total_seconds"] = total;
  out["rays"] = {{"primary", rays.primary},
                 {"shadow", rays.shadow},
                 {"reflected", rays.reflected},
                 {"refracted", rays.refracted},
                 {"total", rays.total()}};
  out["pixels"] = pixels;
  const auto mean_max = [](const std::vector<uint32_t>& counts) {
    uint64_t sum = 0;
    uint32_t most = 0;
    for (const uint32_t count : counts) {
      sum += count;
      most = std::max(most, count);
    }
    return nlohmann::json{{"mean", counts.empty() ? 0.0 : double(sum) / double(counts.size())},
                          {"max", most}};
  };
  if (!primary_per_pixel.empty()) out["rays"]["primary_per_pixel"] = mean_max(primary_per_pixel);
  if (!samples_per_pixel.empty()) out["samples_per_pixel"] = mean_max(samples_per_pixel);
  out["threads"] = threads;
  out["peak_memory_bytes"] = peak_memory_bytes();
  return out;
}

std::string RunStatistics::summary() const {
  std::string text;
  double total = 0;
  for (const auto& [name, seconds] : phases) {
    text += fmt::format("  {:<16} {:>10.3f} s\n", name, seconds);
    total += seconds;
  }
  text += fmt::format("  {:<16} {:>10.3f} s\n", "total", total);
  // No "0 rays, 0.00 Mrays/s" for a method that traced none (a rasterized display).
  if (rays.total() == 0) {
    text += "  rays: none traced\n";
  } else {
    text += fmt::format("  rays: {} primary, {} shadow, {} reflected, {} refracted ({} total", rays.primary,
                        rays.shadow, rays.reflected, rays.refracted, rays.total());
    double render_seconds = 0;
    for (const auto& [name, seconds] : phases)
      if (name == "render") render_seconds = seconds;
    // Three significant digits: a slow render reads 0.00185 Mrays/s, not 0.00.
    if (render_seconds > 0) text += fmt::format(", {:#.3g} Mrays/s", rays.total() / render_seconds / 1e6);
    text += ")\n";
  }
  if (!primary_per_pixel.empty() && pixels > 0) {
    uint32_t most = 0;
    for (const uint32_t count : primary_per_pixel) most = std::max(most, count);
    text += fmt::format("  primary rays per pixel: mean {:.3f}, max {}\n",
                        double(rays.primary) / double(pixels), most);
  }
  text += fmt::format("  pixels: {}, threads: {}, peak memory: {:.1f} MiB\n", pixels, threads,
                      peak_memory_bytes() / (1024.0 * 1024.0));
  return text;
}

uint64_t peak_memory_bytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<uint64_t>(usage.ru_maxrss) * 1024;  // kilobytes on Linux
}

}  // namespace candela
