#include "io/eulumdat_reader.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "math/constants.h"
#include "util/input_file.h"
#include "util/number_text.h"

namespace candela {

namespace {

constexpr uint64_t kEulumdatFileLimit = 16u << 20;
constexpr int kMaxPlanes = 3600;
constexpr int kMaxGammas = 18001;

// The file's lines, one value each.
class LineReader {
 public:
  LineReader(std::string_view text, std::string file) : text_(text), file_(std::move(file)) {}

  std::string_view text(const std::string& what) {
    if (position_ >= text_.size())
      throw InputError({file_, line_ + 1, 0, {}}, fmt::format("the file ends where {} was expected", what));
    const std::size_t end = std::min(text_.find('\n', position_), text_.size());
    std::string_view row = text_.substr(position_, end - position_);
    position_ = end + (end < text_.size() ? 1 : 0);
    ++line_;
    while (!row.empty() && (row.back() == '\r' || row.back() == ' ' || row.back() == '\t'))
      row.remove_suffix(1);
    while (!row.empty() && (row.front() == ' ' || row.front() == '\t')) row.remove_prefix(1);
    return row;
  }
  double number(const std::string& what) {
    const std::string_view row = text(what);
    // Some writers use a decimal comma.
    std::string token(row);
    for (char& c : token)
      if (c == ',') c = '.';
    double value = 0;
    if (!parse_finite_number(token, value))
      fail(fmt::format("\"{}\" is not a number (expected {})", std::string(row), what));
    // The scene file's limit on every number, so that no product of them overflows.
    if (std::fabs(value) > kMaxSceneMagnitude)
      fail(fmt::format("{}: magnitude above {:g} is not supported (found {:g})", what, kMaxSceneMagnitude,
                       value));
    return value;
  }
  int integer(const std::string& what, int low, int high) {
    const double value = number(what);
    if (value != std::floor(value) || value < low || value > high)
      fail(fmt::format("{} must be an integer from {} to {}, not {}", what, low, high, value));
    return static_cast<int>(value);
  }
  [[noreturn]] void fail(const std::string& message) const {
    throw InputError({file_, line_, 0, {}}, message);
  }
  std::size_t lines_left() const {
    std::size_t count = 0;
    for (std::size_t i = position_; i < text_.size(); ++i) count += text_[i] == '\n';
    return count + 1;
  }

