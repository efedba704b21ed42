// Micro-benchmarks per registered accelerator on the bench sphere of about 100,000 triangles
// (shared/BENCH-RAYS.md `--sphere 100000`): BM_Build/<name> times build(), BM_Intersect/<name>
// and BM_Occluded/<name> one ray each, cycling through 256×256 primary rays of the default
// bench camera. "embree" runs in native_triangles mode, as in `candela bench`.
#include <benchmark/benchmark.h>

#include <string>

#include "bench/bench_mesh.h"
#include "bench/bench_runner.h"
#include "bench/ray_sets.h"

namespace candela {
namespace {

struct Fixture {
  BenchMesh mesh = bench_sphere(100'000);
  BenchScene scene{mesh.mesh};
  std::vector<Ray> rays;
  Fixture() {
    RaySetOptions options;
    options.width = 256;
    options.height = 256;
    for (const BenchRay& ray : primary_rays(mesh.bounds, options)) rays.push_back(to_ray(ray));
  }
};

const Fixture& fixture() {
  static const Fixture instance;
  return instance;
}

void build(benchmark::State& state, const std::string& name) {
  const Fixture& f = fixture();
  for (auto _ : state) {
    auto accelerator = make_bench_accelerator(name);
    accelerator->build(f.scene.primitives());
    benchmark::DoNotOptimize(accelerator.get());
  }
  state.counters["triangles"] = static_cast<double>(f.scene.primitives().size());
}

void intersect(benchmark::State& state, const std::string& name, bool any_hit) {
  const Fixture& f = fixture();
  auto accelerator = make_bench_accelerator(name);
  accelerator->build(f.scene.primitives());
  std::size_t next = 0;
  Intersection intersection;
  for (auto _ : state) {
    const Ray& ray = f.rays[next];
    next = next + 1 == f.rays.size() ? 0 : next + 1;
    if (any_hit)
      benchmark::DoNotOptimize(accelerator->occluded(ray));
    else
      benchmark::DoNotOptimize(accelerator->intersect(ray, intersection));
  }
  state.SetItemsProcessed(state.iterations());
}

}  // namespace
}  // namespace candela

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  for (const std::string& name : candela::bench_accelerator_names()) {
    benchmark::RegisterBenchmark(("BM_Build/" + name).c_str(), candela::build, name)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("BM_Intersect/" + name).c_str(), candela::intersect, name, false);
    benchmark::RegisterBenchmark(("BM_Occluded/" + name).c_str(), candela::intersect, name, true);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
