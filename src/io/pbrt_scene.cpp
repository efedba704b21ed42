#include "io/pbrt_scene.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

#include "io/pbrt_spectra.h"
#include "io/pbrt_tokenizer.h"
#include "math/constants.h"
#include "util/error.h"
#include "util/input_file.h"

namespace candela {

namespace {

using Json = nlohmann::json;
using Matrix = Eigen::Matrix4d;
using Kind = PbrtToken::Kind;

// Candela's microfacet lobes need a width (as glTF's roughness 0, io/gltf_scene.cpp).
constexpr double kLeastRoughness = 1e-3;
// The luminous efficacy Candela's photometric keys use (docs/scene-format.md, "Photometric amounts").
constexpr double kLumensPerWatt = 179;
// Include chains deeper than this are refused (a guard, far beyond any real scene).
constexpr int kMostIncludeDepth = 64;
// The most shape entries a document may hold (instances multiply them).
constexpr std::size_t kMostShapes = 4'000'000;

// --- parameters ---------------------------------------------------------------------------------

// One "type name" [values] of a directive's parameter list.
struct Parameter {
  std::string type, name;
  std::vector<double> numbers;
  std::vector<std::string> strings;  // strings, and bools as "true"/"false"
  SourceLocation where;
  mutable bool used = false;
};

bool is_numeric_type(const std::string& type) {
  static const std::set<std::string> types = {"integer", "float",   "point2",   "vector2", "point3",
                                              "vector3", "normal3", "normal",   "point",   "vector",
                                              "rgb",     "color",   "blackbody"};
  return types.count(type) > 0;
}

class Parameters {
 public:
  std::vector<Parameter> list;

  const Parameter* find(const std::string& name) const {
    for (const Parameter& p : list)
      if (p.name == name) {
        p.used = true;
        return &p;
      }
    return nullptr;
  }
  // One number of a "float" or "integer" parameter.
  double number(const std::string& name, double fallback) const {
    const Parameter* p = find(name);
    if (!p) return fallback;
    if (p->numbers.size() != 1)
      throw InputError(p->where, fmt::format("\"{}\" takes one number (found {})", name, p->numbers.size()));
    return p->numbers[0];
  }
  std::vector<double> numbers(const std::string& name) const {
    const Parameter* p = find(name);
    return p ? p->numbers : std::vector<double>{};
  }
  // A point or vector of three numbers.
  Eigen::Vector3d point(const std::string& name, const Eigen::Vector3d& fallback) const {
    const Parameter* p = find(name);
    if (!p) return fallback;
    if (p->numbers.size() != 3) throw InputError(p->where, fmt::format("\"{}\" takes three numbers", name));
    return {p->numbers[0], p->numbers[1], p->numbers[2]};
  }
  std::string string(const std::string& name, const std::string& fallback) const {
    const Parameter* p = find(name);
    if (!p) return fallback;
    if (p->strings.size() != 1) throw InputError(p->where, fmt::format("\"{}\" takes one string", name));
    return p->strings[0];
  }
  bool boolean(const std::string& name, bool fallback) const {
    const Parameter* p = find(name);
    if (!p) return fallback;
    if (p->strings.size() != 1 || (p->strings[0] != "true" && p->strings[0] != "false"))
      throw InputError(p->where, fmt::format("\"{}\" takes true or false", name));
    return p->strings[0] == "true";
  }
  // "name" of the parameters nobody read.
  std::vector<const Parameter*> unused() const {
    std::vector<const Parameter*> out;
    for (const Parameter& p : list)
      if (!p.used) out.push_back(&p);
    return out;
  }
};

// A colour of a pbrt spectrum parameter: RGB, or a blackbody's temperature.
struct PbrtColor {
  PbrtRgb rgb = {1, 1, 1};
  std::optional<double> kelvin;
};

Json rgb_json(const PbrtRgb& c) {
  return Json::array({c[0], c[1], c[2]});
}
PbrtRgb scaled(const PbrtRgb& c, double s) {
  return {c[0] * s, c[1] * s, c[2] * s};
}
Json vector_json(const Eigen::Vector3d& v) {
  return Json::array({v.x(), v.y(), v.z()});
}
Json matrix_json(const Matrix& m) {
  Json rows = Json::array();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) rows.push_back(m(r, c));
  return {{"matrix", rows}};
}
Eigen::Vector3d transform_point(const Matrix& m, const Eigen::Vector3d& p) {
  return (m * p.homogeneous()).head<3>();
}
Eigen::Vector3d transform_vector(const Matrix& m, const Eigen::Vector3d& v) {
  return m.topLeftCorner<3, 3>() * v;
}
bool swaps_handedness(const Matrix& m) {
  return m.topLeftCorner<3, 3>().determinant() < 0;
}

// --- the scene's state ----------------------------------------------------------------------------

struct AreaLight {
  PbrtColor radiance;
  double scale = 1;
  bool two_sided = false;
};

// What AttributeBegin saves (pbrt-v4's graphics state, the parts Candela uses).
struct GraphicsState {
  Matrix ctm = Matrix::Identity();
  // The camera a LookAt (after an optional Scale -1 1 1) made from the identity, kept exactly.
  struct LookAt {
    Eigen::Vector3d eye, target, up;
    bool mirrored_by_scale = false;
  };
  std::optional<LookAt> look_at;
  bool reverse_orientation = false;
  std::string material;  // a key of the document's materials; "" is the default diffuse
  int area_light = -1;   // index of area_lights_
};

// A shape as written, kept until it is emitted (at once, or at each instance of its object).
struct ShapeRecord {
  std::string type;
  Parameters parameters;
  Matrix ctm;
  bool reverse_orientation = false;
  std::string material;
  int area_light = -1;
  std::string file_prefix;  // the folder of the file that names it, relative to the main file's
  std::string folder;       // the same folder, as a path to open
  SourceLocation where;
};

// Reads the tokens of one file.
class Cursor {
 public:
  Cursor(std::vector<PbrtToken> tokens, std::string file)
      : tokens_(std::move(tokens)), file_(std::move(file)) {}
  bool done() const { return at_ >= tokens_.size(); }
  const PbrtToken* peek() const { return done() ? nullptr : &tokens_[at_]; }
  const PbrtToken& next(const SourceLocation& after, const char* what) {
    if (done()) throw InputError(after, fmt::format("the file ends where {} was expected", what));
    return tokens_[at_++];
  }
  SourceLocation end_location() const {
    return done() ? (tokens_.empty() ? SourceLocation{file_, 1, 1, {}} : tokens_.back().where)
                  : tokens_[at_].where;
  }
  double number(const SourceLocation& after) {
    const PbrtToken& t = next(after, "a number");
    if (t.kind != Kind::kNumber)
      throw InputError(t.where, fmt::format("expected a number, found '{}'", t.text));
    return t.number;
  }
  std::string string(const SourceLocation& after) {
    const PbrtToken& t = next(after, "a quoted string");
    if (t.kind != Kind::kString)
      throw InputError(t.where, fmt::format("expected a quoted string, found '{}'", t.text));
    return t.text;
  }
  // n numbers, bare or in brackets (Transform, ConcatTransform).
  std::vector<double> numbers(const SourceLocation& after, std::size_t n) {
    const PbrtToken* first = peek();
    const bool bracketed = first && first->kind == Kind::kOpenBracket;
    SourceLocation open = after;
    if (bracketed) open = next(after, "[").where;
    std::vector<double> out;
    for (std::size_t k = 0; k < n; ++k) out.push_back(number(open));
    if (bracketed) {
      const PbrtToken& close = next(open, "]");
      if (close.kind != Kind::kCloseBracket)
        throw InputError(close.where,
                         fmt::format("expected ] after {} numbers (the [ is at {})", n, open.describe()));
    }
    return out;
  }
  // The parameter list that follows a directive's own arguments: "type name" value pairs.
  Parameters parameters() {
    Parameters out;
    while (!done() && tokens_[at_].kind == Kind::kString) {
      const PbrtToken& declaration = tokens_[at_++];
      Parameter p;
      p.where = declaration.where;
      std::istringstream words(declaration.text);
      std::string extra;
      if (!(words >> p.type >> p.name) || (words >> extra))
        throw InputError(
            declaration.where,
            fmt::format("expected a parameter declaration \"type name\", found \"{}\"", declaration.text));
      read_values(p, declaration.where);
      check_type(p);
      out.list.push_back(std::move(p));
    }
    return out;
  }
  // Skips what follows an unknown directive: every token up to the next directive.
  void skip_arguments() {
    int depth = 0;
    while (!done()) {
      const PbrtToken& t = tokens_[at_];
      if (t.kind == Kind::kOpenBracket) ++depth;
      if (t.kind == Kind::kCloseBracket) --depth;
      if (depth <= 0 && t.kind == Kind::kWord && t.text != "true" && t.text != "false") return;
      ++at_;
    }
  }

