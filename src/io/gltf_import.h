// glTF 2.0 mesh import (the file read by io/gltf_file.h): every TRIANGLES primitive of every mesh
// reached from a scene's nodes (the one asked for, else the file's default, else scene 0; every
// mesh at identity when the file has no scene), placed by its node's world transform (matrix or translation,
// rotation, scale, composed down the node tree; a mirroring transform also reverses the winding), merged into
// one TriangleMesh returned in the same ObjImport result as the OBJ reader (no materials: every triangle's
// material is -1, i.e. the scene entry's; each triangle's material index in the file is in
// triangle_file_material, for a scene that defines them, io/gltf_scene.h).
//
// Read: POSITION (float VEC3), indices (unsigned byte, short or int SCALAR) or none (every three
// vertices a triangle), NORMAL (float VEC3) -> corner normals when every primitive has them,
// TEXCOORD_0 (float VEC2) -> corner uvs, flipped to v' = 1 - v (glTF's v runs down the image,
// Candela's, as OBJ's, up). Images and materials are ignored.
//
// Warnings (each prefixed with the file): a primitive of another mode (points, lines, strips,
// fans), named as "mesh M primitive P", is skipped; tinygltf's own warnings. Errors (InputError
// located at referenced_from, naming the file and, where there is one, the JSON path):
// those of io/gltf_file.h, a missing POSITION, accessors of the wrong type, an accessor or
// bufferView byteOffset or byteStride that is not a non-negative integer (tinygltf would read it
// as 0), offsets, lengths and counts past the end of their bufferView or buffer, sparse
// accessors, an index out of range, a non-finite position or one above 1e16, node numbers
// (matrix, translation, rotation, scale) above 1e16 or a transform composed down the node tree
// that leaves that range, the zero quaternion, a singular node transform, no triangles.
#pragma once

#include <string>

#include "io/obj_import.h"
#include "util/error.h"

namespace candela {

// Reads path (taken as given); ".glb" (any case) is read as binary glTF, anything else as JSON.
// scene: the scene to read (-1: the file's default).
ObjImport import_gltf(const std::string& path, const SourceLocation& referenced_from, int scene = -1);

}  // namespace candela
