// Sub-commands of the `hipair` command-line tool. Each registers itself on the app and
// stores the action to run; main() runs it and turns hipair::Error into one line + exit code.
#pragma once

#include <CLI/CLI.hpp>

#include <hipair/model.hpp>

#include "cli/angles.hpp"
#include "model/exact_trig.hpp"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace hipair::cli {

using Action = std::function<int()>;

void register_validate(CLI::App& app, Action& action);
void register_show(CLI::App& app, Action& action);
void register_analyze(CLI::App& app, Action& action);
void register_certify(CLI::App& app, Action& action);
void register_cspace(CLI::App& app, Action& action);
void register_tolerance(CLI::App& app, Action& action);
void register_simulate(CLI::App& app, Action& action);

/// Reader options from `--set NAME=VALUE` assignments (exact literals in mm or rad) and
/// `--allow-out-of-tolerance`. \throws ModelError naming the bad assignment.
ReadOptions parameter_overrides(const std::vector<std::string>& assignments, bool allow_out_of_tolerance);

/// Adds `--set NAME=VALUE` (repeatable) and `--allow-out-of-tolerance` to a command that reads
/// one model, storing them in `assignments` and `allow_out_of_tolerance` (parameter_overrides
/// turns them into reader options).
void add_parameter_options(CLI::App* command, std::vector<std::string>& assignments, bool& allow_out_of_tolerance);

/// Adds `--rounding B` (the model's rounding bound, docs/model-format.md) to a command; the
/// text is stored in `text` (empty: the model's own bound).
void add_rounding_option(CLI::App* command, std::string& text);
/// Puts a `--rounding` bound in force (overriding the models' own "rounding" key) while the
/// result lives; nullptr for an empty text. \throws ModelError for a malformed number (the
/// range is checked by the reader).
std::unique_ptr<model_detail::RoundingBoundScope> rounding_scope(const std::string& text);

/// CLI::Range for real numbers, with the ends written as numbers ("in [1e-12, 1]"): CLI11's own
/// message prints them with std::to_string, and "Value 0 not in range 0.000000 to 1.000000"
/// names a range that seems to hold the value.
CLI::Validator real_range(double lo, double hi);

}  // namespace hipair::cli
