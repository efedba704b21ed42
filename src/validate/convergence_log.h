// A render's error against a reference image as it goes — the error-against-time data
// researchers compare methods by (pbrt-v4's --mse-reference-image does it for its path tracer).
// Every step a progressive method reports (RenderRequest::on_progress: the path tracer's passes,
// progressive radiosity's shots, Gauss-Seidel's sweeps, meshless iterations) becomes a row with
// the image of that state measured against the reference; the image render returns is the last
// row, so a method without steps (local, whitted, raster, the gaussian solver) gives one point.
//
// Time: `seconds` is the render's own time up to the step — the clock since start(), less what
// the log itself took before it (making the step images, measuring them); `image_seconds` the time
// to make the step's image from the state (the display of a radiosity or meshless solution; for the
// path tracer the mean of the passes). time_to_image() = seconds + image_seconds is when a run
// stopped there would have had its image: the x of the chart. The final row's seconds include
// the method's own display, its image_seconds are 0.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "camera/film.h"
#include "integrators/method.h"
#include "util/statistics.h"

namespace candela {

struct ConvergenceRow {
  std::string method;
  std::string unit;  // "passes", "shots", "sweeps", "iterations"; "final" for the image returned
  uint64_t work = 0;
  double seconds = 0, image_seconds = 0;
  double rmse = 0, relative_mse = 0;
  std::optional<double> unshot_fraction;
  double time_to_image() const { return seconds + image_seconds; }
};

class ConvergenceLog {
 public:
  // mask: empty, or width·height bytes, row by row from the top (image_comparison.h). Throws
  // std::invalid_argument when the mask's size is not the reference's.
  ConvergenceLog(std::string method, Film reference, std::vector<uint8_t> mask = {});

  // Starts the clock: call as the render begins.
  void start();
  // What RenderRequest::on_progress is to call. Throws std::invalid_argument (from
  // compare_images) when a step's image is not the reference's size.
  std::function<void(const ProgressStep&)> observer();
  // The image the render returned, as it returned: the last row.
  void finish(const Film& image);

  const std::vector<ConvergenceRow>& rows() const { return rows_; }
  double overhead_seconds() const { return overhead_; }

 private:
  void add(const std::string& unit, uint64_t work, double seconds, double image_seconds, const Film& image,
           std::optional<double> unshot_fraction);

  std::string method_;
  Film reference_;
  std::vector<uint8_t> mask_;
  Stopwatch clock_;
  double overhead_ = 0;
  std::vector<ConvergenceRow> rows_;
};

// The rows as CSV: method,unit,work,seconds,image_seconds,time_to_image,rmse,relative_mse,
// unshot_fraction (empty where a method has none), one row per line, numbers to 9 digits.
std::string convergence_csv(const std::vector<ConvergenceRow>& rows);

}  // namespace candela
