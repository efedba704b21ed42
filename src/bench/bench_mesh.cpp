#include "bench/bench_mesh.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "bench/ray_sets.h"
#include "math/constants.h"
#include "util/error.h"
#include "util/input_file.h"

namespace candela {

namespace {

Vec3 rounded_to_float(double x, double y, double z) {
  return {round_to_float32(x), round_to_float32(y), round_to_float32(z)};
}

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

// Splits a line into whitespace-separated tokens (views into the line).
void split(std::string_view line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
}

bool parse_float(std::string_view token, float& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  return error == std::errc() && end == token.data() + token.size();
}

bool parse_index(std::string_view token, int64_t& value) {
  token = token.substr(0, token.find('/'));  // i, i/t, i//n, i/t/n: the vertex is first
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  return error == std::errc() && end == token.data() + token.size() && !token.empty();
}

void finish(BenchMesh& bench, const std::string& file) {
  if (bench.mesh->positions.empty()) throw InputError({file, 0, 0, {}}, "no vertices");
  if (bench.mesh->triangles.empty()) throw InputError({file, 0, 0, {}}, "no triangles");
  for (const Vec3& p : bench.mesh->positions) bench.bounds.extend(p);
}

}  // namespace

BenchMesh parse_bench_obj(std::string_view text, const std::string& name) {
  BenchMesh bench;
  bench.name = name;
  bench.mesh = std::make_shared<TriangleMesh>();
  TriangleMesh& mesh = *bench.mesh;
  // Faces are resolved once every vertex is known (positive indices may point forward);
  // negative indices are made absolute as they are read (-1 = the last vertex so far).
  std::vector<int64_t> corners;
  std::vector<std::size_t> face_starts;
  std::vector<std::string_view> tokens;
  int line_number = 0;
  std::size_t position = 0;
  while (position < text.size()) {
    std::size_t end = text.find('\n', position);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(position, end - position);
    position = end + 1;
    ++line_number;
    split(line, tokens);
    if (tokens.empty()) continue;
    if (tokens[0] == "v") {
      float xyz[3];
      if (tokens.size() < 4 || !parse_float(tokens[1], xyz[0]) || !parse_float(tokens[2], xyz[1]) ||
          !parse_float(tokens[3], xyz[2]))
        throw InputError({name, line_number, 0, {}}, "expected \"v x y z\" with three numbers");
      if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2]))
        throw InputError({name, line_number, 0, {}}, "non-finite vertex coordinate");
      mesh.positions.push_back({xyz[0], xyz[1], xyz[2]});
    } else if (tokens[0] == "f") {
      if (tokens.size() - 1 > kMaxBenchFaceCorners)
        throw InputError({name, line_number, 0, {}},
                         "a face of " + std::to_string(tokens.size() - 1) +
                             " corners: the benchmark fans each face from its first corner "
                             "(shared/BENCH-RAYS.md), and so many slivers overlapping at one corner "
                             "make every ray test most of them; at most " +
                             std::to_string(kMaxBenchFaceCorners) + " corners (split the face)");
      face_starts.push_back(corners.size());
      for (std::size_t k = 1; k < tokens.size(); ++k) {
        int64_t index = 0;
        if (!parse_index(tokens[k], index))
          throw InputError({name, line_number, 0, {}}, "bad face index \"" + std::string(tokens[k]) + "\"");
        // 1-based; negative counts back from the vertices read so far; 0 is out of range.
        if (index < 0)
          index += static_cast<int64_t>(mesh.positions.size());
        else
          index -= 1;
        corners.push_back(index);
      }
    }
  }
  face_starts.push_back(corners.size());

  const auto vertex_count = static_cast<int64_t>(mesh.positions.size());
  for (std::size_t face = 0; face + 1 < face_starts.size(); ++face) {
    const std::size_t begin = face_starts[face], end = face_starts[face + 1];
    bool valid = end - begin >= 3;
    for (std::size_t k = begin; k < end && valid; ++k) valid = corners[k] >= 0 && corners[k] < vertex_count;
    if (!valid) {
      ++bench.skipped_faces;
      continue;
    }
    const auto v0 = static_cast<uint32_t>(corners[begin]);
    for (std::size_t k = begin + 1; k + 1 < end; ++k)
      mesh.triangles.push_back(
          {v0, static_cast<uint32_t>(corners[k]), static_cast<uint32_t>(corners[k + 1])});
  }
  finish(bench, name);
  return bench;
}