 private:
  void add_value(Parameter& p, const PbrtToken& t) {
    if (t.kind == Kind::kNumber) {
      p.numbers.push_back(t.number);
    } else if (t.kind == Kind::kString) {
      p.strings.push_back(t.text);
    } else if (t.kind == Kind::kWord && (t.text == "true" || t.text == "false")) {
      p.strings.push_back(t.text);
    } else {
      throw InputError(t.where,
                       fmt::format("expected a value of \"{} {}\", found '{}'", p.type, p.name, t.text));
    }
  }
  void read_values(Parameter& p, const SourceLocation& declaration) {
    const PbrtToken& first = next(declaration, "the parameter's value");
    if (first.kind != Kind::kOpenBracket) {
      add_value(p, first);
      return;
    }
    while (true) {
      if (done()) throw InputError(first.where, "unbalanced [: no ] closes it");
      const PbrtToken& t = tokens_[at_++];
      if (t.kind == Kind::kCloseBracket) return;
      if (t.kind == Kind::kOpenBracket)
        throw InputError(t.where, "unbalanced [: a [ inside a parameter's values");
      if (t.kind == Kind::kWord && t.text != "true" && t.text != "false")
        throw InputError(first.where, fmt::format("unbalanced [: no ] closes it before '{}' at {}", t.text,
                                                  t.where.describe()));
      add_value(p, t);
    }
  }
  static void check_type(const Parameter& p) {
    const bool numeric = is_numeric_type(p.type);
    const bool textual = p.type == "string" || p.type == "texture" || p.type == "bool";
    if (!numeric && !textual && p.type != "spectrum")
      throw InputError(p.where, fmt::format("unknown parameter type \"{}\"", p.type));
    if (numeric && !p.strings.empty())
      throw InputError(p.where, fmt::format("\"{} {}\" takes numbers", p.type, p.name));
    if (textual && !p.numbers.empty())
      throw InputError(p.where, fmt::format("\"{} {}\" takes {}", p.type, p.name,
                                            p.type == "bool" ? "true or false" : "strings"));
    if (p.type == "spectrum" && !p.strings.empty() && !p.numbers.empty())
      throw InputError(p.where, "a spectrum is a name or λ-value pairs, not both");
    if (p.type == "integer")
      for (double x : p.numbers)
        if (x != std::floor(x))
          throw InputError(p.where, fmt::format("\"integer {}\" takes whole numbers", p.name));
    if (p.numbers.empty() && p.strings.empty())
      throw InputError(p.where, fmt::format("\"{} {}\" has no value", p.type, p.name));
  }

  std::vector<PbrtToken> tokens_;
  std::string file_;
  std::size_t at_ = 0;
};

std::string lowercase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

class Translator {
 public:
  explicit Translator(const std::string& main_path) : main_path_(main_path) {}

  PbrtSceneDocument translate(const std::string* text) {
    const std::filesystem::path folder = std::filesystem::path(main_path_).parent_path();
    std::vector<std::string> chain;
    if (text)
      read_text(*text, main_path_, "", folder, chain);
    else
      read_file(main_path_, "", folder, SourceLocation{main_path_, 0, 0, {}}, chain);
    return finish();
  }

 private:
  // --- files ------------------------------------------------------------------------------------

  void read_file(const std::string& path, const std::string& prefix, const std::filesystem::path& folder,
                 const SourceLocation& named_at, std::vector<std::string>& chain) {
    const std::string problem = input_file_problem(path, "the pbrt file");
    if (!problem.empty()) throw InputError(named_at, fmt::format("'{}': {}", path, problem));
    read_text(read_input_file(path, "the pbrt file"), path, prefix, folder, chain);
  }

  void read_text(const std::string& text, const std::string& path, const std::string& prefix,
                 const std::filesystem::path& folder, std::vector<std::string>& chain) {
    std::error_code error;
    const std::string identity = std::filesystem::weakly_canonical(path, error).string();
    chain.push_back(error ? path : identity);
    Cursor cursor(tokenize_pbrt(text, path), path);
    while (!cursor.done()) directive(cursor, prefix, folder, chain);
    chain.pop_back();
  }

  void include(const std::string& written, const SourceLocation& where, const std::string& prefix,
               const std::filesystem::path& folder, std::vector<std::string>& chain) {
    const std::filesystem::path as_written(written);
    const std::filesystem::path full = as_written.is_absolute() ? as_written : folder / as_written;
    std::error_code error;
    const std::string identity = std::filesystem::weakly_canonical(full, error).string();
    const std::string key = error ? full.string() : identity;
    if (std::find(chain.begin(), chain.end(), key) != chain.end()) {
      std::string names;
      for (const std::string& link : chain) names += link + " → ";
      throw InputError(where, fmt::format("recursive Include: {}{}", names, key));
    }
    if (static_cast<int>(chain.size()) >= kMostIncludeDepth)
      throw InputError(where, fmt::format("Include files nest deeper than {}", kMostIncludeDepth));
    const std::string sub_prefix =
        as_written.is_absolute() ? "" : prefix_of(prefix, as_written.parent_path());
    read_file(full.string(), sub_prefix, full.parent_path(), where, chain);
  }

