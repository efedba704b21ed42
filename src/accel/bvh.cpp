#include "accel/bvh.h"

#include <fmt/format.h>
#include <immintrin.h>  // SSE2 everywhere; AVX2 and AVX-512 only in their target regions
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <new>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "accel/bvh_builder.h"
#include "geometry/triangle_mesh.h"
#include "math/lanes.h"
#include "math/next_up.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace candela {

namespace {

constexpr int kLeafHardCap = 16;  // the SAH may keep up to this many in a leaf
// The default bvh.max_leaf_primitives (a node with more is split) for a tree of triangles only
// and for one with other shapes, and the SAH's cost of one packet's float pre-test against a
// traversal step of 1 (measured on dragon_100k and Igea, docs/benchmarks.md).
constexpr int kTriangleLeaf = 8, kShapeLeaf = 4;
constexpr double kPacketCost = 0.6;
// Past this many primitives with one centroid the build warns (16 overlapping leaves of 16).
constexpr uint32_t kCoincidentWarning = 256;
constexpr std::size_t kStackSize =
    (Bvh::kWidth - 1) * 128 + Bvh::kWidth;  // depth below 128, at most 7 left per level
constexpr std::size_t kGrain = 4096;

// [t_min, t_max] is widened by this relative amount plus this much of the scene's scale, far
// more than any shape's rounding of its hit distance near a box face.
constexpr double kSlack = 0x1p-32;

// The smallest float >= v (v rounded to float, then moved one step towards +inf when that
// rounding went below it), without a branch: the traversal rounds a dozen values per ray, and
// with branches on their signs (unpredictable for incoherent rays) that set-up cost more than
// the rest of an occlusion ray's traversal. +inf for v > FLT_MAX, -inf only for v = -inf; never
// -0 (that +0 is the same bound).
inline float round_up(double v) {
  const float f = static_cast<float>(v) + 0.0f;  // -0 becomes +0
  const auto below = static_cast<uint32_t>(static_cast<double>(f) < v);
  uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  // One step up: +1 on the bit pattern of a positive float (+0 to the smallest denormal, FLT_MAX
  // to +inf), -1 on a negative one's (-inf to -FLT_MAX): 1 | (the sign bit spread) is +1 or -1.
  const uint32_t step = 1u | static_cast<uint32_t>(static_cast<int32_t>(bits) >> 31);
  bits += step & (0u - below);
  float result;
  std::memcpy(&result, &bits, sizeof result);
  return result;
}

// The largest float <= v.
inline float round_down(double v) {
  return -round_up(-v);
}

double max_abs(const Vec3& v) {
  return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
}

// What build() does with each primitive.
enum class Kind : uint8_t { unbounded, shape, triangle, never_hit };

// The per-ray constants of the float slab test (FloatSlabs: eight or four lanes at a time).
//
// Why it never culls a box that the ray's segment [t_lo, t_hi] (the double interval the
// triangle tests need, widened by kSlack as before) meets: let t* in [t_lo, t_hi] be a point of
// the segment inside the box (exactly), so that near_a <= t* <= far_a on every axis, with
// near_a = (entry plane - o) / d and far_a = (exit plane - o) / d. Take d > 0 (d < 0 is its
// mirror image: every step below is symmetric under negation, as rounding to nearest is).
// - The origin in float, moved towards the direction for entry planes and away from it for exit
//   planes: o_near = fl(fl(o) + w), o_far = fl(fl(o) - w), w = fl(|fl(o)| 2^-22 + 2^-126). fl(o)
//   is within half an ulp of o (2^-24 |o|, or 2^-150 below the normal range), and the step w
//   exceeds that half ulp plus the rounding of the sum, so o_near >= o >= o_far: entry plane
//   distances come out smaller and exit ones larger.
// - The reciprocal: fl(1 / fl(|d|)) scaled by 1 -+ 2^-21 and rounded, three roundings of at
//   most 2^-24 each (|d| >= 1e-30: no denormals): an entry reciprocal lies in [1 - 2^-20,
//   1 - 2^-22] / |d|, an exit one in [1 + 2^-22, 1 + 2^-20] / |d|.
// - With the two roundings of (plane - o_dir) * reciprocal, a computed entry e satisfies e <= x
//   when x >= 0 and e <= x (1 - 2^-19) when x < 0, x = near_a; likewise a computed exit f >= far_a
//   when far_a >= 0 and f >= far_a (1 + 2^-19) when far_a < 0. So e <= t* when t* >= 0, and
//   e <= t* + |t*| 2^-19 when t* < 0; f >= t* when t* >= 0, and f >= t* - |t*| 2^-19 when t* < 0.
// - Hence max(t0, entries) <= min(t1, exits) + margin, with t0 <= t_lo and t1 >= t_hi (rounded
//   outward as the origin is) and margin >= 2^-17 max(0, -t_lo) plus a floor for underflow (an
//   absolute error of at most 2^-149 per product).
// - Overflow: the float path is taken only when |origin| and the scene's scale are at most
//   1e30 and every direction component is 0 or in [1e-30, 1e30] with the largest >= 1e-6, so
//   that t* <= 2e36: a product overflowing to +inf (an entry) or -inf (an exit) then only culls
//   boxes that the segment cannot meet, and the other overflows are conservative.
// - d = ±0 gives a reciprocal of ±inf: (plane - origin) · inf is ±inf with the exact sign, or
//   NaN, which _mm_max_ps / _mm_min_ps (second operand on NaN) ignore.
// Other rays (never made by the renderer) test every primitive (intersect_all_slots).
struct SlabSetup {
  // The proof's w for a float of magnitude |x|, lane by lane or for one float: the step that
  // moves fl(v) past the double v it was rounded from, in either direction.
  template <class T>
  [[gnu::always_inline]] static T outward_step(const T& magnitude) {
    return magnitude * 0x1p-22f + 0x1p-126f;
  }

  // Lanes x, y, z (the origins' fourth lane moves t_hi, read as t1; the reciprocals' is unused).
  Float4 origin_near, origin_far;
  Float4 inverse_near, inverse_far;
  std::size_t near_offset[3], far_offset[3];  // byte offsets of the rows in a Node
  float t0 = 0, margin = 0;
  float t1 = 0;  // the box tests' far end: t_hi rounded up

