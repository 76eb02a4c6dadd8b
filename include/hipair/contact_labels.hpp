// Contact labels a pair of the model can give (`hipair analyze --expect LABEL` checks its
// patterns against them before the analysis; docs/analysis.md "Unintended contacts").
#pragma once
#include <hipair/model.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace hipair {

/// Whether some contact of one of the model's pairs can carry a label containing `pattern`:
/// the label the kinematic analysis gives a contact, "A feature / B feature (how they touch)"
/// (the parts' names, each feature's label — an edge's label, or "loop L edge E", a vertex
/// "corner of E1 and E2" —, and how a vertex, a segment or an arc touches the other feature),
/// over every feature that can carry a contact (segments, arcs, and vertices that are not
/// strictly reflex nor on a full circle), with the pair's parts in either order.
/// KinematicsOptions::expected_contacts are such substrings: a pattern for which this is false
/// matches no contact of any run. An empty pattern is contained in every label. Motion limits
/// ("motion limit of P") are no contacts here: an expected-contact pattern never applies to them.
bool contact_label_can_contain(const Model& model, const std::string& pattern);

/// The same over the model's pairs with these indices only (an empty list: no label at all,
/// except for the empty pattern).
bool contact_label_can_contain(const Model& model, const std::string& pattern, const std::vector<std::size_t>& pairs);

/// The model's pairs (indices into Model::pairs) whose contacts the kinematic analysis driven by
/// part `driver` (model part index) can report: the pairs of fixed-axis parts, not both fixed,
/// with a moving part reached from the driver through such pairs (the analysis's chain). A pair
/// outside it (two parts the driver never moves, a planar part) gives no contact in the report.
std::vector<std::size_t> driven_pairs(const Model& model, std::size_t driver);

}  // namespace hipair
