#include "io/solution_csv.h"

#include <array>
#include <charconv>
#include <ostream>
#include <string>

namespace candela {

namespace {

// Shortest text that reads back to the same double (std::to_chars without a precision).
void append_number(std::string& text, double value) {
  std::array<char, 32> digits;  // the longest shortest-round-trip double is 24 characters
  const auto result = std::to_chars(digits.data(), digits.data() + digits.size(), value);
  text.append(digits.data(), result.ptr);
}

}  // namespace

void write_solution_csv(std::span<const SolutionElementRow> elements, std::ostream& out) {
  std::string text = "id,patch,area,cx,cy,cz,nx,ny,nz,e_r,e_g,e_b,rho_r,rho_g,rho_b,b_r,b_g,b_b\n";
  for (std::size_t id = 0; id < elements.size(); ++id) {
    const SolutionElementRow& element = elements[id];
    text += std::to_string(id);
    text += ',';
    text += std::to_string(element.patch);
    const auto field = [&text](double value) {
      text += ',';
      append_number(text, value);
    };
    field(element.area);
    for (int axis = 0; axis < 3; ++axis) field(element.centroid[axis]);
    for (int axis = 0; axis < 3; ++axis) field(element.normal[axis]);
    for (int channel = 0; channel < 3; ++channel) field(element.emission[channel]);
    for (int channel = 0; channel < 3; ++channel) field(element.reflectance[channel]);
    for (int channel = 0; channel < 3; ++channel) field(element.radiosity[channel]);
    text += '\n';
  }
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
}

}  // namespace candela
