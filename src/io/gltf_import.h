// glTF 2.0 import through tinygltf (.gltf with embedded data-URI or external buffers, resolved
// against the file's folder, and binary .glb): every TRIANGLES primitive of every mesh reached
// from the default scene's nodes (scene 0 when none is named; every mesh at identity when the
// file has no scene), placed by its node's world transform (matrix or translation, rotation,
// scale, composed down the node tree; a mirroring transform also reverses the winding), merged
// into one TriangleMesh returned in the same ObjImport result as the OBJ reader (no materials:
// every triangle's material is -1, i.e. the scene entry's).
//
// Read: POSITION (float VEC3), indices (unsigned byte, short or int SCALAR) or none (every three
// vertices a triangle), NORMAL (float VEC3) -> corner normals when every primitive has them,
// TEXCOORD_0 (float VEC2) -> corner uvs, flipped to v' = 1 - v (glTF's v runs down the image,
// Candela's, as OBJ's, up). Images and materials are ignored.
//
// Warnings (each prefixed with the file): a primitive of another mode (points, lines, strips,
// fans), named as "mesh M primitive P", is skipped; tinygltf's own warnings. Errors (InputError
// located at referenced_from, naming the file): tinygltf's parse errors, a missing POSITION,
// accessors of the wrong type or outside their buffer, sparse accessors, an index out of range,
// a non-finite position, a singular node transform, no triangles.
#pragma once

#include <string>

#include "io/obj_import.h"
#include "util/error.h"

namespace candela {

// Reads path (taken as given); ".glb" (any case) is read as binary glTF, anything else as JSON.
ObjImport import_gltf(const std::string& path, const SourceLocation& referenced_from);

}  // namespace candela