  // False when the ray is outside the proven range (see above). In float, three axes at once
  // and without a branch but for that one answer: with s the sign of d (+1 or -1, exact to
  // multiply by), the origin moved towards the direction is fl(o) + s w and away from it
  // fl(o) - s w, so no choice depends on the direction's signs, which incoherent rays make
  // unpredictable. The origin's spare fourth lane rounds t_hi up in the same operations.
  [[gnu::always_inline]] bool init(const Ray& ray, double t_lo, double t_hi) {
    const Double4 o = {ray.origin.x, ray.origin.y, ray.origin.z, t_hi};
    const Double4 d = {ray.direction.x, ray.direction.y, ray.direction.z, 1.0};  // lane 3 passes every check
    const auto d_bits = (Int64x4)d, o_bits = (Int64x4)o;
    const auto ad = (Double4)(d_bits & std::numeric_limits<int64_t>::max());
    const auto ao = (Double4)(o_bits & std::numeric_limits<int64_t>::max());
    const Int64x4 valid = (ao <= 1e30) & ((d == 0) | ((ad >= 1e-30) & (ad <= 1e30)));
    const double largest = std::max({ad[0], ad[1], ad[2]});
    if (!(valid[0] & valid[1] & valid[2]) || !(largest >= 1e-6) || !(t_lo >= -1e30)) return false;

    const Float4 origin = __builtin_convertvector(o, Float4);  // lane 3: t_hi
    const auto direction_bits = (Int32x4) __builtin_convertvector(d, Float4);
    const Int32x4 sign = direction_bits & std::numeric_limits<int32_t>::min();
    const auto s = (Float4)(sign | (Int32x4)Float4{1.0f, 1.0f, 1.0f, 1.0f});  // lane 3: +1
    // 1 / ±0 is +inf here, and s gives it the sign the proof wants.
    const Float4 inverse = 1.0f / (Float4)(direction_bits ^ sign);
    inverse_near = s * (inverse * (1.0f - 0x1p-21f));
    inverse_far = s * (inverse * (1.0f + 0x1p-21f));
    const auto magnitude = (Float4)((Int32x4)origin & std::numeric_limits<int32_t>::max());
    const Float4 step = s * outward_step(magnitude);
    origin_near = origin + step;
    origin_far = origin - step;
    t1 = origin_near[3];  // t_hi + its step: rounded up (+inf stays +inf)
    const auto low = static_cast<float>(t_lo);
    t0 = low - outward_step(std::fabs(low));
    margin = std::max(0.0f, -low) * 0x1p-16f + 2e-35f;
    // The rows: lower x, y, z, then upper x, y, z; a negative direction (or -0) enters through
    // the upper one. In the vector lanes, then moved out: the scalar choice per axis was ~30
    // instructions a ray.
    constexpr int kRow = sizeof(float[Bvh::kWidth]), kUpperRows = 3 * kRow;
    constexpr int kBounds = offsetof(Bvh::Node, bounds);
    const Int32x4 lower = {kBounds, kBounds + kRow, kBounds + 2 * kRow, 0};
    const Int32x4 upper_first = (sign >> 31) & kUpperRows;  // kUpperRows where negative, else 0
    const Int32x4 near = lower + upper_first, far = lower + (kUpperRows - upper_first);
    for (int axis = 0; axis < 3; ++axis) {
      near_offset[axis] = static_cast<std::size_t>(near[axis]);
      far_offset[axis] = static_cast<std::size_t>(far[axis]);
    }
    return true;
  }
};

// The box test of one node in vector registers: SlabSetup's constants against all eight
// children at once (AVX2, AVX-512) or four at a time (SSE). Defined per instruction set in
// accel/bvh_traversal.inc.
template <int Isa>
struct FloatSlabs;
// bvh-fast's box test (no outward rounding; accel/bvh_traversal.inc).
template <int Isa>
struct FastSlabs;

// The conservative float pre-test of the watertight triangle test (WatertightRay): the same
// sheared edge functions u, v, w in float, a lane rejected only when they certainly have mixed
// signs, which the exact test rejects too.
// Error bound: with S = scene scale + max |origin| (every vertex and the origin lie within S
// of 0) and |sx|, |sy| <= 1 (kz is the dominant axis), each float sheared coordinate differs
// from the real one by at most 8 · 2^-24 S (roundings of the vertex, the origin, the
// difference, sx, the product and the subtraction) <= delta = 2^-20 S (a factor 2 spare).
// With M the largest |float sheared coordinate| of the triangle, a float edge function differs
// from the real one by at most 4 delta M + 2 delta^2 + 2^-22 M^2 (and the double one by far
// less), so E = 8 delta M + 2^-20 M^2 + 4 delta^2 + 1e-30 covers both with room for the
// roundings of E itself. A lane whose values are NaN (a shape, or overflow) is never rejected.
// The distance, for the lanes the edges keep (few): the exact test's t = sz (u az + v bz + w cz)
// / det with sz = 1 / d[kz], az = p0[kz] − o[kz] (and bz, cz), det = u + v + w, so t − t_min =
// sz G / det with G = u a0 + v a1 + w a2 and a_i = p_i[kz] − (o + t_min d)[kz], each vertex's
// offset along kz from the ray's point at t_min. The float a_i = (p_i[kz] − fl(o[kz])) −
// fl(t_min d[kz]) is off by at most alpha = 2^-20 (S + |t_min d[kz]| + A), A the largest |float
// a_i| (six roundings — vertex, origin, difference, t_min d[kz] in double and in float, the last
// difference — of values below S, |t_min d[kz]| or A, 2^-24 each: a spare of 8 or more; the
// 1e-30 in alpha covers their absolute errors below float's normal range);
// with |u − float u| <= E (and the same for v, w), the float G is off by at most alpha Σ|u| +
// 3 E (A + alpha) + 2^-22 A Σ|u| (its own roundings, in the normal range) <= B = 2 alpha Σ|u| +
// 6 E (A + alpha) + 2^-126, the last term for G's products and sums below the normal range
// (2^-150 each: B itself could round to 0 there while G is −2^-149; a review's one-triangle
// scene at 2^-45 showed it), and the double test's own roundings (2^-50 of the same terms) are
// inside the spare. A G that overflowed (±inf, or NaN) is never used: B need not (a review's
// scene at 2^47 had u a0 = −inf under a finite B). det's sign is known only when one weight is
// beyond E (the exact ones then share its sign, or the exact test rejects): such a lane with
// sign(d[kz]) sign(det) G < −B has t < t_min for the exact test too, and is rejected. Shadow
// rays leave their own triangle at t ~ 0, and a ray's t_min (1e-4 of the scene for the
// benchmark's shadow set) rejects it here instead of in the exact test.
struct FloatShear {
  __m128 origin[3];
  __m128 sx, sy;
  __m128 c1, c2, c3;      // E = M (c1 + c2 M) + c3
  __m128 near_offset;     // fl(t_min d[kz])
  __m128 near_alpha;      // 2^-20 (S + |t_min d[kz]|) + 1e-30 (for denormal roundings), rounded up
  __m128 direction_sign;  // d[kz]'s sign bit
  int kx, ky, kz;
  bool test_t_min;  // whether candidates<true> tests t_min

