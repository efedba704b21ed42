// A pbrt-v4 scene file (.pbrt) as a candela/1 scene document, read after pbrt-v4's file-format
// documentation (https://pbrt.org/fileformat-v4). The document is loaded like any scene file, so
// --set, the ranges and every method apply. What Candela cannot do is a warning naming the
// directive (or parameter) and its file:line; malformed input is an InputError at
// file:line:column.
//
// What each directive becomes is the table of docs/import.md ("pbrt-v4 files"); in short: Film,
// Camera (perspective, orthographic; pbrt's left-handed camera space as camera.mirrored), the
// transform directives, Sampler (path.spp), WorldBegin, AttributeBegin/End, ObjectBegin/End/
// Instance, Include/Import, Shape trianglemesh/bilinearmesh/plymesh/sphere/disk, LightSource
// point/spot/distant/infinite, AreaLightSource diffuse, Material/MakeNamedMaterial/NamedMaterial
// diffuse/coateddiffuse/conductor/dielectric/thindielectric/interface, Texture imagemap/
// checkerboard/scale/constant; anything else is a warning at its file:line.
//
// Units. pbrt-v4 normalises an RGB light spectrum to its colour space's illuminant, so an RGB
// value of 1 is one unit of radiance (or intensity); Candela reads that unit as its W/(m²·sr)
// (W/sr). A material's `emission` and an environment's colour are exitance-like (a seen surface of
// emission E shows E: Candela's pixel values are π × radiance), so pbrt's radiance L becomes
// π·L; a point light's I (W/sr) gives E = I/d² at normal incidence. A Candela image of a pbrt
// scene is therefore π × pbrt's image (`film.exposure` −log₂π ≈ −1.65 shows pbrt's values). A
// blackbody light is pbrt's "1 nit" spectrum of that temperature: Candela's photometric keys of
// the same luminance in its units (179 × the value in cd, 179 lm/W).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace candela {

struct PbrtSceneDocument {
  nlohmann::json document;  // candela/1
  std::vector<std::string> warnings;
};

// The document of the pbrt-v4 scene file at path (its Include files, meshes and images relative
// to the file that names them, written relative to path's folder in the document).
PbrtSceneDocument pbrt_scene_document(const std::string& path);

// The same of the text of a file named path (the fuzz harness and tests).
PbrtSceneDocument pbrt_scene_document_from_text(const std::string& text, const std::string& path);

}  // namespace candela
