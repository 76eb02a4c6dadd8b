// `hipair tolerance MODEL [--pair A:B | --driver P] [--range A:B] [--monte-carlo N --seed S]
// [--threshold] [--chain] [--out DIR]`: kinematic tolerance analysis (docs/tolerance.md) — prints the
// report for designers and writes tolerance.json, variation.csv, sensitivity.csv,
// variation.svg and contact-zone.svg into DIR (all or nothing).
// `hipair tolerance MODEL --certify-interference --range A:B --follower-range A:B [--pair A:B]
// [--certify-scale S] [--vary P...] [--out DIR]`: instead of the analysis, the "never interferes"
// tolerance certificate (hipair::certify_no_interference; docs/certify.md, property
// no_interference), written as interference-certificate.json with report.txt (all or nothing).
#include "cli/commands.hpp"
#include "core/model_scale.hpp"

#include "io/output_directory.hpp"
#include "io/output_paths.hpp"

#include <hipair/certificate.hpp>
#include <hipair/error.hpp>
#include <hipair/tolerance.hpp>
#include <hipair/tolerance_scale.hpp>

#include <unistd.h>

#include <hipair/model.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <iomanip>
#include <iostream>
#include <memory>
#include <set>
#include <numbers>
#include <sstream>

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
  double threshold_bracket = 0;
  bool contact_changes = false;
  bool chain = false;
  bool assume_nominal_contact = false;
  std::size_t chain_split_budget = 4;
  std::vector<std::string> vary;
  double accuracy = 0.1;
  unsigned threads = 0;
  std::string out;
  bool quiet = false;
  bool certify = false;
  std::string certify_scale = "1";
  std::size_t certify_leaves = 20000;
  bool certify_free_path = false;
  std::size_t certify_witness_splits = 6;
  std::set<std::string> given;   // the long options given on the command line
  bool certify_interference = false;
  std::string follower_range;
  std::vector<std::string> overrides;   // --set NAME=VALUE: the design's new nominal values
  bool allow_out_of_tolerance = false;
};

// "A:B" -> (A, B), both non-empty. \throws ModelError naming the option.
std::pair<std::string, std::string> split_pair(const std::string& text, const std::string& option) {
  std::size_t colon = text.find(':');
  if (colon == std::string::npos || trim(text.substr(0, colon)).empty() || trim(text.substr(colon + 1)).empty())
    throw ModelError("", option + " expects A:B, got '" + text + "'");
  return {trim(text.substr(0, colon)), trim(text.substr(colon + 1))};
}

// A driver coordinate: rad by default for a rotating driver ("deg" suffix accepted), mm else.
Rational coordinate(const std::string& text, const std::string& option) {
  const auto [body, unit] = split_unit_suffix(text, {"deg", "rad", "mm"}, "");
  const bool degrees = unit == "deg";
  Rational value;
  try {
    value = parse_rational(body);
  } catch (const Error& error) {   // the parser's message quotes at most 40 characters of it
    throw ModelError("", option + ": " + error.what());
  }
  if (degrees) return degrees_to_radians(value);
  return value;
}

// --certify-scale S (without a T suffix): an exact positive number, at most 10^6 (the box is S
// times the tolerance ranges; until session 32 `1e400` was accepted and the analysis ran on).
// \throws ModelError naming the option.
Rational certify_scale(const std::string& text, const std::string& given) {
  Rational scale;
  try {
    scale = parse_rational(trim(text));
  } catch (const Error&) {
    throw ModelError("", "--certify-scale: '" + given + "' is not a number");
  }
  if (!(scale > 0)) throw ModelError("", "--certify-scale: the scale must be positive");
  if (scale > 1000000) throw ModelError("", "--certify-scale " + given + ": the scale must be at most 1e6");
  return scale;
}

// --range A:B of the analysis: A below B, both in rad (or deg) / mm. \throws ModelError.
std::pair<Rational, Rational> driver_range(const std::string& text) {
  auto [a, b] = split_pair(text, "--range");
  Rational lo = coordinate(a, "--range"), hi = coordinate(b, "--range");
  if (lo == hi)
    throw ModelError("", "--range " + text + ": the range is empty" +
                             (a != b ? std::string(" (both ends are the same position once converted to exact rad)") : ""));
  if (hi < lo) throw ModelError("", "--range " + text + ": A must be below B (the driver runs from A up to B)");
  return {lo, hi};
}

