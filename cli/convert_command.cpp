// candela convert IN OUT [--exposure STOPS] [--tone-map clamp|scale|normalize] [--linear]
// Pictures from one format to another: IN any format read_linear_image reads
// (PNG, JPG, … decoded from sRGB; EXR, PFM, HDR linear), OUT by its extension — .png (tone-mapped
// 8-bit), .exr, .pfm or .hdr (linear) — as render writes them: the exposure multiplies every value
// by 2^STOPS, and for a .png the out-of-range handling (SPEC §6: film.out_of_range) and the sRGB
// curve (or none, --linear) follow. pbrt's imgtool convert and Mitsuba's mtsutil tonemap do the
// same.
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <string>

#include "camera/tone_map.h"
#include "commands.h"
#include "image_arguments.h"
#include "io/image_writer.h"
#include "output_paths.h"
#include "validate/image_comparison.h"

namespace candela::cli {

namespace {

struct ConvertOptions {
  std::string input, output;
  double exposure = 0;
  std::string tone_map;  // empty: clamp
  bool linear = false;
  bool quiet = false;
};

int run_convert(const ConvertOptions& options) {
  ImageFormat format;
  if (!image_format_for_path(options.output, format))
    throw BadArgument("OUT " + options.output + ": unsupported extension (expected " + kImageExtensions +
                      ")");
  if (!std::isfinite(options.exposure) || std::fabs(options.exposure) > 64)
    throw BadArgument("--exposure must be a number of stops within ±64");
  DisplaySettings display;
  display.exposure = options.exposure;
  display.srgb = !options.linear;
  if (!options.tone_map.empty()) {
    const auto mode = kOutOfRangeNames.value(options.tone_map);
    if (!mode)
      throw BadArgument("--tone-map " + options.tone_map +
                        ": unknown mode (expected one of: " + kOutOfRangeNames.names() + ")");
    display.out_of_range = *mode;
  }
  if (format != ImageFormat::png && (!options.tone_map.empty() || options.linear))
    throw BadArgument(std::string(!options.tone_map.empty() ? "--tone-map" : "--linear") +
                      " applies to an 8-bit .png only (" + options.output + " keeps linear values)");
  check_writable(options.output, "OUT");
  refuse_outputs_over_inputs({{options.output, "OUT"}}, {options.input});
  const LinearImage image = read_image_argument(options.input, options.input);
  if (const std::string problem = non_finite_image_problem(image.film, format, display.exposure);
      !problem.empty())
    throw BadArgument(options.input + ": " + problem);
  write_image(image.film, options.output, display);
  if (!options.quiet)
    std::cerr << fmt::format(
        "candela: wrote {} ({}x{}{}{})\n", options.output, image.film.width(), image.film.height(),
        image.srgb_decoded ? ", decoded from sRGB" : "",
        options.exposure != 0 ? fmt::format(", exposure {:+g} stops", options.exposure) : std::string());
  return 0;
}

}  // namespace

void add_convert_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<ConvertOptions>();
  CLI::App* command = app.add_subcommand(
      "convert", "Convert a picture between PNG, EXR, PFM and HDR, with exposure and tone mapping");
  command->add_option("IN", options->input, "The picture to read (PNG, JPG, EXR, PFM, HDR, ...)")->required();
  command->add_option("OUT", options->output, std::string("The picture to write: ") + kImageExtensions)
      ->required();
  command->add_option("--exposure", options->exposure, "Multiply the values by 2^STOPS first (default 0)");
  command->add_option("--tone-map", options->tone_map,
                      ".png: what becomes of values above 1: " + kOutOfRangeNames.names() +
                          " (per channel; the whole image divided by its largest value; each pixel by its "
                          "largest channel, keeping the hue); default clamp");
  command->add_flag("--linear", options->linear, ".png: linear 8-bit values instead of the sRGB curve");
  command->add_flag("-q,--quiet", options->quiet, "No summary");
  command->callback([options, &run]() {
    run = [options]() { return run_reporting_bad_input([&] { return run_convert(*options); }); };
  });
}

}  // namespace candela::cli
