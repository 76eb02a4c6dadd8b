#include "cli/cspace_sliced.hpp"

#include "core/model_scale.hpp"
#include "render/sliced_svg.hpp"

#include <hipair/motion_words.hpp>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>

namespace hipair::cli {
namespace {

using nlohmann::json;

std::string event_name(CriticalEvent event) {
  switch (event) {
    case CriticalEvent::antiparallel_edges: return "antiparallel_edges";
    case CriticalEvent::vertex_on_contact: return "vertex_on_contact";
    case CriticalEvent::three_contacts: return "three_contacts";
  }
  return "?";
}

json angle_json(const SlicedAngle& angle) {
  json out;
  out["half_turn"] = angle.half_turn;
  out["t"] = angle.half_turn ? json(nullptr) : json(to_exact_string(angle.t));
  out["degrees"] = angle.degrees();   // correctly rounded
  return out;
}

// A length of the space (in units of 2^unit mm: SlicedSpace::length_unit_exponent) in mm,
// exactly, as text.
std::string mm_text(const Rational& length, long unit) { return to_exact_string(times_power_of_two(length, unit)); }

// A configuration with exact x, y (mm) and angle (t = tan(theta/2) or the half turn).
json configuration_json(const SlicedConfiguration& q, long unit) {
  json out = angle_json(q.angle);
  out["x"] = mm_text(q.x, unit);
  out["y"] = mm_text(q.y, unit);
  return out;
}

}  // namespace

std::optional<std::pair<std::string, std::string>> sliced_pair(const Model& model, const std::string& first,
                                                               const std::string& second) {
  auto a = model.find_part(first), b = model.find_part(second);
  if (!a || !b) return std::nullopt;
  const Part& p = model.parts[*a];
  const Part& q = model.parts[*b];
  if (p.motion.kind == Motion::Kind::fixed && q.motion.kind == Motion::Kind::planar) return std::pair{p.name, q.name};
  if (q.motion.kind == Motion::Kind::fixed && p.motion.kind == Motion::Kind::planar) return std::pair{q.name, p.name};
  return std::nullopt;
}

std::optional<std::string> planar_pair_not_built(const Model& model, std::size_t first, std::size_t second) {
  const Part& p = model.parts[first];
  const Part& q = model.parts[second];
  if (p.motion.kind != Motion::Kind::planar && q.motion.kind != Motion::Kind::planar) return std::nullopt;
  for (const Part* part : {&p, &q})
    if (part->motion.kind == Motion::Kind::fixed || part->motion.kind == Motion::Kind::pin_slot) return std::nullopt;
  std::string where;
  for (const PairSpec& pair : model.pairs)
    if ((pair.first == first && pair.second == second) || (pair.first == second && pair.second == first)) {
      where = " (" + pair.pointer + ")";
      break;
    }
  const int dimensions = p.motion.degrees_of_freedom() + q.motion.degrees_of_freedom();
  const Part& planar = p.motion.kind == Motion::Kind::planar ? p : q;
  const Part& other = &planar == &p ? q : p;
  return "pair '" + p.name + "':'" + q.name + "'" + where + ": the " + described_part(planar) + " against the " +
         described_part(other) + " has a C-space of " + std::to_string(dimensions) +
         " dimensions, which hipair does not build (a planar part's pair is built against a fixed part)";
}

std::vector<std::pair<std::string, std::string>> sliced_pairs(const Model& model) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const PairSpec& pair : model.pairs)
    if (auto found = sliced_pair(model, model.parts[pair.first].name, model.parts[pair.second].name))
      out.push_back(*found);
  return out;
}

SlicedSpace build_sliced(const Model& model, const std::string& fixed, const std::string& free, bool progress) {
  SlicedBuildOptions options;
  options.normalise_lengths = true;   // a pair at 10^400 mm: sliced in units of 2^L mm, written in mm
  if (progress)
    options.progress = [label = fixed + ":" + free](const std::string& stage) {
      std::cerr << "\rhipair: " << label << " sliced C-space: " << stage << "          " << std::flush;
    };
  SlicedSpace space = SlicedSpace::build(model, fixed, free, options);
  if (progress)   // padded to cover the longest stage line
    std::cerr << "\rhipair: " << fixed << ":" << free << " sliced C-space built" << std::string(32, ' ') << "\n";
  return space;
}

