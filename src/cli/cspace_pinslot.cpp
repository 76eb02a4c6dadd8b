#include "cli/cspace_pinslot.hpp"

#include "cli/angles.hpp"
#include "core/model_scale.hpp"

#include <hipair/error.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <numbers>
#include <set>

namespace hipair::cli {
namespace {

using nlohmann::json;

// The units of a space's lengths: 2^binary mm (PinSlotSpace::length_unit_exponent) of a space
// built on the model divided by 10^decimal (pin_slot_json).
struct LengthUnit {
  long binary = 0, decimal = 0;
};

// A length of the space in mm, exactly, as text.
std::string mm_text(const Rational& length, LengthUnit unit) {
  Rational mm = times_power_of_two(length, unit.binary);
  if (unit.decimal != 0) mm *= power_of_ten_rational(unit.decimal);
  return to_exact_string(mm);
}

json coordinate_json(const PartCoordinate& c, Motion::Kind kind, LengthUnit unit) {
  if (kind == Motion::Kind::fixed) return nullptr;
  if (c.kind == PartCoordinate::Kind::offset) return {{"offset", mm_text(c.value, unit)}};
  if (c.kind == PartCoordinate::Kind::half_turn) return {{"half_turn", true}};
  return {{"t", to_exact_string(c.value)}};
}


// A length given in mm, in the space's units (mm / 10^decimal / 2^binary), exactly.
Rational space_length(const Rational& mm, LengthUnit unit) {
  Rational value = mm;
  if (unit.decimal != 0) value *= power_of_ten_rational(-unit.decimal);
  return times_power_of_two(value, -unit.binary);
}

// A rotating part's position as a half-angle tangent coordinate (the half turn: kind half_turn).
PartCoordinate rotation_coordinate(const ExactPosition& p) {
  PartCoordinate c;
  if (!p.half_turn) {
    c.value = p.value;
  } else if (sgn(p.value) == 0) {
    c.kind = PartCoordinate::Kind::half_turn;
  } else {   // theta = pi + 2 atan(v): tan(theta/2) = -1/v
    c.value = Rational(-1) / p.value;
    c.value.canonicalize();
  }
  return c;
}

double degrees_of_tangent(const Rational& t) { return 2 * std::atan(to_double(t)) * 180 / std::numbers::pi; }

std::string motion_kind(const PinSlotConfiguration& a, const PinSlotConfiguration& b, bool through_half_turn) {
  if (through_half_turn) return "turn_through_half_turn";
  if (a.tau == b.tau) return "in_slice";
  bool same_other = a.other.kind == b.other.kind &&
                    (a.other.kind == PartCoordinate::Kind::half_turn || a.other.value == b.other.value);
  if (same_other && a.slide == b.slide) return "turn";
  return "plane";
}

json configuration_json(const PinSlotSpace& space, const PinSlotConfiguration& q, LengthUnit unit) {
  json j;
  const Motion::Kind kind = space.other_kind();
  j["other"] = coordinate_json(q.other, kind, unit);
  if (kind == Motion::Kind::translation) {
    j["other_mm"] = std::ldexp(to_double(q.other.value), static_cast<int>(unit.binary)) * std::pow(10.0, unit.decimal);
  } else if (kind == Motion::Kind::rotation) {
    j["other_degrees"] = q.other.kind == PartCoordinate::Kind::half_turn ? 180.0 : degrees_of_tangent(q.other.value);
  }
  j["slide"] = mm_text(q.slide, unit);
  j["slide_mm"] = std::ldexp(to_double(q.slide), static_cast<int>(unit.binary)) * std::pow(10.0, unit.decimal);
  j["tau"] = to_exact_string(q.tau);
  j["psi_degrees"] = degrees_of_tangent(q.tau);
  json slice = nullptr;
  for (std::size_t k = 0; k < space.slices().size(); ++k)
    if (space.slices()[k].tau == q.tau) slice = k;
  j["slice"] = slice;
  return j;
}

json path_json(const PinSlotSpace& space, const PinSlotPath& path, LengthUnit unit) {
  json out;
  out["status"] = std::string(to_string(path.status));
  switch (path.status) {
    case PinSlotPath::Status::found:
      out["status_note"] = "every motion between consecutive waypoints is certified free throughout, ends included (exact)";
      break;
    case PinSlotPath::Status::not_shown_connected:
      out["status_note"] =
          "the stack does not show the ends connected (different groups, or an end joined to no slice's cell): not a "
          "proof that they are apart";
      break;
    case PinSlotPath::Status::not_found:
      out["status_note"] = "the ends are in one group, but the planner found no certified path";
      break;
    case PinSlotPath::Status::not_free: out["status_note"] = "an end is not a free configuration"; break;
  }
  json waypoints = json::array();
  if (path.status == PinSlotPath::Status::found)
    for (const auto& w : path.waypoints) waypoints.push_back(configuration_json(space, w, unit));
  out["waypoints"] = waypoints;
  json motions = json::array();
  if (path.status == PinSlotPath::Status::found)
    for (std::size_t i = 0; i + 1 < path.waypoints.size(); ++i)
      motions.push_back({{"from", i}, {"to", i + 1},
                         {"kind", motion_kind(path.waypoints[i], path.waypoints[i + 1], path.through_half_turn[i])}});
  out["motions"] = motions;
  out["motions_note"] =
      "straight in (the other part's coordinate: half-angle tangent or offset, s, tau); in_slice: at constant tau; turn: "
      "the pin-slot part turns at constant (other, s); plane: at constant s; turn_through_half_turn: across psi = 180 "
      "deg, straight in -1/tau";
  out["motions_checked"] = path.motions_checked;
  return out;
}
}  // namespace

std::optional<std::pair<std::string, std::string>> pin_slot_pair(const Model& model, const std::string& first,
                                                                  const std::string& second) {
  auto a = model.find_part(first), b = model.find_part(second);
  if (!a || !b) return std::nullopt;
  const Part& p = model.parts[*a];
  const Part& q = model.parts[*b];
  bool p_pin = p.motion.kind == Motion::Kind::pin_slot, q_pin = q.motion.kind == Motion::Kind::pin_slot;
  if (!p_pin && !q_pin) return std::nullopt;
  const Part& pin = p_pin ? p : q;
  const Part& other = p_pin ? q : p;
  if (other.motion.kind == Motion::Kind::pin_slot || other.motion.kind == Motion::Kind::planar)
    throw GeometryError("pair '" + first + "':'" + second + "': a pin_slot part against a " +
                        (other.motion.kind == Motion::Kind::planar ? std::string("planar") : std::string("pin_slot")) +
                        " part has a C-space of 4 or more dimensions, which hipair does not build (" + other.pointer +
                        ")");
  return std::pair{other.name, pin.name};
}

std::vector<std::pair<std::string, std::string>> pin_slot_pairs(const Model& model) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const PairSpec& pair : model.pairs)
    if (auto found = pin_slot_pair(model, model.parts[pair.first].name, model.parts[pair.second].name))
      out.push_back(*found);
  return out;
}

