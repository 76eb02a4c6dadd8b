// The rules of the feature templates (session 61): each written once, as a margin that must be
// positive, enclosed in certified interval arithmetic, and served to both of its users:
//   - the exact expansion (templates*.cpp, check_template_rules_exactly): the margin's sign
//     decided exactly at the template's exact argument values (lengths in the template's unit,
//     template_geometry.hpp LengthScaleScope); a margin not positive refuses the geometry with
//     the template's own message at the argument the rule names;
//   - a tolerance box (ParametricModel::check_choices): the margin enclosed over the box; a
//     margin not certainly positive refuses the box, naming the toleranced parameters it reads.
// Until session 61 the box check wrote every rule a second time. The templates' constructive
// checks on their rounded geometry (a Geneva driver's pin in its crescent, an anchor's pallets
// meeting under the pivot, an involute flank reaching its circles, a negative angle) stay in the
// expanders, and the shape checks of a box (which pieces exist) in check_choices.
#pragma once

#include "kernels/interval.hpp"
#include "kernels/vector.hpp"
#include "model/interval.hpp"

#include <hipair/rational.hpp>

#include <functional>
#include <string>
#include <vector>

namespace hipair::model_detail {

/// The values a template's rules read: enclosures of its arguments (of one exact vector, or
/// over a tolerance box), in number type T (kernels::Interval here; the exact expansion's own
/// exact reals inside template_rules.cpp).
template <class T>
struct BasicTemplateRuleValues {
  std::function<bool(const char*)> has;
  /// A number argument's value (present: the rules ask only for those or use defaults).
  std::function<T(const char*)> value;
  std::function<kernels::Vector<T>(const char*)> point;
  /// The template's tooth or slot count; 0 when unknown (it depends on a toleranced parameter):
  /// the rules that need it are then not checked.
  long count = 0;
};
using TemplateRuleValues = BasicTemplateRuleValues<kernels::Interval>;

/// One rule: `margin` must be positive (an enclosure: its lower end > 0).
template <class T>
struct BasicTemplateRule {
  const char* key;                   ///< the argument a refusal names
  std::vector<const char*> reads;    ///< the arguments the margin reads (absent ones: defaults)
  std::function<T()> margin;
  std::string rule;                  ///< the rule, as a tolerance box's refusal states it
  std::string refusal;               ///< the exact expansion's message at `key`
};
using TemplateRule = BasicTemplateRule<kernels::Interval>;

/// Calls `check` with every rule of template `name` (in the order the expansion checks them; none
/// for a template without rules). The margins are evaluated only when `check` asks.
void template_rules(const std::string& name, const TemplateRuleValues& values,
                    const std::function<void(const TemplateRule&)>& check);

/// The same rules over MPFI enclosures at the thread's working precision (session 62): the
/// certified box check (ParametricModel::check_choices) when the doubles' enclosures leave a
/// margin undecided; an argument's enclosure over a sub-box of the exact tolerance box.
void template_rules(const std::string& name, const BasicTemplateRuleValues<Interval>& values,
                    const std::function<void(const BasicTemplateRule<Interval>&)>& check);

/// A template's exact argument values (lengths in the template's unit).
struct ExactTemplateRuleValues {
  std::function<bool(const char*)> has;
  std::function<Rational(const char*)> value;
  std::function<kernels::Vector<Rational>(const char*)> point;
  long count = 0;
};

/// The exact expansion's check of template `name`'s rules at `values` (session 61, tol61b): each
/// margin's sign decided exactly, the same rules as template_rules written once over exact reals:
/// rational margins and margins a + b sqrt(s) (a, b, s rational) by exact rational arithmetic
/// (comparing squares), others (pi, sin, cos, atan2) by MPFI enclosures refined from 64 to 65536
/// bits. A margin exactly zero refuses (every rule is strict).
/// \throws ModelError at pointer + "/" + key with the rule's refusal when a margin is not
/// positive, does not evaluate (a square root of a negative, atan2(0, 0)), or is not decided
/// at 65536 bits (only a margin vanishing exactly without being rational or quadratic: refused,
/// as a zero margin is).
void check_template_rules_exactly(const std::string& name, const ExactTemplateRuleValues& values,
                                  const std::string& pointer);

}  // namespace hipair::model_detail
