// The tokens of a pbrt-v4 scene file (pbrt-v4's file-format documentation, "Scene file format"):
// quoted strings ("…", with \" \\ \n \t escapes, on one line), numbers, [ and ], and bare words (the
// directives, and true/false). '#' starts a comment to the end of the line. Each token knows where
// it starts (file, line, column), so every error of the parser that reads them is located.
#pragma once

#include <string>
#include <vector>

#include "util/error.h"

namespace candela {

struct PbrtToken {
  enum class Kind { kString, kNumber, kOpenBracket, kCloseBracket, kWord };
  Kind kind = Kind::kWord;
  std::string text;      // a string's content (escapes resolved), a word or a number as written
  double number = 0;     // kNumber: the value (finite)
  SourceLocation where;  // its first character
};

// All tokens of `text` (the file `file`); throws InputError at the offending character for an
// unterminated string, a bad escape, a malformed or non-finite number, or a stray character.
std::vector<PbrtToken> tokenize_pbrt(const std::string& text, const std::string& file);

}  // namespace candela