  // direction: the ray's, for candidates<true> (null when it is not called).
  FloatShear(const WatertightRay& ray, double scene_scale, const Vec3* direction)
      : kx(ray.kx), ky(ray.ky), kz(ray.kz) {
    for (int axis = 0; axis < 3; ++axis) origin[axis] = _mm_set1_ps(static_cast<float>(ray.origin[axis]));
    sx = _mm_set1_ps(static_cast<float>(ray.sx));
    sy = _mm_set1_ps(static_cast<float>(ray.sy));
    const double scale = scene_scale + max_abs(ray.origin);
    if (scale <= 1e15) {
      const double delta = 0x1p-20 * scale;
      c1 = _mm_set1_ps(round_up(8 * delta));
      c2 = _mm_set1_ps(0x1p-20f);
      c3 = _mm_set1_ps(round_up(4 * delta * delta + 1e-30));
    } else {  // never reject
      c1 = c2 = _mm_setzero_ps();
      c3 = _mm_set1_ps(std::numeric_limits<float>::infinity());
    }
    // The t_min test only where it can reject something near the origin: B >= 2^-19 S |det|
    // (alpha >= 2^-20 S) while |G| = |t − t_min| |d[kz]| |det|, so a rejection needs |t − t_min|
    // |d[kz]| > 2^-19 S, and with |t_min d[kz]| below 2^-18 S (t_min 0, or a tiny offset) the
    // triangles a ray starts on are seldom rejected: the test is skipped (incoherent occlusion
    // with it: 1 % slower, nothing saved).
    const double offset = direction ? ray.t_min * (*direction)[kz] : 0.0;
    test_t_min = std::fabs(offset) > 0x1p-18 * scale && std::fabs(offset) <= 1e30 && scale <= 1e15;
    if (test_t_min) {
      near_offset = _mm_set1_ps(static_cast<float>(offset));
      near_alpha = _mm_set1_ps(round_up(0x1p-20 * (scale + std::fabs(offset)) + 1e-30));
      direction_sign = _mm_and_ps(_mm_set1_ps(static_cast<float>((*direction)[kz])), _mm_set1_ps(-0.0f));
    }
  }

  // Lanes that may hit (bit per lane); with AfterTMin, only those whose distance may be past
  // t_min (see above). That test runs inline, for the packets the edges keep a lane of (few):
  // out of line, recomputing the edges cost as much as the exact tests it saves; inline for every
  // traversal, its registers slowed the nearest hit's edge tests (+4 % instructions), where it
  // saves nothing (its exact tests are nearly all hits).
  template <bool AfterTMin>
  int candidates(const Bvh::Packet& packet) const {
    const __m128 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
    const __m128 sign_mask = _mm_set1_ps(-0.0f);
    __m128 x[3], y[3], z[3];
    __m128 largest = _mm_setzero_ps();
    for (int v = 0; v < 3; ++v) {
      z[v] = _mm_sub_ps(_mm_load_ps(packet.p[v][kz]), origin[kz]);
      x[v] = _mm_sub_ps(_mm_sub_ps(_mm_load_ps(packet.p[v][kx]), origin[kx]), _mm_mul_ps(sx, z[v]));
      y[v] = _mm_sub_ps(_mm_sub_ps(_mm_load_ps(packet.p[v][ky]), origin[ky]), _mm_mul_ps(sy, z[v]));
      largest = _mm_max_ps(largest, _mm_max_ps(_mm_and_ps(x[v], abs_mask), _mm_and_ps(y[v], abs_mask)));
    }
    const __m128 u = _mm_sub_ps(_mm_mul_ps(x[2], y[1]), _mm_mul_ps(y[2], x[1]));
    const __m128 v = _mm_sub_ps(_mm_mul_ps(x[0], y[2]), _mm_mul_ps(y[0], x[2]));
    const __m128 w = _mm_sub_ps(_mm_mul_ps(x[1], y[0]), _mm_mul_ps(y[1], x[0]));
    const __m128 e = _mm_add_ps(_mm_mul_ps(largest, _mm_add_ps(c1, _mm_mul_ps(c2, largest))), c3);
    const __m128 minus_e = _mm_xor_ps(e, sign_mask);
    const __m128 negative =
        _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(u, minus_e), _mm_cmplt_ps(v, minus_e)), _mm_cmplt_ps(w, minus_e));
    const __m128 positive = _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(u, e), _mm_cmpgt_ps(v, e)), _mm_cmpgt_ps(w, e));
    const int kept = ~_mm_movemask_ps(_mm_and_ps(negative, positive)) & 0xf;
    if (!AfterTMin || !test_t_min || kept == 0) return kept;
    __m128 a[3];
    for (int i = 0; i < 3; ++i) a[i] = _mm_sub_ps(z[i], near_offset);
    const __m128 g = _mm_add_ps(_mm_add_ps(_mm_mul_ps(u, a[0]), _mm_mul_ps(v, a[1])), _mm_mul_ps(w, a[2]));
    const __m128 largest_a = _mm_max_ps(_mm_max_ps(_mm_and_ps(a[0], abs_mask), _mm_and_ps(a[1], abs_mask)),
                                        _mm_and_ps(a[2], abs_mask));
    const __m128 weights =
        _mm_add_ps(_mm_add_ps(_mm_and_ps(u, abs_mask), _mm_and_ps(v, abs_mask)), _mm_and_ps(w, abs_mask));
    const __m128 alpha = _mm_add_ps(near_alpha, _mm_mul_ps(_mm_set1_ps(0x1p-20f), largest_a));
    const __m128 bound =
        _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_add_ps(alpha, alpha), weights),
                              _mm_mul_ps(_mm_mul_ps(_mm_set1_ps(6.0f), e), _mm_add_ps(largest_a, alpha))),
                   _mm_set1_ps(0x1p-126f));
    // sign(d[kz]) sign(det) G: det is negative where a weight is below −E.
    const __m128 signed_g = _mm_xor_ps(g, _mm_xor_ps(direction_sign, _mm_and_ps(negative, sign_mask)));
    const __m128 finite =
        _mm_cmplt_ps(_mm_and_ps(g, abs_mask), _mm_set1_ps(std::numeric_limits<float>::infinity()));
    const __m128 before = _mm_and_ps(_mm_and_ps(_mm_or_ps(negative, positive), finite),
                                     _mm_cmplt_ps(signed_g, _mm_xor_ps(bound, sign_mask)));
    return kept & ~_mm_movemask_ps(before);
  }
};

