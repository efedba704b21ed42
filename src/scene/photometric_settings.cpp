#include "scene/photometric_settings.h"

#include "shading/photometric_units.h"

namespace candela {

std::string amount_key(const JsonNode& node, std::initializer_list<const char*> keys) {
  // json().contains does not mark a key as read: a key that is not used stays unknown.
  std::string given;
  for (const char* key : keys)
    if (node.json().contains(key)) {
      if (!given.empty()) node.at(key).fail("give one of " + given + " and " + key + ", not both");
      given = key;
    }
  return given.empty() ? *keys.begin() : given;
}

Color read_photometric_color(const JsonNode& node, std::string_view color_key,
                             std::string_view temperature_key, const Color& fallback) {
  const bool has_color = node.json().contains(color_key),
             has_temperature = node.json().contains(temperature_key);
  if (has_color && has_temperature)
    node.at(temperature_key)
        .fail("give " + std::string(color_key) + " or " + std::string(temperature_key) + ", not both");
  if (has_temperature)
    return blackbody_color(node.number(temperature_key, 6500, {1000, 40000, false, false}));
  if (!has_color) return fallback;
  const Color color = node.color(color_key, Color(1), Range::non_negative());
  if (!(luminance(color) > 0))
    node.at(color_key).fail("must have a luminance > 0 (only its chromaticity counts)");
  return color;
}

}  // namespace candela
