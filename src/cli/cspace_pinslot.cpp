#include "cli/cspace_pinslot.hpp"

#include "core/model_scale.hpp"

#include <hipair/error.hpp>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>

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

std::string pin_slot_json(const PinSlotSpace& space, bool with_times, long decimal_exponent) {
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