// bvh-fast's triangle test (accel/bvh.h): Möller & Trumbore 1997 in float, four lanes at once,
// with the determinant's sign folded into the weights as Embree does, so that no division is
// made for a lane that misses. A lane hits when its weights b1, b2 >= 0, b1 + b2 <= 1 and t_min
// < t <= t_max; the hits' t, b1 and b2 are left in t, b1, b2 for the caller.
struct FloatMoller {
  __m128 origin[3], direction[3];
  // Rounded outward, in every lane: the caller tests a hit's t against the ray's own interval in
  // double.
  __m128 t_min, t_max;  // t_max: the nearest hit's t so far, or the ray's
  alignas(16) float t[4], b1[4], b2[4];

  FloatMoller(const Ray& ray, double t_max)
      : t_min(_mm_set1_ps(round_down(ray.t_min))), t_max(_mm_set1_ps(round_up(t_max))) {
    for (int axis = 0; axis < 3; ++axis) {
      origin[axis] = _mm_set1_ps(static_cast<float>(ray.origin[axis]));
      direction[axis] = _mm_set1_ps(static_cast<float>(ray.direction[axis]));
    }
  }

  // The lanes that hit (bit per lane), in the form of Embree's test: with e1 = p1 − p0,
  // e2 = p2 − p0, the packet's normal N = e1 × e2, C = p0 − o and R = D × C, the triple products
  // give det = −D · N, b1 det = e2 · R, b2 det = −e1 · R and t det = −C · N. The edges and N are
  // made at the build, so a packet costs one cross product (R) where P = D × e2, Q = (o − p0) × e1
  // and the edges took two cross products and six differences, for the same result up to
  // float's rounding (callgrind, 256 × 256 dragon sets: 4.8 % fewer instructions).
  int hits(const Bvh::Packet& packet, const Bvh::PacketNormals& normals) {
    __m128 e1[3], e2[3], c[3], normal[3];
    for (int axis = 0; axis < 3; ++axis) {
      e1[axis] = _mm_load_ps(packet.p[1][axis]);  // bvh-fast's packets: p0, e1, e2
      e2[axis] = _mm_load_ps(packet.p[2][axis]);
      c[axis] = _mm_sub_ps(_mm_load_ps(packet.p[0][axis]), origin[axis]);
      normal[axis] = _mm_load_ps(normals.n[axis]);
    }
    const auto dot = [](const __m128* a, const __m128* b) {
      return _mm_add_ps(_mm_add_ps(_mm_mul_ps(a[0], b[0]), _mm_mul_ps(a[1], b[1])), _mm_mul_ps(a[2], b[2]));
    };
    __m128 r[3];
    for (int axis = 0; axis < 3; ++axis) {
      const int next = (axis + 1) % 3, last = (axis + 2) % 3;
      r[axis] = _mm_sub_ps(_mm_mul_ps(direction[next], c[last]), _mm_mul_ps(direction[last], c[next]));
    }
    const __m128 minus_det = dot(direction, normal);
    const __m128 sign_bit = _mm_set1_ps(-0.0f);
    const __m128 sign = _mm_andnot_ps(minus_det, sign_bit);  // det's sign bit (−det's flipped)
    const __m128 minus_sign = _mm_and_ps(minus_det, sign_bit);
    const __m128 magnitude = _mm_andnot_ps(sign_bit, minus_det);
    const __m128 u = _mm_xor_ps(dot(e2, r), sign);                   // b1 |det|
    const __m128 v = _mm_xor_ps(dot(e1, r), minus_sign);             // b2 |det|
    const __m128 distance = _mm_xor_ps(dot(c, normal), minus_sign);  // t |det|
    const __m128 zero = _mm_setzero_ps();
    __m128 hit = _mm_and_ps(_mm_cmpge_ps(u, zero), _mm_cmpge_ps(v, zero));
    hit = _mm_and_ps(hit, _mm_cmple_ps(_mm_add_ps(u, v), magnitude));
    hit = _mm_and_ps(hit, _mm_cmpgt_ps(distance, _mm_mul_ps(t_min, magnitude)));
    hit = _mm_and_ps(hit, _mm_cmple_ps(distance, _mm_mul_ps(t_max, magnitude)));
    hit = _mm_and_ps(hit, _mm_cmpgt_ps(magnitude, zero));  // an edge-on triangle is missed
    // A lane whose determinant is NaN (a shape's, whose vertices are NaN, or an overflow) is kept,
    // as the exact pre-test keeps it: the leaf loop sends a shape to its own test, and a
    // triangle's NaN t fails the caller's interval test.
    hit = _mm_or_ps(hit, _mm_cmpunord_ps(magnitude, magnitude));
    const int mask = _mm_movemask_ps(hit);
    if (mask != 0) {
      const __m128 inverse = _mm_div_ps(_mm_set1_ps(1.0f), magnitude);
      _mm_store_ps(t, _mm_mul_ps(distance, inverse));
      _mm_store_ps(b1, _mm_mul_ps(u, inverse));
      _mm_store_ps(b2, _mm_mul_ps(v, inverse));
    }
    return mask;
  }
};

