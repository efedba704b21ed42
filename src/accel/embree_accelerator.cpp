#include "accel/embree_accelerator.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "geometry/triangle_mesh.h"
#include "math/next_up.h"

namespace candela {

namespace {

constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

// The float nearest x from below / above (x itself when representable). Out of line: GCC 12.2
// vectorises adjacent double-to-float-to-double round trips and drops the rounding.
[[gnu::noinline]] float float_down(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}
[[gnu::noinline]] float float_up(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

std::string error_name(RTCError error) {
  switch (error) {
    case RTC_ERROR_NONE:
      return "no error";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
    default:
      return "unknown error";
  }
}

}  // namespace

struct EmbreeAccelerator::State {
  Mode mode = Mode::exact;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::atomic<int64_t> device_bytes{0};  // the memory monitor's running total
  std::string last_error;

  std::span<const Primitive> primitives;
  // exact: Embree primID -> primitive index, and the primitives Embree cannot bound.
  std::vector<uint32_t> bounded;
  std::vector<uint32_t> unbounded;
  Bounds3 scene_bounds;  // of the bounded primitives, inflated by margin
  double margin = 0;     // box inflation covering the float ray and Embree's float arithmetic
  // native_triangles: triangle index (Embree primID) -> primitive index.
  std::vector<uint32_t> triangle_to_primitive;

  ~State() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  void check(const char* what) {
    const RTCError error = rtcGetDeviceError(device);
    if (error != RTC_ERROR_NONE)
      throw std::runtime_error(std::string("Embree: ") + what + ": " + error_name(error) +
                               (last_error.empty() ? "" : " (" + last_error + ")"));
  }

  void build_exact();
  void build_native();
};

namespace {

// One rtcIntersect1/rtcOccluded1 call of exact mode. Embree hands back the address of the
// RTCIntersectContext, the first member, so the callbacks reach the double ray and the best
// hit so far through it.
struct ExactContext {
  RTCIntersectContext context;
  const EmbreeAccelerator::State* state = nullptr;
  const Ray* ray = nullptr;
  double t_offset = 0;  // the float ray starts at ray.at(t_offset)
  double margin_t = 0;  // state->margin in units of the ray parameter
  bool found = false;
  bool occluded = false;
  double best_t = 0;
  uint32_t best_primitive = kNone;
  SurfaceHit hit;