PinSlotSpace build_pin_slot(const Model& model, const std::string& other, const std::string& pin_slot, bool progress,
                            std::size_t slices, bool plane_witnesses) {
  PinSlotBuildOptions options;
  options.slices = slices;
  options.plane_witnesses = plane_witnesses;
  options.normalise_lengths = true;   // a pair at 10^400 mm: stacked in units of 2^L mm, written in mm
  if (progress)
    options.progress = [label = other + ":" + pin_slot](const std::string& stage) {
      std::cerr << "\rhipair: " << label << " pin-slot C-space: " << stage << "          " << std::flush;
    };
  PinSlotSpace space = PinSlotSpace::build(model, other, pin_slot, options);
  if (progress)
    std::cerr << "\rhipair: " << other << ":" << pin_slot << " pin-slot C-space built" << std::string(40, ' ') << "\n";
  return space;
}


PinSlotPathEnds pin_slot_path_ends(const Model& model, const std::string& other_name, const std::string& pin_name,
                                   const std::vector<std::string>& at, const std::vector<std::string>& to) {
  const Part& pin = model.parts[*model.find_part(pin_name)];
  const Part& other = model.parts[*model.find_part(other_name)];
  const bool moves = other.motion.kind != Motion::Kind::fixed;
  PinSlotPathEnds ends;
  auto tau_of = [&](const ExactPosition& p, const std::string& option) {
    PartCoordinate c = rotation_coordinate(p);
    if (c.kind == PartCoordinate::Kind::half_turn)
      throw ModelError("", option + ": the pin-slot part's angle is the half turn (180 deg), where tan(psi/2) is "
                               "infinite: give an angle off it");
    return c.value;
  };
  // the start: the model's initial configuration
  ends.from.slide = pin.initial.offset;
  ends.from.tau = tau_of(exact_position_from_angle(pin.initial.angle), "--at (the model's initial configuration)");
  if (other.motion.kind == Motion::Kind::rotation) {
    ends.from.other = rotation_coordinate(exact_position_from_angle(other.initial.angle));
  } else if (other.motion.kind == Motion::Kind::translation) {
    ends.from.other = PartCoordinate{PartCoordinate::Kind::offset, other.initial.offset};
  }
  auto read = [&](const std::vector<std::string>& assignments, const std::string& option, PinSlotConfiguration& q,
                  std::string& described) {
    std::set<std::string> named_parts;   // each part once per option
    for (const std::string& assignment : assignments)
      if (!named_parts.insert(assignment.substr(0, assignment.find('='))).second)
        throw ModelError("", option + " " + assignment + ": part '" + assignment.substr(0, assignment.find('=')) +
                                 "' is given twice in " + option);
    const std::string expected = pin.name + "=SLIDE,ANGLE" + (moves ? " or " + other.name + "=VALUE" : std::string());
    for (const std::string& assignment : assignments) {
      const std::string named = option + " " + assignment;
      described += (described.empty() ? "" : " ") + named;
      auto equals = assignment.find('=');
      std::string name = equals == std::string::npos ? "" : assignment.substr(0, equals);
      std::string rest = equals == std::string::npos ? "" : assignment.substr(equals + 1);
      if (name == pin.name) {
        auto comma = rest.find(',');
        if (comma == std::string::npos)
          throw ModelError("", option + " expects " + pin.name + "=SLIDE,ANGLE for the pin-slot part, got '" + assignment + "'");
        q.slide = parse_angle_literal(rest.substr(0, comma), false, named).value;
        ExactPosition rotation = exact_position_from_text(rest.substr(comma + 1), named);
        if (std::string label = angle_label(rest.substr(comma + 1), rotation); !label.empty())
          ends.notes.push_back(option + ": " + label);
        q.tau = tau_of(rotation, named);
      } else if (moves && name == other.name) {
        if (other.motion.kind == Motion::Kind::rotation) {
          ExactPosition rotation = exact_position_from_text(rest, named);
          if (std::string label = angle_label(rest, rotation); !label.empty()) ends.notes.push_back(option + ": " + label);
          q.other = rotation_coordinate(rotation);
        } else {
          q.other = PartCoordinate{PartCoordinate::Kind::offset, parse_angle_literal(rest, false, named).value};
        }
      } else {
        throw ModelError("", option + " expects " + expected + " (the pair " + other.name + ":" + pin.name + "), got '" +
                                 assignment + "'");
      }
    }
  };
  read(at, "--at", ends.from, ends.from_option);
  if (ends.from_option.empty()) ends.from_option = "--at (the model's initial configuration)";
  ends.to = ends.from;
  read(to, "--to", ends.to, ends.to_option);
  return ends;
}

