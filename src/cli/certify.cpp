// `hipair certify MODEL --claim interference|clearance|jam|free --out CERT`: produces a
// certificate that hipair-verify re-checks independently (docs/certify.md).
#include <hipair/closing_jam.hpp>
#include "cli/angles.hpp"
#include "core/model_scale.hpp"
#include "cli/commands.hpp"
#include "io/atomic_file.hpp"
#include "io/output_paths.hpp"
#include "model/interval.hpp"

#include <hipair/certificate.hpp>
#include <hipair/error.hpp>
#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>
#include <hipair/motion_words.hpp>
#include <hipair/sliced_apart.hpp>
#include <hipair/sliced_certificate.hpp>

#include <cmath>
#include <iostream>
#include <memory>
#include <new>
#include <set>

namespace hipair::cli {
namespace {

struct CertifyArguments {
  std::string path, claim, out, pair, driver, trap;
  std::vector<std::string> overrides, at;
  std::vector<std::string> to;   // free: one driver value; connected/apart: the end pose (a pin-slot pair: and the other part's position)
  std::string distance, from, follower_at, ratio, start, follower_start, step, travel;
  std::string direction = "+1";
  bool allow_out_of_tolerance = false;
  std::set<std::string> given;   // the long options given on the command line
};

// Each claim's own options: one given for another claim is refused naming it (session 45: `--claim
// jam --at lever=0`, `--claim interference --distance 1` and the jam search's `--step` with a
// `--trap` were taken and ignored).
void refuse_options_of_other_claims(const CertifyArguments& arguments) {
  static const std::vector<std::pair<const char*, std::set<std::string>>> claims_of = {
      {"--at", {"interference", "clearance", "connected", "apart"}},
      {"--distance", {"clearance", "free"}},
      {"--driver", {"jam", "free"}},
      {"--from", {"free"}},
      {"--to", {"free", "connected", "apart"}},
      {"--follower-at", {"free"}},
      {"--ratio", {"free"}},
      {"--direction", {"jam"}},
      {"--trap", {"jam"}},
      {"--start", {"jam"}},
      {"--follower-start", {"jam"}},
      {"--step", {"jam"}},
      {"--travel", {"jam"}}};
  for (const auto& [option, claims] : claims_of) {
    if (!arguments.given.count(option) || claims.count(arguments.claim)) continue;
    std::string names;
    for (const std::string& claim : claims) names += (names.empty() ? "" : " or ") + claim;
    throw ModelError("", std::string(option) + ": applies to --claim " + names + ", not to --claim " + arguments.claim);
  }
  if (arguments.claim == "jam" && arguments.given.count("--trap"))
    for (const char* option : {"--start", "--follower-start", "--step", "--travel"})
      if (arguments.given.count(option))
        throw ModelError("", std::string(option) + ": sets the jam search, and --trap names the trap (nothing is searched): "
                                                   "give one or the other");
}

// --direction: exactly +1 (the driver's coordinate increases) or -1; "+" and "-" are synonyms.
int direction_of(const std::string& text) {
  if (text == "+1" || text == "1" || text == "+") return 1;
  if (text == "-1" || text == "-") return -1;
  throw ModelError("", "--direction must be +1 or -1 (or + / -), not '" + text + "'");
}

// An exact literal; angles may end in "deg" (then converted to rad, rounded to 1e-18). A
// position (--at) is read by exact_position_from_text instead: whole quarter turns exact.
Rational value_of(const std::string& text, bool angle, const std::string& option) {
  AngleLiteral literal = parse_angle_literal(text, angle, option);
  return literal.degrees ? degrees_to_radians(literal.value) : literal.value;
}

bool rotates(const Part& part) { return part.motion.kind == Motion::Kind::rotation; }
Rational coordinate(const Part& part) { return rotates(part) ? part.initial.angle : part.initial.offset; }

// An --at angle (rad, or exact at whole quarter turns in deg); an angle in degrees that had to
// be rounded adds how it was taken to `notes` (printed with the result).
ExactPosition angle_at(const std::string& text, std::vector<std::string>& notes, const std::string& option = "--at") {
  ExactPosition position = exact_position_from_text(text, option);
  if (std::string label = angle_label(text, position); !label.empty()) notes.push_back(option + ": " + label);
  return position;
}

// --at PART=VALUE: a rotating part's angle, a translating part's offset (mm).
ExactPosition position_of(const Part& part, const std::string& text, std::vector<std::string>& notes) {
  if (rotates(part)) return angle_at(text, notes);
  return ExactPosition{value_of(text, false, "--at"), true, false, {}, {}};
}

std::pair<std::string, std::string> pair_of(const Model& model, const std::string& text) {
  if (text.empty()) {
    if (model.pairs.empty()) throw ModelError("/pairs", "the model has no pairs: give --pair A:B");
    return {model.parts[model.pairs[0].first].name, model.parts[model.pairs[0].second].name};
  }
  auto colon = text.find(':');
  if (colon == std::string::npos) throw ModelError("", "--pair expects A:B, got '" + text + "'");
  return {text.substr(0, colon), text.substr(colon + 1)};
}

// a part named by an option (--pair, --at, --driver): an unknown name is refused naming the
// option and the parts there are (until session 44: "/parts: no part called 'x'", no option)
const Part& part_named(const Model& model, const std::string& name, const std::string& option) {
  auto index = model.find_part(name);
  if (!index) {
    std::string names;
    for (const Part& part : model.parts) names += (names.empty() ? "'" : ", '") + part.name + "'";
    throw ModelError("", option + ": no part called '" + name + "' (the parts: " + names + ")");
  }
  return model.parts[*index];
}

// a part named by --at or --driver must be one of the pair's two parts (until session 44 a third
// part's name was taken: --driver drove a part outside the pair, --at placed one)
void refuse_outside_pair(const Part& part, const Part& a, const Part& b, const std::string& option) {
  if (&part != &a && &part != &b)
    throw ModelError("", option + ": '" + part.name + "' is not in the pair " + a.name + ":" + b.name +
                             " (give --pair to choose the pair)");
}

RationalInterval range_of(const std::string& text, bool angle, const std::string& option) {
  auto colon = text.find(':');
  if (colon == std::string::npos) throw ModelError("", option + " expects LO:HI, got '" + text + "'");
  RationalInterval range{value_of(text.substr(0, colon), angle, option), value_of(text.substr(colon + 1), angle, option)};
  if (!(range.lo < range.hi)) throw ModelError("", option + " " + text + ": LO must be below HI");
  return range;
}

// The pose of a planar part: the model's initial pose, or OPTION PART=X,Y,ANGLE (the angle in rad
// or NNdeg, rounded to an exact half-angle tangent; exact at whole quarter turns in degrees).
PlanarPose planar_pose(const Part& planar, const std::vector<std::string>& assignments, const std::string& option,
                       std::vector<std::string>& notes) {
  Rational x = planar.initial.x, y = planar.initial.y;
  ExactPosition rotation = exact_position_from_angle(planar.initial.angle);
  for (const std::string& assignment : assignments) {
    auto equals = assignment.find('=');
    if (equals == std::string::npos || assignment.substr(0, equals) != planar.name)
      throw ModelError("", option + " expects " + planar.name + "=X,Y,ANGLE for the planar part, got '" + assignment + "'");
    std::string rest = assignment.substr(equals + 1);
    auto c1 = rest.find(','), c2 = c1 == std::string::npos ? c1 : rest.find(',', c1 + 1);
    if (c2 == std::string::npos) throw ModelError("", option + " expects " + planar.name + "=X,Y,ANGLE, got '" + assignment + "'");
    x = value_of(rest.substr(0, c1), false, option);
    y = value_of(rest.substr(c1 + 1, c2 - c1 - 1), false, option);
    rotation = angle_at(rest.substr(c2 + 1), notes, option);
  }
  return PlanarPose{planar.name, x, y, rotation.value, rotation.half_turn, std::nullopt};
}

// A pin-in-slot pair's configuration: the pin-slot part's pose (slide, angle) and the other part's
// position (absent when it is fixed), from the model's initial configuration or OPTION
// PIN=SLIDE,ANGLE and OPTION OTHER=VALUE (an angle in rad or NNdeg, an offset in mm).
std::pair<PlanarPose, std::optional<ExactPosition>> pin_slot_configuration(const Part& pin_slot, const Part& other,
                                                                           const std::vector<std::string>& assignments,
                                                                           const std::string& option, std::vector<std::string>& notes) {
  Rational slide = pin_slot.initial.offset;
  ExactPosition rotation = exact_position_from_angle(pin_slot.initial.angle);
  std::optional<ExactPosition> other_position;
  if (other.motion.kind != Motion::Kind::fixed)
    other_position = rotates(other) ? exact_position_from_angle(other.initial.angle) : ExactPosition{other.initial.offset, true, false, {}, {}};
  for (const std::string& assignment : assignments) {
    auto equals = assignment.find('=');
    std::string name = equals == std::string::npos ? "" : assignment.substr(0, equals), rest = assignment.substr(equals + 1);
    if (name == pin_slot.name) {
      auto comma = rest.find(',');
      if (comma == std::string::npos)
        throw ModelError("", option + " expects " + pin_slot.name + "=SLIDE,ANGLE for the pin-slot part, got '" + assignment + "'");
      slide = value_of(rest.substr(0, comma), false, option);
      rotation = angle_at(rest.substr(comma + 1), notes, option);
    } else if (name == other.name && other.motion.kind != Motion::Kind::fixed) {
      other_position = rotates(other) ? angle_at(rest, notes, option) : ExactPosition{value_of(rest, false, option), true, false, {}, {}};
    } else {
      throw ModelError("", option + " expects " + pin_slot.name + "=SLIDE,ANGLE" +
                               (other.motion.kind != Motion::Kind::fixed ? " or " + other.name + "=VALUE" : "") + ", got '" +
                               assignment + "'");
    }
  }
  PlanarPose pose{pin_slot.name, 0, 0, rotation.value, rotation.half_turn, std::nullopt};
  pose.slide = slide;
  return {pose, other_position};
}

// A connected claim's result: the certificate written and its statement printed (exit 0), or why
// there is none (exit 1, nothing written).
int connected_written(const SlicedConnectedResult& found, const CertifyArguments& arguments) {
  if (!found.certificate) {
    std::cerr << "hipair: cannot certify: " << found.failure << "\n";
    return 1;
  }
  const SlicedConnectedCertificate& c = *found.certificate;
  io::write_file_atomically(arguments.out, write_sliced_connected_certificate(c));
  std::cout << "certified sliced_connected: " << c.envelope.statement << " ("
            << (c.pin_slot ? c.steps.size() - 1 : c.path.size() - 1) << " moves)\n"
            << "written to " << arguments.out << " (check it with: hipair-verify " << arguments.out << " " << arguments.path << ")\n";
  return 0;
}

// An apart claim's result: the certificate written and its statement printed (exit 0), or why
// there is none (exit 1, nothing written).
int apart_written(const SlicedApartResult& found, const CertifyArguments& arguments) {
  if (!found.certificate) {
    std::cerr << "hipair: cannot certify: " << found.failure << "\n";
    return 1;
  }
  io::write_file_atomically(arguments.out, write_sliced_apart_certificate(*found.certificate));
  std::cout << "certified sliced_apart: " << found.certificate->envelope.statement << " (" << found.leaves << " boxes, "
            << found.blocked << " proved blocked)\n"
            << "written to " << arguments.out << " (check it with: hipair-verify " << arguments.out << " " << arguments.path << ")\n";
  return 0;
}

int run(const CertifyArguments& arguments) {
  // a certificate holds for parameter values within their tolerances only: hipair-verify checks
  // each value against its range (docs/certify.md); the option every other command reading --set
  // takes is refused here with the reason (until session 45 CLI11's "not expected", exit 109)
  if (arguments.allow_out_of_tolerance)
    throw ModelError("", "--allow-out-of-tolerance: a certificate is proved for parameter values within their tolerance "
                         "ranges only (hipair-verify rejects a value outside its range): write the value into the model "
                         "(as its nominal, with its tolerance) and certify that model");
  if (arguments.claim == "interference" || arguments.claim == "clearance" || arguments.claim == "jam" ||
      arguments.claim == "free" || arguments.claim == "connected" || arguments.claim == "apart")
    refuse_options_of_other_claims(arguments);
  refuse_repeated_names(arguments.overrides, "--set", "parameter");
  refuse_repeated_names(arguments.at, "--at", "part");
  refuse_repeated_names(arguments.to, "--to", "part");
  // the --set rule of every command (a message naming the whole item: until session 37 certify
  // named only its value, `--set 4.5=6` for `--set pin-radius=4.5=6`)
  ReadOptions options = parameter_overrides(arguments.overrides, false);
  io::refuse_overwriting_input(arguments.out, "--out", arguments.path);
  io::refuse_unusable_output_files({{arguments.out, "--out"}});   // before the (possibly long) search
  refuse_unknown_parameters(arguments.path, arguments.overrides, "--set");
  Model model = read_model_file(arguments.path, options);
  CertifyContext context{options.parameter_values};
  auto [first, second] = pair_of(model, arguments.pair);
  if (model.find_part(first) && model.find_part(second))
    require_feature_spread(model, *model.find_part(first), *model.find_part(second));   // before work (session 53)
  const Part &a = part_named(model, first, "--pair " + arguments.pair), &b = part_named(model, second, "--pair " + arguments.pair);
  if (&a == &b) throw ModelError("", "--pair " + arguments.pair + ": a pair needs two different parts");
  std::optional<Rational> distance;
  if (!arguments.distance.empty()) {
    distance = value_of(arguments.distance, false, "--distance");
    if (sgn(*distance) <= 0) throw ModelError("", "--distance " + arguments.distance + ": the clearance must be positive (mm)");
  }
  std::optional<Certificate> certificate;
  std::string failure;
  std::vector<std::string> notes;   // how angles in degrees were taken
  const Part* planar = a.motion.kind == Motion::Kind::planar ? &a : b.motion.kind == Motion::Kind::planar ? &b : nullptr;
  const Part* pin_slot = a.motion.kind == Motion::Kind::pin_slot ? &a : b.motion.kind == Motion::Kind::pin_slot ? &b : nullptr;
  if ((arguments.claim == "apart" || arguments.claim == "connected") && pin_slot && !planar) {
    // a pin-in-slot part's two configurations (with the other part's positions) in different
    // components of the pair's free space: the kd-tree over (q, s, u) (<hipair/sliced_apart.hpp>);
    // or joined by steps through it, within the motion limits (<hipair/sliced_certificate.hpp>)
    const Part& other = pin_slot == &a ? b : a;
    if (arguments.to.empty())
      throw ModelError("", "--claim " + arguments.claim + " needs --to " + pin_slot->name + "=SLIDE,ANGLE" +
                               (other.motion.kind != Motion::Kind::fixed ? " and --to " + other.name + "=VALUE" : "") + " (the end)");
    auto [from, from_other] = pin_slot_configuration(*pin_slot, other, arguments.at, "--at", notes);
    auto [to, to_other] = pin_slot_configuration(*pin_slot, other, arguments.to, "--to", notes);
    for (const std::string& note : notes) std::cout << note << "\n";
    if (arguments.claim == "apart")
      return apart_written(certify_pin_slot_apart(model, other.name, from, from_other, to, to_other, context), arguments);
    return connected_written(certify_pin_slot_connected(model, other.name, from, from_other, to, to_other, context), arguments);
  }
  if (arguments.claim == "connected" || arguments.claim == "apart") {
    // a planar part's two poses connected through free space (sliced C-space path, staircase
    // certificate: <hipair/sliced_certificate.hpp>); the certificate is its own kind
    const Part& fixed = planar == &a ? b : a;
    if (!planar || fixed.motion.kind != Motion::Kind::fixed)
      throw ModelError("", "--claim " + arguments.claim + ": the pair " + a.name + ":" + b.name +
                               " must be a fixed part and a part free in the plane (motion \"planar\")" +
                               (arguments.claim == "apart" ? std::string(", or a pin-in-slot part and a fixed, rotating or translating part") : std::string()));
    if (planar->motion.angle_limits || planar->motion.translation_limits)
      throw ModelError("", "--claim " + arguments.claim + ": part '" + planar->name + "' has motion limits (" + arguments.claim +
                               " claims cover parts without limits)");
    if (arguments.to.empty())
      throw ModelError("", "--claim " + arguments.claim + " needs --to " + planar->name + "=X,Y,ANGLE (the end pose)");
    PlanarPose from = planar_pose(*planar, arguments.at, "--at", notes);
    PlanarPose to = planar_pose(*planar, arguments.to, "--to", notes);
    for (const std::string& note : notes) std::cout << note << "\n";
    if (arguments.claim == "apart") {
      // the poses in different components of the free space: a kd-tree of boxes whose blocked
      // leaves wall a's component off (<hipair/sliced_apart.hpp>)
      return apart_written(certify_sliced_apart(model, fixed.name, from, to, context), arguments);
    }
    return connected_written(certify_sliced_connected(model, fixed.name, from, to, context), arguments);
  }
  // a claim the pair's kinds of motion have no certificate for: refused naming --claim and the
  // pair, exit 2, as connected/apart above (session 75, drive75: two planar parts, or a planar
  // or pin-slot part in a jam or free claim, stopped in the certificate with exit 3, "planar
  // certificate: part 'block' must be fixed", "part 'peg' is not a fixed-axis part")
  if (arguments.claim == "interference" || arguments.claim == "clearance") {
    const Part* moving = planar ? planar : pin_slot;
    const Part& other = moving == &a ? b : a;
    if (moving && (planar ? other.motion.kind != Motion::Kind::fixed
                          : other.motion.kind == Motion::Kind::pin_slot || other.motion.kind == Motion::Kind::planar))
      throw ModelError("", "--claim " + arguments.claim + ": the pair " + a.name + ":" + b.name + " has no " +
                               arguments.claim + " certificate: a part free in the plane (motion \"planar\") is certified "
                               "against a fixed part, a pin-in-slot part against a fixed, rotating or translating part ('" +
                               other.name + "' is " + motion_adjective(other.motion.kind) + "; --pair chooses the pair)");
  }
  if ((arguments.claim == "jam" || arguments.claim == "free") && (planar || pin_slot))
    throw ModelError("", "--claim " + arguments.claim + ": the pair " + a.name + ":" + b.name + " has a " +
                             motion_adjective((planar ? planar : pin_slot)->motion.kind) + " part ('" +
                             (planar ? planar : pin_slot)->name + "'); " + arguments.claim +
                             " claims cover fixed, rotating and translating parts (--pair chooses the pair)");
  if (planar && (arguments.claim == "interference" || arguments.claim == "clearance")) {
    // a part free in the plane: its pose (x, y, angle) from the model's initial configuration
    // or --at PART=X,Y,ANGLE; the angle is rounded to an exact half-angle tangent (exact at
    // whole quarter turns in degrees)
    PlanarPose pose = planar_pose(*planar, arguments.at, "--at", notes);
    const std::string& fixed = planar == &a ? b.name : a.name;
    if (arguments.claim == "interference") {
      certificate = certify_planar_interference(model, fixed, pose, context);
      failure = "the parts do not overlap there";
    } else {
      certificate = certify_planar_clearance(model, fixed, pose, distance, context);
      failure = "the parts touch or overlap there, or are closer than the distance";
    }
  } else if (pin_slot && (arguments.claim == "interference" || arguments.claim == "clearance")) {
    // a pin-in-slot part: its pose (slide, angle) from the model's initial configuration or
    // --at PART=SLIDE,ANGLE; the other part (fixed, rotating or translating) at its initial
    // position or --at OTHER=VALUE
    const Part& other = pin_slot == &a ? b : a;
    auto [pose, other_position] = pin_slot_configuration(*pin_slot, other, arguments.at, "--at", notes);
    std::map<std::string, ExactPosition> configuration;
    if (other_position) configuration[other.name] = *other_position;
    if (arguments.claim == "interference") {
      certificate = certify_pin_slot_interference(model, other.name, pose, configuration, context);
      failure = "the parts do not overlap there";
    } else {
      certificate = certify_pin_slot_clearance(model, other.name, pose, configuration, distance, context);
      failure = "the parts touch or overlap there, or are closer than the distance";
    }
  } else if (arguments.claim == "interference" || arguments.claim == "clearance") {
    std::map<std::string, ExactPosition> positions;
    for (const Part* part : {&a, &b})
      if (part->motion.kind != Motion::Kind::fixed)
        positions[part->name] = rotates(*part) ? exact_position_from_angle(part->initial.angle)
                                               : ExactPosition{part->initial.offset, true, false, {}, {}};
    for (const std::string& assignment : arguments.at) {
      auto equals = assignment.find('=');
      if (equals == std::string::npos) throw ModelError("", "--at expects PART=VALUE, got '" + assignment + "'");
      const Part& part = part_named(model, assignment.substr(0, equals), "--at " + assignment);
      refuse_outside_pair(part, a, b, "--at " + assignment);
      // (until session 74 a fixed part's position was taken and ignored; the verifier refuses one)
      if (part.motion.kind == Motion::Kind::fixed)
        throw ModelError("", "--at " + assignment + ": part '" + part.name + "' is fixed and has no position");
      positions[part.name] = position_of(part, assignment.substr(equals + 1), notes);
    }
    if (arguments.claim == "interference") {
      certificate = certify_interference(model, first, second, positions, context);
      failure = "the parts do not overlap there";
    } else {
      certificate = certify_clearance(model, first, second, positions, distance, context);
      failure = "the parts touch or overlap there, or are closer than the distance";
    }
  } else if (arguments.claim == "free" || arguments.claim == "jam") {
    int direction = direction_of(arguments.direction);
    std::string driver_name = arguments.driver;
    if (driver_name.empty()) driver_name = a.motion.kind != Motion::Kind::fixed ? a.name : b.name;
    const Part& driver = part_named(model, driver_name, "--driver " + driver_name);
    refuse_outside_pair(driver, a, b, "--driver " + driver_name);
    const Part& other = driver.name == a.name ? b : a;
    bool follows = other.motion.kind != Motion::Kind::fixed;
    if (arguments.claim == "free") {
      PassagePath path{driver.name, follows ? other.name : "", {}, {}};
      path.range.lo = arguments.from.empty() ? coordinate(driver) : value_of(arguments.from, rotates(driver), "--from");
      if (arguments.to.size() > 1)   // a usage error, as CLI11's for a single-valued option given twice (exit 114)
        throw CLI::ArgumentMismatch("--to: the driver range has one end, given twice ('" + arguments.to[0] + "', then '" +
                                    arguments.to[1] + "')");
      if (!arguments.to.empty()) path.range.hi = value_of(arguments.to[0], rotates(driver), "--to");
      else if (rotates(driver)) path.range.hi = path.range.lo + Rational(6283185307179586, 1000000000000000);
      else throw ModelError("", "give --to for a translating driver");
      if (!(path.range.lo < path.range.hi))
        throw ModelError("", "--from/--to: the driver range [" + to_decimal_string(path.range.lo) + ", " +
                                 to_decimal_string(path.range.hi) + "] is empty or reversed (give --to above --from)");
      if (follows) {
        Rational at = arguments.follower_at.empty() ? coordinate(other) : value_of(arguments.follower_at, rotates(other), "--follower-at");
        Rational ratio = arguments.ratio.empty() ? Rational(0) : value_of(arguments.ratio, false, "--ratio");
        path.polyline = {{path.range.lo, at}, {path.range.hi, at + ratio * (path.range.hi - path.range.lo)}};
      }
      certificate = certify_free_passage(model, first, second, path, distance, context);
      failure = "the parts come closer than the distance (or touch) along the path";
    } else {
      std::optional<JamQuery> query;
      if (!arguments.trap.empty()) {
        auto comma = arguments.trap.find(',');
        query = JamQuery{driver.name, follows ? other.name : "", direction,
                         {range_of(arguments.trap.substr(0, comma), rotates(driver), "--trap"), std::nullopt}, std::nullopt};
        if (follows) {
          if (comma == std::string::npos) throw ModelError("", "--trap needs DRIVER_LO:HI,FOLLOWER_LO:HI for a moving follower");
          query->trap.follower = range_of(arguments.trap.substr(comma + 1), rotates(other), "--trap");
        }
        certificate = certify_jam(model, first, second, *query, context);
      } else {
        Rational start = arguments.start.empty() ? coordinate(driver) : value_of(arguments.start, rotates(driver), "--start");
        Rational follower = arguments.follower_start.empty() ? coordinate(other)
                                                             : value_of(arguments.follower_start, rotates(other), "--follower-start");
        Rational step = arguments.step.empty() ? Rational(rotates(driver) ? Rational(1, 500) : Rational(1, 100))
                                               : value_of(arguments.step, rotates(driver), "--step");
        Rational travel = arguments.travel.empty() ? Rational(rotates(driver) ? Rational(6283, 1000) : Rational(100))
                                                   : value_of(arguments.travel, rotates(driver), "--travel");
        // (a positive angle in degrees can round to 0 on the 10^-18 rad grid degrees are taken to)
        auto rounded = [&](const std::string& text) {
          return rotates(driver) && sgn(parse_angle_literal(text, true, "").value) > 0
                     ? std::string(" (it rounds to 0 rad on the 10^-18 rad grid of angles given in degrees)")
                     : std::string();
        };
        if (sgn(step) <= 0) throw ModelError("", "--step " + arguments.step + ": the step must be positive" + rounded(arguments.step));
        if (sgn(travel) <= 0)
          throw ModelError("", "--travel " + arguments.travel + ": the travel must be positive" + rounded(arguments.travel));
        // A rotating driver's step of a whole turn or more samples no motion: a contact anywhere
        // in the turns between two samples is never seen (session 57: `--travel 1e30 --step 1e24`
        // on the cam-follower stepped 10^6 times at angles up to 10^30 rad, for minutes).
        const Rational whole_turn(6283185307, 1000000000);   // just below 2 pi
        if (rotates(driver) && step >= whole_turn)
          throw ModelError("", "--step " + arguments.step + ": a step of a whole turn (6.283185307 rad) or more samples no motion of '" +
                                   driver.name + "': give a --step of a fraction of a turn");
        // A driver turning without limits against a fixed part meets every configuration of the
        // pair within one turn (poses repeat every 2 pi): a longer travel is searched as one turn.
        const bool one_turn = periodic_jam_search(driver, other) && travel > periodic_jam_travel();
        if (one_turn) travel = periodic_jam_travel();
        // the search takes up to travel / step driver steps (about 50 us each): more than 10^7 is
        // refused at once (session 33: `--step 1e-300` searched 6e300 steps, without end)
        const Rational search_steps = travel / step;
        if (search_steps > 10000000) {
          auto shown = [](const Rational& r) {
            const double d = r.get_d();
            if (!std::isfinite(d)) return std::string("more than 1e308");
            std::ostringstream out;
            out << std::setprecision(6) << d;
            return out.str();
          };
          throw ModelError("", "--step " + (arguments.step.empty() ? step.get_str() : arguments.step) +
                                   ": the jam search takes up to travel / step = " + shown(search_steps) +
                                   " driver steps, more than 10000000: give a --step of at least " +
                                   shown(Rational(travel / 10000000)) + " or a shorter --travel");
        }
        // the driver moves within its motion limits (session 56): a start beyond them is an input
        // error, and a search that reaches the limit unblocked says so
        const std::optional<RationalInterval>& driver_limits = rotates(driver) ? driver.motion.angle_limits : driver.motion.translation_limits;
        const std::string unit = rotates(driver) ? " rad" : " mm";
        if (driver_limits && (start < driver_limits->lo || start > driver_limits->hi))
          throw ModelError("", (arguments.start.empty() ? std::string("the start") : "--start " + arguments.start) + ": " +
                                   to_decimal_string(start) + unit + " lies outside the motion limits [" +
                                   to_decimal_string(driver_limits->lo) + ", " + to_decimal_string(driver_limits->hi) + "]" +
                                   unit + " of '" + driver.name + "'");
        query = find_jam(model, first, second, driver.name, start, follower, direction, step, travel);
        if (!query) {
          const Rational limit = driver_limits ? (direction > 0 ? driver_limits->hi : driver_limits->lo) : Rational(0);
          if (driver_limits && abs(limit - start) < travel + step)
            std::cerr << "hipair: cannot certify: no jam found: '" << driver.name << "' reaches its motion limit "
                      << to_decimal_string(limit) << unit << " without being blocked\n";
          else if (one_turn)
            std::cerr << "hipair: cannot certify: no jam found: the motion was not blocked within a whole turn of '" << driver.name
                      << "' (it turns without limits against a fixed part: every configuration of the pair recurs each turn)\n";
          else
            std::cerr << "hipair: cannot certify: no jam found: the motion was not blocked within the travel\n";
          return 1;
        }
        certificate = certify_found_jam(model, first, second, *query, step, context);
        // The follower's free range closes (a zero-backlash mesh, session 53): the search's
        // follower grid misses the narrow channel. The kinematic analysis over the same driver
        // travel locates the closing; a trap around it is certified from a free start before it.
        if (!certificate && follows) {
          Model posed = model;
          Part& moved = posed.parts[*posed.find_part(other.name)];
          (rotates(other) ? moved.initial.angle : moved.initial.offset) = follower;
          KinematicsOptions analysis;
          analysis.driver = driver.name;
          analysis.direction = direction;
          analysis.range = std::make_pair(start, Rational(start + direction * travel));
          analysis.reversal = false;
          try {
            KinematicsResult result = analyze_kinematics(posed, analysis);
            if (result.jam && result.jam->part == other.name) certificate = certify_closing_jam(model, result, context);
          } catch (const std::bad_alloc&) {
            throw;
          } catch (const Error&) {
            // the analysis cannot run on this pair: the search's verdict stands
          }
        }
      }
      failure = "some configuration of the trap's cut or walls is not certainly blocked, or no configuration tried in the trap is certainly free";
    }
  } else {
    throw ModelError("", "--claim must be interference, clearance, jam, free, connected or apart");
  }
  for (const std::string& note : notes) std::cout << note << "\n";
  if (!certificate) {
    std::cerr << "hipair: cannot certify: " << failure << "\n";
    return 1;
  }
  io::write_file_atomically(arguments.out, write_certificate(*certificate));
  std::cout << "certified " << to_string(certificate->claim) << ": " << certificate->statement << "\n"
            << "written to " << arguments.out << " (check it with: hipair-verify " << arguments.out << " " << arguments.path
            << ")\n";
  return 0;
}

}  // namespace

void register_certify(CLI::App& app, Action& action) {
  auto arguments = std::make_shared<CertifyArguments>();
  CLI::App* command = app.add_subcommand("certify", "Produce a certificate of interference, clearance, jam or free passage");
  command->add_option("model", arguments->path, "model file")->required();
  command->add_option("--claim", arguments->claim, "interference | clearance | jam | free | connected | apart")->required();
  command->add_option("--out", arguments->out, "certificate file to write (JSON)")->required()->check(output_path());
  command->add_option("--pair", arguments->pair, "A:B (default: the model's first pair)");
  command->add_option("--set", arguments->overrides, "override a parameter: NAME=VALUE (repeatable)");
  command->add_option("--at", arguments->at, "interference/clearance/connected/apart: PART=VALUE, angle in rad (or NNdeg) or offset in mm (a planar part: PART=X,Y,ANGLE; "
                                             "a pin-slot part: PART=SLIDE,ANGLE) "
                                             "(default: the initial configuration)");
  command->add_option("--distance", arguments->distance, "clearance/free: the clearance to certify (mm; default: found)");
  command->add_option("--driver", arguments->driver, "jam/free: the driven part (default: the pair's first moving part)");
  command->add_option("--from", arguments->from, "free: start of the driver range (default: its initial position)");
  command->add_option("--to", arguments->to, "free: end of the driver range (default: one turn); connected/apart: the end pose PART=X,Y,ANGLE "
                                             "(a pin-slot part: PART=SLIDE,ANGLE, and OTHER=VALUE for a moving other part, repeatable)");
  command->add_option("--follower-at", arguments->follower_at, "free: follower position at the start (default: initial)");
  command->add_option("--ratio", arguments->ratio, "free: follower moves by RATIO x driver motion (default 0: it stays)");
  command->add_option("--direction", arguments->direction, "jam: +1 (driver coordinate increases) or -1; + and - are synonyms");
  command->add_option("--trap", arguments->trap, "jam: the trap DLO:DHI[,FLO:FHI] (default: searched)");
  command->add_option("--start", arguments->start, "jam search: driver start (default: initial)");
  command->add_option("--follower-start", arguments->follower_start, "jam search: follower start (default: initial)");
  command->add_option("--step", arguments->step, "jam search: driver step (default 0.002 rad / 0.01 mm)");
  command->add_option("--travel", arguments->travel, "jam search: how far to drive (default one turn / 100 mm)");
  command->add_flag("--allow-out-of-tolerance", arguments->allow_out_of_tolerance,
                    "refused: a certificate holds for parameter values within their tolerances only (hipair-verify "
                    "checks them); write an out-of-tolerance value into the model instead");
  command->callback([&action, arguments, command] {
    arguments->given = given_options(*command);
    action = [arguments] { return run(*arguments); };
  });
}

}  // namespace hipair::cli