  static std::string prefix_of(const std::string& prefix, const std::filesystem::path& folder) {
    if (folder.empty()) return prefix;
    return prefix + (folder / "").generic_string();
  }
  // A file named by a .pbrt file, as the document names it (relative to the main file's folder).
  std::string document_path(const std::string& written, const std::string& prefix) const {
    return std::filesystem::path(written).is_absolute() ? written : prefix + written;
  }
  void require_file(const std::string& written, const std::filesystem::path& folder,
                    const SourceLocation& where, const char* what) const {
    const std::filesystem::path as_written(written);
    const std::filesystem::path full = as_written.is_absolute() ? as_written : folder / as_written;
    const std::string problem = input_file_problem(full.string(), what, kLargeInputLimit);
    if (!problem.empty()) throw InputError(where, problem);
  }

  // Each warning once (an object's shapes are emitted at every instance).
  void warn(const SourceLocation& where, const std::string& message) {
    std::string warning = fmt::format("{}:{}: {}", where.file, where.line, message);
    if (warned_.insert(warning).second) warnings_.push_back(std::move(warning));
  }
  void warn_unused(const Parameters& parameters, const std::string& directive) {
    for (const Parameter* p : parameters.unused())
      warn(p->where,
           fmt::format("{}: parameter \"{} {}\" is not used by Candela", directive, p->type, p->name));
  }

  // --- directives -------------------------------------------------------------------------------

