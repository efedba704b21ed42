#include "util/error.h"

namespace candela {

std::string SourceLocation::describe() const {
  std::string text = file.empty() ? std::string("<scene>") : file;
  if (line > 0) {
    text += ':' + std::to_string(line);
    if (column > 0) text += ':' + std::to_string(column);
  }
  if (!json_path.empty()) text += ": " + json_path;
  return text;
}

InputError::InputError(SourceLocation location, const std::string& message)
    : std::runtime_error(location.describe() + ": " + message),
      location_(std::move(location)),
      message_(message) {}

}  // namespace candela