// The leaf loop shared by the nearest-hit and the any-hit traversal (LeafVisitor<Isa>::visit),
// defined per instruction set in accel/bvh_traversal.inc: a template defined out here would be
// compiled for the default target, and the traversal's lambdas (compiled for AVX2 / AVX-512)
// could not be inlined into it — every surviving lane cost a call.
template <int Isa>
struct LeafVisitor;

// The double interval [t_lo, t_hi] every box test must cover: [t_min, t] widened by a small
// relative and scene-scaled slack, far more than any shape's rounding of its hit distance near
// a box face.
struct Slack {
  double slack;
  Slack(const Ray& ray, double scene_scale) : slack(kSlack * (max_abs(ray.origin) + scene_scale)) {}
  double down(double t) const { return t - (std::fabs(t) * kSlack + slack); }
  double up(double t) const { return t + (std::fabs(t) * kSlack + slack); }
};

// A value made on first use, without the zero fill std::optional's storage gets here (the
// large per-ray objects below are made for few rays, and filling them costs more than a node).
template <class T>
struct Lazy {
  static_assert(std::is_trivially_destructible_v<T>);
  union {
    T value;
  };
  bool ready = false;
  Lazy() {}
  template <class... Args>
  T& emplace(Args&&... args) {
    new (&value) T(std::forward<Args>(args)...);
    ready = true;
    return value;
  }
  explicit operator bool() const { return ready; }
  T* operator->() { return &value; }
  const T* operator->() const { return &value; }
  T& operator*() { return value; }
};

// A child still to visit.
struct Pending {
  float t_enter;
  uint32_t child;  // node index or first slot
  uint32_t count;  // 0 for a node
};

}  // namespace

void* bvh_allocate(std::size_t bytes) {
  constexpr std::size_t kLarge = std::size_t{1} << 20, kHuge = std::size_t{2} << 20;
  const std::size_t alignment = bytes >= kLarge ? kHuge : 128;  // Node is 128-byte aligned
  const std::size_t size = (std::max<std::size_t>(bytes, 1) + alignment - 1) / alignment * alignment;
  void* memory = std::aligned_alloc(alignment, size);
  if (!memory) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (alignment == kHuge) madvise(memory, size, MADV_HUGEPAGE);  // a hint; failure is harmless
#endif
  return memory;
}

void bvh_free(void* memory) noexcept {
  std::free(memory);
}

BvhIsa widest_bvh_isa() {
  __builtin_cpu_init();  // may be called from a static constructor, before libgcc's own has run
  // libgcc's checks include the operating system's support for the wider registers (XGETBV).
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
      __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw") &&
      __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi2"))
    return BvhIsa::avx512;
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi2"))
    return BvhIsa::avx2;
  return BvhIsa::sse;
}

Bvh::Bvh(const BvhSettings& settings)
    : max_leaf_primitives_(settings.max_leaf_primitives),
      bins_(settings.bins),
      isa_(settings.isa == BvhIsa::automatic ? widest_bvh_isa() : settings.isa),
      exact_(settings.exact) {
  if (static_cast<int>(isa_) > static_cast<int>(widest_bvh_isa()))
    throw std::invalid_argument(std::string("bvh.isa: this CPU does not support ") +
                                std::string(kBvhIsaNames.name(isa_)) + " (the widest it supports is " +
                                std::string(kBvhIsaNames.name(widest_bvh_isa())) + ")");
  if (max_leaf_primitives_ < 0 || max_leaf_primitives_ > 1024)
    throw std::invalid_argument("bvh.max_leaf_primitives must be in [0, 1024] (0: automatic), got " +
                                std::to_string(max_leaf_primitives_));
  if (bins_ < 2 || bins_ > 256)
    throw std::invalid_argument("bvh.bins must be in [2, 256], got " + std::to_string(bins_));
}

