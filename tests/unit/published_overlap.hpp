// Session 74 (jam74; Issue 11, review73 H1): a published state of a planar simulation checked
// against the exact overlap predicate — no pair of the model's `pairs` may overlap (interiors
// meeting) at any state a run publishes. The oracle is part_overlap (include/hipair/overlap.hpp)
// on the state's exact configurations (PlanarState::configuration: the shift and the rotation's
// rational half-angle tangent about the part's pivot); fixed parts stay where they are drawn.
#pragma once

#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/simulation.hpp>

#include <cstddef>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace hipair::test {

// The exact world placement of a planar part at configuration c (the simulator's: turned about
// `pivot` by the half-angle tangent c.angle.t, then shifted by (c.x, c.y)).
inline Placement planar_placement(const Point& pivot, const SlicedConfiguration& c) {
  Rational cos(-1), sin(0);
  if (!c.angle.half_turn) {
    const Rational t = c.angle.t, d = 1 + t * t;
    cos = (1 - t * t) / d;
    sin = 2 * t / d;
  }
  return placement_about(pivot, cos, sin, Point{c.x, c.y});
}

// The model pairs that overlap at the planar parts' exact configurations (`parts`: their model
// indices, `states` theirs): "first / second" for each, joined by "; " (empty: none overlaps).
inline std::string overlapping_pairs(const Model& model, const std::vector<std::size_t>& parts,
                                     const std::vector<PlanarState>& states) {
  std::vector<Placement> placed(model.parts.size());   // (a fixed part: the identity)
  for (std::size_t k = 0; k < parts.size(); ++k)
    placed[parts[k]] = planar_placement(model.parts[parts[k]].motion.pivot, states[k].configuration);
  std::string found;
  for (const PairSpec& pair : model.pairs) {
    const PartRelation r =
        part_overlap(model.parts[pair.first], placed[pair.first], model.parts[pair.second], placed[pair.second]).relation;
    if (r == PartRelation::overlapping)
      found += (found.empty() ? "" : "; ") + model.parts[pair.first].name + " / " + model.parts[pair.second].name;
  }
  return found;
}

// Session 75 (jam75; review74 M2): the model pairs of the pin-slot part `part` that overlap at a
// pin-slot simulation's exact pair configurations (PinSlotState::pair_configurations: the part
// relative to the pair's other part, about the part's own pivot, one per model pair of the part in
// model order), the other part at its zero configuration. Same format as overlapping_pairs.
inline std::string pin_slot_overlapping_pairs(const Model& model, std::size_t part,
                                              const std::vector<SlicedConfiguration>& configurations) {
  std::string found;
  std::size_t k = 0;
  for (const PairSpec& pair : model.pairs) {
    if (pair.first != part && pair.second != part) continue;
    if (k == configurations.size()) return found + (found.empty() ? "" : "; ") + "(a pair without a configuration)";
    const std::size_t other = pair.first == part ? pair.second : pair.first;
    const Placement placed = planar_placement(model.parts[part].motion.pivot, configurations[k++]);
    if (part_overlap(model.parts[other], Placement{}, model.parts[part], placed).relation == PartRelation::overlapping)
      found += (found.empty() ? "" : "; ") + model.parts[pair.first].name + " / " + model.parts[pair.second].name;
  }
  return found;
}

// The run's state checked now (call after every step and after a stop): a failure names the
// time and the pairs; `checked` counts the states, `bad` the overlapping ones.
struct PublishedOverlapCheck {
  std::size_t checked = 0, bad = 0;
  std::string first_bad;   // the first overlapping state: "t = ...: pairs"
  template <class Sim>
  void operator()(const Sim& sim) {
    ++checked;
    std::string pairs;
    if constexpr (requires { sim.state().states; })
      pairs = overlapping_pairs(sim.model(), sim.state().parts, sim.state().states);
    else if constexpr (requires { sim.state().pair_configurations; })
      pairs = pin_slot_overlapping_pairs(sim.model(), sim.part(), sim.state().pair_configurations);
    else
      pairs = overlapping_pairs(sim.model(), {sim.part()}, {sim.state()});
    if (pairs.empty()) return;
    if (++bad > 1) return;
    std::ostringstream at;
    at.precision(17);
    at << "t = " << sim.state().time << ": " << pairs;
    first_bad = at.str();
  }
};

}  // namespace hipair::test
