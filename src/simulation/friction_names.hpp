// HIPAIR — the pairs' friction data named in a simulator's message (session 64, hunt64): a
// frictional impact or held-contact problem without a consistent stick/slip solution names the
// pairs it involves, their JSON pointers and Coulomb coefficients, as the file gives them (a
// friction of 1e308 makes the slip rows G - mu T overflow, so no assignment is consistent; until
// session 64 the message named no place of the data, and before the candidates' finiteness test
// the velocities were left NaN).
#pragma once

#include <hipair/model.hpp>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

namespace hipair::simulation {

/// "; pairs involved: (a /parts/0, b /parts/1) (/pairs/1, friction 0.3, kinetic 0.2)" (the parts'
/// pointers too: a mass of 1.79e308 makes the problem inconsistent as well) for the model pairs
/// `indices` (into Model::pairs; repeated ones named once), "" for none.
inline std::string named_friction(const Model& model, std::vector<std::size_t> indices) {
  std::sort(indices.begin(), indices.end());
  indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
  std::ostringstream out;
  const char* separator = "; pairs involved: ";
  for (std::size_t i : indices) {
    if (i >= model.pairs.size()) continue;
    const PairSpec& pair = model.pairs[i];
    out << separator << "(" << model.parts[pair.first].name << " " << model.parts[pair.first].pointer << ", "
        << model.parts[pair.second].name << " " << model.parts[pair.second].pointer << ") (" << pair.pointer;
    if (pair.friction) out << ", friction " << pair.friction->get_d();
    if (pair.kinetic_friction) out << ", kinetic " << pair.kinetic_friction->get_d();
    out << ")";
    separator = "; ";
  }
  return out.str();
}

/// The refusal of a frictional impact without a consistent stick/slip solution (the fixed-axis
/// simulator's; session 70, exact70: composed here so that a test reads it): "simulation: at t =
/// <when> the impact problem of <contacts> simultaneous contacts with Coulomb friction has no
/// consistent stick/slip solution; pairs involved: ..." (named_friction of `pairs`) where the
/// exact search was complete (`exhausted`: FrictionalSolution::exhausted); otherwise (session 71,
/// exact71: until then the same words, a verdict, for a search that was not complete) "... no
/// consistent stick/slip solution was found for the impact problem of <contacts> simultaneous
/// contacts with Coulomb friction (the search is complete only up to 12 contacts with at most 8
/// of them frictional: this is not a proof that none exists); pairs involved: ...".
/// The clause a refusal adds where the exact stick/slip search was not complete (session 72,
/// jam72: one constant for the fixed-axis, pin-slot and planar refusals; review71 exact71 L4).
inline constexpr const char* incomplete_frictional_search =
    "the search is complete only up to 12 contacts with at most 8 of them frictional: this is not a proof that none "
    "exists";

/// The planar simulators' refusal of a frictional contact problem without a consistent stick/slip
/// solution (session 72, jam72; review71 exact71 M1): "<problem> has no consistent solution (a
/// Painlevé-type inconsistency of Coulomb friction)" only where the exact search was complete
/// (`exhausted`: FrictionalSolution::exhausted); otherwise "no consistent solution was found for
/// <problem> (<incomplete_frictional_search>)". Until session 72 the planar words were the first
/// form with ", or more than 8 contacts" for every refusal, a verdict where nothing was decided.
inline std::string frictional_refusal(const std::string& problem, bool exhausted) {
  if (exhausted) return problem + " has no consistent solution (a Painlevé-type inconsistency of Coulomb friction)";
  return "no consistent solution was found for " + problem + " (" + incomplete_frictional_search + ")";
}

inline std::string inconsistent_frictional_impact(const std::string& when, std::size_t contacts, const Model& model,
                                                  const std::vector<std::size_t>& pairs, bool exhausted) {
  std::ostringstream out;
  if (exhausted)
    out << "simulation: at t = " << when << " the impact problem of " << contacts
        << " simultaneous contacts with Coulomb friction has no consistent stick/slip solution";
  else
    out << "simulation: at t = " << when << " no consistent stick/slip solution was found for the impact problem of "
        << contacts << " simultaneous contacts with Coulomb friction (" << incomplete_frictional_search << ")";
  out << named_friction(model, pairs);
  return out.str();
}

}  // namespace hipair::simulation