// --seed: decimal digits that fit a uint64 (CLI11's own conversion took "-1" as 2^64 - 1 and
// "18446744073709551616" as 2^64 - 1).
CLI::Validator seed_digits() {
  return CLI::Validator(
      [](std::string& input) -> std::string {
        static const std::string largest = "18446744073709551615";
        bool digits = !input.empty() && std::all_of(input.begin(), input.end(), [](char c) { return c >= '0' && c <= '9'; });
        std::string value = digits ? input.substr(std::min(input.find_first_not_of('0'), input.size())) : input;
        if (!digits || value.size() > largest.size() || (value.size() == largest.size() && value > largest))
          return "Value " + input + " is not a whole number from 0 to " + largest;
        return {};
      },
      "UINT64");
}

bool earlier_output(const std::string& name) {
  return name == "tolerance.json" || name == "variation.csv" || name == "sensitivity.csv" ||
         name == "variation.svg" || name == "contact-zone.svg" || name == "report.txt" ||
         name == "tolerance-certificate.json" || name == "interference-certificate.json";
}

const char* const kOutputNames[] = {"tolerance.json", "variation.csv", "sensitivity.csv", "variation.svg",
                                    "contact-zone.svg", "report.txt", "tolerance-certificate.json",
                                    "interference-certificate.json"};

// Refuses, before a long computation, an --out whose files would replace the model.
void refuse_overwriting_model(const ToleranceCliOptions& options) {
  if (options.out.empty()) return;
  io::refuse_unusable_output_directory(options.out, "--out");
  std::vector<io::PlannedOutput> planned;
  for (const char* name : kOutputNames) planned.push_back({std::filesystem::path(options.out) / name, "--out"});
  io::refuse_overwriting_inputs(planned, {options.model});
}

// A coordinate of `part` from the command line: rad (or a deg suffix) for a rotating part, mm
// (optional suffix) for a translating one; a unit of the other kind is refused.
Rational part_coordinate(const std::string& text, const std::string& option, const Part& part) {
  std::string body = trim(text);
  bool rotating = part.motion.kind == Motion::Kind::rotation;
  auto ends_with = [&](const std::string& unit) {
    return body.size() > unit.size() && body.compare(body.size() - unit.size(), unit.size(), unit) == 0;
  };
  if (!rotating && (ends_with("deg") || ends_with("rad")))
    throw ModelError("", option + ": '" + text + "' is an angle, but '" + part.name + "' translates (give mm)");
  if (rotating && ends_with("mm"))
    throw ModelError("", option + ": '" + text + "' is a length, but '" + part.name + "' rotates (give rad or deg)");
  return coordinate(text, option);
}

std::string unit_of(const Part& part) { return part.motion.kind == Motion::Kind::rotation ? " rad" : " mm"; }

