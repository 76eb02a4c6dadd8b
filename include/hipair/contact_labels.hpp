// Contact labels a pair of the model can give (`hipair analyze --expect LABEL` checks its
// patterns against them before the analysis; docs/analysis.md "Unintended contacts").
#pragma once
#include <hipair/model.hpp>

#include <string>

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

}  // namespace hipair
