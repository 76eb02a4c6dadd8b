#include "cli/analyze_pinslot.hpp"

#include "cli/commands.hpp"
#include "core/length_display.hpp"
#include "io/atomic_file.hpp"

#include <hipair/error.hpp>
#include <hipair/motion_words.hpp>
#include <hipair/pin_slot.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <set>
#include <unistd.h>
#include <utility>
#include <vector>

namespace hipair::cli {

bool has_pin_slot_part(const Model& model) {
  // a pin-slot part paired with a rotating part (its driver): the work cycle applies
  for (const PairSpec& pair : model.pairs) {
    const Part& a = model.parts[pair.first];
    const Part& b = model.parts[pair.second];
    if ((a.motion.kind == Motion::Kind::pin_slot && b.motion.kind == Motion::Kind::rotation) ||
        (b.motion.kind == Motion::Kind::pin_slot && a.motion.kind == Motion::Kind::rotation))
      return true;
  }
  return false;
}

namespace {

// The parts that can drive the work cycle: the rotating parts paired with a pin-in-slot part (in
// the order of the pairs).
std::vector<std::string> cycle_drivers(const Model& model) {
  std::vector<std::string> names;
  for (const PairSpec& pair : model.pairs)
    for (auto [driver, follower] : {std::pair(pair.first, pair.second), std::pair(pair.second, pair.first)}) {
      const Part& part = model.parts[driver];
      if (part.motion.kind == Motion::Kind::rotation && model.parts[follower].motion.kind == Motion::Kind::pin_slot &&
          std::find(names.begin(), names.end(), part.name) == names.end())
        names.push_back(part.name);
    }
  return names;
}

// `--driver` for the work cycle: a rotating part paired with the pin-in-slot part, else refused
// naming the option, exit 2 (session 75, drive75: any other part went on into the cycle, which
// stopped with "pin-slot cycle: the driver 'film' does not rotate", exit 3, or named no option).
// A driven film (or claw) is no kinematic question the cycle answers: the film touches the claw
// only during its pull-down stroke and fixes at most one of the claw's two coordinates (swing
// about the pin, slide along it), the claw's cam another only while it touches, so a film
// position leaves the claw and the cam undetermined; the cycle is the cam's turn, as in the paper.
void check_cycle_driver(const Model& model, const std::string& requested) {
  if (requested.empty()) return;
  std::string list;
  for (const std::string& name : cycle_drivers(model)) list += (list.empty() ? "'" : ", '") + shown_name(name) + "'";
  const std::string hint = "a model with a pin-in-slot part is analysed as its work cycle, one turn of a rotating "
                           "part paired with the pin-in-slot part (parts that can drive: " + list + ")";
  auto index = model.find_part(requested);
  if (!index) throw ModelError("", "--driver: no part named '" + shown_name(requested) + "' (" + hint + ")");
  const Part& part = model.parts[*index];
  const std::vector<std::string> drivers = cycle_drivers(model);
  if (std::find(drivers.begin(), drivers.end(), part.name) != drivers.end()) return;
  std::string why = part.motion.kind == Motion::Kind::rotation
                        ? "rotating but not paired with a pin-in-slot part"
                        : std::string(motion_adjective(part.motion.kind));
  if (part.motion.kind == Motion::Kind::translation)
    why += " (driven, it fixes at most one of the pin-in-slot part's two coordinates, swing and slide, and those "
           "not the driver's angle: no single motion to follow)";
  else if (part.motion.kind == Motion::Kind::pin_slot)
    why += " (two coordinates, swing and slide: a driver moves along one)";
  throw ModelError("", "--driver: part '" + shown_name(requested) + "' is " + why + "; " + hint);
}

// A key of cycle.json holding a length in mm ("advance_mm"), or in units of 10^E mm when the
// cycle ran on the model divided by 10^E ("advance_1e400mm"; length_display_exponent()).
std::string mm_key(const std::string& name) {
  const long e = length_display_exponent();
  return e == 0 ? name + "_mm" : name + "_1e" + std::to_string(e) + "mm";
}

// An exact length of the cycle (in units of 10^E mm) in mm, as text: to_exact_string, with the
// exponent written after it ("8e400", "(3/2)e400") when E is not 0.
std::string exact_mm(const Rational& value) {
  const long e = length_display_exponent();
  std::string text = to_exact_string(value);
  if (e == 0 || value == 0) return text;
  if (text.find('/') != std::string::npos) text = "(" + text + ")";
  return text + "e" + std::to_string(e);
}

}  // namespace

int run_pin_slot_cycle(const Model& model, const PinSlotCycleRequest& request) {
  check_cycle_driver(model, request.driver);
  PinSlotCycleOptions options;
  options.driver = request.driver;
  options.steps = request.steps;
  std::string sense_note;
  if (request.direction == "cw" || request.direction == "-") {
    options.clockwise = true;
  } else if (request.direction == "ccw" || request.direction == "+") {
    options.clockwise = false;
  } else if (!request.direction.empty()) {
    throw ModelError("", "--direction expects cw, ccw, + or -");
  }
  if (request.direction.empty()) {
    // the sense of the driver's torque in the model, else counter-clockwise (as analyze does)
    for (const PairSpec& pair : model.pairs)
      for (std::size_t i : {pair.first, pair.second}) {
        const Part& part = model.parts[i];
        if ((request.driver.empty() || part.name == request.driver) && part.motion.kind == Motion::Kind::rotation &&
            part.dynamics && part.dynamics->torque && sgn(*part.dynamics->torque) != 0) {
          options.clockwise = sgn(*part.dynamics->torque) < 0;
          sense_note = " (the sense of the model's driving torque on " + part.name + ")";
        }
      }
  }
  if (isatty(2) && !request.quiet)
    options.progress = [](const std::string& stage) { std::cerr << "\rhipair: pin-slot cycle: " << stage << "     " << std::flush; };
  PinSlotCycle cycle = pin_slot_cycle(model, options);
  if (options.progress) std::cerr << "\rhipair: pin-slot cycle done" << std::string(40, ' ') << "\n";

  using nlohmann::json;
  json out;
  out["model"] = model.name;
  out["kind"] = "pin_slot_cycle";
  out["driver"] = cycle.driver;
  out["follower"] = cycle.follower;
  out["target"] = cycle.target;
  out["sense"] = options.clockwise ? "clockwise" : "counter-clockwise";
  out["note"] =
      "quasi-static: the target moves only when the follower's pose overlaps it, to the nearest free offset; each "
      "sample is exact (follower pose rational and located exactly against the driver; target offset from the exact "
      "1-D C-space); phase changes are located to the sample spacing; the follower's pose is the middle of its "
      "largest free slide interval near the previous pose (a choice, not a law)";
  json samples = json::array();
  for (const CycleSample& s : cycle.samples) {
    json j;
    j["driver_degrees"] = s.driver_degrees;
    j["driver_t"] = s.driver.kind == PartCoordinate::Kind::half_turn ? json("half turn") : json(to_exact_string(s.driver.value));
    j["slide"] = to_exact_string(s.slide);
    j["tau"] = to_exact_string(s.tau);
    j["psi_degrees"] = s.psi_degrees;
    j[mm_key("follower_clearance")] = s.clearance;
    j["follower_free"] = s.follower_free;
    j["target_offset"] = to_exact_string(s.target_offset);
    j["target_offset_exact"] = s.target_offset_exact;
    j["phase"] = std::string(to_string(s.phase));
    j["contacts"] = s.contacts;
    j["bounded_by"] = s.bounds;
    j["follower_slide_bounded_by"] = s.driver_bounds;
    samples.push_back(j);
  }
  out["samples"] = samples;
  json runs = json::array();
  for (const CycleRun& r : cycle.runs)
    runs.push_back({{"phase", std::string(to_string(r.phase))},
                    {"first_sample", r.first},
                    {"last_sample", r.last},
                    {"driver_degrees", {cycle.samples[r.first].driver_degrees, cycle.samples[r.last].driver_degrees}},
                    {"target_moved", to_exact_string(r.target_moved)},
                    {mm_key("target_moved"), to_double(r.target_moved)}});
  out["phases"] = runs;
  out["advance"] = to_exact_string(cycle.advance);
  out[mm_key("advance")] = to_double(cycle.advance);
  // every length of the file (slides, offsets, moves: exact rationals and doubles) in units of
  // 10^E mm when the cycle ran on the rescaled model (absent for every ordinary model)
  if (length_display_exponent() != 0) out["units"] = {{"length", length_unit_name()}};
  out["seconds"] = cycle.seconds;

  bool all_free = true;
  for (const CycleSample& s : cycle.samples) all_free = all_free && s.follower_free;
  if (!request.quiet) {
    std::printf("%s: work cycle of %s (pin-in-slot) driven by %s, pushing %s; %s%s, %zu samples\n", shown_name(model.name).c_str(),
                cycle.follower.c_str(), cycle.driver.c_str(), cycle.target.c_str(),
                options.clockwise ? "clockwise" : "counter-clockwise", sense_note.c_str(), cycle.samples.size());
    std::printf("  follower pose certified free against %s at %s samples (exact point location)\n",
                cycle.driver.c_str(), all_free ? "all" : "NOT all");
    for (const CycleRun& r : cycle.runs) {
      const CycleSample& a = cycle.samples[r.first];
      const CycleSample& b = cycle.samples[r.last];
      std::string what = r.phase == CyclePhase::clear     ? "clear of the " + cycle.target
                         : r.phase == CyclePhase::engaged ? "engaged (holds the " + cycle.target + ")"
                         : r.phase == CyclePhase::pushing ? "pushing the " + cycle.target
                                                          : "JAMMED";
      std::printf("  %8.1f .. %8.1f deg  %-28s %s moved %s mm (exact %s)\n", a.driver_degrees, b.driver_degrees,
                  what.c_str(), cycle.target.c_str(), length_in_mm(to_decimal_string(r.target_moved, 6)).c_str(),
                  exact_mm(r.target_moved).c_str());
      std::set<std::string> contacts, bounds, driver_bounds;
      for (std::size_t i = r.first; i <= r.last; ++i) {
        for (const auto& c : cycle.samples[i].contacts) contacts.insert(c);
        for (const auto& c : cycle.samples[i].bounds) bounds.insert(c);
        for (const auto& c : cycle.samples[i].driver_bounds) driver_bounds.insert(c);
      }
      for (const auto& c : contacts) std::printf("        contact: %s\n", c.c_str());
      for (const auto& c : bounds) std::printf("        held between contacts: %s\n", c.c_str());
      for (const auto& c : driver_bounds)
        std::printf("        %s slide bounded by (%s): %s\n", cycle.follower.c_str(), cycle.driver.c_str(), c.c_str());
    }
    std::printf("  %s advanced by %s mm (exact %s) over the cycle; %.2f s\n", cycle.target.c_str(),
                length_in_mm(to_decimal_string(cycle.advance, 6)).c_str(), exact_mm(cycle.advance).c_str(), cycle.seconds);
  }
  if (!request.out.empty()) {
    std::filesystem::create_directories(request.out);
    io::write_file_atomically(std::filesystem::path(request.out) / "cycle.json", out.dump(1) + "\n");
  }
  return 0;
}

}  // namespace hipair::cli