// --certify-interference: the "never interferes" tolerance certificate alone (no analysis).
int run_interference(const ToleranceCliOptions& options) {
  if (options.certify || options.threshold || options.contact_changes || options.monte_carlo > 0)
    throw ModelError("", "--certify-interference runs alone: drop --certify, --threshold, --contact-changes and --monte-carlo "
                         "(run the analysis separately)");
  if (options.given.count("--certify-witness-splits"))
    throw ModelError("", "--certify-witness-splits is for the no-jam certificate (--certify or --certify-free-path): "
                         "a never-interferes certificate has no witness paths");
  std::string scale = trim(options.certify_scale);
  if (!scale.empty() && (scale.back() == 'T' || scale.back() == 't'))
    throw ModelError("", "--certify-scale " + scale +
                             " is relative to the jamming threshold, which --certify-interference does not use: give a number");
  InterferenceCertifyOptions certify;
  certify.scale = certify_scale(scale, options.certify_scale);
  certify.vary = options.vary;
  certify.max_leaves = options.certify_leaves;

  Model model = read_model_file(options.model);
  require_feature_spread(model);   // a 1e-999 mm feature on a 40 mm part: refused before work (session 53)
  auto part_named = [&](const std::string& name, const std::string& option) -> const Part& {
    std::optional<std::size_t> k = model.find_part(name);
    if (!k) throw ModelError("", option + ": no part '" + name + "' in the model");
    return model.parts[*k];
  };
  auto moving = [](const Part& part) { return part.motion.kind != Motion::Kind::fixed; };
  const Part* driver = nullptr;
  const Part* follower = nullptr;
  if (!options.pair.empty()) {
    auto [a, b] = split_pair(options.pair, "--pair");
    driver = &part_named(a, "--pair");
    follower = &part_named(b, "--pair");
    if (driver == follower) throw ModelError("", "--pair: '" + a + "' twice (give two different parts)");
  } else {
    if (!options.driver.empty()) driver = &part_named(options.driver, "--driver");
    for (const PairSpec& pair : model.pairs) {
      const Part &p = model.parts[pair.first], &q = model.parts[pair.second];
      if (driver) {
        if (&p == driver) follower = &q;
        else if (&q == driver) follower = &p;
        if (follower) break;
      } else if (moving(p) && moving(q)) {
        driver = &p;
        follower = &q;
        break;
      }
    }
    if (!follower)
      throw ModelError("", driver ? "--driver: '" + driver->name + "' is in no pair of the model"
                                  : std::string("the model has no pair of two moving parts: give --pair DRIVER:FOLLOWER"));
  }
  if (!moving(*follower) && !options.follower_range.empty())
    throw ModelError("", "--follower-range: the follower '" + follower->name +
                             "' is fixed: it has no coordinate to range over (the certificate needs two parts that "
                             "each rotate or translate)");
  for (const Part* part : {driver, follower})
    if (part->motion.kind != Motion::Kind::rotation && part->motion.kind != Motion::Kind::translation)
      throw ModelError("", "--certify-interference: '" + part->name + "' " +
                               (moving(*part) ? "neither rotates nor translates" : "is fixed") +
                               (part == follower && !moving(*part) ? " (it has no follower range)" : "") +
                               "; both parts of the pair must rotate or translate");
  if (options.range.empty())
    throw ModelError("", "--certify-interference needs the driver range: add --range A:B");
  if (options.follower_range.empty())
    throw ModelError("", "--certify-interference needs the follower's range: add --follower-range A:B (or one value, "
                         "e.g. 0, for a follower held still)");

  auto [dlo, dhi] = split_pair(options.range, "--range");
  certify.driver = driver->name;
  certify.follower = follower->name;
  certify.driver_range = {part_coordinate(dlo, "--range", *driver), part_coordinate(dhi, "--range", *driver)};
  if (!(certify.driver_range.lo < certify.driver_range.hi))
    throw ModelError("", "--range: the driver range " + options.range + " is empty (give A:B with A < B)");
  std::string frange = trim(options.follower_range);
  if (frange.find(':') == std::string::npos) {
    Rational at = part_coordinate(frange, "--follower-range", *follower);
    certify.follower_range = {at, at};
  } else {
    auto [flo, fhi] = split_pair(frange, "--follower-range");
    certify.follower_range = {part_coordinate(flo, "--follower-range", *follower),
                              part_coordinate(fhi, "--follower-range", *follower)};
    if (!(certify.follower_range.lo <= certify.follower_range.hi))
      throw ModelError("", "--follower-range: the range " + options.follower_range + " is empty (give A:B with A <= B)");
  }
  refuse_overwriting_model(options);

  // The branch-and-bound has no progress hook: on a terminal, the elapsed time.
  bool terminal = isatty(2) && !options.quiet;
  ToleranceCertification result;
  if (terminal) {
    auto start = std::chrono::steady_clock::now();
    std::future<ToleranceCertification> work =
        std::async(std::launch::async, [&] { return certify_no_interference(options.model, certify); });
    while (work.wait_for(std::chrono::milliseconds(250)) != std::future_status::ready)
      std::cerr << "\rcertifying no interference of " << certify.driver << ":" << certify.follower << " ... "
                << static_cast<long>(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count())
                << " s " << std::flush;
    std::cerr << "\r" << std::string(70, ' ') << "\r" << std::flush;
    result = work.get();
  } else {
    result = certify_no_interference(options.model, certify);
  }

  std::ostringstream report;
  report << "Tolerance certificate (never interferes) for " << certify.driver << ":" << certify.follower << "\n"
         << "  " << certify.driver << " in [" << to_exact_string(certify.driver_range.lo) << ", "
         << to_exact_string(certify.driver_range.hi) << "]" << unit_of(*driver) << ", " << certify.follower << " in ["
         << to_exact_string(certify.follower_range.lo) << ", " << to_exact_string(certify.follower_range.hi) << "]"
         << unit_of(*follower) << "\n  parameters: "
         << (certify.vary.empty() ? std::string("every toleranced one") : std::to_string(certify.vary.size()) + " named")
         << ", tolerances x " << to_exact_string(certify.scale) << "\n";
  switch (result.outcome) {
    case ToleranceCertification::Outcome::certified:
      report << std::fixed << std::setprecision(3) << "  CERTIFIED: " << result.leaves << " leaves (" << result.attempts << " boxes tried) in "
             << result.seconds_produce << " s, re-checked by the verifier's code in " << result.seconds_verify << " s\n";
      break;
    case ToleranceCertification::Outcome::interferes:
      // The reason names the exact witness: the driver's and follower's rational positions and
      // the parameter deviations (result.witness_*).
      report << "  INTERFERES: " << result.reason << "\n";
      break;
    case ToleranceCertification::Outcome::undecided:
    case ToleranceCertification::Outcome::jams:
      report << "  undecided (no certificate): " << result.reason << "\n";
      break;
  }
  std::cout << report.str();
  if (result.outcome != ToleranceCertification::Outcome::certified || !result.certificate) {
    std::cerr << "hipair: cannot certify: "
              << (result.outcome == ToleranceCertification::Outcome::interferes ? "the parts interfere (exact witness above)"
                                                                                 : "undecided: " + result.reason)
              << "\n";
    return 1;
  }
  if (options.out.empty()) {
    std::cout << "\n(use --out DIR to write interference-certificate.json and report.txt)\n";
    return 0;
  }
  std::filesystem::path directory(options.out);
  std::vector<io::RunFile> files{{"report.txt", report.str()},
                                 {"interference-certificate.json", write_certificate(*result.certificate)}};
  io::publish_directory(directory, files, earlier_output, {options.model});
  std::cout << "\nwrote " << (directory / "report.txt").string() << " " << (directory / "interference-certificate.json").string()
            << "\n(check it with: hipair-verify " << (directory / "interference-certificate.json").string() << " "
            << options.model << ")\n";
  return 0;
}

