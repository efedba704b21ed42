// Wavefront OBJ (+ MTL) import through tinyobjloader: one world-space-ready TriangleMesh per file
// (polygons triangulated, every object and group merged), the per-triangle material index and
// the MTL materials in file order.
//
// Polygons: triangulate_face (geometry/face_triangulation.h): a quad is split along its shorter
// diagonal; a larger face that is convex and planar is halved into triangles that shrink towards
// its boundary; any other face of at most kMaxNonConvexFaceCorners corners is ear-clipped in its
// plane, and a larger one is refused (ear clipping costs up to the cube of the corners).
//
// Mapping from MTL: Ka -> ka, Kd -> kd, Ke -> ke, Ks -> ks (mean of the three components),
// Ns -> shininess, kt = 1 - d (tinyobjloader turns Tr into d = 1 - Tr; d wins when both are
// given), clamped to [0, 1], Ni -> ior (1 when absent).
//
// Corner normals come from the file's vn when every triangle corner has one (zero-length vn are
// replaced by the face normal, with a warning); otherwise the mesh is left flat. Corner uvs come
// from vt when any corner has one (corners without vt get the default (0,0), (1,0), (1,1) of
// their triangle, with a warning).
//
// Errors (InputError located at referenced_from, the scene's "file" key): a missing or unreadable
// file, one that is not a regular file or is larger than kLargeInputLimit (the OBJ or an MTL file
// that exists), a parse error (the message names the OBJ and gives tinyobjloader's text with its
// line number), a face index out of range (with the OBJ's line: beyond the 32-bit range, or
// relative and reaching before the first vertex, as well as past the last one), a non-finite
// coordinate, a non-convex face of more than kMaxNonConvexFaceCorners corners, no triangles at
// all. A missing .mtl or an unknown usemtl name is only a warning (those triangles get material
// -1).
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "geometry/face_triangulation.h"
#include "geometry/triangle_mesh.h"
#include "math/vector.h"
#include "util/error.h"

namespace candela {

struct ImportedMaterial {
  std::string name;
  Color ka;
  Color kd;
  Color ke;                     // emission (MTL Ke); black when absent
  double ks = 0;                // mean of the MTL Ks components
  double shininess = 0;         // MTL Ns
  double kt = 0;                // 1 - d (or Tr), clamped to [0, 1]
  double ior = 1;               // MTL Ni
  std::string diffuse_texture;  // MTL map_Kd, resolved against the OBJ's folder; empty if none
};

struct ObjImport {
  std::shared_ptr<TriangleMesh> mesh;       // positions as in the file (object space)
  std::vector<int> triangle_material;       // per triangle: index into materials, -1 = none
  std::vector<ImportedMaterial> materials;  // every material of the .mtl file(s), in order
  // glTF: each triangle's material index in the file (-1: none), which a scene names by
  // position (the mesh entry's "file_materials"); empty for OBJ and PLY.
  std::vector<int> triangle_file_material;
  std::vector<std::string> warnings;  // each prefixed with the OBJ path
};

// Reads path (taken as given: the caller resolves it against the scene's directory); the .mtl
// files named by mtllib are searched for in the OBJ's directory.
ObjImport import_obj(const std::string& path, const SourceLocation& referenced_from);

// The check every mesh reader (OBJ, PLY, glTF) makes first: InputError at referenced_from,
// "<format> file 'PATH' not found" or "... is not a regular file".
void require_mesh_file(const std::string& path, const std::string& format,
                       const SourceLocation& referenced_from);

}  // namespace candela
