#include "io/ies_reader.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "math/constants.h"
#include "util/input_file.h"
#include "util/number_text.h"

namespace candela {

namespace {

constexpr uint64_t kIesFileLimit = 16u << 20;
constexpr std::size_t kMaxAngles = 100'000;

// The numbers after the TILT line: separated by blanks, commas and line ends, each with the
// line and column where it starts.
class NumberReader {
 public:
  NumberReader(std::string_view text, std::size_t position, int line, std::string file)
      : text_(text), position_(position), line_(line), line_start_(position), file_(std::move(file)) {}

  // The next number, `what` naming it for the message when it is missing or not a number.
  double number(const std::string& what) {
    skip_separators();
    const int line = line_, column = column_here();
    if (position_ >= text_.size())
      throw InputError({file_, line, column, {}}, fmt::format("the file ends where {} was expected", what));
    const std::size_t start = position_;
    while (position_ < text_.size() && !is_separator(text_[position_])) ++position_;
    const std::string_view token = text_.substr(start, position_ - start);
    double value = 0;
    if (!parse_finite_number(token, value))
      throw InputError({file_, line, column, {}},
                       fmt::format("\"{}\" is not a number (expected {})", std::string(token), what));
    last_line_ = line;
    last_column_ = column;
    // The scene file's limit on every number, so that no product of them overflows.
    if (std::fabs(value) > kMaxSceneMagnitude)
      fail(fmt::format("{}: magnitude above {:g} is not supported (found {:g})", what, kMaxSceneMagnitude,
                       value));
    return value;
  }
  // The next number, which must be an integer in [low, high].
  int integer(const std::string& what, int low, int high) {
    const double value = number(what);
    if (value != std::floor(value) || value < low || value > high)
      fail(fmt::format("{} must be an integer from {} to {}, not {}", what, low, high, value));
    return static_cast<int>(value);
  }
  // Throws at the number read last.
  [[noreturn]] void fail(const std::string& message) const {
    throw InputError({file_, last_line_, last_column_, {}}, message);
  }
  // A lower bound on the numbers left (every number takes at least two characters but the last).
  std::size_t most_numbers_left() const { return (text_.size() - position_) / 2 + 1; }
  const std::string& file() const { return file_; }

 private:
  static bool is_separator(char c) { return c == ' ' || c == '\t' || c == ',' || c == '\r' || c == '\n'; }
  void skip_separators() {
    while (position_ < text_.size() && is_separator(text_[position_])) {
      if (text_[position_] == '\n') {
        ++line_;
        line_start_ = position_ + 1;
      }
      ++position_;
    }
  }
  int column_here() const { return static_cast<int>(position_ - line_start_) + 1; }

  std::string_view text_;
  std::size_t position_;
  int line_;
  std::size_t line_start_;
  std::string file_;
  int last_line_ = 0, last_column_ = 0;
};

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.back() == '\r' || s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  return s;
}

// count angles, each within [low, high] and increasing.
std::vector<double> read_angles(NumberReader& numbers, std::size_t count, const char* what, double low,
                                double high) {
  std::vector<double> angles(count);
  for (std::size_t i = 0; i < count; ++i) {
    angles[i] = numbers.number(fmt::format("{} angle {} of {}", what, i + 1, count));
    if (angles[i] < low || angles[i] > high)
      numbers.fail(fmt::format("{} angle {} is {}°, outside {}° to {}°", what, i + 1, angles[i], low, high));
    if (i > 0 && !(angles[i] > angles[i - 1]))
      numbers.fail(fmt::format("{} angles must increase: angle {} is {}° after {}°", what, i + 1, angles[i],
                               angles[i - 1]));
  }
  return angles;
}

}  // namespace

