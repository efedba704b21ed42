// The ray sets of shared/BENCH-RAYS.md and the bench runner's checksums.
#include "bench/ray_sets.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <cmath>

#include "accel/bvh.h"
#include "accel/primitive_list.h"
#include "bench/bench_mesh.h"
#include "bench/bench_runner.h"
#include "util/error.h"
#ifdef CANDELA_HAVE_EMBREE
#include "accel/embree_accelerator.h"
#endif

namespace candela {
namespace {

Vec3 origin_of(const BenchRay& r) {
  return {r.origin[0], r.origin[1], r.origin[2]};
}
Vec3 direction_of(const BenchRay& r) {
  return {r.direction[0], r.direction[1], r.direction[2]};
}
Vec3 rounded(const Vec3& v) {
  return {round_to_float32(v.x), round_to_float32(v.y), round_to_float32(v.z)};
}

const Bounds3 kBox{{-1, -2, -3}, {3, 2, 1}};

TEST(RaySets, SplitMix64FirstValues) {
  // By hand from the formula (BENCH-RAYS "Incoherent rays"): seed 1 -> s = 0x9E3779B97F4A7C16,
  // z = (s ^ s>>30) * 0xBF58476D1CE4E5B9, z = (z ^ z>>27) * 0x94D049BB133111EB, z ^ z>>31.
  SplitMix64 one(1);
  EXPECT_EQ(one.next(), 0x910A2DEC89025CC1ull);
  EXPECT_EQ(one.next(), 0xBEEB8DA1658EEC67ull);
  EXPECT_EQ(one.next(), 0xF893A2EEFB32555Eull);
  SplitMix64 zero(0);  // Vigna's published first output for seed 0
  EXPECT_EQ(zero.next(), 0xE220A8397B1DCDAFull);
  // uniform() = (next() >> 11) * 2^-53 = 0x1214 5BD9 1204 B9 * 2^-53 ≈ 0.56656157517228.
  SplitMix64 again(1);
  EXPECT_EQ(again.uniform(), static_cast<double>(0x910A2DEC89025CC1ull >> 11) * 0x1.0p-53);
  EXPECT_NEAR(SplitMix64(1).uniform(), 0.5665615751722809, 1e-16);
}

TEST(RaySets, DefaultViewFromTheBounds) {
  const BenchView view = resolve_view(kBox, {});
  const Vec3 centre{1, 0, -1};
  const double diagonal = std::sqrt(16.0 + 16.0 + 16.0);
  EXPECT_EQ(view.lookat, centre);
  EXPECT_DOUBLE_EQ(view.diagonal, diagonal);
  const Vec3 offset = view.eye - centre;
  EXPECT_NEAR(length(offset), 0.8 * diagonal, 1e-12);
  EXPECT_NEAR(offset.x / offset.z, 0.6, 1e-12);
  EXPECT_NEAR(offset.y / offset.z, 0.45, 1e-12);
  EXPECT_NEAR(view.light.x, 1 + 0.3 * diagonal, 1e-12);
  EXPECT_NEAR(view.light.y, 0 + 1.0 * diagonal, 1e-12);
  EXPECT_NEAR(view.light.z, -1 + 0.5 * diagonal, 1e-12);
}

TEST(RaySets, CentrePixelPointsAtTheLookAtPoint) {
  RaySetOptions options;
  options.width = 5;
  options.height = 3;
  const std::vector<BenchRay> rays = primary_rays(kBox, options);
  ASSERT_EQ(rays.size(), 15u);
  const BenchView view = resolve_view(kBox, options);
  const BenchRay& centre = rays[1 * 5 + 2];  // index y·W + x
  EXPECT_EQ(origin_of(centre), rounded(view.eye));
  const Vec3 look = normalize(view.lookat - view.eye);
  EXPECT_NEAR(centre.direction[0], look.x, 1e-7);
  EXPECT_NEAR(centre.direction[1], look.y, 1e-7);
  EXPECT_NEAR(centre.direction[2], look.z, 1e-7);
  EXPECT_EQ(centre.t_near, 0.0f);
  EXPECT_EQ(centre.t_far, std::numeric_limits<float>::infinity());
  // y = 0 is the top row and x = 0 the left column.
  const Vec3 forward = normalize(view.lookat - view.eye);
  const Vec3 right = normalize(cross(forward, Vec3{0, 1, 0}));
  EXPECT_GT(dot(direction_of(rays[0]), cross(right, forward)), 0.0);
  EXPECT_LT(dot(direction_of(rays[0]), right), 0.0);
  // A given camera (the Cornell override) is used as is.
  options.eye = Vec3{278, 273, -800};
  options.lookat = Vec3{278, 273, 0};
  options.fov_degrees = 39.3;
  const BenchRay cornell = primary_rays(kBox, options)[7];
  EXPECT_EQ(origin_of(cornell), (Vec3{278, 273, -800}));
  EXPECT_EQ(direction_of(cornell), (Vec3{0, 0, 1}));
}

TEST(RaySets, PixelDirectionsFollowTheFormula) {
  RaySetOptions options;
  options.width = 4;
  options.height = 2;
  options.fov_degrees = 60;
  const std::vector<BenchRay> rays = primary_rays(kBox, options);
  const BenchView view = resolve_view(kBox, options);
  const Vec3 forward = normalize(view.lookat - view.eye);
  const Vec3 right = normalize(cross(forward, Vec3{0, 1, 0}));
  const Vec3 up = cross(right, forward);
  const double h = std::tan(kPi / 6);
  // Pixel (3, 1): u = (2·3.5/4 - 1)·h·2, v = (1 - 2·1.5/2)·h.
  const Vec3 expected = normalize((0.75 * h * 2.0) * right + (-0.5 * h) * up + forward);
  EXPECT_EQ(direction_of(rays[1 * 4 + 3]), rounded(expected));
}

TEST(RaySets, IncoherentRaysFromTheStream) {
  const std::vector<BenchRay> rays = incoherent_rays(kBox, 1000, 7);
  ASSERT_EQ(rays.size(), 1000u);
  SplitMix64 random(7);
  const double a = random.uniform(), b = random.uniform(), c = random.uniform();
  const double u1 = random.uniform(), u2 = random.uniform();
  const double z = 1 - 2 * u1, r = std::sqrt(std::max(0.0, 1 - z * z)), phi = 2 * kPi * u2;
  EXPECT_EQ(origin_of(rays[0]), rounded(Vec3{-1 + 4 * a, -2 + 4 * b, -3 + 4 * c}));
  EXPECT_EQ(direction_of(rays[0]), rounded(Vec3{r * std::cos(phi), r * std::sin(phi), z}));
  for (const BenchRay& ray : rays) {
    EXPECT_TRUE(kBox.contains(origin_of(ray)));
    EXPECT_NEAR(length(direction_of(ray)), 1.0, 1e-6);
  }
  // Another seed, other rays.
  EXPECT_NE(origin_of(incoherent_rays(kBox, 1, 8)[0]), origin_of(rays[0]));
}

TEST(RaySets, RaysAreRoundedToFloat32) {
  const std::vector<BenchRay> rays = incoherent_rays(kBox, 10, 1);
  const Ray ray = to_ray(rays[3]);
  // The double ray is the float ray exactly (no further rounding).
  EXPECT_EQ(ray.origin.x, static_cast<double>(rays[3].origin[0]));
  EXPECT_EQ(ray.direction.z, static_cast<double>(rays[3].direction[2]));
  EXPECT_EQ(static_cast<double>(static_cast<float>(ray.origin.y)), ray.origin.y);
  EXPECT_EQ(ray.t_max, kInfinity);
}

TEST(RaySets, ShadowRaysFromHitsToTheLight) {
  RaySetOptions options;
  options.width = 2;
  options.height = 1;
  options.light = Vec3{0, 10, 0};
  const std::vector<BenchRay> primary = primary_rays(kBox, options);
  const std::vector<double> hits = {kInfinity, 2.5};
  const std::vector<BenchRay> shadow = shadow_rays(kBox, options, primary, hits);
  ASSERT_EQ(shadow.size(), 1u);  // only the ray that hit
  const Vec3 p = origin_of(primary[1]) + 2.5 * direction_of(primary[1]);
  const double diagonal = length(kBox.diagonal());
  const Vec3 to_light = Vec3{0, 10, 0} - p;
  EXPECT_EQ(origin_of(shadow[0]), rounded(p));
  EXPECT_EQ(direction_of(shadow[0]), rounded(to_light / length(to_light)));
  EXPECT_EQ(shadow[0].t_near, static_cast<float>(1e-4 * diagonal));
  EXPECT_EQ(shadow[0].t_far, static_cast<float>(length(to_light) - 1e-4 * diagonal));
}

// A small bench scene: a sphere mesh seen by the camera, incoherent rays from inside its bounds.
struct SmallBench {
  BenchMesh mesh = bench_sphere(800);
  BenchScene scene{mesh.mesh};
  RaySetOptions options;
  std::vector<BenchRay> primary, incoherent;
  SmallBench() {
    options.width = 40;
    options.height = 30;
    primary = primary_rays(mesh.bounds, options);
    incoherent = incoherent_rays(mesh.bounds, 2000, 3);
  }
};

Checksums trace_with_threads(const Accelerator& accelerator, const SmallBench& bench,
                             std::span<const BenchRay> rays, RayQuery query, int threads) {
  tbb::global_control allow(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  tbb::task_arena arena(threads);
  TraceResults results;
  arena.execute([&] { trace_rays(accelerator, rays, query, results); });
  return checksums(results, bench.scene, query);
}

TEST(BenchRunner, ChecksumsDoNotDependOnTheThreadCount) {
  const SmallBench bench;
  PrimitiveList list;
  list.build(bench.scene.primitives());
  for (const auto& [rays, query] : {std::pair{std::span<const BenchRay>(bench.primary), RayQuery::nearest},
                                    std::pair{std::span<const BenchRay>(bench.incoherent), RayQuery::nearest},
                                    std::pair{std::span<const BenchRay>(bench.incoherent), RayQuery::any}}) {
    const Checksums one = trace_with_threads(list, bench, rays, query, 1);
    const Checksums two = trace_with_threads(list, bench, rays, query, 2);
    EXPECT_GT(one.hits, 0u);
    EXPECT_EQ(one.hits, two.hits);
    EXPECT_EQ(one.sum_t, two.sum_t);  // summed in ray order: bit for bit
    EXPECT_EQ(one.sum_prim, two.sum_prim);
  }
  // Every incoherent ray starts inside the closed sphere's bounds; most start inside it.
  const Checksums any = trace_with_threads(list, bench, bench.incoherent, RayQuery::any, 2);
  EXPECT_GT(any.hits, 1000u);
}

TEST(BenchRunner, SumPrimCountsTriangleIds) {
  // Two triangles, the first degenerate: the hit primitive 0 is triangle 1.
  const BenchMesh mesh = parse_bench_obj("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n", "two.obj");
  const BenchScene scene(mesh.mesh);
  PrimitiveList list;
  list.build(scene.primitives());
  BenchRay ray{{0.25f, 0.25f, 1.0f}, {0, 0, -1}, 0, std::numeric_limits<float>::infinity()};
  TraceResults results;
  trace_rays(list, std::span<const BenchRay>(&ray, 1), RayQuery::nearest, results);
  const Checksums sums = checksums(results, scene, RayQuery::nearest);
  EXPECT_EQ(sums.hits, 1u);
  EXPECT_EQ(sums.sum_t, 1.0);
  EXPECT_EQ(sums.sum_prim, 1u);
}

TEST(BenchRunner, RunsEverySetAndWritesJson) {
  const BenchMesh mesh = bench_terrain(200);
  BenchOptions options;
  options.accelerators = {"list"};
  options.threads = {1, 2};
  options.rays.width = 16;
  options.rays.height = 8;
  options.rays.incoherent_rays = 100;
  options.repeat = 1;
  const BenchReport report = run_bench(mesh, options);
  ASSERT_EQ(report.results.size(), 8u);  // 4 sets × 2 thread counts
  EXPECT_EQ(report.builds.size(), 2u);
  EXPECT_EQ(report.results[0].set, "primary");
  EXPECT_EQ(report.results[0].rays, 128u);
  EXPECT_EQ(report.results[1].rays, 100u);
  EXPECT_EQ(report.results[2].set, "shadow");
  EXPECT_EQ(report.results[2].rays, report.results[0].checksums.hits);
  EXPECT_EQ(report.results[3].set, "incoherent_occlusion");
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(report.results[k].checksums.hits, report.results[k + 4].checksums.hits);
    EXPECT_EQ(report.results[k].checksums.sum_t, report.results[k + 4].checksums.sum_t);
  }
  const nlohmann::json json = report.to_json();
  EXPECT_EQ(json["mesh"], "terrain 200");
  EXPECT_EQ(json["triangles"], 200);
  EXPECT_EQ(json["results"].size(), 8u);
  EXPECT_EQ(json["results"][0].size(), 8u);
  EXPECT_EQ(json["results"][0]["accel"], "list");
  EXPECT_TRUE(json["results"][0].contains("mrays_per_s"));
  EXPECT_EQ(json["builds"][1]["threads"], 2);
  EXPECT_NE(report.table().find("incoherent_occlusion"), std::string::npos);
  options.accelerators = {"no-such-accelerator"};
  EXPECT_THROW(run_bench(mesh, options), std::invalid_argument);
}

// `candela bench --set NAME.key=value`: the accelerator reads its settings as from a scene's
// "NAME" object; other accelerators keep their defaults; unknown names and values are refused.
TEST(BenchRunner, SetAssignmentsReachTheNamedAccelerator) {
  const BenchMesh mesh = bench_sphere(2000);
  const BenchScene scene{mesh.mesh};
  const auto figure = [&](Accelerator& accelerator, const std::string& name) {
    accelerator.build(scene.primitives());
    for (const auto& [key, value] : accelerator.report().figures)
      if (key.rfind(name, 0) == 0) return value;
    return -1.0;
  };
  // Up to 64 a leaf: more than any default tree holds (at most 16).
  const std::vector<std::string> settings = {"bvh.isa=sse", "bvh.max_leaf_primitives=64"};
  const auto bvh = make_bench_accelerator("bvh", settings);
  ASSERT_NE(bvh, nullptr);
  EXPECT_EQ(figure(*bvh, "instruction set"), 1.0);
  EXPECT_GT(figure(*bvh, "primitives per leaf"), 16);
  const auto automatic = make_bench_accelerator("bvh");
  EXPECT_LE(figure(*automatic, "primitives per leaf"), 16);
  EXPECT_EQ(figure(*automatic, "instruction set"), static_cast<double>(widest_bvh_isa()));
  EXPECT_NE(make_bench_accelerator("grid", settings), nullptr);  // bvh.* is not the grid's
  EXPECT_THROW(make_bench_accelerator("bvh", {"bvh.isa=neon"}), InputError);
  EXPECT_THROW(make_bench_accelerator("bvh", {"bvh.leaf=2"}), InputError);
  EXPECT_THROW(make_bench_accelerator("bvh", {"radiosity.patch_size=5"}), InputError);
  // bvh-fast reads the same keys from its own object.
  const auto fast =
      make_bench_accelerator("bvh-fast", {"bvh-fast.isa=sse", "bvh-fast.max_leaf_primitives=64"});
  ASSERT_NE(fast, nullptr);
  EXPECT_EQ(fast->name(), "bvh-fast");
  EXPECT_EQ(figure(*fast, "instruction set"), 1.0);
  EXPECT_GT(figure(*fast, "primitives per leaf"), 16);
  EXPECT_EQ(make_bench_accelerator("bvh-fast", settings)->name(), "bvh-fast");  // bvh.* is not its
  EXPECT_THROW(make_bench_accelerator("bvh-fast", {"bvh-fast.leaf=2"}), InputError);
}

#ifdef CANDELA_HAVE_EMBREE
TEST(BenchRunner, ListAndEmbreeExactAgreeRayForRay) {
  const SmallBench bench;
  PrimitiveList list;
  list.build(bench.scene.primitives());
  EmbreeAccelerator embree(EmbreeAccelerator::Mode::exact);
  embree.build(bench.scene.primitives());
  for (const auto& rays :
       {std::span<const BenchRay>(bench.primary), std::span<const BenchRay>(bench.incoherent)}) {
    TraceResults a, b;
    trace_rays(list, rays, RayQuery::nearest, a);
    trace_rays(embree, rays, RayQuery::nearest, b);
    EXPECT_EQ(a.t, b.t);
    EXPECT_EQ(a.primitive, b.primitive);
    trace_rays(list, rays, RayQuery::any, a);
    trace_rays(embree, rays, RayQuery::any, b);
    EXPECT_EQ(a.t, b.t);
  }
}

TEST(BenchRunner, EmbreeMeansNativeMode) {
  const auto embree = make_bench_accelerator("embree");
  ASSERT_NE(embree, nullptr);
  EXPECT_EQ(dynamic_cast<const EmbreeAccelerator&>(*embree).mode(),
            EmbreeAccelerator::Mode::native_triangles);
  const auto exact = make_bench_accelerator("embree-exact");
  EXPECT_EQ(dynamic_cast<const EmbreeAccelerator&>(*exact).mode(), EmbreeAccelerator::Mode::exact);
}
#endif

}  // namespace
}  // namespace candela
