// The meshes of `candela bench` (SPEC §14), read and generated exactly as shared/BENCH-RAYS.md
// says, so that every accelerator here and any other program trace the same triangles:
//
// - read_bench_obj: only `v x y z` and `f i j k ...` lines (indices `i`, `i/t`, `i//n`,
//   `i/t/n`; negative indices count back from the vertices read so far, positive ones may
//   refer to any vertex of the file). A polygon v0..v(n-1) becomes the fan (v0, vk, vk+1),
//   k = 1..n-2, in file order; triangle ids are the positions in TriangleMesh::triangles.
//   Faces with an out-of-range index, or fewer than three corners, are skipped and counted; a
//   face of more than kMaxBenchFaceCorners corners is refused (the fan of a 10⁵-corner
//   disc is 10⁵ slivers whose boxes all meet at its first corner, 0.007 Mrays/s in a BVH).
//   Every other line is ignored.
// - bench_sphere(N): the UV sphere of 4S(S-1) triangles, S = max(2, round(sqrt(N/4))).
// - bench_terrain(N): the height field of 2G² triangles, G = max(1, round(sqrt(N/2))).
//
// Coordinates are rounded to float32 (the file's decimal text is read as a float; the
// generators evaluate in double and round), so the double-precision accelerators see exactly
// the float vertices Embree gets. Degenerate triangles are kept: they have ids too.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "geometry/triangle_mesh.h"
#include "math/bounds.h"

namespace candela {

// The most corners of one face of a bench mesh (see read_bench_obj above).
inline constexpr std::size_t kMaxBenchFaceCorners = 1000;

struct BenchMesh {
  std::string name;  // the file as given, or "sphere N" / "terrain N"
  std::shared_ptr<TriangleMesh> mesh;
  Bounds3 bounds;                 // over every vertex read, used by a face or not
  std::size_t skipped_faces = 0;  // out-of-range index or fewer than three corners
};

// Throws InputError (file and line) for an unreadable file, a malformed number or index, a
// non-finite coordinate, or a file without vertices or triangles.
BenchMesh read_bench_obj(const std::string& path);
// The same reader over text in memory; name is used in messages and as BenchMesh::name.
BenchMesh parse_bench_obj(std::string_view text, const std::string& name);

BenchMesh bench_sphere(uint64_t n);
BenchMesh bench_terrain(uint64_t n);

}  // namespace candela
