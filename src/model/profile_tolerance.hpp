// Geometric profile tolerances (docs/model-format.md "Profile tolerances", docs/tolerance.md):
// a part's `profile_tolerances` entry gives a loop (or a circle/pin feature) a band of total
// width t around its nominal profile. The translation rewrites the document before it is
// read: one new parameter δ per toleranced loop (nominal 0, tolerance ±t/2, the entry's
// distribution), and every vertex of the loop becomes an expression of δ and of the texts the
// file gave (so it still follows the other parameters): the whole loop is offset uniformly by
// δ (δ > 0 adds material). Internal: not part of the public API.
#pragma once

#include "model/json_document.hpp"

#include <hipair/model.hpp>

#include <string_view>
#include <vector>

namespace hipair::model_detail {

/// True when some part of `root` has a `profile_tolerances` key.
bool has_profile_tolerances(const JsonValue& root);

/// Rewrites `root` in place: removes every part's `profile_tolerances`, adds one parameter per
/// entry to `parameters` and rewrites the toleranced loops' points (or circle radius) as
/// offsets by that parameter. `nominal` is the model read from `root` without its profile
/// tolerances (for the loops' orientation, holes and the exact corner tests).
/// \throws ModelError naming the entry's JSON pointer.
std::vector<ProfileTolerance> translate_profile_tolerances(JsonValue& root, const Model& nominal);

/// The model of a parsed document that has no profile tolerances (reader.cpp).
Model read_model_root(const JsonValue& root, std::string_view source_name, const ReadOptions& options = {});
/// The rounding bound a document asks for (its "rounding" key, a --rounding override in force,
/// else the default; reader.cpp). \throws ModelError for a bad key.
Rational model_rounding_bound(const JsonValue& root);

/// A copy of `root` without the parts' `profile_tolerances` keys.
JsonValue strip_profile_tolerances(const JsonValue& root);

}  // namespace hipair::model_detail
