#include "io/json_document.h"

#include <algorithm>
#include <charconv>
#include <iterator>

namespace candela {

namespace {

// An input iterator over the text that records the furthest character the parser has read,
// so the SAX events below know where the parser stands.
class TrackingIterator {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  TrackingIterator() = default;
  TrackingIterator(const char* position, const char** furthest) : position_(position), furthest_(furthest) {}
  reference operator*() const {
    if (furthest_ && position_ + 1 > *furthest_) *furthest_ = position_ + 1;
    return *position_;
  }
  TrackingIterator& operator++() {
    ++position_;
    return *this;
  }
  TrackingIterator operator++(int) {
    auto copy = *this;
    ++position_;
    return copy;
  }
  bool operator==(const TrackingIterator& other) const { return position_ == other.position_; }
  bool operator!=(const TrackingIterator& other) const { return position_ != other.position_; }

 private:
  const char* position_ = nullptr;
  const char** furthest_ = nullptr;
};

std::string child_path(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}
std::string element_path(const std::string& parent, std::size_t index) {
  return parent + "[" + std::to_string(index) + "]";
}

}  // namespace

// Builds the DOM like nlohmann's own SAX DOM parser and, for every value, records where its
// first character is: the first character after the previous token that is not white space,
// a separator or a comment.
class LocatingSaxHandler {
 public:
  using json = nlohmann::json;
  using number_integer_t = json::number_integer_t;
  using number_unsigned_t = json::number_unsigned_t;
  using number_float_t = json::number_float_t;
  using string_t = json::string_t;
  using binary_t = json::binary_t;

  LocatingSaxHandler(JsonDocument& document, const std::string& text, const char** furthest)
      : document_(document), text_(text), furthest_(furthest) {}

  bool null() { return add(json(nullptr)); }
  bool boolean(bool value) { return add(json(value)); }
  bool number_integer(number_integer_t value) { return add(json(value)); }
  bool number_unsigned(number_unsigned_t value) { return add(json(value)); }
  bool number_float(number_float_t value, const string_t&) { return add(json(value)); }
  bool string(string_t& value) { return add(json(std::move(value))); }
  bool binary(binary_t&) { return fail("binary values are not JSON"); }
  bool start_object(std::size_t) { return open(json::object()); }
  bool start_array(std::size_t) { return open(json::array()); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }

  bool key(string_t& key) {
    const std::size_t start = token_start();
    Frame& frame = stack_.back();
    if (frame.value->contains(key)) {
      error_offset_ = start;
      error_ = "duplicate key \"" + key + "\"";
      return false;
    }
    frame.key = key;
    mark_consumed();
    return true;
  }

  bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& e) {
    error_offset_ = position > 0 ? position - 1 : 0;
    // "[json.exception.parse_error.101] parse error at line 1, column 2: syntax error ..." or
    // "[json.exception.out_of_range.406] number overflow parsing '1e999'": keep the reason.
    std::string message = e.what();
    if (const auto bracket = message.find("] "); bracket != std::string::npos)
      message = message.substr(bracket + 2);
    if (message.rfind("parse error", 0) == 0)
      if (const auto colon = message.find(": "); colon != std::string::npos)
        message = message.substr(colon + 2);
    error_ = message;
    return false;
  }

  const std::string& error() const { return error_; }
  std::size_t error_offset() const { return error_offset_; }
  json take_root() { return std::move(root_); }

 private:
  struct Frame {
    json* value;
    std::string path;
    std::string key;
  };

  std::size_t skip_separators(std::size_t at) const {
    while (at < text_.size()) {
      const char c = text_[at];
      if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == ',' || c == ':') {
        ++at;
      } else if (c == '/' && at + 1 < text_.size() && text_[at + 1] == '/') {
        while (at < text_.size() && text_[at] != '\n') ++at;
      } else if (c == '/' && at + 1 < text_.size() && text_[at + 1] == '*') {
        const auto end = text_.find("*/", at + 2);
        at = end == std::string::npos ? text_.size() : end + 2;
      } else {
        break;
      }
    }
    return at;
  }
  std::size_t token_start() const { return skip_separators(consumed_); }
  void mark_consumed() { consumed_ = static_cast<std::size_t>(*furthest_ - text_.data()); }

  // Inserts value at the current position; returns the inserted value and its path.
  json* insert(json value, std::string& path) {
    const std::size_t start = token_start();
    json* slot = nullptr;
    if (stack_.empty()) {
      root_ = std::move(value);
      slot = &root_;
      path.clear();
    } else {
      Frame& frame = stack_.back();
      if (frame.value->is_object()) {
        path = child_path(frame.path, frame.key);
        slot = &((*frame.value)[frame.key] = std::move(value));
      } else {
        path = element_path(frame.path, frame.value->size());
        frame.value->push_back(std::move(value));
        slot = &frame.value->back();
      }
    }
    const auto [line, column] = advance_to(start);
    document_.positions_[path] = {line, column, {}};
    return slot;
  }

  bool add(json value) {
    std::string path;
    insert(std::move(value), path);
    mark_consumed();
    return true;
  }
  bool open(json value) {
    // Deeper nesting serves no scene and would cost memory for every level's path.
    if (stack_.size() >= kMaxDepth)
      return fail("nesting deeper than " + std::to_string(kMaxDepth) + " levels");
    std::string path;
    json* slot = insert(std::move(value), path);
    stack_.push_back({slot, path, {}});
    mark_consumed();
    return true;
  }
  bool close() {
    stack_.pop_back();
    mark_consumed();
    return true;
  }
  bool fail(const std::string& message) {
    error_offset_ = token_start();
    error_ = message;
    return false;
  }

 public:
  // Line and column of offset, counting on from the previous call: values arrive in order,
  // so the whole file is scanned once.
  std::pair<int, int> advance_to(std::size_t offset) {
    offset = std::min(offset, text_.size());
    if (offset < counted_to_) return line_and_column(text_, offset);
    for (; counted_to_ < offset; ++counted_to_) {
      if (text_[counted_to_] == '\n') {
        ++line_;
        line_start_ = counted_to_ + 1;
      }
    }
    return {line_, static_cast<int>(offset - line_start_) + 1};
  }

  static std::pair<int, int> line_and_column(const std::string& text, std::size_t offset) {
    offset = std::min(offset, text.size());
    int line = 1;
    std::size_t line_start = 0;
    for (std::size_t i = 0; i < offset; ++i) {
      if (text[i] == '\n') {
        ++line;
        line_start = i + 1;
      }
    }
    return {line, static_cast<int>(offset - line_start) + 1};
  }

 private:
  JsonDocument& document_;
  const std::string& text_;
  const char** furthest_;
  static constexpr std::size_t kMaxDepth = 256;
  std::size_t consumed_ = 0;
  std::size_t counted_to_ = 0, line_start_ = 0;
  int line_ = 1;
  std::vector<Frame> stack_;
  json root_;
  std::string error_;
  std::size_t error_offset_ = 0;
};