void Bvh::build(std::span<const Primitive> primitives) {
  primitives_ = primitives;
  nodes_.clear();
  packets_.clear();
  corners_.clear();
  normals_.clear();
  slot_count_ = triangle_count_ = 0;
  unbounded_.clear();
  only_mesh_ = nullptr;
  scene_scale_ = 0;
  tree_nodes_ = leaves_ = depth_ = largest_coincident_group_ = 0;
  sah_cost_ = 0;
  const std::size_t count = primitives.size();
  if (count >= kShapeSlot) throw std::invalid_argument("BVH: too many primitives (at most 2^31 - 1)");

  BvhArray<Bounds3> bounds(count);  // written for the reportable primitives only, read for them only
  std::vector<Kind> kinds(count, Kind::never_hit);
  // Only the reportable primitives go in (degenerate triangles and repeated ones stay never_hit).
  const std::vector<uint32_t> reportable = reportable_primitives(primitives);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, reportable.size(), kGrain),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t r = range.begin(); r < range.end(); ++r) {
                        const uint32_t i = reportable[r];
                        const Shape* shape = primitives[i].shape;
                        bounds[i] = shape->bounds();
                        if (!bounds[i].is_finite() || bounds[i].empty()) {
                          kinds[i] = Kind::unbounded;
                        } else if (dynamic_cast<const MeshTriangle*>(shape)) {
                          kinds[i] = Kind::triangle;
                        } else {
                          kinds[i] = Kind::shape;
                        }
                      }
                    });

  std::vector<uint32_t> tree_primitive;
  tree_primitive.reserve(reportable.size());
  BvhArray<Bounds3> tree_bounds(reportable.size());
  for (std::size_t i = 0; i < count; ++i) {
    const auto index = static_cast<uint32_t>(i);
    switch (kinds[i]) {
      case Kind::unbounded:
        unbounded_.push_back(index);
        break;
      case Kind::shape:
      case Kind::triangle:
        tree_bounds[tree_primitive.size()] = bounds[i];
        tree_primitive.push_back(index);
        break;
      case Kind::never_hit:
        break;
    }
  }
  bounds = {};
  tree_bounds.shrink(tree_primitive.size());
  if (tree_primitive.empty()) return;
  // What the tree holds: its triangles, their meshes, whether every vertex is a float (then the
  // packets alone hold them exactly, and no double copies are kept).
  bool only_triangles = true, float_exact = true, first_mesh = true;
  for (uint32_t index : tree_primitive) {
    if (kinds[index] != Kind::triangle) {
      only_triangles = false;
      continue;
    }
    ++triangle_count_;
    const auto* shape = static_cast<const MeshTriangle*>(primitives[index].shape);
    const TriangleMesh* mesh = &shape->mesh();
    if (first_mesh)
      only_mesh_ = mesh;
    else if (mesh != only_mesh_)
      only_mesh_ = nullptr;
    first_mesh = false;
    for (const uint32_t corner : mesh->triangles[shape->triangle_index()])
      for (int axis = 0; axis < 3; ++axis) {
        const double value = mesh->positions[corner][axis];
        float_exact = float_exact && static_cast<double>(static_cast<float>(value)) == value;
      }
  }

  // A tree of triangles only is costed per packet of four (one float pre-test tests them all)
  // with a lower cost per packet, which makes leaves of 4-8 triangles and a tree two levels
  // shallower: each level is a dependent cache miss, and on Igea that was worth 15-20 % of the
  // incoherent rays' time. Shapes are tested one by one through their Shape.
  BvhBuildSettings settings;
  settings.max_leaf_primitives =
      max_leaf_primitives_ > 0 ? max_leaf_primitives_ : (only_triangles ? kTriangleLeaf : kShapeLeaf);
  settings.max_leaf_hard = std::max(kLeafHardCap, settings.max_leaf_primitives);
  settings.bins = bins_;
  if (only_triangles) {
    settings.block_size = 4;
    settings.intersection_cost = kPacketCost;
  }
  const BvhBuildResult tree =
      build_bvh(std::span<const Bounds3>(tree_bounds.data(), tree_bounds.size()), settings);
  tree_bounds = {};
  tree_nodes_ = static_cast<uint32_t>(tree.nodes.size());
  leaves_ = tree.leaves;
  depth_ = tree.depth;
  sah_cost_ = tree.sah_cost;
  largest_coincident_group_ = tree.largest_coincident_group;
  scene_scale_ = std::max(max_abs(tree.nodes[0].bounds.lower), max_abs(tree.nodes[0].bounds.upper));

  // Packets: each leaf's primitives in groups of four, in leaf order.
  slot_count_ = tree.order.size();
  std::vector<uint32_t> packet_of(slot_count_);  // first packet of the leaf starting at a slot
  struct PacketSlots {
    uint32_t first, end;  // its slots
  };
  std::vector<PacketSlots> packet_slots;
  for (const BvhBuildNode& built : tree.nodes) {
    if (built.count == 0) continue;
    packet_of[built.index] = static_cast<uint32_t>(packet_slots.size());
    const uint32_t end = built.index + built.count;
    for (uint32_t first = built.index; first < end; first += 4)
      packet_slots.push_back({first, std::min(first + 4, end)});
  }
  packets_.resize(packet_slots.size());
  if (!float_exact) corners_.resize(4 * packets_.size());
  if (!exact_) normals_.resize(packets_.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, packets_.size(), kGrain / 4),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k < range.end(); ++k) {
                        Packet& packet = packets_[k];
                        const auto [first, end] = packet_slots[k];
                        for (int lane = 0; lane < 4; ++lane) {
                          const uint32_t s = first + static_cast<uint32_t>(lane);
                          Vec3 corner[3];
                          packet.primitive[lane] = kShapeSlot;
                          packet.triangle[lane] = 0;
                          bool triangle = false;
                          if (s < end) {
                            const uint32_t index = tree_primitive[tree.order[s]];
                            triangle = kinds[index] == Kind::triangle;
                            packet.primitive[lane] = triangle ? index : index | kShapeSlot;
                            if (triangle) {
                              const auto* shape = static_cast<const MeshTriangle*>(primitives[index].shape);
                              const TriangleMesh& mesh = shape->mesh();
                              const auto& corners = mesh.triangles[shape->triangle_index()];
                              packet.triangle[lane] = static_cast<uint32_t>(shape->triangle_index());
                              for (int v = 0; v < 3; ++v) corner[v] = mesh.positions[corners[v]];
                            }
                          }
                          for (int v = 0; v < 3; ++v)
                            for (int axis = 0; axis < 3; ++axis)
                              packet.p[v][axis][lane] = triangle ? static_cast<float>(corner[v][axis])
                                                                 : std::numeric_limits<float>::quiet_NaN();
                          if (!corners_.empty()) {
                            Corners& kept = corners_[4 * k + static_cast<std::size_t>(lane)];
                            for (int v = 0; v < 3; ++v) kept.p[v] = triangle ? corner[v] : Vec3{};
                          }
                          if (!normals_.empty()) {  // a shape's lane: NaN, from its NaN vertices
                            float e1[3], e2[3];
                            for (int axis = 0; axis < 3; ++axis) {
                              e1[axis] = packet.p[1][axis][lane] - packet.p[0][axis][lane];
                              e2[axis] = packet.p[2][axis][lane] - packet.p[0][axis][lane];
                            }
                            for (int axis = 0; axis < 3; ++axis) {
                              const int next = (axis + 1) % 3, last = (axis + 2) % 3;
                              normals_[k].n[axis][lane] = e1[next] * e2[last] - e1[last] * e2[next];
                              packet.p[1][axis][lane] = e1[axis];  // bvh-fast's packets hold the edges
                              packet.p[2][axis][lane] = e2[axis];
                            }
                          }
                        }
                      }
                    });

  // Collapse the binary tree into eight-wide nodes, depth first: a node's children start as
  // the two children of a binary inner node, and the inner child of largest surface area is
  // replaced by its own two children until there are eight (or only leaves). A lone leaf gets
  // a node of its own.
  const auto half_area = [&](std::size_t built) {
    const Vec3 d = tree.nodes[built].bounds.diagonal();
    return d.x * d.y + d.y * d.z + d.z * d.x;
  };
  const auto empty_node = [] {
    Node node{};
    for (int lane = 0; lane < kWidth; ++lane) {
      for (int axis = 0; axis < 3; ++axis) {
        node.bounds[axis][lane] = std::numeric_limits<float>::infinity();
        node.bounds[axis + 3][lane] = -std::numeric_limits<float>::infinity();
      }
    }
    return node;
  };
  const auto set_lane = [&](Node& node, int lane, std::size_t built, uint32_t inner_index) {
    const BvhBuildNode& child = tree.nodes[built];
    for (int axis = 0; axis < 3; ++axis) {
      node.bounds[axis][lane] = round_down(child.bounds.lower[axis]);
      node.bounds[axis + 3][lane] = round_up(child.bounds.upper[axis]);
    }
    node.child[lane] = child.count > 0 ? packet_of[child.index] : inner_index;
    node.count[lane] = static_cast<uint16_t>(child.count);
  };
  if (tree.nodes[0].count > 0) {
    Node node = empty_node();
    set_lane(node, 0, 0, 0);
    nodes_.push_back(node);
  } else {
    nodes_.reserve(tree.nodes.size() / 2);
    const auto emit = [&](const auto& self, std::size_t built) -> uint32_t {
      const auto index = static_cast<uint32_t>(nodes_.size());
      nodes_.emplace_back();
      std::size_t kids[kWidth] = {built + 1, tree.nodes[built].index};
      int n = 2;
      while (n < kWidth) {
        int widest = -1;
        double widest_area = -1;
        for (int i = 0; i < n; ++i) {
          if (tree.nodes[kids[i]].count == 0 && half_area(kids[i]) > widest_area) {
            widest = i;
            widest_area = half_area(kids[i]);
          }
        }
        if (widest < 0) break;
        const std::size_t split = kids[widest];
        kids[widest] = split + 1;
        kids[n++] = tree.nodes[split].index;
      }
      Node node = empty_node();
      for (int lane = 0; lane < n; ++lane)
        set_lane(node, lane, kids[lane], tree.nodes[kids[lane]].count > 0 ? 0 : self(self, kids[lane]));
      nodes_[index] = node;
      return index;
    };
    emit(emit, 0);
  }
}

