// candela compare A B [--mask M] [--diff out.png] [--diff-metric abs|relative|signed]
//                     [--diff-scale X] [--json FILE]
// Error metrics of image A against the reference B (validate/image_comparison.h): RMSE, relative
// MSE, PSNR, mean and max absolute error, mean luminances and their ratio, printed as a table;
// --json writes them as JSON; --diff writes a false-color picture of the per-pixel luminance
// difference with its color bar beneath (io/false_color.h). PNG and other 8-bit files are
// decoded from sRGB to linear first; EXR and PFM are compared as stored; --luminance compares
// their luminances in cd/m² (efficacy × Y / π). See docs/compare.md.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "commands.h"
#include "false_color_options.h"
#include "image_arguments.h"
#include "io/false_color.h"
#include "io/image_writer.h"
#include "output_paths.h"
#include "shading/photometric_units.h"
#include "util/atomic_file.h"
#include "validate/image_comparison.h"

namespace candela::cli {

namespace {

struct CompareOptions {
  std::string image, reference, mask, diff, diff_metric = "abs", json;
  std::optional<double> diff_scale;
  bool luminance = false;  // compare the luminances in cd/m² (efficacy × Y / π)
  double efficacy = kLuminousEfficacy;
};

std::string number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return fmt::format("{:.6g}", value);
}

std::string describe(const std::string& path, const LinearImage& image) {
  return fmt::format("{} ({}x{}, {})", path, image.film.width(), image.film.height(),
                     image.srgb_decoded ? "sRGB decoded to linear" : "linear as stored");
}

struct DiffPicture {
  DifferenceMetric metric;
  std::string description;  // what a pixel shows
  double low = 0, high = 0;
  ColorMap map = ColorMap::viridis;
  Film film{0, 0};
};

DiffPicture make_diff(const CompareOptions& options, const Film& image, const Film& reference,
                      const std::vector<uint8_t>* mask) {
  DiffPicture diff;
  if (options.diff_metric == "abs") {
    diff.metric = DifferenceMetric::absolute;
    diff.description = "|Y_A - Y_B|";
  } else if (options.diff_metric == "relative") {
    diff.metric = DifferenceMetric::relative;
    diff.description = fmt::format("|Y_A - Y_B| / (|Y_B| + {})", kRelativeMseEpsilon);
  } else {
    diff.metric = DifferenceMetric::signed_difference;
    diff.description = "Y_A - Y_B";
    diff.map = ColorMap::diverging;
  }
  const std::vector<double> values = difference_values(image, reference, diff.metric, mask);
  double largest = 0;
  for (const double value : values)
    if (std::isfinite(value)) largest = std::max(largest, std::abs(value));
  // Identical images: a scale of 0 .. 1 rather than an empty one.
  const double top = options.diff_scale ? *options.diff_scale : (largest > 0 ? largest : 1.0);
  diff.low = diff.metric == DifferenceMetric::signed_difference ? -top : 0.0;
  diff.high = top;
  FalseColorScale scale;
  scale.low = diff.low;
  scale.high = diff.high;
  scale.quantity = diff.description;
  scale.unit = options.luminance && diff.metric != DifferenceMetric::relative ? "cd/m²" : "";
  diff.film = false_color_image(values, image.width(), image.height(), scale, diff.map);
  return diff;
}

int run_compare(const CompareOptions& options) {
  if (!options.luminance && options.efficacy != kLuminousEfficacy)
    throw BadArgument("--efficacy needs --luminance (it converts to cd/m²)");
  if (options.diff_scale && !(std::isfinite(*options.diff_scale) && *options.diff_scale > 0))
    throw BadArgument(fmt::format("--diff-scale {}: must be a positive number", *options.diff_scale));
  if (!options.diff.empty()) {
    ImageFormat format;
    if (!image_format_for_path(options.diff, format))
      throw BadArgument("--diff " + options.diff + ": unsupported extension (expected " + kImageExtensions +
                        ")");
    check_writable(options.diff, "--diff");
  }
  if (!options.json.empty()) check_writable(options.json, "--json");
  // Neither output may be an image compared, the mask, or the other output.
  std::vector<OutputFile> outputs;
  if (!options.diff.empty()) outputs.push_back({options.diff, "--diff"});
  if (!options.json.empty()) outputs.push_back({options.json, "--json"});
  refuse_outputs_over_inputs(outputs, {options.image, options.reference, options.mask});

  LinearImage image = read_image_argument(options.image, "A");
  LinearImage reference = read_image_argument(options.reference, "B (reference)");
  // In luminance, cd/m² — efficacy × Y / π of a rendered value (π × the radiance), the one
  // conversion of shading/photometric_units.h — of linear images only.
  if (options.luminance) {
    check_efficacy(options.efficacy);
    for (LinearImage* linear : {&image, &reference}) {
      if (linear->srgb_decoded)
        throw BadArgument(
            fmt::format("--luminance: {} is an 8-bit display image; compare .exr or .pfm renders",
                        linear == &image ? options.image : options.reference));
      linear->film = luminance_film(linear->film, options.efficacy);
    }
  }
  const Film& a = image.film;
  const Film& b = reference.film;
  if (a.width() != b.width() || a.height() != b.height())
    throw BadArgument(fmt::format("the images differ in size: A {} is {}x{}, B {} is {}x{}", options.image,
                                  a.width(), a.height(), options.reference, b.width(), b.height()));
  std::vector<uint8_t> mask;
  if (!options.mask.empty()) {
    mask = read_mask_argument(options.mask, "--mask", a.width(), a.height(), "the images");
  }
  const std::vector<uint8_t>* mask_pointer = options.mask.empty() ? nullptr : &mask;
  const ImageComparison result = compare_images(a, b, mask_pointer);
  std::optional<DiffPicture> diff;
  if (!options.diff.empty()) diff = make_diff(options, a, b, mask_pointer);

  // The table.
  const char* channels[3] = {"R", "G", "B"};
  std::string table;
  if (options.luminance)
    table += fmt::format("units        luminance, cd/m² (efficacy {} lm/W × Y / π)\n", options.efficacy);
  table += fmt::format("A            {}\n", describe(options.image, image));
  table += fmt::format("B reference  {}\n", describe(options.reference, reference));
  if (!options.mask.empty())
    table += fmt::format("mask         {} ({} of {} pixels compared)\n", options.mask, result.pixels_compared,
                         std::size_t(a.width()) * std::size_t(a.height()));
  const auto row = [&](const std::string& name, const std::string& value, const std::string& note) {
    table += fmt::format("  {:<22} {:>12}{}\n", name, value, note.empty() ? "" : "  " + note);
  };
  row("RMSE", number(result.rmse), "");
  row("relative MSE", number(result.relative_mse),
      fmt::format("(a-b)^2/(b^2+{}), B the reference", kRelativeMseEpsilon));
  row("PSNR (dB)", number(result.psnr),
      fmt::format("peak {} = B's largest value{}", number(result.peak),
                  reference.srgb_decoded ? " (linear; 1 for a white 8-bit pixel)" : ""));
  row("mean absolute error", number(result.mean_absolute_error), "");
  row("max absolute error", number(result.max_absolute_error),
      fmt::format("at x {}, y {}, {}", result.max_error_x, result.max_error_y,
                  channels[result.max_error_channel]));
  row("mean luminance A", number(result.mean_luminance), "Rec. 709 Y");
  row("mean luminance B", number(result.mean_luminance_reference), "");
  row("luminance ratio A/B", number(result.luminance_ratio), "");
  if (diff)
    table += fmt::format("difference   {}: {}, {} color map, scale {} .. {} (color bar below the image)\n",
                         options.diff, diff->description,
                         diff->map == ColorMap::viridis ? "viridis" : "blue-white-red", number(diff->low),
                         number(diff->high));

  // Outputs, each written atomically, only once everything has been computed.
  if (diff) write_image(diff->film, options.diff, DisplaySettings{});
  if (!options.json.empty()) {
    nlohmann::json json = result.to_json();
    json["units"] = options.luminance ? "cd/m2" : "linear";
    json["image"] = {{"path", options.image}, {"srgb_decoded", image.srgb_decoded}};
    json["reference"] = {{"path", options.reference}, {"srgb_decoded", reference.srgb_decoded}};
    json["mask"] = options.mask.empty() ? nlohmann::json(nullptr) : nlohmann::json(options.mask);
    if (diff)
      json["diff"] = {{"path", options.diff},
                      {"metric", options.diff_metric},
                      {"color_map", diff->map == ColorMap::viridis ? "viridis" : "diverging"},
                      {"low", diff->low},
                      {"high", diff->high}};
    write_text_atomically(options.json, json.dump(2) + "\n");
  }
  std::cout << table;
  return 0;
}

}  // namespace

