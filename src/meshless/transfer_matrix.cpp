#include "meshless/transfer_matrix.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "distributed/task_farm.h"
#include "math/constants.h"
#include "scene/scene.h"
#include "util/progress.h"

namespace candela {

double TransferMatrix::density() const {
  const double n = static_cast<double>(S.rows());
  return n > 0 ? static_cast<double>(S.nonZeros()) / (n * n) : 0.0;
}

std::size_t TransferMatrix::bytes() const {
  return static_cast<std::size_t>(S.nonZeros()) * (sizeof(float) + sizeof(int32_t)) +
         static_cast<std::size_t>(S.rows() + 1) * sizeof(int32_t);
}

namespace {

// One entry of a row of S: a flat pair, so rows cross between ranks as arrays.
struct Entry {
  int32_t column;
  float value;
};
using Row = std::vector<Entry>;

}  // namespace

TransferMatrix compute_transfer_matrix(const Scene& scene, const std::vector<Site>& sites,
                                       const std::vector<double>& effective_area, std::size_t max_entries,
                                       Cluster* cluster, ProgressReporter* progress) {
  if (effective_area.size() != sites.size())
    throw std::invalid_argument("transfer matrix: " + std::to_string(effective_area.size()) + " areas for " +
                                std::to_string(sites.size()) + " sites");
  const auto start = std::chrono::steady_clock::now();
  const std::size_t n = sites.size();
  TransferMatrix result;
  std::vector<Row> rows(n);
  std::atomic<uint64_t> rays{0};
  std::atomic<std::size_t> kept{0};
  std::atomic<bool> too_many{false};
  // Row j: what receiver j gathers from every other site; returns the visibility rays it traced.
  const auto compute_row = [&](std::size_t j, Row& row) -> uint64_t {
    const Site& receiver = sites[j];
    const double receiver_offset = scene.ray_offset(receiver.position);
    uint64_t row_rays = 0;
    for (std::size_t k = 0; k < n; ++k) {
      if (k == j || !(effective_area[k] > 0)) continue;
      const Site& sender = sites[k];
      const Vec3 between = receiver.position - sender.position;  // v_kj · d
      const double d2 = dot(between, between);
      if (!(d2 > 0)) continue;
      const double d = std::sqrt(d2);
      const Vec3 v = between / d;
      const double cos_sender = dot(v, sender.normal), cos_receiver = -dot(v, receiver.normal);
      if (!(cos_sender > 0) || !(cos_receiver > 0)) continue;
      // 002 eq. 5.2 times A_k, clamped at 1 for close pairs (see the header).
      const double transfer = std::min(1.0, cos_sender * cos_receiver * effective_area[k] / (kPi * d2));
      // V: a shadow ray from the receiver toward the sender, both ends off their surfaces.
      Ray ray;
      ray.origin = receiver.position + receiver.normal * receiver_offset;
      const Vec3 target = sender.position + sender.normal * scene.ray_offset(sender.position);
      const Vec3 to_target = target - ray.origin;
      const double distance = length(to_target);
      if (!(distance > 0)) continue;
      ray.direction = to_target / distance;
      ray.t_max = distance * (1 - 1e-9);
      ++row_rays;
      if (scene.occluded(ray)) continue;
      row.push_back({static_cast<int32_t>(k), static_cast<float>(transfer)});
    }
    // A receiver sees at most its hemisphere: Σ_k F A_k ≤ 1 (000 eq. 6-6 for closed scenes). Near a
    // corner eq. 5.2 overshoots (the sites across it are closer than their areas are wide); such
    // a row is scaled back to 1, or the iteration would diverge.
    double row_sum = 0;
    for (const Entry& entry : row) row_sum += entry.value;
    if (row_sum > 1)
      for (Entry& entry : row) entry.value = static_cast<float>(entry.value / row_sum);
    return row_rays;
  };
  const auto keep = [&](std::size_t entries) {
    if (max_entries > 0 && (kept += entries) > max_entries) too_many = true;
  };
  if (!cluster || !cluster->distributed()) {
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t j) {
      if (too_many.load(std::memory_order_relaxed)) return;
      rays += compute_row(j, rows[j]);
      keep(rows[j].size());
      if (progress) progress->advance();
    });
  } else {
    // Across ranks (issue 11): chunks of receivers handed out dynamically, every rank ends with
    // every row (each rank iterates λ with the whole S), each row exactly as one process has it.
    const std::size_t chunk = std::clamp<std::size_t>(n / (std::size_t(cluster->size()) * 16), 1, 256);
    const std::size_t tasks = (n + chunk - 1) / chunk;
    std::vector<uint64_t> task_rays(tasks, 0), task_entries(tasks, 0);
    // A chunk's rows as bytes: what a rank sends, and what rank 0 rebuilds from `rows` to pass on.
    // The header holds the chunk's entry count as computed: past the limit rank 0 keeps no rows,
    // and every rank must still count them to refuse the matrix alike.
    const auto chunk_bytes = [](uint64_t chunk_rays, uint64_t chunk_entries, const Row* chunk_rows,
                                std::size_t count) {
      ByteWriter writer;
      writer.put<uint64_t>(chunk_rays);
      writer.put<uint64_t>(chunk_entries);
      for (std::size_t k = 0; k < count; ++k) writer.put_array(chunk_rows[k]);
      return writer.take();
    };
    run_task_farm_everywhere(
        *cluster, tasks,
        [&](std::size_t task) {
          const std::size_t first = task * chunk, count = std::min(chunk, n - first);
          std::vector<Row> chunk_rows(count);
          std::atomic<uint64_t> chunk_rays{0};
          tbb::parallel_for(std::size_t(0), count,
                            [&](std::size_t k) { chunk_rays += compute_row(first + k, chunk_rows[k]); });
          std::size_t entries = 0;
          for (const Row& row : chunk_rows) entries += row.size();
          return chunk_bytes(chunk_rays.load(), entries, chunk_rows.data(), count);
        },
        [&](std::size_t task, std::span<const std::byte> result) {
          const std::size_t first = task * chunk, count = std::min(chunk, n - first);
          ByteReader reader(result);
          task_rays[task] = reader.get<uint64_t>();
          task_entries[task] = reader.get<uint64_t>();
          keep(task_entries[task]);
          for (std::size_t k = 0; k < count; ++k) {
            Row row = reader.get_array<Entry>();
            // Past the limit nothing more is kept (the build is refused below): memory stays bounded.
            rows[first + k] = too_many ? Row() : std::move(row);
          }
          if (progress) progress->advance(count);
        },
        [&](std::size_t task) {
          const std::size_t first = task * chunk, count = std::min(chunk, n - first);
          return chunk_bytes(task_rays[task], task_entries[task], rows.data() + first, count);
        });
    uint64_t rays_elsewhere = 0;
    for (const uint64_t r : task_rays) rays_elsewhere += r;
    rays = rays_elsewhere;  // every row's rays, wherever it was computed
  }
  if (too_many)
    throw std::invalid_argument("transfer matrix: more than " + std::to_string(max_entries) +
                                " entries; raise meshless.spacing (fewer sites)");
  // Rows straight into the compressed row storage (no triplet list: at 20,000 sites that list
  // alone would take gigabytes), each row's memory released as it is copied.
  std::size_t total = 0;
  for (const auto& row : rows) total += row.size();
  result.S.resize(static_cast<int32_t>(n), static_cast<int32_t>(n));
  result.S.reserve(static_cast<Eigen::Index>(total));
  for (std::size_t j = 0; j < n; ++j) {
    result.S.startVec(static_cast<int32_t>(j));
    for (const auto& [k, value] : rows[j]) result.S.insertBack(static_cast<int32_t>(j), k) = value;
    Row().swap(rows[j]);
  }
  result.S.finalize();
  result.visibility_rays = rays;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