  // Tests one primitive against the double ray, keeping the closer hit (closer_hit's tie rule:
  // the test limit is nextafter(best_t) so that an equal t with a lower index is seen).
  bool consider(uint32_t primitive) {
    Ray test = *ray;
    if (found) test.t_max = next_up(best_t);
    SurfaceHit candidate;
    if (!state->primitives[primitive].shape->intersect(test, candidate)) return false;
    if (found && !closer_hit(candidate.t, primitive, best_t, best_primitive)) return false;
    found = true;
    best_t = candidate.t;
    best_primitive = primitive;
    hit = candidate;
    return true;
  }
  // A float bound on the ray parameter of the float ray that keeps every hit with t <= best_t.
  float far_bound(double t) const { return float_up(std::max(0.0, t - t_offset + margin_t)); }
};

void exact_bounds(const RTCBoundsFunctionArguments* args) {
  const auto* state = static_cast<const EmbreeAccelerator::State*>(args->geometryUserPtr);
  const Bounds3 b = state->primitives[state->bounded[args->primID]].shape->bounds();
  RTCBounds* out = args->bounds_o;
  out->lower_x = float_down(b.lower.x - state->margin);
  out->lower_y = float_down(b.lower.y - state->margin);
  out->lower_z = float_down(b.lower.z - state->margin);
  out->upper_x = float_up(b.upper.x + state->margin);
  out->upper_y = float_up(b.upper.y + state->margin);
  out->upper_z = float_up(b.upper.z + state->margin);
}

void exact_intersect(const RTCIntersectFunctionNArguments* args) {
  if (args->N != 1 || !args->valid[0]) return;
  auto* context = reinterpret_cast<ExactContext*>(args->context);
  const uint32_t primitive = context->state->bounded[args->primID];
  if (!context->consider(primitive)) return;
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, 1);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, 1);
  RTCRayN_tfar(ray, 1, 0) = std::min(RTCRayN_tfar(ray, 1, 0), context->far_bound(context->best_t));
  RTCHitN_primID(hit, 1, 0) = args->primID;
  RTCHitN_geomID(hit, 1, 0) = args->geomID;
}

void exact_occluded(const RTCOccludedFunctionNArguments* args) {
  if (args->N != 1 || !args->valid[0]) return;
  auto* context = reinterpret_cast<ExactContext*>(args->context);
  const uint32_t primitive = context->state->bounded[args->primID];
  if (!context->state->primitives[primitive].shape->occluded(*context->ray)) return;
  context->occluded = true;
  RTCRayN_tfar(args->ray, 1, 0) = -std::numeric_limits<float>::infinity();  // Embree: stop
}

bool monitor_memory(void* user, ssize_t bytes, bool /*post*/) {
  static_cast<EmbreeAccelerator::State*>(user)->device_bytes += static_cast<int64_t>(bytes);
  return true;
}

void record_error(void* user, RTCError /*code*/, const char* message) {
  if (message) static_cast<EmbreeAccelerator::State*>(user)->last_error = message;
}

// The float ray of exact mode: from where the double ray enters the (inflated) bounds of all
// bounded primitives, so that the origin, and therefore its rounding, stays small.
bool start_exact(const EmbreeAccelerator::State& state, const Ray& ray, ExactContext& context, RTCRay& out) {
  double t_enter = 0, t_exit = 0;
  if (state.scene_bounds.empty() || !state.scene_bounds.intersect(ray, t_enter, t_exit)) return false;
  const double length = candela::length(ray.direction);
  if (!(length > 0) || !std::isfinite(length)) return false;
  context.t_offset = t_enter;
  context.margin_t = state.margin / length * 4.0;
  const Vec3 origin = ray.at(t_enter);
  out.org_x = static_cast<float>(origin.x);
  out.org_y = static_cast<float>(origin.y);
  out.org_z = static_cast<float>(origin.z);
  out.dir_x = static_cast<float>(ray.direction.x);
  out.dir_y = static_cast<float>(ray.direction.y);
  out.dir_z = static_cast<float>(ray.direction.z);
  out.tnear = 0.0f;
  out.tfar = context.far_bound(t_exit);
  out.time = 0.0f;
  out.mask = 0xFFFFFFFFu;
  out.id = 0;
  out.flags = 0;
  return true;
}

}  // namespace

void EmbreeAccelerator::State::build_exact() {
  bounded.clear();
  unbounded.clear();
  scene_bounds = Bounds3{};
  for (const uint32_t index : reportable_primitives(primitives)) {
    const Bounds3 b = primitives[index].shape->bounds();
    if (b.empty() || !b.is_finite()) {
      unbounded.push_back(index);
      continue;
    }
    bounded.push_back(index);
    scene_bounds.extend(b);
  }
  if (bounded.empty()) return;
  // The float ray differs from the double one by about 2^-24 (|origin| + t) per coordinate,
  // where the origin lies in the bounds and t is at most their diagonal; Embree's own float
  // arithmetic adds a few ulps of the same size. 2^-16 leaves a factor of 256.
  const Vec3 magnitude = max(abs(scene_bounds.lower), abs(scene_bounds.upper));
  margin =
      std::ldexp(std::max({magnitude.x, magnitude.y, magnitude.z}) + length(scene_bounds.diagonal()), -16);
  if (!(margin > 0)) margin = std::numeric_limits<double>::min();
  scene_bounds.lower = scene_bounds.lower - Vec3{margin, margin, margin};
  scene_bounds.upper = scene_bounds.upper + Vec3{margin, margin, margin};

  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(geometry, static_cast<unsigned>(bounded.size()));
  rtcSetGeometryUserData(geometry, this);
  rtcSetGeometryBoundsFunction(geometry, exact_bounds, nullptr);
  rtcSetGeometryIntersectFunction(geometry, exact_intersect);
  rtcSetGeometryOccludedFunction(geometry, exact_occluded);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene, geometry);
  rtcReleaseGeometry(geometry);
}