JsonDocument JsonDocument::parse(const std::string& text, const std::string& file) {
  JsonDocument document;
  document.file_ = file;
  const char* furthest = text.data();
  LocatingSaxHandler handler(document, text, &furthest);
  const TrackingIterator first(text.data(), &furthest);
  const TrackingIterator last(text.data() + text.size(), &furthest);
  const bool ok = nlohmann::json::sax_parse(first, last, &handler, nlohmann::json::input_format_t::json,
                                            /*strict=*/true, /*ignore_comments=*/true);
  if (!ok) {
    const auto [line, column] = LocatingSaxHandler::line_and_column(text, handler.error_offset());
    throw InputError({file, line, column, {}}, handler.error());
  }
  document.root_ = handler.take_root();
  return document;
}

void JsonDocument::apply_override(const std::string& assignment) {
  const auto equals = assignment.find('=');
  const SourceLocation origin{"--set " + assignment, 0, 0, {}};
  if (equals == std::string::npos || equals == 0)
    throw InputError(origin, "expected key=value, e.g. camera.width=640");
  const std::string key = assignment.substr(0, equals);
  const std::string text = assignment.substr(equals + 1);
  nlohmann::json value;
  try {
    value = nlohmann::json::parse(text);
  } catch (const nlohmann::json::out_of_range&) {
    throw InputError(origin, "the number " + text + " is out of range");
  } catch (const nlohmann::json::exception&) {
    value = text;  // a bare word such as clamp or whitted
  }
  nlohmann::json* node = &root_;
  std::string path;
  std::size_t begin = 0;
  while (begin <= key.size()) {
    const auto dot = key.find('.', begin);
    const std::string segment = key.substr(begin, dot == std::string::npos ? dot : dot - begin);
    if (segment.empty()) throw InputError(origin, "empty segment in the key \"" + key + "\"");
    const bool is_index = std::all_of(segment.begin(), segment.end(), ::isdigit);
    if (node->is_array() && is_index) {
      std::size_t index = 0;
      const auto [end, error] = std::from_chars(segment.data(), segment.data() + segment.size(), index);
      if (error != std::errc() || end != segment.data() + segment.size() || index >= node->size())
        throw InputError(origin, path + " has " + std::to_string(node->size()) + " elements; index " +
                                     segment + " is out of range");
      path = element_path(path, index);
      node = &(*node)[index];
    } else if (node->is_object() || node->is_null()) {
      path = child_path(path, segment);
      // An object the assignment creates is located at the assignment, so that an error about
      // it (an unknown key such as a misspelt "whited") names the --set, not the file.
      if (!node->is_object() || !node->contains(segment)) positions_[path] = {0, 0, "--set " + assignment};
      node = &(*node)[segment];
    } else {
      throw InputError(origin, (path.empty() ? std::string("the root") : path) +
                                   " is not an object, so it has no \"" + segment + "\"");
    }
    if (dot == std::string::npos) break;
    begin = dot + 1;
  }
  *node = std::move(value);
  positions_[path] = {0, 0, "--set " + assignment};
}

SourceLocation JsonDocument::locate(const std::string& json_path) const {
  // The nearest recorded ancestor stands in for a value that is not in the file (a default).
  std::string path = json_path;
  while (true) {
    const auto found = positions_.find(path);
    if (found != positions_.end()) {
      const Position& p = found->second;
      if (!p.origin.empty()) return {p.origin, 0, 0, json_path};
      return {file_, p.line, p.column, json_path};
    }
    if (path.empty()) break;
    const auto cut = path.find_last_of(".[");
    path = cut == std::string::npos ? std::string() : path.substr(0, cut);
  }
  return {file_, 0, 0, json_path};
}

}  // namespace candela
