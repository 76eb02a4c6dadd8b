// Sub-commands of the `hipair` command-line tool. Each registers itself on the app and
// stores the action to run; main() runs it and turns hipair::Error into one line + exit code.
#pragma once

#include <CLI/CLI.hpp>

#include <hipair/model.hpp>

#include <functional>
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

}  // namespace hipair::cli