  void directive(Cursor& cursor, const std::string& prefix, const std::filesystem::path& folder,
                 std::vector<std::string>& chain) {
    const PbrtToken& token = cursor.next(cursor.end_location(), "a directive");
    const SourceLocation& at = token.where;
    if (token.kind == Kind::kCloseBracket) throw InputError(at, "unbalanced ]: no [ opens it");
    if (token.kind != Kind::kWord)
      throw InputError(at, fmt::format("expected a directive, found the {} '{}'",
                                       token.kind == Kind::kString ? "string" : "value", token.text));
    const std::string& name = token.text;
    GraphicsState& g = state_;
    if (name == "LookAt") {
      std::vector<double> v;
      for (int k = 0; k < 9; ++k) v.push_back(cursor.number(at));
      look_at(at, {v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]});
    } else if (name == "Translate") {
      const double x = cursor.number(at), y = cursor.number(at), z = cursor.number(at);
      Matrix m = Matrix::Identity();
      m.topRightCorner<3, 1>() = Eigen::Vector3d(x, y, z);
      concatenate(m);
    } else if (name == "Scale") {
      const double x = cursor.number(at), y = cursor.number(at), z = cursor.number(at);
      const bool was_identity = g.ctm == Matrix::Identity() && !g.look_at;
      concatenate(Eigen::Vector4d(x, y, z, 1).asDiagonal().toDenseMatrix());
      // Scale -1 1 1 first: what exporters write so that a LookAt camera is right-handed.
      pending_mirror_ = was_identity && x == -1 && y == 1 && z == 1;
    } else if (name == "Rotate") {
      const double angle = cursor.number(at), x = cursor.number(at), y = cursor.number(at),
                   z = cursor.number(at);
      const Eigen::Vector3d axis(x, y, z);
      if (!(axis.norm() > 0)) throw InputError(at, "Rotate needs a non-zero axis");
      Matrix m = Matrix::Identity();
      m.topLeftCorner<3, 3>() = Eigen::AngleAxisd(angle * kPi / 180, axis.normalized()).toRotationMatrix();
      concatenate(m);
    } else if (name == "Transform" || name == "ConcatTransform") {
      const std::vector<double> v = cursor.numbers(at, 16);
      // pbrt lists the matrix column by column (its Transform() transposes what it reads).
      Matrix m;
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) m(r, c) = v[static_cast<std::size_t>(4 * c + r)];
      if (name == "Transform") {
        g.ctm = m;
        g.look_at.reset();
        pending_mirror_ = false;
      } else {
        concatenate(m);
      }
    } else if (name == "Identity") {
      g.ctm = Matrix::Identity();
      g.look_at.reset();
      pending_mirror_ = false;
    } else if (name == "CoordinateSystem") {
      named_systems_[cursor.string(at)] = {g.ctm, g.look_at};
    } else if (name == "CoordSysTransform") {
      const std::string system = cursor.string(at);
      const auto found = named_systems_.find(system);
      if (found == named_systems_.end()) {
        warn(at,
             fmt::format("CoordSysTransform: no coordinate system \"{}\" (the transform is kept)", system));
      } else {
        g.ctm = found->second.first;
        g.look_at = found->second.second;
      }
    } else if (name == "ReverseOrientation") {
      g.reverse_orientation = !g.reverse_orientation;
    } else if (name == "TransformBegin") {
      transform_stack_.push_back({g.ctm, g.look_at});
    } else if (name == "TransformEnd") {
      if (transform_stack_.empty()) throw InputError(at, "TransformEnd without TransformBegin");
      g.ctm = transform_stack_.back().first;
      g.look_at = transform_stack_.back().second;
      transform_stack_.pop_back();
    } else if (name == "AttributeBegin") {
      attribute_stack_.push_back({g, at});
    } else if (name == "AttributeEnd") {
      if (attribute_stack_.empty()) throw InputError(at, "AttributeEnd without AttributeBegin");
      g = attribute_stack_.back().first;
      attribute_stack_.pop_back();
    } else if (name == "Camera") {
      camera_type_ = cursor.string(at);
      camera_parameters_ = cursor.parameters();
      camera_where_ = at;
      camera_from_world_ = g.ctm;
      camera_look_at_ = g.look_at;
      named_systems_["camera"] = {g.ctm.inverse(), std::nullopt};
    } else if (name == "Film") {
      cursor.string(at);
      film_ = cursor.parameters();
      film_where_ = at;
    } else if (name == "Sampler") {
      const std::string type = cursor.string(at);
      const Parameters p = cursor.parameters();
      spp_ = static_cast<long long>(p.number("pixelsamples", 16));
      if (*spp_ < 0 || *spp_ > (1 << 24)) throw InputError(at, "Sampler: pixelsamples must lie in [0, 2^24]");
      warn(at, fmt::format(
                   "Sampler \"{}\": only pixelsamples is used (path.spp; Candela's sampler is path.sampler)",
                   type));
    } else if (name == "Integrator") {
      const std::string type = cursor.string(at);
      const Parameters p = cursor.parameters();
      if (p.find("maxdepth")) {
        max_depth_ = static_cast<long long>(p.number("maxdepth", 5));
        if (*max_depth_ < 0 || *max_depth_ > 1024)
          throw InputError(at, "Integrator: maxdepth must lie in [0, 1024]");
      }
      warn(at, fmt::format("Integrator \"{}\" is not used: the method is render.method (\"path\" here){}",
                           type, max_depth_ ? "; maxdepth is path.max_depth" : ""));
    } else if (name == "WorldBegin") {
      g.ctm = Matrix::Identity();
      g.look_at.reset();
      pending_mirror_ = false;
      named_systems_["world"] = {g.ctm, std::nullopt};
    } else if (name == "WorldEnd") {
      // pbrt-v3's end of the scene: nothing to do.
    } else if (name == "Include" || name == "Import") {
      include(cursor.string(at), at, prefix, folder, chain);
    } else if (name == "ObjectBegin") {
      if (current_object_) throw InputError(at, "ObjectBegin inside the object \"" + *current_object_ + "\"");
      const std::string object = cursor.string(at);
      attribute_stack_.push_back({g, at});
      current_object_ = object;
      objects_[object].clear();
    } else if (name == "ObjectEnd") {
      if (!current_object_) throw InputError(at, "ObjectEnd without ObjectBegin");
      current_object_.reset();
      g = attribute_stack_.back().first;
      attribute_stack_.pop_back();
    } else if (name == "ObjectInstance") {
      const std::string object = cursor.string(at);
      if (current_object_)
        throw InputError(at, "ObjectInstance inside an object definition (pbrt-v4 allows none)");
      const auto found = objects_.find(object);
      if (found == objects_.end())
        throw InputError(at, fmt::format("ObjectInstance: no object \"{}\"", object));
      for (const ShapeRecord& record : found->second) emit_shape(record, g.ctm * record.ctm);
    } else if (name == "Shape") {
      ShapeRecord record;
      record.type = cursor.string(at);
      record.parameters = cursor.parameters();
      record.ctm = g.ctm;
      record.reverse_orientation = g.reverse_orientation;
      record.material = g.material;
      record.area_light = g.area_light;
      record.file_prefix = prefix;
      record.folder = folder.string();
      record.where = at;
      if (current_object_) {
        if (record.area_light >= 0) {
          warn(
              at,
              "Shape in an object: area lights do not apply to instances (pbrt-v4), the shape does not emit");
          record.area_light = -1;
        }
        objects_[*current_object_].push_back(std::move(record));
      } else {
        emit_shape(record, record.ctm);
      }
    } else if (name == "LightSource") {
      const std::string type = cursor.string(at);
      light_source(type, cursor.parameters(), at, prefix, folder);
    } else if (name == "AreaLightSource") {
      const std::string type = cursor.string(at);
      const Parameters p = cursor.parameters();
      if (type != "diffuse") {
        warn(at, fmt::format("AreaLightSource \"{}\" is not supported: the shapes do not emit", type));
        g.area_light = -1;
        return;
      }
      AreaLight light;
      light.radiance = color(p, "L", {{1, 1, 1}, std::nullopt});
      light.scale = p.number("scale", 1);
      light.two_sided = p.boolean("twosided", false);
      warn_unused(p, "AreaLightSource \"diffuse\"");
      area_lights_.push_back(light);
      g.area_light = static_cast<int>(area_lights_.size()) - 1;
    } else if (name == "Material") {
      const std::string type = cursor.string(at);
      const Parameters p = cursor.parameters();
      const std::string material = fmt::format("material-{}", ++anonymous_materials_);
      materials_[material] = material_json(type, p, at);
      g.material = material;
    } else if (name == "MakeNamedMaterial") {
      const std::string material = cursor.string(at);
      const Parameters p = cursor.parameters();
      const std::string type = p.string("type", "");
      if (type.empty())
        throw InputError(at, fmt::format("MakeNamedMaterial \"{}\" needs \"string type\"", material));
      materials_[material] = material_json(type, p, at);
    } else if (name == "NamedMaterial") {
      const std::string material = cursor.string(at);
      if (!materials_.contains(material))
        throw InputError(at, fmt::format("NamedMaterial: no material \"{}\"", material));
      g.material = material;
    } else if (name == "Texture") {
      const std::string texture = cursor.string(at);
      const std::string kind = cursor.string(at);
      const std::string type = cursor.string(at);
      const Parameters p = cursor.parameters();
      textures_[texture] = texture_json(kind, type, p, at, prefix, folder);
    } else if (name == "ActiveTransform") {
      const PbrtToken& which = cursor.next(at, "All, StartTime or EndTime");
      warn(which.where, "ActiveTransform is not used (Candela has no motion blur)");
    } else if (name == "TransformTimes") {
      cursor.number(at);
      cursor.number(at);
      warn(at, "TransformTimes is not used (Candela has no motion blur)");
    } else if (name == "ColorSpace" || name == "MediumInterface" || name == "PixelFilter" ||
               name == "Accelerator" || name == "MakeNamedMedium" || name == "Attribute" ||
               name == "Option") {
      // Their positional strings and parameters, read to check them.
      while (cursor.peek() && cursor.peek()->kind == Kind::kString) {
        if (cursor.peek()->text.find(' ') != std::string::npos) break;
        cursor.string(at);
      }
      cursor.parameters();
      warn(at, fmt::format("{} is not used by Candela", name));
    } else {
      warn(at, fmt::format("unknown directive \"{}\" is skipped", name));
      cursor.skip_arguments();
    }
  }

  void concatenate(const Matrix& m) {
    state_.ctm = state_.ctm * m;
    state_.look_at.reset();
    pending_mirror_ = false;
  }

  // pbrt's LookAt: the camera-from-world matrix of a camera at eye looking at target, +x = up × gaze.
  void look_at(const SourceLocation& at, const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
               const Eigen::Vector3d& up) {
    const Eigen::Vector3d gaze = target - eye;
    if (!(gaze.norm() > 0)) throw InputError(at, "LookAt: the eye and the point looked at coincide");
    const Eigen::Vector3d z = gaze.normalized();
    const Eigen::Vector3d x_raw = up.normalized().cross(z);
    if (!(x_raw.norm() > 1e-12)) throw InputError(at, "LookAt: up is parallel to the view direction");
    const Eigen::Vector3d x = x_raw.normalized();
    const Eigen::Vector3d y = z.cross(x);
    Matrix world_from_camera = Matrix::Identity();
    world_from_camera.block<3, 1>(0, 0) = x;
    world_from_camera.block<3, 1>(0, 1) = y;
    world_from_camera.block<3, 1>(0, 2) = z;
    world_from_camera.block<3, 1>(0, 3) = eye;
    const bool exact = (state_.ctm == Matrix::Identity() && !state_.look_at) || pending_mirror_;
    const bool mirrored_by_scale = pending_mirror_;
    state_.ctm = state_.ctm * world_from_camera.inverse();
    state_.look_at.reset();
    pending_mirror_ = false;
    if (exact) state_.look_at = GraphicsState::LookAt{eye, target, up, mirrored_by_scale};
  }

  // --- colours, textures, materials -------------------------------------------------------------

  // A spectrum-valued parameter as a colour (a texture is refused here: lights take none).
  PbrtColor color(const Parameters& p, const std::string& name, const PbrtColor& fallback) {
    const Parameter* value = p.find(name);
    if (!value) return fallback;
    if (value->type == "rgb" || value->type == "color") {
      if (value->numbers.size() != 3)
        throw InputError(value->where, fmt::format("\"rgb {}\" takes three numbers", name));
      return {{value->numbers[0], value->numbers[1], value->numbers[2]}, std::nullopt};
    }
    if (value->type == "blackbody") {
      const double kelvin = value->numbers[0];
      if (!(kelvin >= 1000 && kelvin <= 40000))
        throw InputError(value->where, "a blackbody's temperature must lie in [1000, 40000] K for Candela");
      return {{1, 1, 1}, kelvin};
    }
    if (value->type == "float") {
      const double x = value->numbers[0];
      return {{x, x, x}, std::nullopt};
    }
    if (value->type == "spectrum") {
      if (!value->strings.empty()) {
        if (const auto metal = pbrt_metal_spectrum(value->strings[0])) return {*metal, std::nullopt};
        warn(value->where,
             fmt::format("named spectrum \"{}\" is not known to Candela: 1 is used", value->strings[0]));
        return {{1, 1, 1}, std::nullopt};
      }
      if (value->numbers.size() < 2 || value->numbers.size() % 2 != 0)
        throw InputError(value->where, "a spectrum's values are λ-value pairs");
      double sum = 0;
      for (std::size_t k = 1; k < value->numbers.size(); k += 2) sum += value->numbers[k];
      const double mean = sum / static_cast<double>(value->numbers.size() / 2);
      warn(value->where,
           fmt::format("spectrum \"{}\" of λ-value pairs is read as the grey of their mean, {}", name, mean));
      return {{mean, mean, mean}, std::nullopt};
    }
    throw InputError(value->where, fmt::format("\"{} {}\" is not a colour", value->type, name));
  }

  // A material's colour or number: a constant, or a texture of Textures.
  Json texture_or_color(const Parameters& p, const std::string& name, const Json& fallback) {
    const Parameter* value = p.find(name);
    if (!value) return fallback;
    if (value->type == "texture") {
      const auto found = textures_.find(value->strings[0]);
      if (found == textures_.end())
        throw InputError(value->where, fmt::format("no texture \"{}\"", value->strings[0]));
      return found->second;
    }
    if (value->type == "float") return value->numbers[0];
    const PbrtColor c = color(p, name, {});
    if (c.kelvin) {
      warn(value->where, fmt::format("\"blackbody {}\" of a material is read as grey 0.5", name));
      return 0.5;
    }
    return rgb_json(c.rgb);
  }

  // The largest channel of a constant colour; nothing for a texture.
  static std::optional<double> largest(const Json& value) {
    if (value.is_number()) return value.get<double>();
    if (value.is_array())
      return std::max({value[0].get<double>(), value[1].get<double>(), value[2].get<double>()});
    return std::nullopt;
  }

  // pbrt's roughness as Candela's GGX α.
  double roughness(const Parameters& p, const SourceLocation& at) {
    double r = p.number("roughness", -1);
    const double u = p.number("uroughness", r < 0 ? 0 : r), v = p.number("vroughness", r < 0 ? 0 : r);
    if (r < 0) {
      if (u != v)
        warn(at, fmt::format("anisotropic roughness ({}, {}) is drawn isotropic, of their mean", u, v));
      r = (u + v) / 2;
    }
    if (r < 0) throw InputError(at, "roughness must be ≥ 0");
    const double alpha = p.boolean("remaproughness", true) ? std::sqrt(r) : r;
    return std::max(alpha, kLeastRoughness);
  }

  double index_of_refraction(const Parameters& p) {
    const Parameter* value = p.find("eta");
    if (!value) return 1.5;
    if (value->type == "float") return value->numbers[0];
    if (value->type == "spectrum" && !value->strings.empty()) {
      if (const auto glass = pbrt_glass_index(value->strings[0])) return *glass;
      warn(value->where,
           fmt::format("named spectrum \"{}\" is not a glass Candela knows: 1.5", value->strings[0]));
      return 1.5;
    }
    const PbrtColor c = color(p, "eta", {});
    return (c.rgb[0] + c.rgb[1] + c.rgb[2]) / 3;
  }

  Json conductor(const Parameters& p, const SourceLocation& at) {
    Json m = {{"type", "cook-torrance"},
              {"kd", 0},
              {"ks", 1},
              {"microfacet", "ggx"},
              {"roughness", roughness(p, at)}};
    if (p.find("reflectance")) {
      const PbrtColor r = color(p, "reflectance", {});
      m["fresnel_f0"] =
          rgb_json({std::min(r.rgb[0], 0.999), std::min(r.rgb[1], 0.999), std::min(r.rgb[2], 0.999)});
      return m;
    }
    const PbrtRgb copper_eta = *pbrt_metal_spectrum("metal-Cu-eta"),
                  copper_k = *pbrt_metal_spectrum("metal-Cu-k");
    m["fresnel_ior"] = rgb_json(color(p, "eta", {copper_eta, std::nullopt}).rgb);
    m["fresnel_k"] = rgb_json(color(p, "k", {copper_k, std::nullopt}).rgb);
    return m;
  }

  Json material_json(const std::string& type, const Parameters& p, const SourceLocation& at) {
    Json m;
    if (type == "diffuse") {
      m = {{"kd", texture_or_color(p, "reflectance", 0.5)}};
    } else if (type == "coateddiffuse") {
      const Json kd = texture_or_color(p, "reflectance", 0.5);
      const std::optional<double> most = largest(kd);
      m = {{"type", "cook-torrance"},
           {"kd", kd},
           {"ks", most ? std::max(0.0, 1 - *most) : 0.2},
           {"microfacet", "ggx"},
           {"fresnel_ior", index_of_refraction(p)},
           {"roughness", roughness(p, at)}};
      p.find("thickness");  // the coat's thickness only weighs its absorption, which Candela does not model
    } else if (type == "conductor") {
      m = conductor(p, at);
    } else if (type == "coatedconductor") {
      warn(at, "material \"coatedconductor\" is drawn as its conductor (no coat)");
      Parameters inner;
      for (const Parameter& q : p.list) {
        if (q.name.rfind("conductor.", 0) != 0) continue;
        Parameter renamed = q;
        renamed.name = q.name.substr(10);
        inner.list.push_back(renamed);
        q.used = true;
      }
      m = conductor(inner, at);
    } else if (type == "dielectric" || type == "thindielectric") {
      m = {{"kd", 0}, {"kt", 1}, {"ior", index_of_refraction(p)}};
      if (type == "thindielectric") m["thin"] = true;
      if (p.find("roughness") || p.find("uroughness") || p.find("vroughness"))
        warn(at, fmt::format("a rough \"{}\" is drawn smooth", type));
    } else if (type == "interface") {
      m = {{"kd", 0}, {"pbrt-interface", true}};
    } else if (type == "diffusetransmission") {
      warn(
          at,
          "material \"diffusetransmission\" is drawn as diffuse (its reflectance); the transmission is lost");
      m = {{"kd", texture_or_color(p, "reflectance", 0.25)}};
      p.find("transmittance");
    } else if (type == "mix") {
      const Parameter* both = p.find("materials");
      if (both && !both->strings.empty() && materials_.contains(both->strings[0])) {
        warn(at, fmt::format("material \"mix\" is drawn as its first material, \"{}\"", both->strings[0]));
        m = materials_[both->strings[0]];
      } else {
        warn(at, "material \"mix\" without a known first material: diffuse 0.5");
        m = {{"kd", 0.5}};
      }
      p.find("amount");
    } else {
      warn(at, fmt::format("unknown material type \"{}\": diffuse 0.5", type));
      return {{"kd", 0.5}};
    }
    p.find("type");
    if (p.find("displacement") || p.find("normalmap"))
      warn(at, "displacement and normal maps are not used by Candela");
    warn_unused(p, fmt::format("material \"{}\"", type));
    return m;
  }

  Json uv_mapping(const Parameters& p, const SourceLocation& at) {
    const std::string mapping = p.string("mapping", "uv");
    if (mapping != "uv") warn(at, fmt::format("texture mapping \"{}\" is drawn as \"uv\"", mapping));
    const double su = p.number("uscale", 1), sv = p.number("vscale", 1);
    const double du = p.number("udelta", 0), dv = p.number("vdelta", 0);
    Json out = {{"type", "uv"}};
    if (su != 1 || sv != 1) out["scale"] = Json::array({su, sv});
    if (du != 0 || dv != 0) out["offset"] = Json::array({du, dv});
    return out;
  }

  Json texture_json(const std::string& kind, const std::string& type, const Parameters& p,
                    const SourceLocation& at, const std::string& prefix,
                    const std::filesystem::path& folder) {
    if (kind != "float" && kind != "spectrum" && kind != "rgb" && kind != "color")
      throw InputError(at, fmt::format("a texture is \"float\" or \"spectrum\" (found \"{}\")", kind));
    Json out;
    if (type == "imagemap") {
      const std::string file = p.string("filename", "");
      if (file.empty()) throw InputError(at, "Texture \"imagemap\" needs \"string filename\"");
      require_file(file, folder, at, "the image file");
      out = {{"type", "image"}, {"file", document_path(file, prefix)}, {"mapping", uv_mapping(p, at)}};
      const std::string encoding = lowercase(p.string("encoding", "sRGB"));
      out["encoding"] = encoding == "linear" ? "linear" : encoding == "srgb" ? "srgb" : "auto";
      if (encoding != "linear" && encoding != "srgb")
        warn(at, fmt::format("image encoding \"{}\" is read as auto", encoding));
      const double multiplier = p.number("scale", 1);
      if (multiplier != 1) out["multiplier"] = multiplier;
      const std::string wrap = p.string("wrap", "repeat");
      out["wrap"] = wrap == "repeat" ? "repeat" : "clamp";
      if (wrap != "repeat" && wrap != "clamp") warn(at, fmt::format("wrap \"{}\" is drawn as clamp", wrap));
      if (p.boolean("invert", false)) warn(at, "an inverted image texture is not supported: drawn as it is");
      p.find("filter");
      p.find("maxanisotropy");
    } else if (type == "checkerboard") {
      const Json even = texture_or_color(p, "tex1", 1.0), odd = texture_or_color(p, "tex2", 0.0);
      if (!largest(even) || !largest(odd)) {
        warn(at, "a checkerboard of textures is not supported: grey 0.5");
        return 0.5;
      }
      if (static_cast<int>(p.number("dimension", 2)) == 3)
        out = {{"type", "checkerboard"}, {"even", even}, {"odd", odd}, {"size", 1}};
      else
        out = {{"type", "checker2d"}, {"even", even}, {"odd", odd}, {"mapping", uv_mapping(p, at)}};
    } else if (type == "scale") {
      Json base = texture_or_color(p, "tex", 1.0);
      const Json factor = texture_or_color(p, "scale", 1.0);
      if (!factor.is_number()) {
        warn(at, "Texture \"scale\": only a constant float scale is supported (1 is used)");
        return base;
      }
      const double s = factor.get<double>();
      if (base.is_number()) return base.get<double>() * s;
      if (base.is_array())
        return Json::array({base[0].get<double>() * s, base[1].get<double>() * s, base[2].get<double>() * s});
      if (base.is_object() && base.value("type", "") == "image") {
        base["multiplier"] = base.value("multiplier", 1.0) * s;
        return base;
      }
      warn(at, "Texture \"scale\" of this texture is not supported: the texture is used unscaled");
      return base;
    } else if (type == "constant") {
      return texture_or_color(p, "value", 1.0);
    } else {
      warn(at, fmt::format("unknown texture type \"{}\": grey 0.5", type));
      return 0.5;
    }
    warn_unused(p, fmt::format("Texture \"{}\"", type));
    return out;
  }

  // The material of a shape: its own, with the area light's emission when it has one.
  std::string material_of(const std::string& material, int area_light) {
    const std::string base = material.empty() ? default_material() : material;
    if (area_light < 0) return base;
    const std::string name = fmt::format("{}+light-{}", base, area_light);
    if (!materials_.contains(name)) {
      Json m = materials_[base];
      const AreaLight& light = area_lights_[static_cast<std::size_t>(area_light)];
      if (light.radiance.kelvin) {
        m["emission_luminance"] = kLumensPerWatt * light.scale;
        m["emission_temperature"] = *light.radiance.kelvin;
      } else {
        m["emission"] = rgb_json(scaled(light.radiance.rgb, kPi * light.scale));
      }
      materials_[name] = m;
    }
    return name;
  }
  std::string default_material() {
    if (!materials_.contains("pbrt-default")) materials_["pbrt-default"] = {{"kd", 0.5}};
    return "pbrt-default";
  }

  // --- shapes -----------------------------------------------------------------------------------

  void push_shape(Json shape, const ShapeRecord& record, bool flip) {
    if (shapes_.size() >= kMostShapes)
      throw InputError(record.where, fmt::format("the scene would hold more than {} shapes", kMostShapes));
    shape["name"] =
        fmt::format("{}:{}", std::filesystem::path(record.where.file).filename().string(), record.where.line);
    shape["material"] = material_of(record.material, record.area_light);
    if (flip) shape["flip_normals"] = true;
    if (record.area_light >= 0 && area_lights_[static_cast<std::size_t>(record.area_light)].two_sided)
      shape["two_sided"] = true;
    shapes_.push_back(std::move(shape));
  }

  std::vector<Eigen::Vector3d> points(const Parameters& p, const char* name, const Matrix& m,
                                      const SourceLocation& at) {
    const std::vector<double> v = p.numbers(name);
    if (v.empty() || v.size() % 3 != 0)
      throw InputError(at, fmt::format("\"point3 {}\" needs x y z triples", name));
    std::vector<Eigen::Vector3d> out;
    for (std::size_t k = 0; k < v.size(); k += 3)
      out.push_back(transform_point(m, {v[k], v[k + 1], v[k + 2]}));
    return out;
  }
  static std::vector<std::size_t> indices(const Parameters& p, std::size_t group, std::size_t count,
                                          const SourceLocation& at) {
    const Parameter* given = p.find("indices");
    std::vector<std::size_t> out;
    if (!given) {
      if (count != group)
        throw InputError(
            at, fmt::format("\"integer indices\" is required unless P holds exactly {} points", group));
      for (std::size_t k = 0; k < group; ++k) out.push_back(k);
      return out;
    }
    if (given->numbers.size() % group != 0)
      throw InputError(given->where, fmt::format("\"indices\" holds a multiple of {} numbers", group));
    for (double x : given->numbers) {
      if (x < 0 || x >= static_cast<double>(count))
        throw InputError(given->where, fmt::format("index {} is not one of the {} points of P", x, count));
      out.push_back(static_cast<std::size_t>(x));
    }
    return out;
  }

  void emit_shape(const ShapeRecord& record, const Matrix& world_from_object) {
    if (!record.material.empty() && materials_[record.material].contains("pbrt-interface")) return;
    const Parameters& p = record.parameters;
    const SourceLocation& at = record.where;
    const bool mesh_flip = record.reverse_orientation != swaps_handedness(world_from_object);
    const bool identity = world_from_object == Matrix::Identity();
    const auto triangle = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
      push_shape(
          {{"type", "triangle"}, {"vertices", Json::array({vector_json(a), vector_json(b), vector_json(c)})}},
          record, mesh_flip);
    };
    if (record.type == "trianglemesh") {
      const std::vector<Eigen::Vector3d> P = points(p, "P", world_from_object, at);
      const std::vector<std::size_t> index = indices(p, 3, P.size(), at);
      for (std::size_t k = 0; k < index.size(); k += 3)
        triangle(P[index[k]], P[index[k + 1]], P[index[k + 2]]);
      for (const char* dropped : {"N", "uv", "S"})
        if (p.find(dropped))
          warn(at, fmt::format("trianglemesh: \"{}\" is not used (Candela's triangles have none)", dropped));
    } else if (record.type == "bilinearmesh") {
      const std::vector<Eigen::Vector3d> P = points(p, "P", world_from_object, at);
      const std::vector<std::size_t> index = indices(p, 4, P.size(), at);
      for (std::size_t k = 0; k < index.size(); k += 4) {
        const Eigen::Vector3d &p00 = P[index[k]], &p10 = P[index[k + 1]], &p01 = P[index[k + 2]],
                              &p11 = P[index[k + 3]];
        const double size = std::max((p10 - p00).norm(), (p01 - p00).norm());
        if ((p00 + p11 - p10 - p01).norm() <= 1e-9 * size) {
          push_shape({{"type", "quad"},
                      {"corner", vector_json(p00)},
                      {"edge_u", vector_json(p10 - p00)},
                      {"edge_v", vector_json(p01 - p00)}},
                     record, mesh_flip);
        } else {
          triangle(p00, p10, p11);
          triangle(p00, p11, p01);
        }
      }
      for (const char* dropped : {"N", "uv"})
        if (p.find(dropped)) warn(at, fmt::format("bilinearmesh: \"{}\" is not used", dropped));
    } else if (record.type == "plymesh") {
      const std::string file = p.string("filename", "");
      if (file.empty()) throw InputError(at, "Shape \"plymesh\" needs \"string filename\"");
      if (lowercase(file).ends_with(".gz")) {
        warn(at, fmt::format("plymesh \"{}\": compressed PLY files are not read by Candela: skipped", file));
        return;
      }
      require_file(file, record.folder, at, "the PLY file");
      Json shape = {{"type", "mesh"}, {"file", document_path(file, record.file_prefix)}};
      if (!identity) shape["transform"] = matrix_json(world_from_object);
      if (p.find("displacement")) warn(at, "plymesh: displacement is not used");
      p.find("edgelength");
      push_shape(std::move(shape), record, mesh_flip);
    } else if (record.type == "sphere") {
      const double radius = p.number("radius", 1);
      if (!(radius > 0)) throw InputError(at, "sphere: radius must be > 0");
      if (p.find("zmin") || p.find("zmax") || p.find("phimax"))
        warn(at, "sphere: a partial sphere is drawn whole");
      Json shape = {{"type", "sphere"}, {"center", Json::array({0, 0, 0})}, {"radius", radius}};
      if (!identity) shape["transform"] = matrix_json(world_from_object);
      push_shape(std::move(shape), record, record.reverse_orientation);
    } else if (record.type == "disk") {
      const double radius = p.number("radius", 1), inner = p.number("innerradius", 0),
                   height = p.number("height", 0);
      if (!(radius > 0) || inner < 0 || inner >= radius)
        throw InputError(at, "disk: needs 0 ≤ innerradius < radius");
      if (p.find("phimax")) warn(at, "disk: a partial disk is drawn whole");
      Json shape = {{"type", "disc"},
                    {"center", Json::array({0, 0, height})},
                    {"normal", Json::array({0, 0, 1})},
                    {"radius", radius}};
      if (inner > 0) shape["inner_radius"] = inner;
      if (!identity) shape["transform"] = matrix_json(world_from_object);
      push_shape(std::move(shape), record, record.reverse_orientation);
    } else {
      warn(at, fmt::format("unknown shape type \"{}\" is skipped", record.type));
      return;
    }
    if (p.find("alpha")) warn(at, fmt::format("{}: \"alpha\" is not used", record.type));
    warn_unused(p, fmt::format("Shape \"{}\"", record.type));
  }

  // --- lights -----------------------------------------------------------------------------------

  void light_source(const std::string& type, const Parameters& p, const SourceLocation& at,
                    const std::string& prefix, const std::filesystem::path& folder) {
    const Matrix& m = state_.ctm;
    const double scale = p.number("scale", 1);
    Json light;
    if (type == "point" || type == "spot") {
      const PbrtColor I = color(p, "I", {});
      const Eigen::Vector3d from = transform_point(m, p.point("from", {0, 0, 0}));
      light = {{"type", type}, {"position", vector_json(from)}};
      double factor = scale;
      const double power = p.number("power", -1);
      const double cone = p.number("coneangle", 30), delta = p.number("conedeltaangle", 5);
      if (type == "spot") {
        if (!(cone > 0 && cone < 180) || delta < 0 || delta > cone)
          throw InputError(at, "spot: needs 0 < coneangle < 180 and 0 ≤ conedeltaangle ≤ coneangle");
        const Eigen::Vector3d to = transform_point(m, p.point("to", {0, 0, 1}));
        light["target"] = vector_json(to);
        light["cutoff"] = cone;
        light["falloff_start"] = cone - delta;
      }
      if (power > 0) {
        const double cos_end = std::cos(cone * kPi / 180), cos_start = std::cos((cone - delta) * kPi / 180);
        // pbrt-v4's solid angle of the light (its PointLight and SpotLight::Create).
        factor *=
            power / (type == "point" ? 4 * kPi : 2 * kPi * ((1 - cos_start) + (cos_start - cos_end) / 2));
      }
      if (I.kelvin) {
        light["luminous_intensity"] = kLumensPerWatt * factor;
        light["temperature"] = *I.kelvin;
      } else {
        // "inverse-square" is 1/(4π d²): intensity 4π·I gives E = I/d².
        light["intensity"] = rgb_json(scaled(I.rgb, 4 * kPi * factor));
        light["attenuation"] = "inverse-square";
      }
    } else if (type == "distant") {
      const PbrtColor L = color(p, "L", {});
      const Eigen::Vector3d from = p.point("from", {0, 0, 0}), to = p.point("to", {0, 0, 1});
      const Eigen::Vector3d direction = transform_vector(m, to - from);
      if (!(direction.norm() > 0)) throw InputError(at, "distant: from and to coincide");
      const double illuminance = p.number("illuminance", -1);
      const double factor = scale * (illuminance > 0 ? illuminance : 1);
      light = {{"type", "directional"}, {"direction", vector_json(direction.normalized())}};
      if (L.kelvin) {
        light["illuminance"] = kLumensPerWatt * factor;
        light["temperature"] = *L.kelvin;
      } else {
        light["intensity"] = rgb_json(scaled(L.rgb, factor));
      }
    } else if (type == "infinite") {
      if (!environment_.is_null())
        warn(at, "a second infinite light replaces the first (Candela has one environment)");
      const std::string file = p.string("filename", "");
      const double illuminance = p.number("illuminance", -1);
      if (!file.empty()) {
        require_file(file, folder, at, "the environment image");
        warn(at,
             "infinite: pbrt-v4's image maps are equal-area octahedral; Candela reads the file as an "
             "equirectangular panorama (up: the light's +z)");
        environment_ = {{"type", "equirectangular"},
                        {"file", document_path(file, prefix)},
                        {"up", vector_json(transform_vector(m, {0, 0, 1}).normalized())},
                        {"forward", vector_json(transform_vector(m, {-1, 0, 0}).normalized())},
                        {"multiplier", kPi * scale}};
        if (illuminance > 0) warn(at, "infinite: illuminance of an image map is not used");
      } else {
        const PbrtColor L = color(p, "L", {});
        if (L.kelvin) warn(at, "infinite: a blackbody sky is drawn white");
        // pbrt scales a uniform sky of illuminance E to radiance L·E/π: the colour (π × radiance) is L·E.
        const double factor = illuminance > 0 ? scale * illuminance : kPi * scale;
        environment_ = {{"type", "constant"}, {"color", rgb_json(scaled(L.rgb, factor))}};
      }
      p.find("portal");
    } else {
      warn(at, fmt::format("LightSource \"{}\" is not supported: skipped", type));
      return;
    }
    if (!light.is_null()) lights_.push_back(std::move(light));
    warn_unused(p, fmt::format("LightSource \"{}\"", type));
  }

  // --- the document -----------------------------------------------------------------------------

  Json camera_json() {
    const Parameters& f = film_;
    const int width = static_cast<int>(f.number("xresolution", 1280));
    const int height = static_cast<int>(f.number("yresolution", 720));
    if (width < 1 || height < 1 || width > 65536 || height > 65536)
      throw InputError(film_where_, "Film: xresolution and yresolution must lie in [1, 65536]");
    f.find("filename");
    warn_unused(f, "Film");
    Json camera = {{"width", width}, {"height", height}};
    if (camera_type_.empty()) {
      warn(SourceLocation{main_path_, 1, 1, {}}, "no Camera: pbrt's default, at the origin looking down +z");
      camera_type_ = "perspective";
    }
    // The view: pbrt's camera space looks down +z with +y up and +x to the image's right.
    Eigen::Vector3d eye, target, up;
    bool mirrored;
    if (camera_look_at_) {
      eye = camera_look_at_->eye;
      target = camera_look_at_->target;
      up = camera_look_at_->up;
      mirrored = !camera_look_at_->mirrored_by_scale;
    } else {
      const Matrix world_from_camera = camera_from_world_.inverse();
      if (!world_from_camera.allFinite())
        throw InputError(camera_where_, "Camera: the transform is not invertible");
      eye = transform_point(world_from_camera, {0, 0, 0});
      const Eigen::Vector3d gaze = transform_vector(world_from_camera, {0, 0, 1}).normalized();
      target = eye + gaze;
      up = transform_vector(world_from_camera, {0, 1, 0});
      const Eigen::Vector3d right = transform_vector(world_from_camera, {1, 0, 0});
      // Candela's image right is gaze × up; pbrt's is the camera's +x.
      mirrored = gaze.cross(up).dot(right) < 0;
    }
    camera["eye"] = vector_json(eye);
    camera["target"] = vector_json(target);
    camera["up"] = vector_json(up);
    if (mirrored) camera["mirrored"] = true;
    const Parameters& c = camera_parameters_;
    const double aspect = static_cast<double>(width) / height;
    if (camera_type_ == "perspective") {
      camera["type"] = "perspective";
      const double fov = c.number("fov", 90);
      if (!(fov > 0 && fov < 180)) throw InputError(camera_where_, "Camera: fov must lie in (0, 180)");
      // pbrt's fov spans the shorter image side.
      camera[width > height ? "vertical_fov" : "fov"] = fov;
      if (c.find("lensradius") && c.number("lensradius", 0) > 0)
        warn(camera_where_, "Camera: depth of field is not supported");
      c.find("focaldistance");
    } else if (camera_type_ == "orthographic") {
      camera["type"] = "orthographic";
      std::vector<double> window = c.numbers("screenwindow");
      if (window.empty())
        window = aspect > 1 ? std::vector<double>{-aspect, aspect, -1, 1}
                            : std::vector<double>{-1, 1, -1 / aspect, 1 / aspect};
      if (window.size() != 4 || !(window[1] > window[0]) || !(window[3] > window[2]))
        throw InputError(camera_where_,
                         "Camera: screenwindow is [xmin xmax ymin ymax] with xmax > xmin, ymax > ymin");
      camera["window"] = Json::array({window[0], window[1], window[2], window[3]});
      c.find("lensradius");
      c.find("focaldistance");
    } else {
      warn(camera_where_,
           fmt::format("Camera \"{}\" is not supported: a perspective camera of fov 90", camera_type_));
      camera["type"] = "perspective";
      camera[width > height ? "vertical_fov" : "fov"] = 90;
    }
    warn_unused(c, fmt::format("Camera \"{}\"", camera_type_));
    return camera;
  }

  PbrtSceneDocument finish() {
    if (!attribute_stack_.empty())
      warn(attribute_stack_.back().second, "AttributeBegin without AttributeEnd");
    Json document = {{"format", "candela/1"}};
    document["camera"] = camera_json();
    document["render"] = {{"method", "path"}};
    Json path = Json::object();
    if (spp_) path["spp"] = *spp_;
    if (max_depth_) path["max_depth"] = *max_depth_;
    if (!path.empty()) document["path"] = path;
    if (!environment_.is_null()) document["environment"] = environment_;
    Json materials = Json::object();
    for (auto& [name, material] : materials_)
      if (!material.contains("pbrt-interface")) materials[name] = material;
    document["materials"] = materials;
    document["shapes"] = std::move(shapes_);
    document["lights"] = std::move(lights_);
    return {std::move(document), std::move(warnings_)};
  }

  std::string main_path_;
  GraphicsState state_;
  bool pending_mirror_ = false;
  std::vector<std::pair<GraphicsState, SourceLocation>> attribute_stack_;
  std::vector<std::pair<Matrix, std::optional<GraphicsState::LookAt>>> transform_stack_;
  std::map<std::string, std::pair<Matrix, std::optional<GraphicsState::LookAt>>> named_systems_;
  std::optional<std::string> current_object_;
  std::map<std::string, std::vector<ShapeRecord>> objects_;
  std::vector<AreaLight> area_lights_;
  std::map<std::string, Json> materials_;
  std::map<std::string, Json> textures_;
  int anonymous_materials_ = 0;
  std::string camera_type_;
  Parameters camera_parameters_, film_;
  SourceLocation camera_where_, film_where_;
  Matrix camera_from_world_ = Matrix::Identity();
  std::optional<GraphicsState::LookAt> camera_look_at_;
  std::optional<long long> spp_, max_depth_;
  Json environment_;
  Json shapes_ = Json::array();
  Json lights_ = Json::array();
  std::vector<std::string> warnings_;
  std::set<std::string> warned_;
};

}  // namespace

PbrtSceneDocument pbrt_scene_document(const std::string& path) {
  return Translator(path).translate(nullptr);
}

PbrtSceneDocument pbrt_scene_document_from_text(const std::string& text, const std::string& path) {
  return Translator(path).translate(&text);
}

}  // namespace candela