void EmbreeAccelerator::State::build_native() {
  triangle_to_primitive.clear();
  const TriangleMesh* mesh = nullptr;
  std::vector<uint8_t> reportable(primitives.size(), 0);
  for (const uint32_t index : reportable_primitives(primitives)) reportable[index] = 1;
  for (uint32_t index = 0; index < primitives.size(); ++index) {
    const auto* triangle = dynamic_cast<const MeshTriangle*>(primitives[index].shape);
    if (!triangle) throw std::invalid_argument("Embree native_triangles mode needs mesh triangles only");
    if (!mesh) {
      mesh = &triangle->mesh();
      triangle_to_primitive.assign(mesh->triangles.size(), kNone);
    } else if (&triangle->mesh() != mesh) {
      throw std::invalid_argument("Embree native_triangles mode needs the triangles of one mesh");
    }
    if (!reportable[index]) continue;  // left out like the others (reportable_primitives)
    uint32_t& slot = triangle_to_primitive[triangle->triangle_index()];
    if (slot == kNone) slot = index;  // a triangle listed twice: the lower index wins ties
  }
  if (!mesh || mesh->triangles.empty() || mesh->positions.empty()) return;

  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh->positions.size()));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh->triangles.size()));
  if (!vertices || !indices) {
    rtcReleaseGeometry(geometry);
    check("rtcSetNewGeometryBuffer");
    throw std::runtime_error("Embree: cannot allocate the mesh buffers");
  }
  for (std::size_t v = 0; v < mesh->positions.size(); ++v) {
    vertices[3 * v + 0] = static_cast<float>(mesh->positions[v].x);
    vertices[3 * v + 1] = static_cast<float>(mesh->positions[v].y);
    vertices[3 * v + 2] = static_cast<float>(mesh->positions[v].z);
  }
  for (std::size_t t = 0; t < mesh->triangles.size(); ++t) {
    const bool used = triangle_to_primitive[t] != kNone;
    for (int corner = 0; corner < 3; ++corner)
      indices[3 * t + corner] = used ? mesh->triangles[t][corner] : mesh->triangles[t][0];
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene, geometry);
  rtcReleaseGeometry(geometry);
}

EmbreeAccelerator::EmbreeAccelerator(Mode mode) : state_(std::make_unique<State>()) {
  state_->mode = mode;
  state_->device = rtcNewDevice(nullptr);
  if (!state_->device)
    throw std::runtime_error("Embree: cannot create a device: " + error_name(rtcGetDeviceError(nullptr)));
  rtcSetDeviceErrorFunction(state_->device, record_error, state_.get());
  rtcSetDeviceMemoryMonitorFunction(state_->device, monitor_memory, state_.get());
}

EmbreeAccelerator::~EmbreeAccelerator() = default;

EmbreeAccelerator::Mode EmbreeAccelerator::mode() const {
  return state_->mode;
}

