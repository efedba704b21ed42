// candela falsecolor IMAGE -o out.png [--scale LO,HI] [--log] [--contours N] [--efficacy E]
//                        [--exposure STOPS] [--json FILE]
// Radiance's falsecolor for a rendered image: each pixel's luminance in cd/m²,
// L = efficacy × Y / π (a rendered value is π × the radiance, in the scene's W/m²; Y the Rec. 709
// luminance; 179 lm/W by default, the one conversion of shading/photometric_units.h), drawn in
// false colour with its bar and unit ("cd/m²") beneath — the fixed range, log scale and
// iso-contours of io/false_color.h, as probe's work planes. Only linear images (.exr, .pfm, as
// render writes them): an 8-bit PNG holds display values, not luminances. See docs/probe.md.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "false_color_options.h"
#include "image_arguments.h"
#include "io/false_color.h"
#include "io/image_writer.h"
#include "list_option.h"
#include "math/constants.h"
#include "output_paths.h"
#include "shading/photometric_units.h"
#include "util/atomic_file.h"
#include "validate/image_comparison.h"

namespace candela::cli {

namespace {

struct FalseColorOptions {
  std::string image, output, json;
  std::vector<double> scale;
  bool log = false;
  int contours = 0;
  double efficacy = kLuminousEfficacy;
  double exposure = 0;
};

int run_falsecolor(const FalseColorOptions& options) {
  ImageFormat format;
  if (!image_format_for_path(options.output, format) || format != ImageFormat::png)
    throw BadArgument("-o " + options.output + ": expected a .png file");
  check_writable(options.output, "-o");
  if (!options.json.empty()) check_writable(options.json, "--json");
  std::vector<OutputFile> outputs = {{options.output, "-o"}};
  if (!options.json.empty()) outputs.push_back({options.json, "--json"});
  refuse_outputs_over_inputs(outputs, {options.image});
  check_false_color_options(options.scale, options.log, options.contours, "cd/m²");
  check_efficacy(options.efficacy);
  if (!std::isfinite(options.exposure) || std::fabs(options.exposure) > 64)
    throw BadArgument("--exposure must be a number of stops within ±64");
  const LinearImage image = read_image_argument(options.image, options.image);
  if (image.srgb_decoded)
    throw BadArgument(
        options.image +
        ": an 8-bit display image holds no luminances; render to .exr or .pfm (linear) for falsecolor");
  // The film's exposure multiplied the stored values by 2^exposure: undone here.
  const double to_luminance = options.efficacy / kPi / std::exp2(options.exposure);
  const Film& film = image.film;
  std::vector<double> values;
  values.reserve(film.pixels().size());
  double low = std::numeric_limits<double>::infinity(), high = 0, sum = 0;
  std::size_t finite = 0;
  for (const Color& pixel : film.pixels()) {
    const double value = to_luminance * luminance(pixel);
    values.push_back(value);
    if (!std::isfinite(value)) continue;
    low = std::min(low, value);
    high = std::max(high, value);
    sum += value;
    ++finite;
  }
  if (finite == 0) throw BadArgument(options.image + ": no pixel has a finite value");
  const FalseColorScale scale =
      false_color_scale(high, options.scale, options.log, options.contours, "cd/m²", "luminance");
  write_image(false_color_image(values, film.width(), film.height(), scale, ColorMap::viridis),
              options.output, DisplaySettings{});
  const double average = sum / double(finite);  // over the finite pixels (a NaN is drawn grey)
  if (!options.json.empty()) {
    const nlohmann::json json = {{"image", options.image},
                                 {"unit", "cd/m2"},
                                 {"efficacy_lm_per_w", options.efficacy},
                                 {"exposure_stops_undone", options.exposure},
                                 {"luminance", {{"minimum", low}, {"average", average}, {"maximum", high}}},
                                 {"scale",
                                  {{"low", scale.low},
                                   {"high", scale.high},
                                   {"logarithmic", scale.logarithmic},
                                   {"contours", scale.contours}}}};
    write_text_atomically(options.json, json.dump(2) + "\n");
  }
  std::cout << fmt::format(
      "luminance of {} ({}x{}): min {}, average {}, max {} cd/m² (efficacy {} lm/W); scale {} to {}{}{}; "
      "wrote {}\n",
      options.image, film.width(), film.height(), format_scale_value(low), format_scale_value(average),
      format_scale_value(high), options.efficacy, format_scale_value(scale.low),
      format_scale_value(scale.high), scale.logarithmic ? ", logarithmic" : "",
      scale.contours > 1 ? fmt::format(", {} contour steps", scale.contours) : "", options.output);
  return 0;
}

}  // namespace

void add_falsecolor_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<FalseColorOptions>();
  CLI::App* command = app.add_subcommand(
      "falsecolor", "Luminance (cd/m²) of a rendered linear image in false colour, with its legend");
  command->add_option("image", options->image, "A linear image as render writes it (.exr or .pfm)")
      ->required();
  command->add_option("-o,--output,--outfile", options->output, "The false-colour picture (.png)")
      ->required();
  add_list_option(command, "--scale", options->scale,
                  "The color scale's range LO,HI in cd/m² (default 0 to the maximum)", 2);
  command->add_flag("--log", options->log,
                    "Logarithmic scale (default range: three decades below the maximum)");
  command->add_option("--contours", options->contours,
                      "Iso-luminance lines between N equal steps of the scale");
  command->add_option("--efficacy", options->efficacy, "Luminous efficacy in lm/W (default 179)");
  command->add_option("--exposure", options->exposure,
                      "The film.exposure (stops) the image was written with, undone (default 0)");
  command->add_option("--json", options->json, "Write the minimum, average and maximum luminance as JSON");
  command->callback([options, &run]() {
    run = [options]() { return run_reporting_bad_input([&] { return run_falsecolor(*options); }); };
  });
}

}  // namespace candela::cli
