#include "validate/convergence_log.h"

#include <fmt/format.h>

#include <stdexcept>
#include <utility>

#include "validate/image_comparison.h"

namespace candela {

ConvergenceLog::ConvergenceLog(std::string method, Film reference, std::vector<uint8_t> mask)
    : method_(std::move(method)), reference_(std::move(reference)), mask_(std::move(mask)) {
  if (!mask_.empty() && mask_.size() != reference_.pixels().size())
    throw std::invalid_argument(
        fmt::format("the mask has {} pixels, the reference {}", mask_.size(), reference_.pixels().size()));
}

void ConvergenceLog::start() {
  clock_ = Stopwatch();
  overhead_ = 0;
  rows_.clear();
}

void ConvergenceLog::add(const std::string& unit, uint64_t work, double seconds, double image_seconds,
                         const Film& image, std::optional<double> unshot_fraction) {
  const ImageComparison comparison = compare_images(image, reference_, mask_.empty() ? nullptr : &mask_);
  rows_.push_back({method_, unit, work, seconds, image_seconds, comparison.rmse, comparison.relative_mse,
                   unshot_fraction});
}

std::function<void(const ProgressStep&)> ConvergenceLog::observer() {
  return [this](const ProgressStep& step) {
    const double called = clock_.seconds();
    const double seconds = called - overhead_;
    const Stopwatch image_time;
    const Film image = step.image();
    add(std::string(step.unit), step.work, seconds, image_time.seconds(), image, step.unshot_fraction);
    overhead_ += clock_.seconds() - called;
  };
}

void ConvergenceLog::finish(const Film& image) {
  const double seconds = clock_.seconds() - overhead_;
  const uint64_t work = rows_.empty() ? 1 : rows_.back().work;
  add("final", work, seconds, 0, image, std::nullopt);
}

std::string convergence_csv(const std::vector<ConvergenceRow>& rows) {
  std::string text =
      "method,unit,work,seconds,image_seconds,time_to_image,rmse,relative_mse,unshot_fraction\n";
  for (const ConvergenceRow& row : rows)
    text += fmt::format("{},{},{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{}\n", row.method, row.unit, row.work,
                        row.seconds, row.image_seconds, row.time_to_image(), row.rmse, row.relative_mse,
                        row.unshot_fraction ? fmt::format("{:.9g}", *row.unshot_fraction) : std::string());
  return text;
}

}  // namespace candela