 private:
  std::string_view text_;
  std::string file_;
  std::size_t position_ = 0;
  int line_ = 0;
};

}  // namespace

Photometry parse_eulumdat(std::string_view text, const std::string& file) {
  Photometry result;
  result.format = "EULUMDAT";
  result.type = PhotometricType::c;
  result.metres = true;
  LineReader lines(text, file);
  const auto keep = [&](const char* name, std::string_view value) {
    result.keywords.emplace_back(name, std::string(value));
  };
  keep("COMPANY", lines.text("the company identification (line 1)"));
  lines.integer("the type indicator Ityp (line 2)", 0, 3);
  const int symmetry = lines.integer("the symmetry indicator Isym (line 3)", 0, 4);
  const int planes = lines.integer("the number of C-planes Mc (line 4)", 1, kMaxPlanes);
  lines.number("the distance between C-planes Dc (line 5)");
  const int gammas = lines.integer("the number of intensities per C-plane Ng (line 6)", 1, kMaxGammas);
  lines.number("the distance between intensities Dg (line 7)");
  keep("TEST", lines.text("the measurement report number (line 8)"));
  keep("LUMINAIRE", lines.text("the luminaire name (line 9)"));
  keep("LUMCAT", lines.text("the luminaire number (line 10)"));
  keep("FILENAME", lines.text("the file name (line 11)"));
  keep("DATE", lines.text("the date/user (line 12)"));
  for (const char* what :
       {"the luminaire length (line 13)", "the luminaire width (line 14)", "the luminaire height (line 15)"})
    lines.number(what);
  result.length = lines.number("the luminous area's length (line 16)") / 1000;
  result.width = lines.number("the luminous area's width (line 17)") / 1000;
  double heights = 0;
  for (const char* what : {"the luminous area's height at C0 (line 18)", "its height at C90 (line 19)",
                           "its height at C180 (line 20)", "its height at C270 (line 21)"})
    heights += lines.number(what);
  result.height = heights / 4 / 1000;
  lines.number("the downward flux fraction (line 22)");
  lines.number("the light output ratio (line 23)");
  const double conversion = lines.number("the conversion factor for luminous intensities (line 24)");
  if (!(conversion > 0)) lines.fail(fmt::format("the conversion factor must be > 0, not {}", conversion));
  result.tilt = fmt::format("{}", lines.number("the tilt during measurement (line 25)"));
  const int sets = lines.integer("the number of standard sets of lamps n (line 26)", 1, 1000);
  // Per set six lines, in the order 26a for every set, then 26b for every set, …
  std::vector<double> lamp_counts(sets), fluxes(sets), watts(sets);
  for (int s = 0; s < sets; ++s)
    lamp_counts[s] = lines.number(fmt::format("the number of lamps of set {}", s + 1));
  for (int s = 0; s < sets; ++s) lines.text(fmt::format("the type of lamps of set {}", s + 1));
  for (int s = 0; s < sets; ++s) {
    fluxes[s] = lines.number(fmt::format("the total luminous flux of lamps of set {} (lm)", s + 1));
    if (!(fluxes[s] > 0)) lines.fail(fmt::format("the luminous flux of lamp set {} must be > 0", s + 1));
  }
  for (int s = 0; s < sets; ++s) lines.text(fmt::format("the colour of set {}", s + 1));
  for (int s = 0; s < sets; ++s) lines.text(fmt::format("the colour rendering of set {}", s + 1));
  for (int s = 0; s < sets; ++s) watts[s] = lines.number(fmt::format("the wattage of set {} (W)", s + 1));
  // Held to the IES reader's 1 to 1,000,000 (a count of 1e16 once wrapped round an int).
  result.lamps = static_cast<int>(std::clamp(std::lround(std::fabs(lamp_counts[0])), 1L, 1'000'000L));
  result.lumens_per_lamp = fluxes[0] / result.lamps;
  result.input_watts = watts[0];
  for (int k = 0; k < 10; ++k) lines.number(fmt::format("direct ratio {} of 10 (line 27)", k + 1));

  // The planes the symmetry keeps.
  int first_plane = 0, stored = planes;
  switch (symmetry) {
    case 1:
      stored = 1;
      break;
    case 2:
      stored = planes / 2 + 1;
      break;
    case 3:
      first_plane = planes / 4;
      stored = planes / 2 + 1;
      break;
    case 4:
      stored = planes / 4 + 1;
      break;
    default:
      break;
  }
  if ((symmetry == 2 && planes % 2 != 0) || ((symmetry == 3 || symmetry == 4) && planes % 4 != 0))
    lines.fail(fmt::format("Isym {} needs a number of C-planes divisible by {}, not {}", symmetry,
                           symmetry == 2 ? 2 : 4, planes));
  const std::size_t values = std::size_t(stored) * std::size_t(gammas);
  if (planes + gammas + values > lines.lines_left())
    lines.fail(fmt::format("{} C-angles, {} γ-angles and {} intensities do not fit in the rest of the file",
                           planes, gammas, values));
  std::vector<double> c_angles(planes);
  for (int i = 0; i < planes; ++i) {
    c_angles[i] = lines.number(fmt::format("C-angle {} of {}", i + 1, planes));
    if (c_angles[i] < 0 || c_angles[i] >= 360 || (i > 0 && !(c_angles[i] > c_angles[i - 1])))
      lines.fail(
          fmt::format("C-angles must increase from 0° to below 360°: C-angle {} is {}°", i + 1, c_angles[i]));
  }
  result.vertical.resize(gammas);
  for (int i = 0; i < gammas; ++i) {
    result.vertical[i] = lines.number(fmt::format("γ-angle {} of {}", i + 1, gammas));
    if (result.vertical[i] < 0 || result.vertical[i] > 180 ||
        (i > 0 && !(result.vertical[i] > result.vertical[i - 1])))
      lines.fail(fmt::format("γ-angles must increase within 0° to 180°: γ-angle {} is {}°", i + 1,
                             result.vertical[i]));
  }
  if (symmetry == 1) {
    result.horizontal = {0};
  } else {
    if (first_plane + stored > planes) lines.fail("the stored C-planes run past C-angle 360°");
    result.horizontal.assign(c_angles.begin() + first_plane, c_angles.begin() + first_plane + stored);
    // The last stored plane of a symmetric file is C90, C180 or C270.
    const double expected_last = symmetry == 2 ? 180 : symmetry == 3 ? 270 : symmetry == 4 ? 90 : -1;
    if (expected_last >= 0 && result.horizontal.back() != expected_last)
      lines.fail(fmt::format("Isym {}: the stored planes must end at C{}, not C{}", symmetry, expected_last,
                             result.horizontal.back()));
  }
  const double scale = fluxes[0] / 1000 * conversion;
  result.candela.resize(values);
  for (int p = 0; p < stored; ++p)
    for (int g = 0; g < gammas; ++g) {
      const double value = lines.number(
          fmt::format("the intensity at C{}°, γ {}° (cd/klm)", result.horizontal[p], result.vertical[g]));
      if (value < 0) lines.fail(fmt::format("intensities cannot be negative ({})", value));
      // Two large legal numbers made every intensity infinite (and 0 × inf NaN).
      if (value * scale > kMaxSceneMagnitude)
        lines.fail(fmt::format(
            "the intensity {:g} cd/klm × the lamp flux {:g} lm / 1000 × the conversion factor {:g} is {:g} "
            "cd, above {:g} (the largest intensity supported)",
            value, fluxes[0], conversion, value * scale, kMaxSceneMagnitude));
      result.candela[std::size_t(p) * gammas + g] = value * scale;
    }
  return result;
}

Photometry read_eulumdat(const std::string& path) {
  return parse_eulumdat(read_input_file(path, "the EULUMDAT file", kEulumdatFileLimit), path);
}

}  // namespace candela
