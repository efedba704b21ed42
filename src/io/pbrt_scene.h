// A pbrt-v4 scene file (.pbrt) as a candela/1 scene document, read after pbrt-v4's file-format
// documentation (https://pbrt.org/fileformat-v4). The document is loaded like any scene file, so
// --set, the ranges and every method apply. What Candela cannot do is a warning naming the
// directive (or parameter) and its file:line; malformed input is an InputError at
// file:line:column.
//
// | pbrt-v4 directive | what it becomes in Candela |
// | --- | --- |
// | `Film` (any type) | `xresolution`, `yresolution` (1280 × 720) → `camera.width`, `camera.height`; the rest
// is ignored (warning) | | `Camera "perspective"` | `camera` of type perspective from the world-from-camera
// matrix; `fov` (90°) spans the image's shorter side: `vertical_fov` for a landscape image, `fov`
// (horizontal) otherwise; `lensradius`, `focaldistance`, `screenwindow`: warning | | `Camera "orthographic"`
// | `camera` of type orthographic, `screenwindow` (default [−aspect, aspect, −1, 1], or [−1, 1, −1/aspect,
// 1/aspect] for a portrait image) → `window` | | camera handedness | pbrt's camera space is left-handed (+x
// right, +y up, looking down +z). When the world-from-camera matrix keeps handedness (a plain `LookAt`), the
// image is the right-handed view mirrored left to right: `camera.mirrored: true`. `Scale -1 1 1` before
// `LookAt` (what exporters write) gives the plain right-handed camera. A camera made by (`Scale -1 1 1`)
// `LookAt` alone keeps the LookAt's eye, target and up exactly | | `LookAt`, `Translate`, `Scale`, `Rotate`,
// `Transform`, `ConcatTransform`, `Identity`, `CoordinateSystem`, `CoordSysTransform`, `TransformBegin`/`End`
// | the current transform, as pbrt composes it (`Transform` lists the matrix column by column); named systems
// "camera" and "world" are known | | `Sampler` | `pixelsamples` (16) → `path.spp`; the sampler type: warning
// | | `Integrator` | not used (warning; Candela's method is `render.method`, "path" by default); `maxdepth` →
// `path.max_depth` | | `PixelFilter`, `Accelerator`, `ColorSpace`, `Option`, `Attribute`, `MakeNamedMedium`,
// `MediumInterface`, `ActiveTransform`, `TransformTimes` | not used (warning) | | `WorldBegin` | the
// transform becomes the identity | | `AttributeBegin`/`AttributeEnd` | save and restore the transform,
// material, area light and orientation (`AttributeEnd` with nothing saved: error) | |
// `ObjectBegin`/`ObjectEnd`/`ObjectInstance` | the object's shapes are kept with their transforms and emitted
// again at each instance with the instance's transform composed before theirs; an instance inside an object:
// error; area lights do not apply to objects (pbrt-v4's rule: warning) | | `Include`, `Import` | the file,
// relative to the including file, read in place; a file that includes itself through a chain: error naming
// the chain | | `Shape "trianglemesh"` | one `triangle` per triangle of `P` by `indices` (3 points without
// indices: one), in world coordinates; `N`, `uv`, `S`: warning (Candela's triangles have none) | | `Shape
// "bilinearmesh"` | each patch of `P` by `indices` (p00 p10 p01 p11): a `quad` (corner p00, edge_u p10 − p00,
// edge_v p01 − p00, so its uv and normal are pbrt's) when it is a parallelogram, else two `triangle`s | |
// `Shape "plymesh"` | a `mesh` entry of the `.ply` file (relative to the .pbrt file) with the transform as a
// matrix; `displacement`: warning; `.ply.gz`: warning, skipped | | `Shape "sphere"` | `sphere` of `radius`
// (1) at the origin, the transform as a matrix; `zmin`, `zmax`, `phimax`: warning | | `Shape "disk"` | `disc`
// at (0, 0, `height`) facing +z, `radius` (1), `innerradius` (0) → `inner_radius`, the transform as a matrix
// | | orientation | `ReverseOrientation`, and for triangles, quads and meshes a transform that swaps
// handedness, → `flip_normals` (pbrt's rule) | | `LightSource "point"` | `point` at the transformed `from`,
// `intensity` 4π·I·`scale` with `attenuation` "inverse-square" (so E = I·scale/d²); `power` P: I =
// rgb·P/(4π), as pbrt | | `LightSource "spot"` | `spot` from `from` to `to`, `cutoff` = `coneangle` (30°),
// `falloff_start` = coneangle − `conedeltaangle` (5°), intensity as a point light's; `power` as pbrt: I =
// rgb·P / (2π(1 − cos start) + π(cos start − cos cutoff)) | | `LightSource "distant"` | `directional` along
// `to` − `from`, `intensity` L·`scale` (× `illuminance` when given): the irradiance on a surface facing it |
// | `LightSource "infinite"` | `L` → `environment` constant of colour π·L·`scale` (with `illuminance` E:
// L·E·`scale`, pbrt's E on an upward surface); `filename` → `environment` equirectangular of multiplier
// π·`scale` (pbrt-v4's maps are equal-area octahedral: warning) | | `AreaLightSource "diffuse"` | the
// following shapes' material gains `emission` π·L·`scale` (a copy of the material per light); `twosided` →
// the shapes' `two_sided` (radiosity meshes both sides); `filename`, `power`: warning | | `Material`,
// `MakeNamedMaterial`, `NamedMaterial` | a named material of `materials` ("material-N" for an anonymous one);
// default: diffuse 0.5 | | `"diffuse"` | `kd` = `reflectance` (0.5) | | `"coateddiffuse"` | cook-torrance,
// `kd` = `reflectance` (0.5), `ks` = 1 − max kd (a texture: 0.2), `fresnel_ior` = `eta` (1.5), GGX
// `roughness` α | | `"conductor"` | cook-torrance, `kd` 0, `ks` 1, `fresnel_ior` = `eta`, `fresnel_k` = `k`
// (named spectra "metal-Cu/Au/Ag/Al-eta/-k" → RGB, io/pbrt_spectra.h; default copper), or `reflectance` →
// `fresnel_f0`; GGX `roughness` α | | `"dielectric"` | `kd` 0, `kt` 1, `ior` = `eta` (1.5, or a named glass);
// rough glass is drawn smooth (warning) | | `"thindielectric"` | as dielectric with `thin`: true | |
// `"interface"` | the shapes are not emitted (an invisible boundary) | | other materials | warning; diffuse
// 0.5 (`diffusetransmission`: its `reflectance`; `coatedconductor`: its conductor; `mix`: its first material)
// | | roughness | `roughness` (0) or the mean of `uroughness`/`vroughness` (warning when they differ); α = √r
// when `remaproughness` (true), else r; at least 10⁻³ | | `Texture "imagemap"` | `image` texture of
// `filename` (relative to the .pbrt file), `encoding` sRGB or linear, `scale` → `multiplier`,
// `uscale`/`vscale`/`udelta`/`vdelta` → the uv mapping's `scale`/`offset`, `wrap` repeat/clamp ("black":
// clamp, warning) | | `Texture "checkerboard"` | 2D: `checker2d` of `tex1` (even) and `tex2` (odd) with the
// uv mapping; 3D: `checkerboard` of size 1 | | `Texture "scale"`, `"constant"` | `tex` × `scale` folded into
// a constant or an image's multiplier; `value` | | other textures | warning; grey 0.5 | | parameter types |
// `float`, `integer`, `bool`, `string`, `texture`, `point*`, `vector*`, `normal*`, `rgb` (and `color`),
// `spectrum` (a named spectrum, or λ-value pairs: their mean, warning), `blackbody` (a light's colour of that
// temperature: photometric keys `…temperature`; elsewhere grey, warning) |
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
