// A parsed JSON file that remembers where each value started (line, column), so every
// error can name file, line, column and JSON path (SPEC §3).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <unordered_map>
#include <vector>

#include "util/error.h"

namespace candela {

class JsonDocument {
 public:
  // Parses text (JSON with // and /* */ comments allowed). Throws InputError on a syntax
  // error or a duplicate key, with the line and column of the offending character.
  static JsonDocument parse(const std::string& text, const std::string& file);

  // Applies "dotted.path=value" overrides (SPEC §3 --set). The value is read as JSON when it
  // parses as JSON, else as a string. Array elements are addressed by number
  // ("shapes.2.radius"). Throws InputError when the path crosses a non-container.
  void apply_override(const std::string& assignment);

  const nlohmann::json& root() const { return root_; }
  // The root to add to (a scene's "include"): what the text located keeps its position, so
  // additions go after what was parsed (new keys, array elements appended), never before it.
  nlohmann::json& root_to_extend() { return root_; }
  const std::string& file() const { return file_; }
  // The location of the value at json_path ("shapes[3].radius"); file only when unknown.
  SourceLocation locate(const std::string& json_path) const;

 private:
  struct Position {
    int line = 0;
    int column = 0;
    std::string origin;  // a --set assignment, else empty (the file)
  };
  friend class LocatingSaxHandler;
  nlohmann::json root_;
  std::string file_;
  std::unordered_map<std::string, Position> positions_;
};

}  // namespace candela
