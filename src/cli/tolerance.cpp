// `hipair tolerance MODEL [--pair A:B | --driver P] [--range A:B] [--monte-carlo N --seed S]
// [--threshold] [--out DIR]`: kinematic tolerance analysis (docs/tolerance.md) — prints the
// report for designers and writes tolerance.json, variation.csv, sensitivity.csv,
// variation.svg and contact-zone.svg into DIR (all or nothing).
#include "cli/commands.hpp"

#include "io/output_directory.hpp"
#include "io/output_paths.hpp"

#include <hipair/certificate.hpp>
#include <hipair/error.hpp>
#include <hipair/tolerance.hpp>

#include <unistd.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <numbers>

namespace hipair::cli {
namespace {

struct ToleranceCliOptions {
  std::string model;
  std::string pair;
  std::string driver;
  std::string range;
  std::size_t monte_carlo = 0;
  std::uint64_t seed = 1;
  std::size_t positions = 360;
  bool threshold = false;
  std::vector<std::string> vary;
  double accuracy = 0.1;
  unsigned threads = 0;
  std::string out;
  bool quiet = false;
  bool certify = false;
  std::string certify_scale = "1";
  std::size_t certify_leaves = 20000;
};

std::string trim(const std::string& text) {
  std::size_t first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  std::size_t last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

// "A:B" -> (A, B), both non-empty. \throws ModelError naming the option.
std::pair<std::string, std::string> split_pair(const std::string& text, const std::string& option) {
  std::size_t colon = text.find(':');
  if (colon == std::string::npos || trim(text.substr(0, colon)).empty() || trim(text.substr(colon + 1)).empty())
    throw ModelError("", option + " expects A:B, got '" + text + "'");
  return {trim(text.substr(0, colon)), trim(text.substr(colon + 1))};
}

// A driver coordinate: rad by default for a rotating driver ("deg" suffix accepted), mm else.
Rational coordinate(const std::string& text, const std::string& option) {
  std::string body = trim(text);
  bool degrees = false;
  for (const char* unit : {"deg", "rad", "mm"}) {
    std::string u = unit;
    if (body.size() > u.size() && body.compare(body.size() - u.size(), u.size(), u) == 0) {
      degrees = u == "deg";
      body = trim(body.substr(0, body.size() - u.size()));
    }
  }
  Rational value;
  try {
    value = parse_rational(body);
  } catch (const Error&) {
    throw ModelError("", option + ": '" + text + "' is not a number");
  }
  if (degrees) return Rational(value.get_d() * std::numbers::pi / 180);
  return value;
}

bool earlier_output(const std::string& name) {
  return name == "tolerance.json" || name == "variation.csv" || name == "sensitivity.csv" ||
         name == "variation.svg" || name == "contact-zone.svg" || name == "report.txt" ||
         name == "tolerance-certificate.json";
}

int run(const ToleranceCliOptions& options) {
  ToleranceOptions analysis;
  if (!options.pair.empty() && !options.driver.empty())
    throw ModelError("", "give either --pair or --driver, not both");
  if (!options.pair.empty()) {
    auto [a, b] = split_pair(options.pair, "--pair");
    analysis.driver = a;
    analysis.follower = b;
  }
  if (!options.driver.empty()) analysis.driver = options.driver;
  if (!options.range.empty()) {
    auto [a, b] = split_pair(options.range, "--range");
    analysis.range = std::make_pair(coordinate(a, "--range"), coordinate(b, "--range"));
    if (analysis.range->first == analysis.range->second) throw ModelError("", "--range: the range is empty");
  }
  analysis.monte_carlo = options.monte_carlo;
  analysis.seed = options.seed;
  analysis.positions = options.positions;
  analysis.threshold = options.threshold;
  analysis.threshold_parameters = options.vary;
  analysis.relative_accuracy = options.accuracy;
  analysis.threads = options.threads;
  analysis.certify = options.certify;
  std::string scale = trim(options.certify_scale);
  if (!scale.empty() && (scale.back() == 'T' || scale.back() == 't')) {
    if (!options.threshold) throw ModelError("", "--certify-scale " + scale + " is relative to the jamming threshold: add --threshold");
    analysis.certify_relative_to_threshold = true;
    scale.pop_back();
  }
  try {
    analysis.certify_scale = parse_rational(trim(scale));
  } catch (const Error&) {
    throw ModelError("", "--certify-scale: '" + options.certify_scale + "' is not a number");
  }
  if (!(analysis.certify_scale > 0)) throw ModelError("", "--certify-scale: the scale must be positive");
  analysis.certify_max_leaves = options.certify_leaves;
  bool terminal = isatty(2) && !options.quiet;
  if (terminal)
    analysis.progress = [](double fraction) {
      int width = 30, filled = static_cast<int>(fraction * width);
      std::cerr << "\rtolerance [" << std::string(static_cast<std::size_t>(filled), '#')
                << std::string(static_cast<std::size_t>(width - filled), ' ') << "] "
                << static_cast<int>(fraction * 100) << "% " << std::flush;
    };
  if (!options.out.empty()) {
    // Refuse before the (long) analysis when an output would replace the model.
    std::vector<io::PlannedOutput> planned;
    for (const char* name : {"tolerance.json", "variation.csv", "sensitivity.csv", "variation.svg",
                             "contact-zone.svg", "report.txt", "tolerance-certificate.json"})
      planned.push_back({std::filesystem::path(options.out) / name, "--out"});
    io::refuse_overwriting_inputs(planned, {options.model});
  }
  ToleranceResult result = analyze_tolerances(options.model, analysis);
  if (terminal) std::cerr << "\r" << std::string(50, ' ') << "\r" << std::flush;
  std::string report = tolerance_text_report(result);
  std::cout << report;
  if (options.out.empty()) {
    std::cout << "\n(use --out DIR to write tolerance.json, the CSV tables and the pictures)\n";
    return 0;
  }
  std::filesystem::path directory(options.out);
  std::vector<io::RunFile> files{{"report.txt", report},
                                 {"tolerance.json", tolerance_json_report(result)},
                                 {"variation.csv", tolerance_csv(result)},
                                 {"sensitivity.csv", tolerance_sensitivity_csv(result)},
                                 {"variation.svg", tolerance_band_svg(result)},
                                 {"contact-zone.svg", tolerance_zone_svg(result)}};
  if (result.certification && result.certification->certificate)
    files.push_back({"tolerance-certificate.json", write_certificate(*result.certification->certificate)});
  io::publish_directory(directory, files, earlier_output, {options.model});
  std::cout << "\nwrote";
  for (const io::RunFile& file : files) std::cout << " " << (directory / file.name).string();
  std::cout << "\n";
  return 0;
}

}  // namespace

void register_tolerance(CLI::App& app, Action& action) {
  auto options = std::make_shared<ToleranceCliOptions>();
  CLI::App* command = app.add_subcommand(
      "tolerance", "Kinematic tolerance analysis: sensitivities, worst-case and statistical variation, Monte Carlo, jamming threshold");
  command->add_option("model", options->model, "model file (JSON, see docs/model-format.md)")->required();
  command->add_option("--pair", options->pair, "DRIVER:FOLLOWER (default: the first pair of two moving parts)");
  command->add_option("--driver", options->driver, "part to drive (its pair's other part follows)");
  command->add_option("--range", options->range, "driver range A:B (rad, or with a deg suffix; mm for a translation)");
  command->add_option("--monte-carlo", options->monte_carlo, "Monte Carlo samples (default 0: none)")
      ->check(CLI::Range(std::size_t{0}, std::size_t{10000000}));
  command->add_option("--seed", options->seed, "Monte Carlo seed (default 1)");
  command->add_option("--positions", options->positions, "driver positions per turn (default 360)")
      ->check(CLI::Range(std::size_t{16}, std::size_t{100000}));
  command->add_flag("--threshold", options->threshold, "find the jamming threshold and confirm it with an exact C-space");
  command->add_option("--vary", options->vary, "parameters the threshold search scales (default: every toleranced one)");
  command->add_option("--accuracy", options->accuracy,
                      "certified band: at most this much (relative) wider than the linearised one (default 0.1)")
      ->check(CLI::Range(1e-6, 10.0));
  command->add_option("--threads", options->threads, "Monte Carlo threads (default: all cores)");
  command->add_option("--out", options->out, "directory for tolerance.json, variation.csv, sensitivity.csv, variation.svg, contact-zone.svg");
  command->add_flag("--quiet", options->quiet, "no progress bar");
  command->add_flag("--certify", options->certify,
                    "prove by interval branch-and-bound that the pair never jams for any parameters in the box; "
                    "writes tolerance-certificate.json (check it with hipair-verify)");
  command->add_option("--certify-scale", options->certify_scale,
                      "the certificate's box: this times the varied tolerance ranges (default 1; --vary names them); "
                      "with a T suffix (0.95T), times the jamming threshold found by --threshold");
  command->add_option("--certify-leaves", options->certify_leaves, "give up beyond this many leaves (default 20000)")
      ->check(CLI::Range(std::size_t{1}, std::size_t{10000000}));
  command->callback([options, &action] { action = [options] { return run(*options); }; });
}

}  // namespace hipair::cli