void EmbreeAccelerator::build(std::span<const Primitive> primitives) {
  State& state = *state_;
  if (state.scene) {
    rtcReleaseScene(state.scene);
    state.scene = nullptr;
  }
  state.primitives = primitives;
  state.scene = rtcNewScene(state.device);
  if (state.mode == Mode::exact) {
    rtcSetSceneFlags(state.scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(state.scene, RTC_BUILD_QUALITY_MEDIUM);
    state.build_exact();
  } else {
    rtcSetSceneFlags(state.scene, RTC_SCENE_FLAG_NONE);
    rtcSetSceneBuildQuality(state.scene, RTC_BUILD_QUALITY_HIGH);
    state.build_native();
  }
  rtcCommitScene(state.scene);
  state.check("rtcCommitScene");
}

bool EmbreeAccelerator::intersect(const Ray& ray, Intersection& intersection) const {
  const State& state = *state_;
  if (state.mode == Mode::native_triangles) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rayhit;
    rayhit.ray.org_x = static_cast<float>(ray.origin.x);
    rayhit.ray.org_y = static_cast<float>(ray.origin.y);
    rayhit.ray.org_z = static_cast<float>(ray.origin.z);
    rayhit.ray.dir_x = static_cast<float>(ray.direction.x);
    rayhit.ray.dir_y = static_cast<float>(ray.direction.y);
    rayhit.ray.dir_z = static_cast<float>(ray.direction.z);
    rayhit.ray.tnear = static_cast<float>(ray.t_min);
    rayhit.ray.tfar = static_cast<float>(ray.t_max);
    rayhit.ray.time = 0.0f;
    rayhit.ray.mask = 0xFFFFFFFFu;
    rayhit.ray.id = 0;
    rayhit.ray.flags = 0;
    rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(state.scene, &context, &rayhit);
    if (rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    intersection.primitive = state.triangle_to_primitive[rayhit.hit.primID];
    SurfaceHit& surface = intersection.surface;
    surface = SurfaceHit{};
    surface.t = rayhit.ray.tfar;
    surface.position = ray.at(surface.t);
    surface.object_position = surface.position;
    surface.geometric_normal = normalize(Vec3{rayhit.hit.Ng_x, rayhit.hit.Ng_y, rayhit.hit.Ng_z});
    surface.shading_normal = surface.geometric_normal;
    return true;
  }

  ExactContext context;
  rtcInitIntersectContext(&context.context);
  context.state = &state;
  context.ray = &ray;
  RTCRayHit rayhit;
  if (start_exact(state, ray, context, rayhit.ray)) {
    rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(state.scene, &context.context, &rayhit);
  }
  for (const uint32_t primitive : state.unbounded) context.consider(primitive);
  if (!context.found) return false;
  intersection.surface = context.hit;
  intersection.primitive = context.best_primitive;
  return true;
}

bool EmbreeAccelerator::occluded(const Ray& ray) const {
  const State& state = *state_;
  if (state.mode == Mode::native_triangles) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay shadow;
    shadow.org_x = static_cast<float>(ray.origin.x);
    shadow.org_y = static_cast<float>(ray.origin.y);
    shadow.org_z = static_cast<float>(ray.origin.z);
    shadow.dir_x = static_cast<float>(ray.direction.x);
    shadow.dir_y = static_cast<float>(ray.direction.y);
    shadow.dir_z = static_cast<float>(ray.direction.z);
    shadow.tnear = static_cast<float>(ray.t_min);
    shadow.tfar = static_cast<float>(ray.t_max);
    shadow.time = 0.0f;
    shadow.mask = 0xFFFFFFFFu;
    shadow.id = 0;
    shadow.flags = 0;
    rtcOccluded1(state.scene, &context, &shadow);
    return shadow.tfar < 0.0f;  // Embree sets -inf on a hit
  }

  ExactContext context;
  rtcInitIntersectContext(&context.context);
  context.state = &state;
  context.ray = &ray;
  RTCRay shadow;
  if (start_exact(state, ray, context, shadow)) {
    rtcOccluded1(state.scene, &context.context, &shadow);
    if (context.occluded) return true;
  }
  for (const uint32_t primitive : state.unbounded)
    if (state.primitives[primitive].shape->occluded(ray)) return true;
  return false;
}

AcceleratorReport EmbreeAccelerator::report() const {
  const State& state = *state_;
  AcceleratorReport report;
  if (state.mode == Mode::exact) {
    report.figures = {{"primitives", static_cast<double>(state.bounded.size())},
                      {"unbounded", static_cast<double>(state.unbounded.size())},
                      {"build quality (1 medium, 2 high)", 1.0}};
  } else {
    report.figures = {{"triangles", static_cast<double>(state.triangle_to_primitive.size())},
                      {"build quality (1 medium, 2 high)", 2.0}};
  }
  const int64_t device = std::max<int64_t>(0, state.device_bytes.load());
  report.bytes = static_cast<uint64_t>(device) + (state.bounded.capacity() + state.unbounded.capacity() +
                                                  state.triangle_to_primitive.capacity()) *
                                                     sizeof(uint32_t);
  return report;
}

}  // namespace candela
