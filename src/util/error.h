// Errors that point at the input: file, line, column and JSON path (SPEC §3, §15).
#pragma once

#include <stdexcept>
#include <string>

namespace candela {

struct SourceLocation {
  std::string file;       // empty for the built-in scene or command-line overrides
  int line = 0;           // 1-based; 0 when unknown
  int column = 0;         // 1-based; 0 when unknown
  std::string json_path;  // e.g. "shapes[3].radius"; empty when not inside a JSON document

  // "file:line:column: json_path" with the parts that are known.
  std::string describe() const;
};

// Bad input (scene file, mesh file, command-line value). Exit code 2, nothing written.
class InputError : public std::runtime_error {
 public:
  InputError(SourceLocation location, const std::string& message);
  const SourceLocation& location() const { return location_; }
  const std::string& message() const { return message_; }

 private:
  SourceLocation location_;
  std::string message_;
};

}  // namespace candela
