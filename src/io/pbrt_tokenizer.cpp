#include "io/pbrt_tokenizer.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

namespace candela {

namespace {

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}
// Where a number or a word ends: white space, a bracket, a quote or a comment.
bool ends_token(char c) {
  return is_space(c) || c == '[' || c == ']' || c == '"' || c == '#';
}
bool starts_number(char c) {
  return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.';
}
bool is_letter(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_';
}

class Tokenizer {
 public:
  Tokenizer(const std::string& text, const std::string& file) : text_(text), file_(file) {}

  std::vector<PbrtToken> run() {
    std::vector<PbrtToken> tokens;
    while (skip_space_and_comments()) {
      const SourceLocation start = here();
      const char c = text_[at_];
      if (c == '"') {
        tokens.push_back({PbrtToken::Kind::kString, read_string(start), 0, start});
      } else if (c == '[' || c == ']') {
        advance();
        tokens.push_back({c == '[' ? PbrtToken::Kind::kOpenBracket : PbrtToken::Kind::kCloseBracket,
                          std::string(1, c), 0, start});
      } else if (starts_number(c)) {
        const std::string written = read_run();
        tokens.push_back({PbrtToken::Kind::kNumber, written, parse_number(written, start), start});
      } else if (is_letter(c)) {
        tokens.push_back({PbrtToken::Kind::kWord, read_run(), 0, start});
      } else {
        throw InputError(start, fmt::format("unexpected character '{}' (0x{:02x})",
                                            (c >= 32 && c < 127) ? c : '?', static_cast<unsigned char>(c)));
      }
    }
    return tokens;
  }

 private:
  SourceLocation here() const { return {file_, line_, column_, {}}; }
  void advance() {
    if (text_[at_] == '\n') {
      ++line_;
      column_ = 1;
    } else {
      ++column_;
    }
    ++at_;
  }
  // False at the end of the text.
  bool skip_space_and_comments() {
    while (at_ < text_.size()) {
      if (is_space(text_[at_])) {
        advance();
      } else if (text_[at_] == '#') {
        while (at_ < text_.size() && text_[at_] != '\n') advance();
      } else {
        return true;
      }
    }
    return false;
  }
  std::string read_run() {
    const std::size_t begin = at_;
    while (at_ < text_.size() && !ends_token(text_[at_])) advance();
    return text_.substr(begin, at_ - begin);
  }
  std::string read_string(const SourceLocation& start) {
    advance();  // the opening quote
    std::string out;
    while (true) {
      if (at_ >= text_.size() || text_[at_] == '\n')
        throw InputError(start, "unterminated string (a string ends with \" on the line it starts)");
      const char c = text_[at_];
      if (c == '"') {
        advance();
        return out;
      }
      if (c == '\\') {
        const SourceLocation escape = here();
        advance();
        if (at_ >= text_.size()) throw InputError(start, "unterminated string");
        const char e = text_[at_];
        if (e == 'n')
          out += '\n';
        else if (e == 't')
          out += '\t';
        else if (e == '\\' || e == '"' || e == '\'')
          out += e;
        else
          throw InputError(escape, fmt::format("unknown escape '\\{}' in a string", e));
        advance();
        continue;
      }
      out += c;
      advance();
    }
  }
  static double parse_number(const std::string& written, const SourceLocation& start) {
    // from_chars takes no leading '+'.
    const char* first = written.data() + (written[0] == '+' ? 1 : 0);
    const char* last = written.data() + written.size();
    double value = 0;
    const auto [end, error] = std::from_chars(first, last, value);
    if (error != std::errc() || end != last || !std::isfinite(value) || first == last)
      throw InputError(start, fmt::format("bad number '{}'", written));
    return value;
  }

  const std::string& text_;
  std::string file_;
  std::size_t at_ = 0;
  int line_ = 1, column_ = 1;
};

}  // namespace

std::vector<PbrtToken> tokenize_pbrt(const std::string& text, const std::string& file) {
  return Tokenizer(text, file).run();
}

}  // namespace candela