std::string sliced_json(const SlicedSpace& space, bool with_times) {
  // every length below (the bound, cell samples, witnesses) in mm, exactly
  const long unit = space.length_unit_exponent();
  json out;
  out["pair"] = {space.fixed_part(), space.free_part()};
  out["dimension"] = 3;
  out["kind"] = "sliced";
  out["coordinates"] =
      "(x, y, theta) of the planar part relative to the fixed one: its body point q at pivot + R(theta)(q - pivot) "
      "+ (x, y); theta carried by t = tan(theta/2), or the half turn; slices are translating C-spaces in (x, y) mm";
  out["bound"] = mm_text(space.bound(), unit);
  json critical = json::array();
  for (std::size_t i = 0; i < space.critical_angles().size(); ++i) {
    const CriticalAngle& c = space.critical_angles()[i];
    json j;
    j["index"] = i;
    j["half_turn"] = c.half_turn;
    if (c.half_turn) {
      j["t"] = nullptr;
    } else {
      j["t"] = {{"exact", c.t.to_string("t")}, {"decimal", nearest_double(c.t)}};
      if (!c.t.exact) j["t"]["interval"] = {to_exact_string(c.t.lower), to_exact_string(c.t.upper)};
    }
    j["degrees"] = c.degrees;
    json events = json::array();
    for (CriticalEvent e : c.events) events.push_back(event_name(e));
    j["events"] = events;
    critical.push_back(j);
  }
  out["critical_angles"] = critical;
  json slices = json::array();
  for (std::size_t i = 0; i < space.intervals().size(); ++i) {
    const SlicedInterval& in = space.intervals()[i];
    auto slice = space.slice(in.representative);
    json j;
    j["index"] = i;
    j["lower_critical"] = in.lower_critical == no_index ? json(nullptr) : json(in.lower_critical);
    j["upper_critical"] = in.upper_critical == no_index ? json(nullptr) : json(in.upper_critical);
    j["label"] = render::sliced_interval_label(space, i);
    j["representative"] = angle_json(in.representative);
    json cells = json::array();
    for (std::size_t k = 0; k < in.free_cells.size(); ++k) {
      const auto& cell = in.free_cells[k];
      json c;
      c["index"] = k;
      c["slice_cell"] = cell.slice_cell;
      c["contacts"] = cell.contacts;
      c["component"] = cell.component == no_index ? json(nullptr) : json(cell.component);
      if (cell.slice_cell < slice->cells().size()) {
        const auto& sc = slice->cells()[cell.slice_cell];
        c["sample"] = {{"x", mm_text(sc.sample_x, unit)}, {"y", mm_text(sc.sample_y, unit)}};
      }
      cells.push_back(c);
    }
    j["free_cells"] = cells;
    j["slice_cells"] = slice->cells().size();
    slices.push_back(j);
  }
  out["slices"] = slices;
  json crossings = json::array();
  for (const SlicedCrossing& crossing : space.crossings()) {
    json j;
    j["critical"] = crossing.critical;
    j["left_slice"] = crossing.left_interval;
    j["right_slice"] = crossing.right_interval;
    json connections = json::array();
    json witnesses = json::array();   // parallel to connections
    for (const auto& c : crossing.connections) {
      connections.push_back({c.left_cell, c.right_cell});
      json w = {{"left", configuration_json(c.left_witness, unit)},
                {"right", configuration_json(c.right_witness, unit)},
                {"through_half_turn", c.through_half_turn}};
      witnesses.push_back(w);
    }
    j["connections"] = connections;
    j["witnesses"] = witnesses;
    j["ending"] = crossing.ending;
    j["starting"] = crossing.starting;
    crossings.push_back(j);
  }
  out["crossings"] = crossings;
  out["components"] = space.components();
  const SlicedStatistics& s = space.statistics();
  out["statistics"] = {{"candidate_polynomials", s.candidate_polynomials},
                       {"candidate_roots", s.candidate_roots},
                       {"irrelevant_roots", s.irrelevant_roots},
                       {"slices_built", s.slices_built}};
  // wall times differ from run to run: only with --stats, so that the same input gives the same bytes
  if (with_times)
    out["statistics"]["seconds"] = {{"critical", s.seconds_critical}, {"slices", s.seconds_slices}, {"total", s.seconds_total}};
  return out.dump(1) + "\n";
}

void print_sliced_statistics(const SlicedSpace& space) {
  const SlicedStatistics& s = space.statistics();
  std::size_t cells = 0;
  for (const auto& in : space.intervals()) cells += in.free_cells.size();
  std::printf("pair %s:%s (3-D sliced: x, y, theta)\n", space.fixed_part().c_str(), space.free_part().c_str());
  std::printf("  critical angles %zu (candidate polynomials %zu, roots %zu, %zu certified irrelevant)\n",
              space.critical_angles().size(), s.candidate_polynomials, s.candidate_roots, s.irrelevant_roots);
  std::printf("  slices %zu, free cells %zu, components %zu; slices built %zu\n", space.intervals().size(), cells,
              space.components(), s.slices_built);
  std::printf("  time (ms): critical angles %.1f, slices %.1f, total %.1f\n", s.seconds_critical * 1e3,
              s.seconds_slices * 1e3, s.seconds_total * 1e3);
}

}  // namespace hipair::cli
