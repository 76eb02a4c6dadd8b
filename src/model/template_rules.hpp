// The rules of the feature templates (session 61): each written once, as a margin that must be
// positive, enclosed in certified interval arithmetic, and served to both of its users:
//   - the exact expansion (templates*.cpp, check_template_rules_exactly): the margin enclosed at
//     the template's exact argument values (lengths in the template's unit, template_geometry.hpp
//     LengthScaleScope); a margin not certainly positive refuses the geometry with the
//     template's own message at the argument the rule names;
//   - a tolerance box (ParametricModel::check_choices): the margin enclosed over the box; a
//     margin not certainly positive refuses the box, naming the toleranced parameters it reads.
// Until session 61 the box check wrote every rule a second time. The templates' constructive
// checks on their rounded geometry (a Geneva driver's pin in its crescent, an anchor's pallets
// meeting under the pivot, an involute flank reaching its circles, a negative angle) stay in the
// expanders, and the shape checks of a box (which pieces exist) in check_choices.
#pragma once

#include "kernels/interval.hpp"
#include "kernels/vector.hpp"

#include <functional>
#include <string>
#include <vector>

namespace hipair::model_detail {

/// The values a template's rules read: enclosures of its arguments (of one exact vector, or
/// over a tolerance box).
struct TemplateRuleValues {
  std::function<bool(const char*)> has;
  /// A number argument's enclosure (present: the rules ask only for those or use defaults).
  std::function<kernels::Interval(const char*)> value;
  std::function<kernels::Vector<kernels::Interval>(const char*)> point;
  /// The template's tooth or slot count; 0 when unknown (it depends on a toleranced parameter):
  /// the rules that need it are then not checked.
  long count = 0;
};

/// One rule: `margin` must be certainly positive (its enclosure's lower end > 0).
struct TemplateRule {
  const char* key;                   ///< the argument a refusal names
  std::vector<const char*> reads;    ///< the arguments the margin reads (absent ones: defaults)
  std::function<kernels::Interval()> margin;
  std::string rule;                  ///< the rule, as a tolerance box's refusal states it
  std::string refusal;               ///< the exact expansion's message at `key`
};

/// Calls `check` with every rule of template `name` (in the order the expansion checks them; none
/// for a template without rules). The margins are evaluated only when `check` asks.
void template_rules(const std::string& name, const TemplateRuleValues& values,
                    const std::function<void(const TemplateRule&)>& check);

/// The exact expansion's check of template `name`'s rules at `values` (a point).
/// \throws ModelError at pointer + "/" + key with the rule's refusal when a margin is not
/// certainly positive (or does not evaluate).
void check_template_rules_exactly(const std::string& name, const TemplateRuleValues& values, const std::string& pointer);

}  // namespace hipair::model_detail