PinSlotPath pin_slot_path(const PinSlotSpace& space, const PinSlotPathEnds& ends, long decimal_exponent) {
  const LengthUnit unit{space.length_unit_exponent(), decimal_exponent};
  auto in_space = [&](PinSlotConfiguration q) {
    q.slide = space_length(q.slide, unit);
    if (q.other.kind == PartCoordinate::Kind::offset) q.other.value = space_length(q.other.value, unit);
    q.slide.canonicalize();
    q.other.value.canonicalize();
    q.tau.canonicalize();
    return q;
  };
  const PinSlotConfiguration from = in_space(ends.from), to = in_space(ends.to);
  for (const auto& [q, option] : {std::pair{&from, &ends.from_option}, std::pair{&to, &ends.to_option}}) {
    if (q->other.kind == PartCoordinate::Kind::half_turn)
      throw ModelError("", *option + ": the other part at its half turn (180 deg) is not a configuration a path takes "
                                     "here (its half-angle tangent is infinite): give an angle off it");
    switch (space.locate(*q).kind) {
      case PinSlotLocation::Kind::free: break;
      case PinSlotLocation::Kind::outside:
        throw ModelError("", *option + ": the configuration is outside the limits (the pin-slot part's angle or slide "
                                       "limits, or the other part's): a path runs through free configurations");
      case PinSlotLocation::Kind::blocked:
        throw ModelError("", *option + ": the configuration is blocked (the parts overlap there, exactly): a path runs "
                                       "through free configurations");
      case PinSlotLocation::Kind::contact:
        throw ModelError("", *option + ": the parts touch at the configuration (exactly): a path runs through free "
                                       "configurations");
    }
  }
  return space.path(from, to);
}