// Brings a child's cache lines in while the nearer children are visited. Always inlined: GCC
// finds that this function has no side effects (a prefetch is none to it) and, when it is not
// inlined early, deletes its calls as dead code; the traversal then prefetched nothing.
[[gnu::always_inline]] inline void Bvh::prefetch_child(uint32_t child, uint32_t count) const {
  if (count == 0) {
    const char* address = reinterpret_cast<const char*>(&nodes_[child]);
    for (int line = 0; line < 4; ++line) _mm_prefetch(address + 64 * line, _MM_HINT_T0);
  } else {
    // A packet is 176 bytes on a 16-byte boundary: up to four lines.
    const char* address = reinterpret_cast<const char*>(&packets_[child]);
    _mm_prefetch(address, _MM_HINT_T0);
    _mm_prefetch(address + 64, _MM_HINT_T0);
    _mm_prefetch(address + 128, _MM_HINT_T0);
    _mm_prefetch(address + sizeof(Packet) - 1, _MM_HINT_T0);
    if (!normals_.empty()) {  // bvh-fast: 48 bytes on a 16-byte boundary, up to two lines
      const char* normals = reinterpret_cast<const char*>(&normals_[child]);
      _mm_prefetch(normals, _MM_HINT_T0);
      _mm_prefetch(normals + sizeof(PacketNormals) - 1, _MM_HINT_T0);
    }
  }
}

// The double vertices of a leaf's first four lanes (288 bytes), when kept: fetched with the
// packet so that the two misses overlap (always inlined, as prefetch_child).
[[gnu::always_inline]] inline void Bvh::prefetch_corners(uint32_t packet) const {
  if (corners_.empty()) return;
  const char* lanes = reinterpret_cast<const char*>(&corners_[4 * std::size_t{packet}]);
  for (int line = 0; line < 5; ++line) _mm_prefetch(lanes + 64 * line, _MM_HINT_T0);
}

inline void Bvh::lane_corners(uint32_t packet, int lane, Vec3& p0, Vec3& p1, Vec3& p2) const {
  if (!corners_.empty()) {
    const Corners& corners = corners_[4 * std::size_t{packet} + static_cast<std::size_t>(lane)];
    p0 = corners.p[0];
    p1 = corners.p[1];
    p2 = corners.p[2];
    return;
  }
  const Packet& data = packets_[packet];
  p0 = {data.p[0][0][lane], data.p[0][1][lane], data.p[0][2][lane]};
  p1 = {data.p[1][0][lane], data.p[1][1][lane], data.p[1][2][lane]};
  p2 = {data.p[2][0][lane], data.p[2][1][lane], data.p[2][2][lane]};
  if (!exact_) {
    // bvh-fast's edges, rounded to float at the build (2^-24 of the edge): the corners they give
    // are that close to the triangle's, which is all its filled hit needs.
    p1 += p0;
    p2 += p0;
  }
}

bool Bvh::intersect_all_slots(const Ray& ray, Intersection& intersection) const {
  double best_t = ray.t_max;
  uint32_t best = std::numeric_limits<uint32_t>::max();
  SurfaceHit best_hit, hit;
  Ray test = ray;
  for (std::size_t i = 0; i < primitives_.size(); ++i) {
    const auto primitive = static_cast<uint32_t>(i);
    if (primitives_[i].shape->intersect(test, hit) && closer_hit(hit.t, primitive, best_t, best)) {
      best_t = hit.t;
      best = primitive;
      best_hit = hit;
      test.t_max = next_up(hit.t);
    }
  }
  if (best == std::numeric_limits<uint32_t>::max()) return false;
  intersection.surface = best_hit;
  intersection.primitive = best;
  return true;
}