TransferSolution solve_transfer(const TransferMatrix& transfer, const std::vector<Color>& albedo,
                                const std::vector<Color>& eta, double tolerance, std::size_t max_iterations,
                                ProgressReporter* progress) {
  const auto n = static_cast<std::size_t>(transfer.S.rows());
  if (albedo.size() != n || eta.size() != n)
    throw std::invalid_argument("meshless solve: " + std::to_string(n) + " sites, " +
                                std::to_string(albedo.size()) + " albedos, " + std::to_string(eta.size()) +
                                " direct terms");
  TransferSolution solution;
  solution.lambda = eta;
  double largest_eta = 0;
  for (const Color& e : eta)
    largest_eta = std::max({largest_eta, std::fabs(e.r), std::fabs(e.g), std::fabs(e.b)});
  std::vector<Color> next(n);
  for (std::size_t iteration = 0; iteration < max_iterations; ++iteration) {
    // λ' = η + Q S λ, each row by one thread.
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t j) {
      Color gathered;
      for (Eigen::SparseMatrix<float, Eigen::RowMajor, int32_t>::InnerIterator entry(transfer.S,
                                                                                     static_cast<int32_t>(j));
           entry; ++entry)
        gathered +=
            solution.lambda[static_cast<std::size_t>(entry.col())] * static_cast<double>(entry.value());
      next[j] = eta[j] + albedo[j] * gathered;
    });
    double change = 0, largest = 0;
    for (std::size_t j = 0; j < n; ++j)
      for (int c = 0; c < 3; ++c) {
        change = std::max(change, std::fabs(next[j][c] - solution.lambda[j][c]));
        largest = std::max(largest, std::fabs(next[j][c]));
      }
    solution.lambda.swap(next);
    solution.iterations = iteration + 1;
    solution.final_change = largest > 0 ? change / largest : 0;
    if (progress) {
      const auto done = static_cast<uint64_t>(1000 * convergence_progress(solution.final_change, tolerance));
      progress->set_detail(
          fmt::format("change {:.3g} after {} iterations", solution.final_change, solution.iterations));
      progress->advance_to(done);
    }
    // Diverging (a row of R summing past 1) or overflowed: stop and say so.
    if (!std::isfinite(largest) || !std::isfinite(change) || largest > 1e12 * std::max(largest_eta, 1e-300)) {
      solution.diverged = true;
      break;
    }
    if (solution.final_change <= tolerance) {
      solution.converged = true;
      break;
    }
  }
  return solution;
}

}  // namespace candela