void add_compare_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<CompareOptions>();
  CLI::App* command = app.add_subcommand("compare", "Error metrics of image A against the reference B");
  command->add_option("A", options->image, "The image to judge (PNG, EXR, PFM, ...)")->required();
  command->add_option("B", options->reference, "The reference image, the same size")->required();
  command->add_option(
      "--mask", options->mask,
      "Image of the same size: pixels whose luminance is <= 0.5 (after decoding) are left out");
  command->add_option("--diff", options->diff,
                      "Write a false-color difference image with its color bar (.png)");
  command
      ->add_option("--diff-metric", options->diff_metric,
                   "What --diff shows: abs (default), relative or signed")
      ->check(CLI::IsMember({"abs", "relative", "signed"}));
  command->add_option("--diff-scale", options->diff_scale,
                      "Fixed top of the --diff scale (signed: -X .. X); default: the largest difference");
  command->add_option("--json", options->json, "Write the metrics as JSON");
  command->add_flag("--luminance", options->luminance,
                    "Compare luminances in cd/m² (efficacy × Y / π; linear .exr/.pfm images only)");
  command->add_option("--efficacy", options->efficacy, "With --luminance: lm/W (default 179)");
  command->callback([options, &run]() {
    run = [options]() { return run_reporting_bad_input([&] { return run_compare(*options); }); };
  });
}

}  // namespace candela::cli