bool Bvh::occluded_all_slots(const Ray& ray) const {
  for (const Primitive& primitive : primitives_)
    if (primitive.shape->occluded(ray)) return true;
  return false;
}

// The traversal, compiled once per instruction set: the same source (accel/bvh_traversal.inc)
// for SSE2 (every x86-64), for AVX2 and FMA, and for AVX-512, each in its own target region so
// that only the traversal uses the wider instructions; the constructor picks the widest the CPU
// has (or bvh.isa).
// The traversals are member templates (external linkage) whose lambdas capture this file's
// anonymous-namespace types; they are instantiated here only, so GCC's warning that another
// file could not name those types does not apply.
#if !defined(__clang__)  // a GCC warning (clang has no such group)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wsubobject-linkage"
#endif
#define CANDELA_BVH_ISA 0
#include "accel/bvh_traversal.inc"
#undef CANDELA_BVH_ISA

// A target region: GCC's push_options / target pragmas; clang (scripts/fuzz.sh builds with it)
// spells them as an attribute applied to every function of the region.
#define CANDELA_PRAGMA(text) _Pragma(#text)
#if defined(__clang__)
#define CANDELA_TARGET_BEGIN(features) \
  CANDELA_PRAGMA(clang attribute push(__attribute__((target(features))), apply_to = function))
#define CANDELA_TARGET_END CANDELA_PRAGMA(clang attribute pop)
#else
#define CANDELA_TARGET_BEGIN(features) CANDELA_PRAGMA(GCC push_options) CANDELA_PRAGMA(GCC target(features))
#define CANDELA_TARGET_END CANDELA_PRAGMA(GCC pop_options)
#endif

CANDELA_TARGET_BEGIN("avx2,fma,bmi,bmi2,lzcnt,popcnt")
#define CANDELA_BVH_ISA 1
#include "accel/bvh_traversal.inc"
#undef CANDELA_BVH_ISA
CANDELA_TARGET_END

CANDELA_TARGET_BEGIN("avx512f,avx512vl,avx512dq,avx512bw,avx2,fma,bmi,bmi2,lzcnt,popcnt")
#define CANDELA_BVH_ISA 2
#include "accel/bvh_traversal.inc"
#undef CANDELA_BVH_ISA
CANDELA_TARGET_END

#if !defined(__clang__)
#pragma GCC diagnostic pop
#endif

#undef CANDELA_TARGET_BEGIN
#undef CANDELA_TARGET_END
#undef CANDELA_PRAGMA

// FastSlabs' o / d, with d at least 1e-18: within float's range for |o| and the boxes up to 1e18.
bool Bvh::in_fast_range(const Ray& ray) const {
  return scene_scale_ <= 1e18 && max_abs(ray.origin) <= 1e18;
}

bool Bvh::intersect(const Ray& ray, Intersection& intersection) const {
  // bvh-fast's other rays: its packets hold edges, not the corners the exact traversal tests.
  if (!exact_ && !in_fast_range(ray)) return intersect_all_slots(ray, intersection);
  switch (isa_) {
    case BvhIsa::avx512:
      return exact_ ? intersect_tree<true>(IsaTag<2>{}, ray, intersection)
                    : intersect_tree<false>(IsaTag<2>{}, ray, intersection);
    case BvhIsa::avx2:
      return exact_ ? intersect_tree<true>(IsaTag<1>{}, ray, intersection)
                    : intersect_tree<false>(IsaTag<1>{}, ray, intersection);
    default:
      return exact_ ? intersect_tree<true>(IsaTag<0>{}, ray, intersection)
                    : intersect_tree<false>(IsaTag<0>{}, ray, intersection);
  }
}

bool Bvh::occluded_in_tree(const Ray& ray) const {
  if (!exact_ && !in_fast_range(ray)) return occluded_all_slots(ray);
  switch (isa_) {
    case BvhIsa::avx512:
      return exact_ ? occluded_tree<true>(IsaTag<2>{}, ray) : occluded_tree<false>(IsaTag<2>{}, ray);
    case BvhIsa::avx2:
      return exact_ ? occluded_tree<true>(IsaTag<1>{}, ray) : occluded_tree<false>(IsaTag<1>{}, ray);
    default:
      return exact_ ? occluded_tree<true>(IsaTag<0>{}, ray) : occluded_tree<false>(IsaTag<0>{}, ray);
  }
}

bool Bvh::occluded(const Ray& ray) const {
  for (uint32_t primitive : unbounded_)
    if (primitives_[primitive].shape->occluded(ray)) return true;
  return !nodes_.empty() && occluded_in_tree(ray);
}

AcceleratorReport Bvh::report() const {
  AcceleratorReport report;
  report.figures = {
      {"nodes", static_cast<double>(tree_nodes_)},
      {"leaves", static_cast<double>(leaves_)},
      {"depth", static_cast<double>(depth_)},
      {"SAH cost", sah_cost_},
      {"primitives per leaf", leaves_ > 0 ? static_cast<double>(slot_count_) / leaves_ : 0.0},
      {"unbounded primitives", static_cast<double>(unbounded_.size())},
      {"instruction set (1 sse, 2 avx2, 3 avx512)", static_cast<double>(isa_)},
  };
  report.bytes = nodes_.size() * sizeof(Node) + packets_.size() * sizeof(Packet) +
                 corners_.size() * sizeof(Corners) + normals_.size() * sizeof(PacketNormals) +
                 unbounded_.size() * sizeof(uint32_t);
  if (triangle_count_ > 0)
    report.figures.emplace_back("bytes per triangle", static_cast<double>(report.bytes) / triangle_count_);
  if (largest_coincident_group_ > 0)
    report.figures.emplace_back("largest coincident group", static_cast<double>(largest_coincident_group_));
  if (largest_coincident_group_ >= kCoincidentWarning)
    report.warnings.push_back(fmt::format(
        "bvh: {} primitives share one centroid (copies or rotations of one shape about a point): no split "
        "separates them, so every ray that meets one of them tests them all",
        largest_coincident_group_));
  return report;
}

}  // namespace candela
