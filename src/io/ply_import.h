// Stanford PLY import (hand-written reader, no library): one TriangleMesh per file, returned in
// the same ObjImport result as the OBJ reader so that the "mesh" shape treats both alike (no
// materials; every triangle's material is -1, i.e. the scene entry's).
//
// Accepted: "format ascii 1.0", "binary_little_endian 1.0", "binary_big_endian 1.0"; "comment"
// and "obj_info" lines; scalar types char uchar short ushort int uint float double and their
// sized spellings int8 uint8 int16 uint16 int32 uint32 float32 float64. The "vertex" element
// must have x y z; nx ny nz (all three) become corner normals, u v / s t / texture_u texture_v /
// texture_s texture_t become corner uvs. The "face" element's list property vertex_indices (or
// vertex_index) gives polygons: triangles and quads fanned from their first corner, larger
// faces by triangulate_face as OBJ faces (geometry/face_triangulation.h: halved when convex,
// ear-clipped up to 1,000 corners, refused beyond); faces of fewer than 3 corners are skipped with
// a warning. Every other element and property (lists included) is read past and ignored.
//
// Errors (InputError located at referenced_from; the message names the PLY file and, in ASCII,
// the line, in binary, the byte offset): a bad header, an element count the rest of the file
// cannot hold (checked before anything is allocated), truncated data, a vertex index out of
// range, a non-finite coordinate, normal or uv (naming the vertex, counted from 0), no
// triangles. A zero-length normal is replaced by the face normal with a warning.
#pragma once

#include <string>

#include "io/obj_import.h"
#include "util/error.h"

namespace candela {

// Reads path (taken as given: the caller resolves it against the scene's directory).
ObjImport import_ply(const std::string& path, const SourceLocation& referenced_from);

}  // namespace candela
