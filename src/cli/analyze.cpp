// `hipair analyze MODEL [--driver PART] [--direction cw|ccw|+|-] [--range A:B | --cycles N]
// [--out DIR] ...`: kinematic analysis — prints the report for designers and writes
// report.json, kinematics.csv, kinematics.svg and cspace-PAIR.svg into DIR.
#include "cli/analyze_pinslot.hpp"
#include "cli/commands.hpp"

#include "core/length_display.hpp"
#include "core/model_scale.hpp"
#include "io/atomic_file.hpp"
#include "io/output_directory.hpp"
#include "io/output_paths.hpp"
#include "render/cspace_svg.hpp"
#include "render/kinematics_svg.hpp"

#include <hipair/certificate.hpp>
#include <hipair/contact_labels.hpp>
#include <hipair/cspace_region.hpp>
#include <hipair/error.hpp>
#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>
#include <hipair/motion_words.hpp>
#include <hipair/shared_curves.hpp>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <numbers>
#include <optional>

namespace hipair::cli {
namespace {

// At most this many turns (or cycles) of the driver: the analysis keeps every turn's samples.
constexpr long max_turns = 100;

struct AnalyzeOptions {
  std::string model;
  std::vector<std::string> overrides;
  bool allow_out_of_tolerance = false;
  std::string rounding;
  std::string driver;
  std::string direction;
  std::string range;
  std::string cycles = "1";
  std::string out;
  unsigned steps = 720;
  std::vector<std::string> loads;
  bool no_model_loads = false;
  std::vector<std::string> expected;
  bool accelerations = false;
  bool no_reversal = false;
  std::string method = "auto";
  unsigned columns = 240;
  bool no_pictures = false;
  bool quiet = false;
  std::set<std::string> given;   // the long options given on the command line
};

// A number with an optional unit suffix: angles in the model's unit unless "deg"/"rad" is
// given; converted to rad (degrees through a double: a driver position, rounded anyway).
Rational coordinate_value(const std::string& text, bool angle, const std::string& unit, const std::string& what) {
  const auto [body, suffix] = split_unit_suffix(text, {"deg", "rad", "mm"}, angle ? unit : "mm");
  Rational value;
  try {
    value = parse_rational(body);
  } catch (const Error& error) {   // the parser's message quotes at most 40 characters of it
    throw ModelError("", what + ": " + error.what());
  }
  if (angle && suffix == "deg") return degrees_to_radians(value);
  if (!angle && suffix != "mm") throw ModelError("", what + ": a translating driver takes mm");
  return value;
}

FollowerLoad parse_load(const std::string& text, std::string& part) {
  std::size_t equals = text.find('=');
  if (equals == std::string::npos) throw ModelError("", "--load expects PART=none|+|-|cw|ccw|spring:REST, got '" + text + "'");
  part = trim(text.substr(0, equals));
  std::string value = trim(text.substr(equals + 1));
  FollowerLoad load;
  load.source = "--load " + text;
  if (value == "none") load.kind = FollowerLoad::Kind::none;
  else if (value == "+" || value == "ccw") load.kind = FollowerLoad::Kind::positive;
  else if (value == "-" || value == "cw") load.kind = FollowerLoad::Kind::negative;
  else if (value.rfind("spring:", 0) == 0) {
    load.kind = FollowerLoad::Kind::spring;
    try {
      load.rest = parse_rational(trim(value.substr(7)));
    } catch (const Error&) {
      throw ModelError("", "--load " + text + ": the rest position is not a number");
    }
  } else {
    throw ModelError("", "--load " + text + ": expected none, +, -, cw, ccw or spring:REST");
  }
  return load;
}

std::string file_name_part(const std::string& text) {
  std::string out;
  for (char c : text) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') ? c : '-';
  return out;
}

// Files that `analyze --out` writes; those of an earlier run that this run does not write
// again (a C-space picture of another pair, a certificate it no longer finds) are removed.
bool earlier_output(const std::string& name) {
  auto ends_with = [&](const std::string& suffix) {
    return name.size() >= suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  if (name == "report.json" || name == "kinematics.csv" || name == "kinematics.svg") return true;
  if (name.rfind("cspace-", 0) == 0 && ends_with(".svg")) return true;
  if (name.rfind("certificate-", 0) == 0 && ends_with(".json")) {
    std::string number = name.substr(12, name.size() - 12 - 5);
    return !number.empty() && number.find_first_not_of("0123456789") == std::string::npos;
  }
  return false;
}

bool can_drive(const Part& part) {
  return part.motion.kind == Motion::Kind::rotation || part.motion.kind == Motion::Kind::translation;
}

// The part to drive: `--driver` checked, or the first rotating or translating part of the first
// pair that has one; the messages say which parts could drive, or why none can.
std::size_t choose_driver(const Model& model, const std::string& requested) {
  std::vector<std::string> candidates;
  for (const PairSpec& pair : model.pairs)
    for (std::size_t k : {pair.first, pair.second}) {
      const std::string& name = model.parts[k].name;
      if (can_drive(model.parts[k]) && std::find(candidates.begin(), candidates.end(), name) == candidates.end())
        candidates.push_back(name);
    }
  auto list = [](const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& name : names) out += (out.empty() ? "'" : ", '") + name + "'";
    return out;
  };
  if (!requested.empty()) {
    auto index = model.find_part(requested);
    std::string hint = candidates.empty() ? "no part of a pair rotates or translates, so none can drive"
                                          : "parts that can drive: " + list(candidates);
    if (!index) throw ModelError("", "--driver: no part named '" + requested + "' (" + hint + ")");
    if (!can_drive(model.parts[*index]))
      throw ModelError("", "--driver: part '" + requested + "' is " + motion_adjective(model.parts[*index].motion.kind) +
                               "; analyze drives a rotating or translating part (" + hint + ")");
    return *index;
  }
  if (!candidates.empty()) return *model.find_part(candidates.front());
  std::string parts;
  for (const PairSpec& pair : model.pairs)
    for (std::size_t k : {pair.first, pair.second}) {
      std::string item = "'" + model.parts[k].name + "' " + motion_adjective(model.parts[k].motion.kind);
      if (parts.find(item) == std::string::npos) parts += (parts.empty() ? "" : ", ") + item;
    }
  if (model.pairs.empty())
    throw ModelError("/pairs", "nothing to drive: the model has no pair of parts that can touch");
  throw ModelError("/pairs", "nothing to drive: analyze drives a rotating or translating part of a pair, and the "
                             "pairs have only fixed, planar or pin-slot parts (" + parts + ")");
}

// The exact C-space to draw a pair's path on: a whole space the analysis was given, or one
// built now — the whole space when the pair is small (a few hundred boundary edges build in
// about a second), else its operating region along the path: the tiles of the channel the
// path starts in that the path runs through (a gear pair's z1 + z2 tooth encounters instead
// of z1 z2, and of those only the ones the analysed turns meet, where slicing 240 columns of
// the whole space cost more than the analysis itself); nullopt: draw the sampled picture
// instead (a pair the builder cannot handle).
std::optional<CSpace> exact_space_for_picture(const Model& model, const PairPath& path, const std::vector<CSpace>& spaces) {
  for (const CSpace& space : spaces)
    if (space.complete() && space.dimension() == 2 && space.x_part() == path.x_part && space.y_part() == path.y_part)
      return space;
  auto x = model.find_part(path.x_part), y = model.find_part(path.y_part);
  if (!x || !y) return std::nullopt;
  std::size_t edges = 0;
  for (std::size_t part : {*x, *y})
    for (const Loop& loop : model.parts[part].loops) edges += loop.edges.size();
  try {
    std::vector<std::array<double, 2>> along;
    for (const PathPoint& point : path.points) along.push_back({point.x, point.y});
    CSpaceBuildOptions options;
    options.operating_region = edges > 120;   // a path-less large pair: its whole flooded region
    CSpace space = edges > 120 && !along.empty()
                       ? build_operating_region_along(model, path.x_part, path.y_part, along)
                       : CSpace::build(model, path.x_part, path.y_part, options);
    if (space.dimension() == 2 && space.x_part() == path.x_part && space.y_part() == path.y_part) return space;
  } catch (const GeometryError&) {   // a pair the builder cannot handle: the sampled picture
  } catch (const NumericError&) {
  }
  return std::nullopt;
}

int run_analyze(const AnalyzeOptions& options) {
  // refused before the analysis when a file every run writes is the model; the whole list of
  // the run's files is checked again before anything is written
  io::refuse_unusable_output_directory(options.out, "--out");
  if (!options.out.empty())
    for (const char* name : {"report.json", "kinematics.csv", "kinematics.svg"})
      if (!options.no_pictures || std::string(name) != "kinematics.svg")
        io::refuse_overwriting_input(std::filesystem::path(options.out) / name, "--out", options.model);
  OnceEach once_per_part("--load", "part");   // (part names as parse_load reads them: trimmed)
  for (const std::string& text : options.loads)
    if (auto equals = text.find('='); equals != std::string::npos) once_per_part.add(trim(text.substr(0, equals)), text);
  auto rounding = rounding_scope(options.rounding);
  ReadOptions overrides = parameter_overrides(options.overrides, options.allow_out_of_tolerance);
  refuse_unknown_parameters(options.model, options.overrides, "--set");
  Model model = read_model_file(options.model, overrides);
  require_feature_spread(model);   // a 1e-999 mm face on a 40 mm cam: refused before work (session 53)
  // a pin-in-slot follower (the film advance): its work cycle (cli/analyze_pinslot.cpp), which
  // takes --driver, --direction, --steps, --out and --quiet; an option of the driven analysis is
  // refused naming it (session 45: they were taken and ignored)
  if (has_pin_slot_part(model))
    for (const char* option : {"--range", "--cycles", "--load", "--no-model-loads", "--expect", "--accelerations",
                               "--no-reversal", "--method", "--columns", "--no-pictures"})
      if (options.given.count(option))
        throw ModelError("", std::string(option) +
                                 ": does not apply to a model with a pin-in-slot part, whose analysis is its work cycle "
                                 "(one turn of the driver in --steps steps; it takes --driver, --direction, --steps, "
                                 "--out and --quiet)");
  if (has_pin_slot_part(model)) {
    // at an extreme scale (lengths outside about 1e-9 .. 1e9 mm) the cycle runs on the model
    // divided exactly by 10^E, as the driven analysis below (session 54: the film advance at
    // 10^-300 gave another cycle, at 10^400 it was refused); its lengths shown in mm
    const long exponent = kinematic_decimal_exponent(model);
    if (exponent != 0) model = decimal_scaled_model(model, exponent);
    LengthDisplayScope length_display(exponent);
    return run_pin_slot_cycle(model, PinSlotCycleRequest{options.driver, options.direction,
                                                         options.steps == 720 ? 72u : options.steps, options.out,
                                                         options.quiet});
  }
  // A mechanism with a translating part drawn at an extreme scale (lengths outside about 1e-9 mm
  // .. 1e9 mm: the analysis's resolutions are absolute) is analysed on the model exactly divided
  // by 10^E (core/model_scale.hpp, kinematic_decimal_exponent), and every length is shown in mm
  // with the exponent written out (core/length_display.hpp); until session 53 it was refused.
  // --range (a translating driver) and --load spring rests (a translating part) are given in mm
  // and divided likewise below.
  const long length_exponent = kinematic_decimal_exponent(model);
  // a rotation-only mechanism's findings are angles: certified on the model as read (below)
  const std::optional<Model> rotation_only =
      length_exponent != 0 && std::none_of(model.parts.begin(), model.parts.end(),
                                           [](const Part& part) {
                                             return part.motion.kind != Motion::Kind::rotation && part.motion.kind != Motion::Kind::fixed;
                                           })
          ? std::optional<Model>(model)
          : std::nullopt;
  if (length_exponent != 0) model = decimal_scaled_model(model, length_exponent);
  LengthDisplayScope length_display(length_exponent);
  auto to_copy_units = [&](Rational mm) {
    if (length_exponent == 0) return mm;
    mpz_class power;
    mpz_ui_pow_ui(power.get_mpz_t(), 10, static_cast<unsigned long>(std::labs(length_exponent)));
    return length_exponent > 0 ? Rational(mm / Rational(power)) : Rational(mm * Rational(power));
  };
  KinematicsOptions analysis;
  analysis.driver = options.driver;
  analysis.steps_per_cycle = options.steps;
  analysis.accelerations = options.accelerations;
  analysis.reversal = !options.no_reversal;
  analysis.expected_contacts = options.expected;
  analysis.model_loads = !options.no_model_loads;
  if (options.method == "kernels") analysis.method = SliceMethod::kernels;
  else if (options.method == "cspace") analysis.method = SliceMethod::cspace;
  else if (options.method != "auto") throw ModelError("", "--method expects auto, kernels or cspace");
  for (const std::string& text : options.loads) {
    std::string part;
    FollowerLoad load = parse_load(text, part);
    if (!model.find_part(part)) throw ModelError("", "--load: no part named '" + part + "'");
    if (load.kind == FollowerLoad::Kind::spring && model.parts[*model.find_part(part)].motion.kind != Motion::Kind::rotation)
      load.rest = to_copy_units(load.rest);   // a rest offset in mm (a rest angle is no length)
    analysis.loads[part] = load;
  }
  // which part is driven decides the units of --range
  std::size_t driver_index = choose_driver(model, options.driver);
  // a driver named by --driver whose chain of pairs reaches no moving part: refused naming the
  // option (session 75, drive75: the analysis said "/pairs: part 'bar' drives no other part",
  // as it still does for the part it chooses itself)
  if (!options.driver.empty()) {
    bool moves_another = false;
    for (std::size_t p : driven_pairs(model, driver_index))
      for (std::size_t k : {model.pairs[p].first, model.pairs[p].second})
        moves_another = moves_another || (k != driver_index && model.parts[k].motion.kind != Motion::Kind::fixed);
    if (!moves_another)
      throw ModelError("", "--driver " + shown_name(options.driver) + ": part '" + shown_name(options.driver) +
                               "' drives no other part (its pairs are with fixed parts only; where a fixed part "
                               "stops it is shown by 'hipair cspace' and 'hipair certify')");
  }
  // a pattern no contact label of the driven pairs contains matches nothing: every contact
  // would be reported as unintended (session 45: `--expect nobody` was taken silently; session
  // 46: a pattern of a pair the driver does not move, such as a second mechanism's, likewise)
  if (!options.expected.empty()) {
    std::vector<std::size_t> driven = driven_pairs(model, driver_index);
    for (const std::string& pattern : options.expected) {
      if (contact_label_can_contain(model, pattern, driven)) continue;
      if (!contact_label_can_contain(model, pattern))
        throw ModelError("", shortened_message("--expect " + pattern) +
                                 ": no contact of the model's pairs has a label containing it (a label names both "
                                 "parts and features and how they touch, e.g. 'driver pin / wheel slot 1 wall R (arc "
                                 "tangent to segment)'; the report's contact sequence lists them)");
      auto pair_name = [&](std::size_t p) {
        return shown_name(model.parts[model.pairs[p].first].name) + ":" + shown_name(model.parts[model.pairs[p].second].name);
      };
      std::string others, chain;
      for (std::size_t p = 0; p < model.pairs.size(); ++p)
        if (std::find(driven.begin(), driven.end(), p) == driven.end() &&
            contact_label_can_contain(model, pattern, std::vector<std::size_t>{p}))
          others += (others.empty() ? "" : ", ") + pair_name(p);
      for (std::size_t p : driven) chain += (chain.empty() ? "" : ", ") + pair_name(p);
      throw ModelError("", shortened_message("--expect " + pattern) + ": only a contact of " + others +
                               " has a label containing it, a pair the analysis driven by '" +
                               shown_name(model.parts[driver_index].name) + "' does not move (its pairs: " +
                               (chain.empty() ? std::string("none") : chain) + "; --driver chooses the driver)");
    }
  }
  // a load acts on a driven part: one on the driver, or on a part that is not driven by the
  // analysis (fixed, planar, pin-slot), was taken and ignored until session 45
  for (const auto& [part, load] : analysis.loads) {
    const Part& loaded = model.parts[*model.find_part(part)];
    if (&loaded == &model.parts[driver_index])
      throw ModelError("", load.source + ": '" + part + "' is the driver; a load acts on a driven part (the driver moves "
                                         "as --range / --direction say)");
    if (!can_drive(loaded))
      throw ModelError("", load.source + ": '" + part + "' is " + motion_adjective(loaded.motion.kind) +
                               "; a load acts on a rotating or translating part the driver pushes");
    // a part no pair of the driver's chain moves is not analysed: its load was taken and
    // ignored until session 46 (a second mechanism's part, an unconnected one)
    bool driven = false;
    for (std::size_t p : driven_pairs(model, driver_index))
      driven = driven || model.parts[model.pairs[p].first].name == part || model.parts[model.pairs[p].second].name == part;
    if (!driven)
      throw ModelError("", load.source + ": '" + part + "' is not moved by the analysis driven by '" +
                               shown_name(model.parts[driver_index].name) +
                               "' (no chain of pairs connects them; --driver chooses the driver)");
  }
  analysis.driver = model.parts[driver_index].name;
  bool rotates = model.parts[driver_index].motion.kind == Motion::Kind::rotation;
  std::string direction_note;
  if (options.direction.empty() && options.range.empty()) {
    // no direction given: the way the model's driving torque or force turns the driver
    const Part& driver_part = model.parts[driver_index];
    if (driver_part.dynamics && driver_part.dynamics->torque && rotates && sgn(*driver_part.dynamics->torque) != 0) {
      analysis.direction = sgn(*driver_part.dynamics->torque);
      direction_note = std::string("direction: ") + (analysis.direction > 0 ? "counter-clockwise" : "clockwise") +
                       ", as the model's driving torque turns " + driver_part.name + " (--direction to change)";
    }
  }
  if (!options.direction.empty()) {
    const std::string& d = options.direction;
    if (d == "ccw" || d == "+") analysis.direction = 1;
    else if (d == "cw" || d == "-") analysis.direction = -1;
    else throw ModelError("", "--direction expects cw, ccw, + or -");
    if (!rotates && (d == "cw" || d == "ccw")) throw ModelError("", "--direction: a translating driver moves + or -");
  }
  if (!options.range.empty()) {
    std::size_t colon = options.range.find(':');
    if (colon == std::string::npos) throw ModelError("", "--range expects A:B");
    Rational a = coordinate_value(options.range.substr(0, colon), rotates, model.angle_unit, "--range");
    Rational b = coordinate_value(options.range.substr(colon + 1), rotates, model.angle_unit, "--range");
    if (a == b) throw ModelError("", "--range: the range is empty");
    // the analysis keeps every turn's samples (about 3.5 MB and 0.3 s a turn for the cam
    // follower): 30,000 turns ran out of memory before "driver range too long" (hunt41)
    if (rotates && abs(Rational(b - a)) > Rational(2 * max_turns) * Rational(355, 113))
      throw ModelError("", "--range " + options.range + ": more than " + std::to_string(max_turns) +
                               " turns of the driver (analyse a shorter range)");
    if (!options.direction.empty() && (b > a) != (analysis.direction > 0))
      throw ModelError("", "--range runs against --direction");
    if (!rotates) {
      a = to_copy_units(a);
      b = to_copy_units(b);
    }
    analysis.range = std::make_pair(a, b);
  } else {
    try {
      analysis.cycles = parse_rational(options.cycles);
    } catch (const Error&) {
      throw ModelError("", "--cycles: '" + options.cycles + "' is not a number");
    }
    if (analysis.cycles <= 0) throw ModelError("", "--cycles must be positive");
    if (analysis.cycles > max_turns)
      throw ModelError("", "--cycles " + options.cycles + ": at most " + std::to_string(max_turns) + " cycles");
  }
  bool terminal = isatty(2) && !options.quiet;
  if (terminal)
    // written when the whole percent changes: each grid step wrote it until session 36 (a
    // 1 500 rad range wrote 2.5 MB of progress to the terminal)
    analysis.progress = [shown = -1](double fraction) mutable {
      int percent = static_cast<int>(fraction * 100);
      if (percent == shown) return;
      if (shown < 0) std::cerr << "\r" << std::string(60, ' ');   // the initial stage's line below
      shown = percent;
      std::cerr << "\ranalyze: " << percent << "% " << std::flush;
    };
  // the analysis's kernel slicers form each pair's contact curves; the C-space pictures below
  // build the same pairs and take those curves instead of forming them again (same pictures)
  SharedContactCurves shared_curves;
  std::vector<CSpace> spaces;
  if (analysis.method == SliceMethod::cspace) {
    CSpaceBuildOptions build;
    if (terminal) build.progress = stderr_progress();
    spaces = CSpace::build_all(model, build);
  }
  // the initial configuration's slices come before the sweep's first percent (a 100 x 103 gear
  // pair: 15 s, silent until session 37)
  if (terminal) std::cerr << "\ranalyze: slicing the initial configuration..." << std::flush;
  KinematicsResult result = analyze_kinematics(model, analysis, spaces);
  if (terminal) std::cerr << "\r              \r" << std::flush;
  if (!direction_note.empty()) std::cout << "(" << direction_note << ")\n";
  std::cout << kinematics_text_report(result);
  if (options.out.empty()) {
    std::cout << "\n(use --out DIR to write report.json, kinematics.csv and the pictures)\n";
    return 0;
  }
  std::filesystem::path directory(options.out);
  // Every file of the run is made in memory, then published together (or not at all).
  std::vector<io::RunFile> files;
  files.push_back({"report.json", kinematics_json_report(result)});
  files.push_back({"kinematics.csv", kinematics_csv(result)});
  if (!options.no_pictures) {
    files.push_back({"kinematics.svg", render::kinematics_plot_svg(result)});
    for (const PairPath& path : result.paths) {
      if (path.y_part.empty()) continue;
      if (terminal) std::cerr << "\ranalyze: drawing the C-space of " << path.pair << "..." << std::flush;
      std::string name = "cspace-" + file_name_part(path.x_part) + "-" + file_name_part(path.y_part) + ".svg";
      if (std::optional<CSpace> exact = exact_space_for_picture(model, path, spaces)) {
        // the exact arrangement (as `hipair cspace` draws it) with the path over it
        render::CSpaceSvgOptions picture;
        for (const PathPoint& point : path.points) picture.path.push_back({point.x, point.y, point.contact});
        if (!path.points.empty()) picture.marks.push_back({path.points.front().x, path.points.front().y, "start"});
        picture.title = "exact C-space of " + path.pair + " with the motion path";
        if (length_exponent != 0) picture.title += " (lengths in units of " + length_unit_name() + ")";
        if (!exact->complete())
          picture.title += " (built: operating region along the path, " +
                           std::to_string(exact->statistics().region_tiles) + " tiles)";
        files.push_back({name, render::cspace_svg(*exact, picture)});
      } else {
        CSpaceRaster raster = sample_cspace(model, path.x_part, path.y_part, options.columns);   // axes: length_unit_name()
        files.push_back({name, render::cspace_path_svg(raster, path)});
      }
      if (terminal) std::cerr << "\r" << std::string(60, ' ') << "\r" << std::flush;
    }
  }
  // Certificates for the interference and jamming findings (docs/certify.md), about the model
  // read with the --set values (recorded as overridden, as `hipair certify --set` does).
  // `hipair-verify` reads the file with its own rounding key: under --rounding the certificate is
  // checked against the file as the verifier will read it, and written only if it verifies there.
  // A rotation-only mechanism's findings are angles, the same on the rescaled copy: certified on
  // the model as read (certify_kinematic_findings normalises it itself). Any other rescaled
  // copy's certificate would hold the copy's offsets and points, which the verifier checks
  // against the model file: none is given, the finding stays with the reason.
  std::vector<CertifiedFinding> findings =
      certify_kinematic_findings(rotation_only ? *rotation_only : model, result, CertifyContext{overrides.parameter_values});
  if (length_exponent != 0 && !rotation_only)
    for (CertifiedFinding& finding : findings)
      if (finding.certificate) {
        finding.certificate.reset();
        finding.note = "the analysis ran on the model divided by 1e" + std::to_string(length_exponent) +
                       " (its lengths beyond about 1e-9 .. 1e9 mm); a certificate would be about that copy: certify "
                       "the model itself with `hipair certify`";
      }
  bool rounding_given = rounding != nullptr;
  rounding.reset();   // the verifier's reading: the file's own rounding
  std::string model_text = rounding_given && !findings.empty() ? io::read_file(options.model) : std::string();
  std::size_t certificates = 0;
  for (const CertifiedFinding& finding : findings) {
    if (!finding.certificate) {
      std::cout << "not certified: " << finding.finding << " (" << finding.note << ")\n";
      continue;
    }
    if (rounding_given) {
      VerificationResult check = check_certificate_text(*finding.certificate, model_text, options.model);
      if (!check.valid) {
        std::cout << "not certified: " << finding.finding << " (--rounding " << options.rounding
                  << " reads the model otherwise than hipair-verify, which reads the file's own rounding: "
                  << check.reason << ")\n";
        continue;
      }
    }
    files.push_back({"certificate-" + std::to_string(++certificates) + ".json", write_certificate(*finding.certificate)});
  }
  std::vector<io::PlannedOutput> planned;
  for (const io::RunFile& file : files) planned.push_back({directory / file.name, "--out"});
  io::refuse_overwriting_inputs(planned, {options.model});
  io::publish_directory(directory, files, earlier_output, {options.model});
  std::vector<std::string> written;
  for (const io::RunFile& file : files) written.push_back(file.name);
  std::cout << "\nwrote";
  for (const std::string& name : written) std::cout << " " << (directory / name).string();
  std::cout << "\n";
  return 0;
}

}  // namespace

void register_analyze(CLI::App& app, Action& action) {
  auto options = std::make_shared<AnalyzeOptions>();
  CLI::App* command = app.add_subcommand(
      "analyze", "Kinematic analysis: drive one part and report how the others move (contacts, dwell, play, jamming)");
  command->add_option("model", options->model, "model file (JSON, see docs/model-format.md)")->required();
  add_parameter_options(command, options->overrides, options->allow_out_of_tolerance);
  add_rounding_option(command, options->rounding);
  command->add_option("--driver", options->driver, "part to drive (default: the first moving part of the first pair)");
  command->add_option("--direction", options->direction, "cw, ccw (rotation) or +, - (default: the sense of the model's driving torque, else ccw / +)");
  auto* range = command->add_option("--range", options->range,
                                    "driver range A:B (angles in the model's unit or with a deg/rad suffix; mm)");
  command->add_option("--cycles", options->cycles, "full driver turns from the initial configuration (default 1)")
      ->excludes(range);
  command->add_option("--out", options->out, "directory for report.json, kinematics.csv, kinematics.svg, cspace-*.svg")
      ->check(output_path());
  command->add_option("--steps", options->steps, "driver grid steps per turn (default 720)")->check(CLI::Range(16u, 100000u));
  command->add_option("--load", options->loads,
                      "load on a driven part: PART=none|+|-|cw|ccw|spring:REST (replaces the model's dynamics data)");
  command->add_flag("--no-model-loads", options->no_model_loads, "ignore springs/torques/forces of the model");
  command->add_option("--expect", options->expected,
                      "label text of an expected contact; every other contact is reported as unintended");
  command->add_flag("--accelerations", options->accelerations, "also sample accelerations into the CSV");
  command->add_flag("--no-reversal", options->no_reversal, "skip the lost-motion (reversal) checks");
  command->add_option("--method", options->method, "slices from: auto (default), kernels, cspace");
  command->add_option("--columns", options->columns, "columns of the C-space pictures (default 240)")
      ->check(CLI::Range(16u, 4000u));
  command->add_flag("--no-pictures", options->no_pictures, "write no SVG pictures");
  command->add_flag("--quiet", options->quiet, "no progress on the terminal");
  command->callback([&action, options, command] {
    options->given = given_options(*command);
    action = [options] { return run_analyze(*options); };
  });
}

}  // namespace hipair::cli
