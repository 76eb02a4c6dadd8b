// HIPAIR — reading a model for a simulation (docs/model-format.md, "Within the doubles' range").
#pragma once

#include <hipair/model.hpp>

#include <filesystem>
#include <string_view>

namespace hipair {

/// read_model / read_model_file as `hipair simulate` reads: dynamics data (a part's `dynamics`,
/// the `simulation` object, a pair's friction and restitution) whose nonzero magnitude lies
/// outside [DBL_MIN, DBL_MAX] is refused at its pointer, since the simulator holds it in
/// doubles. The exact commands read with read_model / read_model_file, which accept it: a model
/// scaled to 10^-300 or 10^400 (inertias scaled by s^2) stays valid for them.
Model read_model_for_simulation(std::string_view json_text, std::string_view source_name = "<string>",
                                const ReadOptions& options = {});
Model read_model_file_for_simulation(const std::filesystem::path& path, const ReadOptions& options = {});

/// The same check on the data converted to the simulator's internal units (s, mN): in a file in
/// ms or N, a rate, gravity, force, torque, stiffness or damping within the doubles' range in the
/// file's units may not be in the simulator's (1e306 rad/ms is 1e309 rad/s); refused at its
/// pointer (ModelError) with the largest value allowed. Called by the two readers above.
void require_internal_units_in_double_range(const Model& model);

}  // namespace hipair
