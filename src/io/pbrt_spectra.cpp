#include "io/pbrt_spectra.h"

#include <map>

namespace candela {

std::optional<PbrtRgb> pbrt_metal_spectrum(const std::string& name) {
  // η and κ per channel (R, G, B), from Palik's and Rakić's measurements as the RGB tables of
  // Mitsuba 0.5's conductor plugin and pbrt-v3's scenes give them.
  static const std::map<std::string, PbrtRgb> table = {
      {"metal-Cu-eta", {0.200438, 0.924033, 1.10221}},  {"metal-Cu-k", {3.91295, 2.45285, 2.14219}},
      {"metal-Au-eta", {0.143119, 0.374957, 1.44248}},  {"metal-Au-k", {3.98316, 2.38572, 1.60322}},
      {"metal-Ag-eta", {0.155265, 0.116723, 0.138381}}, {"metal-Ag-k", {4.82835, 3.12225, 2.14696}},
      {"metal-Al-eta", {1.65746, 0.880369, 0.521229}},  {"metal-Al-k", {9.22387, 6.26952, 4.837}},
  };
  const auto found = table.find(name);
  if (found == table.end()) return std::nullopt;
  return found->second;
}

std::optional<double> pbrt_glass_index(const std::string& name) {
  // Schott's optical glass catalogue, n_d at 587.56 nm; pbrt-v4's "glass-F5", "-F10" and "-F11" are
  // its Sellmeier data of SF5, SF10 and SF11.
  static const std::map<std::string, double> table = {
      {"glass-BK7", 1.5168}, {"glass-BAF10", 1.6700}, {"glass-FK51A", 1.4866}, {"glass-LASF9", 1.8503},
      {"glass-F5", 1.6727},  {"glass-F10", 1.7283},   {"glass-F11", 1.7847},
  };
  const auto found = table.find(name);
  if (found == table.end()) return std::nullopt;
  return found->second;
}

}  // namespace candela
