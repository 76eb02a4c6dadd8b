// Sub-commands of the `hipair` command-line tool. Each registers itself on the app and
// stores the action to run; main() runs it and turns hipair::Error into one line + exit code.
#pragma once

#include <CLI/CLI.hpp>

#include <hipair/model.hpp>

#include "cli/angles.hpp"
#include "core/console_text.hpp"
#include "model/exact_trig.hpp"

#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
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

/// Refuses an item NAME=VALUE of `option` (`--set`, `simulate --sweep`) whose NAME is no parameter
/// of the model file at `path` (its "/parameters" keys, as the reader takes them), naming the
/// option, the item and the parameters there are; until session 45 the reader's
/// "/parameters: cannot override unknown parameter 'x'" named no option. A file that does not
/// parse is left to the reader; an item "NAME=" is shown as NAME (`tolerance --vary NAME`). \throws ModelError.
void refuse_unknown_parameters(const std::string& path, const std::vector<std::string>& items, const std::string& option);
/// The long options of `command` given on the command line ("--expect", "--full-slices"), for the
/// checks that refuse an option that does not apply to the model or the other options (session
/// 45: `analyze --expect nobody` and `cspace --full-slices` on a pair without slices were taken
/// and ignored).
std::set<std::string> given_options(const CLI::App& command);
/// `value` read as the model's exact literal (docs/model-format.md: no space, no '+', the
/// decimal exponent within 1000, at most 4096 bits). \throws ModelError "<argument>: <why><note>",
/// the argument (`--set p=V`) cut after 120 characters.
Rational exact_option_literal(const std::string& value, const std::string& argument, const std::string& note = "");

/// Adds `--set NAME=VALUE` (repeatable) and `--allow-out-of-tolerance` to a command that reads
/// one model, storing them in `assignments` and `allow_out_of_tolerance` (parameter_overrides
/// turns them into reader options).
void add_parameter_options(CLI::App* command, std::vector<std::string>& assignments, bool& allow_out_of_tolerance);

/// Refuses a repeatable option that names one target twice (`--set p=1 --set p=2`, `--load
/// wheel=cw --load wheel=ccw`, `--at lever=0.1 --at lever=0.2`, `--config driver=1,driver=2`): the
/// last value would silently win (session 35, hunt35). Give every item's target in order.
/// \throws CLI::ArgumentMismatch (exit 114, as CLI11 refuses a single-valued option given twice)
/// naming the option, the target and both items.
class OnceEach {
 public:
  /// `what` names a target in the message ("parameter", "part").
  OnceEach(std::string option, std::string what) : option_(std::move(option)), what_(std::move(what)) {}
  void add(const std::string& target, const std::string& item);

 private:
  std::string option_, what_;
  std::map<std::string, std::string> seen_;   // target -> the item that named it first
};

/// OnceEach over items NAME=VALUE, the target being the NAME (items without '=' are left to the
/// option's own parser). \throws CLI::ArgumentMismatch.
void refuse_repeated_names(const std::vector<std::string>& items, const std::string& option, const std::string& what);

/// Adds `--rounding B` (the model's rounding bound, docs/model-format.md) to a command; the
/// text is stored in `text` (empty: the model's own bound).
void add_rounding_option(CLI::App* command, std::string& text);
/// Puts a `--rounding` bound in force (overriding the models' own "rounding" key) while the
/// result lives; nullptr for an empty text. \throws ModelError for a malformed number (the
/// range is checked by the reader).
std::unique_ptr<model_detail::RoundingBoundScope> rounding_scope(const std::string& text);

// shown_name and shortened_message (console text of long names and messages) live in
// core/console_text.hpp, shared with hipair-verify.
using console::shown_name;
using console::shortened_message;

/// CLI::Range for real numbers, with the ends written as numbers ("in [1e-12, 1]"): CLI11's own
/// message prints them with std::to_string, and "Value 0 not in range 0.000000 to 1.000000"
/// names a range that seems to hold the value.
CLI::Validator real_range(double lo, double hi);

/// A path to write: refuses an empty one (`--out ""`, an unset shell variable), which each command
/// took as no output at all — exit 0 and nothing written (until session 52).
CLI::Validator output_path();

}  // namespace hipair::cli