Photometry parse_ies(std::string_view text, const std::string& file) {
  Photometry ies;
  // Lines up to and including TILT=.
  std::size_t position = 0;
  int line = 0;
  bool first = true, tilt_found = false;
  while (position < text.size()) {
    const std::size_t end = std::min(text.find('\n', position), text.size());
    const std::string_view row = trimmed(text.substr(position, end - position));
    ++line;
    position = end + (end < text.size() ? 1 : 0);
    if (first) {
      first = false;
      if (row.starts_with("IESNA:LM-63-1995")) {
        ies.format = "LM-63-1995";
        continue;
      }
      if (row.starts_with("IESNA:LM-63-2002") || row.starts_with("IES:LM-63-2002")) {
        ies.format = "LM-63-2002";
        continue;
      }
      if (row.starts_with("IESNA91")) {
        ies.format = "LM-63-1991";
        continue;
      }
      ies.format = "LM-63-1986";
    }
    if (row.starts_with("TILT=")) {
      ies.tilt = std::string(trimmed(row.substr(5)));
      if (ies.tilt.empty()) throw InputError({file, line, 6, {}}, "TILT= needs NONE, INCLUDE or a file name");
      tilt_found = true;
      break;
    }
    if (row.starts_with("[")) {
      const std::size_t close = row.find(']');
      if (close == std::string_view::npos)
        throw InputError({file, line, 1, {}}, "a keyword line must be [KEYWORD] text (no closing ])");
      ies.keywords.emplace_back(std::string(row.substr(1, close - 1)),
                                std::string(trimmed(row.substr(close + 1))));
    }
    // Other lines before TILT= (the 1986 format's free text) are labels.
  }
  if (!tilt_found)
    throw InputError({file, line, 0, {}}, "no TILT= line (expected TILT=NONE, TILT=INCLUDE or TILT=<file>)");

  NumberReader numbers(text, position, line + 1, file);
  if (ies.tilt == "INCLUDE") {
    numbers.integer("the lamp-to-luminaire geometry (1, 2 or 3)", 1, 3);
    const int count = numbers.integer("the number of tilt angles", 0, static_cast<int>(kMaxAngles));
    if (2 * std::size_t(count) > numbers.most_numbers_left())
      numbers.fail(fmt::format("{} tilt angles and factors do not fit in the rest of the file", count));
    for (int i = 0; i < count; ++i) numbers.number(fmt::format("tilt angle {} of {}", i + 1, count));
    for (int i = 0; i < count; ++i) numbers.number(fmt::format("tilt factor {} of {}", i + 1, count));
  }
  ies.lamps = numbers.integer("the number of lamps", 1, 1'000'000);
  ies.lumens_per_lamp = numbers.number("the lumens per lamp");
  if (!(ies.lumens_per_lamp > 0) && ies.lumens_per_lamp != -1)
    numbers.fail(fmt::format("the lumens per lamp must be > 0 or -1 (absolute photometry), not {}",
                             ies.lumens_per_lamp));
  ies.candela_multiplier = numbers.number("the candela multiplier");
  if (!(ies.candela_multiplier > 0))
    numbers.fail(fmt::format("the candela multiplier must be > 0, not {}", ies.candela_multiplier));
  const int vertical_count =
      numbers.integer("the number of vertical angles", 1, static_cast<int>(kMaxAngles));
  const int horizontal_count =
      numbers.integer("the number of horizontal angles", 1, static_cast<int>(kMaxAngles));
  ies.type = static_cast<PhotometricType>(numbers.integer("the photometric type (1 C, 2 B, 3 A)", 1, 3));
  ies.metres = numbers.integer("the units type (1 feet, 2 metres)", 1, 2) == 2;
  ies.width = numbers.number("the luminous opening's width");
  ies.length = numbers.number("the luminous opening's length");
  ies.height = numbers.number("the luminous opening's height");
  ies.ballast_factor = numbers.number("the ballast factor");
  if (!(ies.ballast_factor > 0))
    numbers.fail(fmt::format("the ballast factor must be > 0, not {}", ies.ballast_factor));
  numbers.number("the ballast-lamp photometric factor (reserved)");
  ies.input_watts = numbers.number("the input watts");
  const std::size_t values = std::size_t(vertical_count) * std::size_t(horizontal_count);
  if (vertical_count + horizontal_count + values > numbers.most_numbers_left())
    numbers.fail(fmt::format("{} × {} angles and their {} candela values do not fit in the rest of the file",
                             vertical_count, horizontal_count, values));
  const bool type_c = ies.type == PhotometricType::c;
  ies.vertical = read_angles(numbers, vertical_count, "vertical", type_c ? 0 : -90, type_c ? 180 : 90);
  ies.horizontal = read_angles(numbers, horizontal_count, "horizontal", type_c ? 0 : -90, type_c ? 360 : 90);
  if (type_c && horizontal_count > 1) {
    const double h0 = ies.horizontal.front(), h1 = ies.horizontal.back();
    const bool known = h0 == 0 ? (h1 == 90 || h1 == 180 || h1 > 180) : (h0 == 90 && h1 == 270);
    if (!known)
      numbers.fail(fmt::format(
          "type C horizontal angles {}° to {}° are none of LM-63's symmetries (0 to 90, 0 to 180, 0 to "
          "more than 180, 90 to 270)",
          h0, h1));
  }
  if (type_c && horizontal_count == 1 && ies.horizontal[0] != 0)
    numbers.fail("a single type C horizontal angle must be 0 (rotational symmetry)");
  if (!type_c && horizontal_count > 1 && ies.horizontal.front() != 0 && ies.horizontal.front() != -90)
    numbers.fail("type A or B horizontal angles must start at 0 or -90");
  ies.candela.resize(values);
  const double scale = ies.candela_multiplier * ies.ballast_factor;
  for (int h = 0; h < horizontal_count; ++h)
    for (int v = 0; v < vertical_count; ++v) {
      const double value = numbers.number(fmt::format(
          "the candela value at vertical angle {}°, horizontal {}°", ies.vertical[v], ies.horizontal[h]));
      if (value < 0) numbers.fail(fmt::format("candela values cannot be negative ({})", value));
      // Two large legal numbers made every intensity infinite (and 0 × inf NaN).
      if (value * scale > kMaxSceneMagnitude)
        numbers.fail(fmt::format(
            "the candela value {:g} × the candela multiplier {:g} × the ballast factor {:g} is {:g} cd, "
            "above {:g} (the largest intensity supported)",
            value, ies.candela_multiplier, ies.ballast_factor, value * scale, kMaxSceneMagnitude));
      ies.candela[std::size_t(h) * vertical_count + v] = value * scale;
    }
  return ies;
}

Photometry read_ies(const std::string& path) {
  return parse_ies(read_input_file(path, "the IES file", kIesFileLimit), path);
}

}  // namespace candela