BenchMesh read_bench_obj(const std::string& path) {
  // A regular file of at most 4 GiB (a FIFO blocked, a device was read without end).
  return parse_bench_obj(read_input_file(path, "the mesh file", kLargeInputLimit), path);
}

BenchMesh bench_sphere(uint64_t n) {
  const int64_t s = std::max<int64_t>(2, std::llround(std::sqrt(static_cast<double>(n) / 4.0)));
  const int64_t l = 2 * s;
  BenchMesh bench;
  bench.name = "sphere " + std::to_string(n);
  bench.mesh = std::make_shared<TriangleMesh>();
  TriangleMesh& mesh = *bench.mesh;
  mesh.positions.reserve(static_cast<std::size_t>(2 + (s - 1) * l));
  mesh.positions.push_back({0, 1, 0});
  mesh.positions.push_back({0, -1, 0});
  for (int64_t i = 1; i <= s - 1; ++i) {
    const double theta = kPi * static_cast<double>(i) / static_cast<double>(s);
    for (int64_t j = 0; j < l; ++j) {
      const double phi = 2.0 * kPi * static_cast<double>(j) / static_cast<double>(l);
      mesh.positions.push_back(rounded_to_float(std::sin(theta) * std::cos(phi), std::cos(theta),
                                                std::sin(theta) * std::sin(phi)));
    }
  }
  const auto r = [l](int64_t i, int64_t j) { return static_cast<uint32_t>(2 + (i - 1) * l + j % l); };
  mesh.triangles.reserve(static_cast<std::size_t>(4 * s * (s - 1)));
  for (int64_t j = 0; j < l; ++j) mesh.triangles.push_back({0, r(1, j + 1), r(1, j)});
  for (int64_t i = 1; i <= s - 2; ++i)
    for (int64_t j = 0; j < l; ++j) {
      const uint32_t a = r(i, j), b = r(i, j + 1), c = r(i + 1, j + 1), d = r(i + 1, j);
      mesh.triangles.push_back({a, b, c});
      mesh.triangles.push_back({a, c, d});
    }
  for (int64_t j = 0; j < l; ++j) mesh.triangles.push_back({1, r(s - 1, j), r(s - 1, j + 1)});
  finish(bench, bench.name);
  return bench;
}

BenchMesh bench_terrain(uint64_t n) {
  const int64_t g = std::max<int64_t>(1, std::llround(std::sqrt(static_cast<double>(n) / 2.0)));
  BenchMesh bench;
  bench.name = "terrain " + std::to_string(n);
  bench.mesh = std::make_shared<TriangleMesh>();
  TriangleMesh& mesh = *bench.mesh;
  mesh.positions.reserve(static_cast<std::size_t>((g + 1) * (g + 1)));
  for (int64_t i = 0; i <= g; ++i)
    for (int64_t j = 0; j <= g; ++j) {
      const double x = -1.0 + 2.0 * static_cast<double>(j) / static_cast<double>(g);
      const double z = -1.0 + 2.0 * static_cast<double>(i) / static_cast<double>(g);
      const double y = 0.15 * std::sin(3 * x + 0.5) * std::cos(2 * z) +
                       0.05 * std::sin(11 * x + 1) * std::cos(13 * z + 2) +
                       0.02 * std::sin(37 * x) * std::sin(41 * z);
      mesh.positions.push_back(rounded_to_float(x, y, z));
    }
  const auto v = [g](int64_t i, int64_t j) { return static_cast<uint32_t>(i * (g + 1) + j); };
  mesh.triangles.reserve(static_cast<std::size_t>(2 * g * g));
  for (int64_t i = 0; i < g; ++i)
    for (int64_t j = 0; j < g; ++j) {
      const uint32_t a = v(i, j), b = v(i, j + 1), c = v(i + 1, j + 1), d = v(i + 1, j);
      mesh.triangles.push_back({a, c, b});
      mesh.triangles.push_back({a, d, c});
    }
  finish(bench, bench.name);
  return bench;
}

}  // namespace candela