int run(const ToleranceCliOptions& options) {
  if (!options.pair.empty() && !options.driver.empty())
    throw ModelError("", "give either --pair or --driver, not both");
  if (options.certify_interference && options.chain) throw ModelError("", "--certify-interference is per pair: drop --chain");
  ReadOptions overrides = parameter_overrides(options.overrides, options.allow_out_of_tolerance);
  refuse_unknown_parameters(options.model, options.overrides, "--set");
  // --vary names parameters too (until session 45 "/parameters: unknown parameter 'x' for the
  // threshold search", no option)
  std::vector<std::string> varied;
  OnceEach once_varied("--vary", "parameter");   // (until session 74 a repeat was taken silently)
  for (const std::string& name : options.vary) {
    once_varied.add(name, name);
    varied.push_back(name + "=");
  }
  refuse_unknown_parameters(options.model, varied, "--vary");
  if (options.certify_interference && !overrides.parameter_values.empty())
    throw ModelError("", "--certify-interference certifies the model file as written (hipair-verify checks the "
                         "certificate against it): drop --set, or write the changed nominal values into the model");
  if (options.certify_interference) return run_interference(options);
  if (!options.follower_range.empty()) throw ModelError("", "--follower-range is for --certify-interference");
  ToleranceOptions analysis;
  analysis.parameter_values = overrides.parameter_values;
  analysis.allow_out_of_tolerance = overrides.allow_out_of_tolerance;
  // the design as --set makes it (a 1e-999 mm face on a 40 mm cam): refused before work (session 53)
  require_feature_spread(read_model_file(options.model, overrides));
  if ((options.certify || options.certify_free_path) && !analysis.parameter_values.empty())
    throw ModelError("", "--certify: tolerance certificates are about the model file as written (hipair-verify "
                         "checks them against it): drop --set, or write the changed nominal values into the model");
  if (!options.pair.empty() && !options.driver.empty())
    throw ModelError("", "give either --pair or --driver, not both");
  if (!options.pair.empty()) {
    auto [a, b] = split_pair(options.pair, "--pair");
    // the same refusal as the --certify-interference path's (until session 44 "--pair A:A" here
    // said "/pairs: no pair ... matches the driver and pair asked for", naming no option)
    if (a == b) throw ModelError("", "--pair: '" + a + "' twice (give two different parts)");
    analysis.driver = a;
    analysis.follower = b;
  }
  if (!options.driver.empty()) analysis.driver = options.driver;
  if (!options.range.empty()) analysis.range = driver_range(options.range);
  if (options.assume_nominal_contact && !options.chain) throw ModelError("", "--assume-nominal-contact is for --chain");
  analysis.chain_assume_nominal_holder = options.assume_nominal_contact;
  if (options.given.count("--chain-split-budget") && !options.chain)
    throw ModelError("", "--chain-split-budget is for --chain");
  analysis.chain_failure_boxes = options.chain_split_budget;
  analysis.monte_carlo = options.monte_carlo;
  analysis.seed = options.seed;
  analysis.positions = options.positions;
  analysis.threshold = options.threshold;
  analysis.threshold_bracket = options.threshold_bracket;
  if (options.threshold_bracket > 0 && !options.threshold) throw ModelError("", "--threshold-bracket needs --threshold");
  analysis.threshold_parameters = options.vary;
  analysis.relative_accuracy = options.accuracy;
  analysis.threads = options.threads;
  analysis.certify = options.certify;
  analysis.contact_changes = options.contact_changes;
  analysis.chain = options.chain;
  std::string scale = trim(options.certify_scale);
  if (!scale.empty() && (scale.back() == 'T' || scale.back() == 't')) {
    if (!options.threshold) throw ModelError("", "--certify-scale " + scale + " is relative to the jamming threshold: add --threshold");
    analysis.certify_relative_to_threshold = true;
    scale.pop_back();
  }
  analysis.certify_scale = certify_scale(scale, options.certify_scale);
  analysis.certify_max_leaves = options.certify_leaves;
  analysis.certify_free_path = options.certify_free_path;
  analysis.certify_witness_splits = options.certify_witness_splits;
  // the certificate's scale and budget without a certificate were taken and ignored (session 45;
  // checked after the scale's own checks)
  if (!options.certify && !options.certify_free_path)
    for (const char* option : {"--certify-scale", "--certify-leaves"})
      if (options.given.count(option))
        throw ModelError("", std::string(option) + " is for --certify, --certify-free-path or --certify-interference");
  if (!options.certify && !options.certify_free_path && options.given.count("--certify-witness-splits"))
    throw ModelError("", "--certify-witness-splits is for --certify or --certify-free-path");
  bool terminal = isatty(2) && !options.quiet;
  if (terminal)
    // written when the percent grows (the nominal sweep's fractions are not monotonic: docs/performance.md, session 36)
    analysis.progress = [shown = -1](double fraction) mutable {
      if (static_cast<int>(fraction * 100) <= shown) return;
      shown = static_cast<int>(fraction * 100);
      int width = 30, filled = static_cast<int>(fraction * width);
      std::cerr << "\rtolerance [" << std::string(static_cast<std::size_t>(filled), '#')
                << std::string(static_cast<std::size_t>(width - filled), ' ') << "] "
                << static_cast<int>(fraction * 100) << "% " << std::flush;
    };
  refuse_overwriting_model(options);   // before the (long) analysis
  // a model whose parameters lie beyond the doubles (session 67): their units, for the reports
  std::vector<long> exponents;
  ToleranceResult result = analyze_tolerances(options.model, analysis, exponents);
  if (terminal) std::cerr << "\r" << std::string(50, ' ') << "\r" << std::flush;
  std::string report = tolerance_text_report(result, exponents);
  std::cout << report;
  if (options.out.empty()) {
    std::cout << "\n(use --out DIR to write tolerance.json, the CSV tables and the pictures)\n";
    return 0;
  }
  std::filesystem::path directory(options.out);
  std::vector<io::RunFile> files{{"report.txt", report},
                                 {"tolerance.json", tolerance_json_report(result, exponents)},
                                 {"variation.csv", tolerance_csv(result, exponents)},
                                 {"sensitivity.csv", tolerance_sensitivity_csv(result, exponents)},
                                 {"variation.svg", tolerance_band_svg(result, exponents)},
                                 {"contact-zone.svg", tolerance_zone_svg(result, exponents)}};
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
  command->add_option("--seed", options->seed, "Monte Carlo seed: a whole number from 0 to 18446744073709551615 (default 1)")
      ->check(seed_digits());
  command->add_option("--positions", options->positions, "driver positions per turn for a rotating driver, along the range for a translating one (default 360)")
      ->check(CLI::Range(std::size_t{16}, std::size_t{100000}));
  command->add_flag("--threshold", options->threshold, "find the jamming threshold and confirm it with an exact C-space");
  command->add_option("--threshold-bracket", options->threshold_bracket,
                      "with --threshold: bisect the scale until the bracket is this narrow (relative; e.g. 1e-6), "
                      "an exact jam witness at its upper end confirmed by an exact C-space")
      ->check(real_range(1e-12, 1.0));
  command->add_flag("--chain", options->chain,
                    "analyse the assembly chain from the driver (--driver P, or --pair P:OUTPUT) to its output part: "
                    "the pairs' kinematic functions and sensitivities composed (docs/tolerance.md \"Assembly chains\")");
  command->add_flag("--assume-nominal-contact", options->assume_nominal_contact,
                    "with --chain: follow each pair's nominal touching feature pair over the whole box (no hand-over "
                    "envelope); the band is then certified only under that assumption (docs/tolerance.md \"Hand-overs\")");
  command->add_option("--chain-split-budget", options->chain_split_budget,
                      "with --chain: where a position's band cannot be certified over the whole tolerance box, bisect "
                      "the box into at most this many sub-boxes there (default 4; 1 to 1024; larger bounds more hand-over "
                      "positions at their cost; recorded in tolerance.json's budgets)")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1024}));
  command->add_flag("--contact-changes", options->contact_changes,
                    "look for contacts that appear or disappear for some parameters in the tolerance box; "
                    "confirm each with an exact C-space at a witness vector");
  command->add_option("--vary", options->vary, "parameters the threshold search scales (default: every toleranced one)");
  command->add_option("--accuracy", options->accuracy,
                      "certified band: at most this much (relative) wider than the linearised one (default 0.1)")
      ->check(real_range(1e-6, 10.0));
  command->add_option("--threads", options->threads,
                      "threads for the Monte Carlo, the certified band and the zones (default 0: all cores; at most 256)")
      ->check(CLI::Range(0u, 256u));
  command->add_option("--out", options->out, "directory for tolerance.json, variation.csv, sensitivity.csv, variation.svg, contact-zone.svg")
      ->check(output_path());
  command->add_flag("--quiet", options->quiet, "no progress bar");
  command->add_option("--set", options->overrides,
                      "change a parameter's nominal value: NAME=VALUE (exact literal in mm or rad; repeatable); its "
                      "tolerance moves with it (a range stays)");
  command->add_flag("--allow-out-of-tolerance", options->allow_out_of_tolerance,
                    "accept --set values outside the parameter's tolerance range");
  command->add_flag("--certify", options->certify,
                    "interval branch-and-bound showing that the channel's named contact sides stay apart for any "
                    "parameters in the box; writes tolerance-certificate.json, which hipair-verify answers 'valid' "
                    "when it also proves a free follower path across the range, else 'unproven' (docs/certify.md)");
  command->add_option("--certify-scale", options->certify_scale,
                      "the certificate's box: this times the varied tolerance ranges (default 1; --vary names them); "
                      "with a T suffix (0.95T), times the jamming threshold found by --threshold");
  command->add_option("--certify-leaves", options->certify_leaves, "give up beyond this many leaves (default 20000)")
      ->check(CLI::Range(std::size_t{1}, std::size_t{10000000}));
  command->add_flag("--certify-free-path", options->certify_free_path,
                    "with --certify: accept a leaf only when the verifier's check 7 also proves its witness path "
                    "free (else split it), so that the certificate verifies 'valid' where the plain search writes "
                    "an 'unproven' one");
  command->add_option("--certify-witness-splits", options->certify_witness_splits,
                      "with --certify: split a leaf whose sides are proved apart but which has no witness follower "
                      "path at most this many times along a branch (default 6; 0 to 64); beyond, it is accepted and "
                      "the certificate is written 'unproven', naming that leaf")
      ->check(CLI::Range(std::size_t{0}, std::size_t{64}));
  command->add_flag("--certify-interference", options->certify_interference,
                    "instead of the analysis: prove that the pair never interferes for any parameters in the box, "
                    "driver in --range and follower in --follower-range; writes interference-certificate.json "
                    "(check it with hipair-verify)");
  command->add_option("--follower-range", options->follower_range,
                      "--certify-interference: the follower's range A:B, or one value for a follower held still");
  command->callback([options, &action, command] {
    options->given = given_options(*command);
    action = [options] { return run(*options); };
  });
}

}  // namespace hipair::cli