std::string pin_slot_path_summary(const PinSlotSpace& space, const PinSlotPath& path) {
  std::string out = "path " + space.other_part() + ":" + space.pin_slot_part() + ": " + std::string(to_string(path.status));
  if (path.status == PinSlotPath::Status::found) {
    std::size_t between = 0;
    for (std::size_t i = 0; i + 1 < path.waypoints.size(); ++i)
      between += path.waypoints[i].tau != path.waypoints[i + 1].tau ? 1 : 0;
    out += ", " + std::to_string(path.waypoints.size()) + " waypoints, " + std::to_string(path.waypoints.size() - 1) +
           " motions (" + std::to_string(between) + " between slices), each certified free";
  } else if (path.status == PinSlotPath::Status::not_shown_connected) {
    out += " (the stack does not show the ends connected; not a proof that they are apart)";
  } else if (path.status == PinSlotPath::Status::not_found) {
    out += " (the ends are in one group; the planner found no certified path)";
  }
  return out;
}

std::string pin_slot_json(const PinSlotSpace& space, bool with_times, long decimal_exponent, const PinSlotPath* path) {
  // every length below (samples' and witnesses' slides and offsets) in mm, exactly
  const LengthUnit unit{space.length_unit_exponent(), decimal_exponent};
  json out;
  out["pair"] = {space.other_part(), space.pin_slot_part()};
  out["dimension"] = space.dimension();
  out["kind"] = "pin_slot";
  out["coordinates"] =
      "(q, s, psi): q the other part's coordinate (rotation: t = tan(phi/2) or the half turn; translation: offset mm; "
      "none when fixed), s the slide along the slot (mm), psi the pin-slot part's angle about its pivot, carried by "
      "tau = tan(psi/2); each slice is the exact fixed-axis C-space at a rational tau (x = q, y = s; 1-D: x = s)";
  out["tau_range"] = {to_exact_string(space.tau_lower()), to_exact_string(space.tau_upper())};
  Motion::Kind kind = space.other_kind();
  json slices = json::array();
  for (std::size_t i = 0; i < space.slices().size(); ++i) {
    const PinSlotSlice& s = space.slices()[i];
    json j;
    j["index"] = i;
    j["tau"] = to_exact_string(s.tau);
    j["degrees"] = s.degrees;
    j["refinement"] = s.refinement;
    j["cells"] = s.cells;
    json cells = json::array();
    for (std::size_t k = 0; k < s.free_cells.size(); ++k) {
      const PinSlotCell& c = s.free_cells[k];
      cells.push_back({{"index", k},
                       {"slice_cell", c.slice_cell},
                       {"contacts", c.contacts},
                       {"group", c.group},
                       {"sample", {{"other", coordinate_json(c.sample_other, kind, unit)}, {"slide", mm_text(c.sample_slide, unit)}}}});
    }
    j["free_cells"] = cells;
    slices.push_back(j);
  }
  out["slices"] = slices;
  json connections = json::array();
  for (const PinSlotConnection& c : space.connections())
    connections.push_back({{"kind", c.kind == PinSlotConnection::Kind::vertical ? "vertical" : "plane"},
                           {"lower_slice", c.lower},
                           {"upper_slice", c.lower + 1 == space.slices().size() ? 0 : c.lower + 1},
                           {"lower_cell", c.lower_cell},
                           {"upper_cell", c.upper_cell},
                           {"witness", {{"other", coordinate_json(c.witness_other, kind, unit)},
                                        {"other_upper", coordinate_json(c.witness_other_upper, kind, unit)},
                                        {"slide", mm_text(c.witness_slide, unit)}}}});
  out["connections"] = connections;
  json changes = json::array();
  for (const PinSlotChange& c : space.changes())
    changes.push_back({{"between_slices", {c.lower, c.lower + 1}},
                       {"tau_interval", {to_exact_string(space.slices()[c.lower].tau), to_exact_string(space.slices()[c.lower + 1].tau)}},
                       {"degrees", {space.slices()[c.lower].degrees, space.slices()[c.lower + 1].degrees}},
                       {"what", c.description}});
  out["changes"] = changes;
  out["critical_values_exact"] = space.critical_values_exact();
  json critical = json::array();
  for (const PinSlotCritical& c : space.critical_values())
    if (c.half_turn)
      critical.push_back({{"tau", "infinite (the half turn)"}, {"degrees", c.degrees}, {"half_turn", true}});
    else
      critical.push_back({{"tau", c.tau.to_string("tau")}, {"degrees", c.degrees}});
  out["critical_values"] = critical;
  out["critical_values_note"] =
      "when exact (the other part fixed or translating, slides within limits): every tau in (tau_range) where the "
      "slice's structure may change, exact algebraic numbers; each interval between consecutive ones holds a slice, "
      "and slices with no critical value between them are alike";
  out["changes_note"] =
      "each interval certainly contains a change of the free-cell structure (both slices exact); gaps between alike "
      "slices are not certified free of changes";
  out["groups"] = space.groups();
  out["groups_note"] =
      "free cells in one group are certainly connected (exact witnesses); different groups are not claimed apart";
  const PinSlotStatistics& st = space.statistics();
  out["statistics"] = {{"slices_built", st.slices_built},
                       {"witness_spaces", st.witness_spaces},
                       {"plane_witness_spaces", st.plane_spaces},
                       {"witness_candidates", st.witness_candidates}};
  if (path) out["path"] = path_json(space, *path, unit);
  // wall times differ from run to run: only with --stats, so that the same input gives the same bytes
  if (with_times)
    out["statistics"]["seconds"] = {{"slices", st.seconds_slices}, {"connections", st.seconds_connections}, {"total", st.seconds_total}};
  return out.dump(1) + "\n";
}

void print_pin_slot_statistics(const PinSlotSpace& space) {
  const PinSlotStatistics& s = space.statistics();
  std::size_t cells = 0;
  for (const auto& slice : space.slices()) cells += slice.free_cells.size();
  std::printf("pair %s:%s (%d-D pin-in-slot stack)\n", space.other_part().c_str(), space.pin_slot_part().c_str(),
              space.dimension());
  std::printf("  slices %zu, free cells %zu, connections %zu, changes %zu, groups %zu\n", space.slices().size(), cells,
              space.connections().size(), space.changes().size(), space.groups());
  std::printf("  slices built %zu, witness spaces %zu 1-D + %zu 2-D (candidates %zu)\n", s.slices_built,
              s.witness_spaces, s.plane_spaces, s.witness_candidates);
  std::printf("  time (ms): slices %.1f, connections %.1f, total %.1f\n", s.seconds_slices * 1e3,
              s.seconds_connections * 1e3, s.seconds_total * 1e3);
}

}  // namespace hipair::cli
