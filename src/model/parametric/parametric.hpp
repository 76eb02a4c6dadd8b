// The parametric model (issue 10 item 3; docs/tolerance.md "The parametric model"): every
// geometric value of a model — loop vertices, arc centres and radii, rotation pivots,
// translation directions — recorded as a formula of the named parameters, so that the model
// yields its geometry for any number type at any parameter vector without re-reading the file:
//   exact rationals   exact_model(): the same steps as the reader (rational + pi arithmetic,
//                     directions rounded to exact rational unit vectors, recorded), then the
//                     exact validation and orientation of every part: a Model identical to the
//                     one read_model gives with the parameter values overridden;
//   double, certified intervals (kernels::Interval), AutoDiff over all parameters
//                     part_geometry<T>(): the smooth geometry (no rounding), loops oriented
//                     as in the nominal model.
//
// Parameter vector: one deviation per parameter (Model::parameters order), 0 = nominal. An
// independent parameter's value is nominal + deviation; a parameter whose nominal is an
// expression of other parameters (a derived parameter) is that expression at their values,
// plus its own deviation (its tolerance): correlated parameters vary together.
//
// Number types: this header needs only Arithmetic<T> (arithmetic.hpp: double); include
// number_traits.hpp for the kernels' intervals and AutoDiff (the independent verifier supplies
// its own MPFI arithmetic, certify/tolerance_check.cpp).
#pragma once

#include "kernels/vector.hpp"
#include "model/parametric/formula.hpp"
#include "model/templates.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace hipair::model_detail {

/// One number slot of the file: its text (exact path) and its formula (generic path).
struct Slot {
  std::string text;
  std::string pointer;
  bool literal = false;   ///< a JSON number
  FormulaPtr formula;     ///< the value in mm / rad (a plain angle in a degree file converted)
};

struct PointRecipe {
  bool polar = false;
  Slot x, y;                             ///< cartesian
  std::shared_ptr<PointRecipe> center;   ///< polar
  Slot radius, angle;                    ///< polar
};

struct EdgeRecipe {
  bool arc = false;
  PointRecipe target;
  PointRecipe center;   ///< arc
  bool ccw = true;
};

struct LoopRecipe {
  bool circle = false;
  PointRecipe center;   ///< circle
  Slot radius;          ///< circle
  PointRecipe start;
  std::vector<EdgeRecipe> edges;
};

/// A feature template occurrence: its arguments as slots / points / words.
struct FeatureRecipe {
  std::string name;
  std::string pointer;
  struct Argument {
    ArgumentKind kind = ArgumentKind::length;
    Slot number;
    PointRecipe point;
    std::string word;
  };
  std::map<std::string, Argument> arguments;
  std::size_t loop_count = 0;   ///< loops it expanded to in the nominal model
  long teeth = 0;               ///< the tooth (slot) count; 0 when it varies with a toleranced parameter (no generic form)
  /// spur_gear (flank_radius form): which crossing of the flank circle with the tip (root)
  /// circle the exact template takes (+1 / -1 along perp(centre), decided at nominal), and the
  /// flank arc's turning sense there.
  int tip_side = 1, root_side = 1;
  bool flank_ccw = true;
  /// The loops it expanded to in the nominal model (template order, before orientation): their
  /// edge counts and each edge's turning sense (arcs). The generic forms of geneva_wheel,
  /// geneva_driver, escape_wheel, anchor, balance and spur_gear's involute fit follow that
  /// structure (which pieces exist, each arc's sense: decided by the exact expansion at nominal;
  /// ParametricModel::check_choices refuses a box that would change them).
  std::vector<std::size_t> edge_counts;
  std::vector<std::vector<bool>> ccw;
};

/// The canonical tooth's right flank of a spur_gear with flank_radius (axis along +x, the
/// flank y < 0; templates_gears.cpp expand_spur_gear): the arc's centre and its ends on the
/// root and tip circles.
template <class T>
struct SpurFlank {
  kernels::Vector<T> centre, root, tip, pitch_point;
};

struct MotionRecipe {
  bool has_pivot = false;
  PointRecipe pivot;
  bool has_direction = false;
  bool direction_is_angle = false;
  Slot direction_angle;
  Slot direction_x, direction_y;
};

struct PartRecipe {
  std::vector<LoopRecipe> loops;           ///< explicit loops (first in Part::loops)
  std::vector<FeatureRecipe> features;     ///< then the templates' loops
  MotionRecipe motion;
  std::vector<bool> reversed;              ///< per Part::loops entry: reversed by orientation
};

/// An edge of a part in body coordinates (world coordinates at its zero configuration).
template <class T>
struct EdgeValue {
  bool arc = false;
  kernels::Vector<T> source, target, center;
  T radius_squared{0};
  bool ccw = true;
};

/// A part's geometry and motion axis for number type T.
template <class T>
struct PartGeometry {
  std::vector<std::vector<EdgeValue<T>>> loops;   ///< Part::loops order, oriented as nominal
  kernels::Vector<T> pivot{T(0), T(0)};
  kernels::Vector<T> direction{T(1), T(0)};
};

/// A model with its geometry recorded as formulas of its parameters.
class ParametricModel {
 public:
  /// Reads the model (read_model) and records its formulas. \throws as read_model.
  /// With `options.parameter_values`, those parameters' nominal values are replaced
  /// (ReadOptions::overrides_set_nominal: the design as changed, its tolerances about it).
  static ParametricModel read(std::string_view json_text, std::string_view source_name = "<string>",
                              const ReadOptions& options = {});
  /// A model read as read() reads it (ReadOptions::overrides_set_nominal set), with the
  /// precision its reader needed: for a caller that needs the model itself as well as its
  /// parametric form, so that the file is read and validated once.
  struct Nominal {
    std::shared_ptr<const Model> model;
    long precision_bits = 256;
  };
  static Nominal read_nominal(std::string_view json_text, std::string_view source_name = "<string>",
                              const ReadOptions& options = {});
  /// read() on a model `nominal` that read_nominal gave for the same text, source and options:
  /// the formulas recorded without reading the model again. The self-check (self_check.hpp)
  /// compares the parametric form's exact geometry at the nominal vector with `nominal`'s parts.
  static ParametricModel read(std::string_view json_text, std::string_view source_name, const ReadOptions& options,
                              Nominal nominal);
  static ParametricModel read_file(const std::filesystem::path& path);

  const Model& nominal() const { return *nominal_; }
  std::size_t parameter_count() const { return nominal_->parameters.size(); }
  /// Whether parameter i is defined by an expression of other parameters.
  bool derived(std::size_t i) const { return derived_[i]; }
  /// Whether every part's geometry has a generic (non-exact) form: false when a part uses a
  /// feature template other than circle/pin (those are exact only; see docs/tolerance.md).
  bool generic() const { return generic_; }
  /// The first template that is exact only, for messages.
  const std::string& exact_only_feature() const { return exact_only_feature_; }
  /// \throws ModelError when the model has no generic form: at a template's tooth or slot count
  /// when one varies with a toleranced parameter (session 62: the analysis keeps counts fixed),
  /// else naming the first template that is exact only.
  void require_generic() const;

  /// The exact model at a deviation vector. \throws ModelError when the geometry is invalid
  /// there (loops crossing, ...), naming the pointer.
  Model exact_model(const std::vector<Rational>& deviations) const;

  /// The parametric form of the model divided by 10^exponent (decimal_scaled_model,
  /// core/model_scale.hpp): its nominal() and exact_model() are the models read divided so, and
  /// every length formula (points, radii, template lengths, pivots) is the formula read times
  /// 10^-exponent with the factor carried into its constants (formula_scaled): a model written
  /// at 10^E times an ordinary one (tests/fuzz/scale_model.py) evaluates, for every number type,
  /// as that ordinary one. Parameters, angles and directions are not rescaled. The tolerance
  /// analysis of a mechanism drawn at an extreme scale runs on it (session 54).
  /// \throws ModelError naming the first length slot whose double value at the nominal vector
  /// is not finite or lies outside the doubles' normal range once divided (a parameter itself
  /// of about 10^400 mm), and for a model with profile tolerances (their offset parameters are
  /// lengths: not rescaled).
  ParametricModel rescaled(long exponent) const;
  /// The exponent of rescaled(), 0 for a model as read.
  long length_exponent() const { return length_exponent_; }

  /// The value of every parameter at a deviation vector, for number type T.
  template <class T>
  std::vector<T> parameter_values(const std::vector<T>& deviations) const;

  /// One edge of a part (Part::loops[loop].edges[edge], oriented as nominal) for number type T
  /// at the parameter values `parameters` (from parameter_values): only its own formulas.
  template <class T>
  EdgeValue<T> edge_value(std::size_t part, std::size_t loop, std::size_t edge, const std::vector<T>& parameters) const {
    return edge_value(part, loop, edge, parameters, static_cast<const SpurFlank<T>*>(nullptr));
  }
  /// A part's pivot and direction for number type T at the parameter values.
  template <class T>
  void motion_value(std::size_t part, const std::vector<T>& parameters, kernels::Vector<T>& pivot,
                    kernels::Vector<T>& direction) const;

  /// Part `part`'s geometry for number type T at the deviations.
  /// \throws ModelError when the part uses an exact-only feature template.
  template <class T>
  PartGeometry<T> part_geometry(std::size_t part, const std::vector<T>& deviations) const;

  /// Checks that every deviation vector of the box [lo, hi] keeps the choices the generic
  /// forms took at nominal (a template's pieces: an escape wheel's flat tooth tops, a Geneva
  /// driver's inner locking arc, the involute fit's radial segment below the base circle and
  /// the turning sense of its flank arcs), decided by certified interval enclosures over the
  /// box. \throws ModelError naming the template's argument when a vector of the box may
  /// change a choice (the generic form would then describe another shape than the exact one).
  /// The box given in doubles: checked as the exact box of those doubles.
  void check_choices(const std::vector<double>& lo, const std::vector<double>& hi) const;
  /// The exact box of deviations (session 62): the templates' rules are decided over it exactly
  /// where the doubles' enclosures cannot (a box within 2^-k of a rule's bound, lengths far
  /// beyond the doubles); since session 63 the shape choices too (MPFI over the exact box where
  /// the doubles over its outward rounding leave them open).
  void check_choices(const std::vector<Rational>& lo, const std::vector<Rational>& hi) const;

 private:
  /// Edge `edge` of a ratchet_wheel's loop in the template's own order (templates_gears.cpp:
  /// tip and root vertices centre + r u(phase + 2 pi k / teeth), the smooth form of the exact
  /// expansion's rounded unit vectors).
  /// Edges of a generic feature template's loop (circle, pin: 1).
  static std::size_t feature_edge_count(const FeatureRecipe& feature, std::size_t sub = 0) {
    if (feature.name == "ratchet_wheel") return 2 * static_cast<std::size_t>(feature.teeth);
    if (feature.name == "spur_gear" && feature.arguments.count("flank_radius"))
      return 4 * static_cast<std::size_t>(feature.teeth);
    if (sub < feature.edge_counts.size()) return feature.edge_counts[sub];
    return 1;
  }
  /// The feature a loop of the part (Part::loops index, past the explicit loops) comes from,
  /// and which of its loops it is.
  static std::pair<const FeatureRecipe*, std::size_t> feature_loop(const PartRecipe& recipe, std::size_t loop) {
    std::size_t l = loop - recipe.loops.size();
    for (const FeatureRecipe& feature : recipe.features) {
      std::size_t count = std::max<std::size_t>(feature.loop_count, 1);
      if (l < count) return {&feature, l};
      l -= count;
    }
    throw ModelError("", "internal error: no feature template loop " + std::to_string(loop));
  }
  /// Edge `edge` (template order) of loop `sub` of a geneva_wheel, geneva_driver, escape_wheel,
  /// anchor, balance or involute-fit spur_gear: the smooth form of templates*.cpp's expansion.
  template <class T>
  void template_edge(const FeatureRecipe& feature, std::size_t sub, std::size_t edge, const std::vector<T>& parameters,
                     EdgeValue<T>& value) const;
  template <class T>
  void ratchet_edge(const FeatureRecipe& feature, std::size_t edge, const std::vector<T>& parameters,
                    EdgeValue<T>& value) const;
  /// edge_value; on a spur_gear's loop with `flank` given, that canonical flank (spur_flank at
  /// the same parameters, computed once for all the loop's edges by part_geometry) instead of
  /// computing it for the edge: the same values.
  template <class T>
  EdgeValue<T> edge_value(std::size_t part, std::size_t loop, std::size_t edge, const std::vector<T>& parameters,
                          const SpurFlank<T>* flank) const;

  /// The canonical right flank of a spur_gear with flank_radius (the smooth form of the exact
  /// expansion: its rounded unit vectors and the ends' rounding to exact points of the flank
  /// circle are the recorded roundings), with the crossings `tip_side` / `root_side`.
  template <class T>
  SpurFlank<T> spur_flank(const FeatureRecipe& feature, const std::vector<T>& parameters, int tip_side,
                          int root_side) const;
  /// Edge `edge` of a spur_gear's loop (flank_radius form) in the template's order: per tooth
  /// k, right flank (root -> tip), tip arc, left flank (mirror, tip -> root), root arc to tooth
  /// k + 1, each placed by u(phase + 2 pi k / teeth) about the centre.
  template <class T>
  void spur_gear_edge(const FeatureRecipe& feature, std::size_t edge, const std::vector<T>& parameters,
                      const SpurFlank<T>* flank, EdgeValue<T>& value) const;

  std::shared_ptr<const Model> nominal_;
  long length_exponent_ = 0;
  /// rescaled(): the form as read, whose exact_model() is divided by 10^length_exponent_
  std::shared_ptr<const ParametricModel> unscaled_;
  bool profile_tolerances_ = false;   ///< the model has profile tolerances (offset parameters)
  std::string text_;
  long precision_bits_ = 256;
  std::map<std::string, Rational> nominal_overrides_;  ///< ReadOptions::parameter_values as read  ///< the reader's working precision for this model (read_model_escalating)
  bool degrees_ = false;
  std::vector<Slot> parameter_nominals_;
  std::vector<bool> derived_;
  std::vector<PartRecipe> parts_;
  bool generic_ = true;
  std::string exact_only_feature_;
  /// the first tooth or slot count varying with a toleranced parameter: its pointer, the refusal
  std::pair<std::string, std::string> count_refusal_;

  friend class RecipeBuilder;
};

// ---------------------------------------------------------------- generic evaluation

template <class T>
std::vector<T> ParametricModel::parameter_values(const std::vector<T>& deviations) const {
  std::size_t n = parameter_count();
  if (deviations.size() != n)
    throw ModelError("/parameters", "expected " + std::to_string(n) + " parameter deviations, got " +
                                        std::to_string(deviations.size()));
  std::vector<T> values(n, Arithmetic<T>::constant(Rational(0)));
  std::vector<char> done(n, 0);
  std::function<T(std::size_t)> value_of = [&](std::size_t i) -> T {
    if (done[i]) return values[i];
    T base = derived_[i] ? evaluate_formula<T>(*parameter_nominals_[i].formula, value_of)
                         : Arithmetic<T>::constant(nominal_->parameters[i].nominal);
    values[i] = T(base + deviations[i]);
    done[i] = 1;
    return values[i];
  };
  for (std::size_t i = 0; i < n; ++i) value_of(i);
  return values;
}

namespace parametric_detail {

template <class T>
T slot_value(const Slot& slot, const std::vector<T>& parameters) {
  return evaluate_formula<T>(*slot.formula, [&](std::size_t i) { return parameters[i]; });
}

template <class T>
kernels::Vector<T> point_value(const PointRecipe& recipe, const std::vector<T>& parameters) {
  if (!recipe.polar) return {slot_value(recipe.x, parameters), slot_value(recipe.y, parameters)};
  kernels::Vector<T> center = point_value(*recipe.center, parameters);
  T radius = slot_value(recipe.radius, parameters);
  T angle = slot_value(recipe.angle, parameters);
  return {T(center.x + radius * Arithmetic<T>::cos(angle)), T(center.y + radius * Arithmetic<T>::sin(angle))};
}

template <class T>
T squared_distance(const kernels::Vector<T>& a, const kernels::Vector<T>& b) {
  kernels::Vector<T> d = a - b;
  return kernels::dot(d, d);
}

}  // namespace parametric_detail

template <class T>
PartGeometry<T> ParametricModel::part_geometry(std::size_t part, const std::vector<T>& deviations) const {
  const PartRecipe& recipe = parts_.at(part);
  std::vector<T> p = parameter_values(deviations);
  PartGeometry<T> geometry;
  std::size_t loops = recipe.loops.size();
  for (const FeatureRecipe& feature : recipe.features) loops += std::max<std::size_t>(feature.loop_count, 1);
  for (std::size_t l = 0; l < loops; ++l) {
    std::size_t edges = l < recipe.loops.size() && !recipe.loops[l].circle ? recipe.loops[l].edges.size() : 1;
    std::optional<SpurFlank<T>> flank;   // a spur gear's canonical flank: one for all its edges
    if (l >= recipe.loops.size()) {
      auto [feature, sub] = feature_loop(recipe, l);
      edges = feature_edge_count(*feature, sub);
      if (feature->name == "spur_gear" && feature->arguments.count("flank_radius"))
        flank = spur_flank(*feature, p, feature->tip_side, feature->root_side);
    }
    std::vector<EdgeValue<T>> values;
    for (std::size_t e = 0; e < edges; ++e) values.push_back(edge_value(part, l, e, p, flank ? &*flank : nullptr));
    geometry.loops.push_back(std::move(values));
  }
  motion_value(part, p, geometry.pivot, geometry.direction);
  return geometry;
}

template <class T>
EdgeValue<T> ParametricModel::edge_value(std::size_t part, std::size_t loop, std::size_t edge, const std::vector<T>& p,
                                         const SpurFlank<T>* flank) const {
  using namespace parametric_detail;
  const PartRecipe& recipe = parts_.at(part);
  bool reversed = loop < recipe.reversed.size() && recipe.reversed[loop];
  EdgeValue<T> value;
  auto circle = [&](const kernels::Vector<T>& center, const T& radius) {
    value.arc = true;
    value.center = center;
    value.source = kernels::Vector<T>{T(center.x + radius), center.y};
    value.target = value.source;
    value.radius_squared = T(radius * radius);
    value.ccw = true;
  };
  if (loop < recipe.loops.size()) {
    const LoopRecipe& l = recipe.loops[loop];
    if (l.circle) {
      circle(point_value(l.center, p), slot_value(l.radius, p));
    } else {
      std::size_t count = l.edges.size();
      std::size_t index = reversed ? count - 1 - edge : edge;
      const EdgeRecipe& e = l.edges.at(index);
      value.arc = e.arc;
      value.source = point_value(index == 0 ? l.start : l.edges[index - 1].target, p);
      value.target = point_value(e.target, p);
      if (e.arc) {
        value.center = point_value(e.center, p);
        value.radius_squared = squared_distance(value.source, value.center);
        value.ccw = e.ccw;
      }
    }
  } else {
    auto [found, sub] = feature_loop(recipe, loop);
    const FeatureRecipe& feature = *found;
    std::size_t count = feature_edge_count(feature, sub);
    if (feature.name == "ratchet_wheel") {
      ratchet_edge(feature, reversed ? count - 1 - edge : edge, p, value);
    } else if (feature.name == "spur_gear" && feature.arguments.count("flank_radius")) {
      spur_gear_edge(feature, reversed ? count - 1 - edge : edge, p, flank, value);
    } else if (feature.name == "circle" || feature.name == "pin") {
      circle(point_value(feature.arguments.at("center").point, p), slot_value(feature.arguments.at("radius").number, p));
    } else {
      if (sub >= feature.ccw.size())
        throw ModelError(feature.pointer, "feature template '" + feature.name +
                                              "' has an exact parametric form only here (no derivatives or intervals)");
      template_edge(feature, sub, reversed ? count - 1 - edge : edge, p, value);
    }
  }
  if (reversed) {
    std::swap(value.source, value.target);
    value.ccw = !value.ccw;
  }
  return value;
}

template <class T>
void ParametricModel::ratchet_edge(const FeatureRecipe& feature, std::size_t edge, const std::vector<T>& p,
                                   EdgeValue<T>& value) const {
  using namespace parametric_detail;
  using A = Arithmetic<T>;
  auto argument = [&](const char* key) { return feature.arguments.find(key); };
  kernels::Vector<T> center = point_value(argument("center")->second.point, p);
  T tip = slot_value(argument("tip_radius")->second.number, p);
  T root = slot_value(argument("root_radius")->second.number, p);
  T phase = argument("phase") != feature.arguments.end() ? slot_value(argument("phase")->second.number, p)
                                                         : A::constant(Rational(0));
  bool free_ccw = argument("dir") == feature.arguments.end() || argument("dir")->second.word == "ccw";
  long n = feature.teeth;
  auto vertex = [&](long k, const T& radius) {
    T angle = T(phase + A::constant(Rational(2 * (k % n), n)) * A::pi());
    return kernels::Vector<T>{T(center.x + radius * A::cos(angle)), T(center.y + radius * A::sin(angle))};
  };
  long k = static_cast<long>(edge / 2);
  // ccw: root k -> tip k (face), tip k -> root k+1 (back); cw: tip k -> root k, root k -> tip k+1.
  bool first = edge % 2 == 0;
  if (free_ccw) {
    value.source = first ? vertex(k, root) : vertex(k, tip);
    value.target = first ? vertex(k, tip) : vertex(k + 1, root);
  } else {
    value.source = first ? vertex(k, tip) : vertex(k, root);
    value.target = first ? vertex(k, root) : vertex(k + 1, tip);
  }
  value.arc = false;
}

template <class T>
SpurFlank<T> ParametricModel::spur_flank(const FeatureRecipe& feature, const std::vector<T>& p, int tip_side,
                                         int root_side) const {
  using namespace parametric_detail;
  using A = Arithmetic<T>;
  auto number = [&](const char* key) { return slot_value(feature.arguments.at(key).number, p); };
  T pitch = number("pitch_radius"), radius = number("flank_radius");
  T tip_radius = T(pitch + number("addendum")), root_radius = T(pitch - number("dedendum"));
  auto pressure = feature.arguments.find("pressure_angle");
  T alpha = pressure != feature.arguments.end() ? slot_value(pressure->second.number, p)
                                                : T(A::constant(Rational(1, 9)) * A::pi());
  T beta = T(number("tooth_thickness") / T(pitch + pitch));
  SpurFlank<T> flank;
  flank.pitch_point = {T(pitch * A::cos(beta)), T(-(pitch * A::sin(beta)))};
  // the flank normal u(pi/2 + alpha - beta) at the pitch point
  T turn = T(alpha - beta);
  flank.centre = {T(flank.pitch_point.x - radius * A::sin(turn)), T(flank.pitch_point.y + radius * A::cos(turn))};
  // the flank circle's crossing with the circle of radius R about the gear's centre
  const kernels::Vector<T>& c = flank.centre;
  T d2 = T(c.x * c.x + c.y * c.y);
  T d = A::sqrt(d2);
  auto crossing = [&](const T& circle, int side) {
    T along = T(T(circle * circle - radius * radius + d2) / T(d + d));
    T across = A::sqrt(T(circle * circle - along * along));
    T a = T(along / d), h = T(across / d);
    if (side < 0) h = T(-h);
    return kernels::Vector<T>{T(a * c.x - h * c.y), T(a * c.y + h * c.x)};
  };
  flank.tip = crossing(tip_radius, tip_side);
  flank.root = crossing(root_radius, root_side);
  return flank;
}

template <class T>
void ParametricModel::spur_gear_edge(const FeatureRecipe& feature, std::size_t edge, const std::vector<T>& p,
                                     const SpurFlank<T>* given_flank, EdgeValue<T>& value) const {
  using namespace parametric_detail;
  using A = Arithmetic<T>;
  kernels::Vector<T> center = point_value(feature.arguments.at("center").point, p);
  auto phase_argument = feature.arguments.find("phase");
  T phase = phase_argument != feature.arguments.end() ? slot_value(phase_argument->second.number, p)
                                                      : A::constant(Rational(0));
  std::optional<SpurFlank<T>> own;
  if (!given_flank) own = spur_flank(feature, p, feature.tip_side, feature.root_side);
  const SpurFlank<T>& flank = given_flank ? *given_flank : *own;
  long n = feature.teeth;
  long k = static_cast<long>(edge / 4);
  auto place = [&](long tooth, const kernels::Vector<T>& local, bool mirrored) {
    T angle = T(phase + A::constant(Rational(2 * (tooth % n), n)) * A::pi());
    T cs = A::cos(angle), sn = A::sin(angle);
    T y = mirrored ? T(-local.y) : local.y;
    return kernels::Vector<T>{T(center.x + T(local.x * cs - y * sn)), T(center.y + T(local.x * sn + y * cs))};
  };
  value.arc = true;
  switch (edge % 4) {
    case 0:   // right flank, root -> tip
      value.source = place(k, flank.root, false);
      value.target = place(k, flank.tip, false);
      value.center = place(k, flank.centre, false);
      value.ccw = feature.flank_ccw;
      break;
    case 1:   // tip arc about the centre
      value.source = place(k, flank.tip, false);
      value.target = place(k, flank.tip, true);
      value.center = center;
      value.ccw = true;
      break;
    case 2:   // left flank (the mirror image, run from the tip down: same turning sense)
      value.source = place(k, flank.tip, true);
      value.target = place(k, flank.root, true);
      value.center = place(k, flank.centre, true);
      value.ccw = feature.flank_ccw;
      break;
    default:  // root arc to the next tooth
      value.source = place(k, flank.root, true);
      value.target = place(k + 1, flank.root, false);
      value.center = center;
      value.ccw = true;
      break;
  }
  value.radius_squared = squared_distance(value.source, value.center);
}

// ------------------------------------------------ generic forms of the other templates (session 57)

namespace parametric_detail {

template <class T>
T constant(long numerator, long denominator = 1) {
  Rational q(numerator, denominator);
  q.canonicalize();
  return Arithmetic<T>::constant(q);
}

/// u(angle) = (cos angle, sin angle).
template <class T>
kernels::Vector<T> unit(const T& angle) {
  return {Arithmetic<T>::cos(angle), Arithmetic<T>::sin(angle)};
}

/// `p` rotated by the unit vector `u` (the complex product: template_geometry.cpp rotate).
template <class T>
kernels::Vector<T> turned(const kernels::Vector<T>& p, const kernels::Vector<T>& u) {
  return {T(p.x * u.x - p.y * u.y), T(p.x * u.y + p.y * u.x)};
}

template <class T>
kernels::Vector<T> mirrored(const kernels::Vector<T>& p) {
  return {p.x, T(-p.y)};
}

/// The angle 2 pi k / n (a multiple of pi: exact_unit_vector_pi's argument).
template <class T>
T tooth_angle(long k, long n) {
  long m = ((k % n) + n) % n;
  return T(constant<T>(2 * m, n) * Arithmetic<T>::pi());
}

/// A feature's number argument, or `fallback` when absent.
template <class T>
T argument_or(const FeatureRecipe& feature, const char* key, const std::vector<T>& p, const T& fallback) {
  auto found = feature.arguments.find(key);
  return found != feature.arguments.end() ? slot_value(found->second.number, p) : fallback;
}

/// The canonical right flank of a spur_gear's involute fit (templates_gears.cpp
/// expand_spur_gear without flank_radius), smooth: the arcs tangent at the pitch point P with
/// centres on the normal n there, through the involute's points on the tip circle and on the
/// base circle (then a radial segment down to the root circle: `radial`) or on the root circle.
/// The exact expansion rounds the centres' distances along n and places the ends at exact
/// points of the arcs' circles next to the involute points (recorded roundings).
template <class T>
struct InvoluteFlank {
  std::size_t pieces = 2;
  kernels::Vector<T> start;
  kernels::Vector<T> ends[3];
  kernels::Vector<T> centres[3];
};

template <class T>
InvoluteFlank<T> involute_flank(const FeatureRecipe& feature, const std::vector<T>& p, bool radial) {
  using A = Arithmetic<T>;
  auto number = [&](const char* key) { return slot_value(feature.arguments.at(key).number, p); };
  T pitch = number("pitch_radius");
  T tip_radius = T(pitch + number("addendum")), root_radius = T(pitch - number("dedendum"));
  T alpha = argument_or(feature, "pressure_angle", p, T(constant<T>(1, 9) * A::pi()));
  T beta = T(number("tooth_thickness") / T(pitch + pitch));
  kernels::Vector<T> pitch_point{T(pitch * A::cos(beta)), T(-(pitch * A::sin(beta)))};
  T turn = T(alpha - beta);
  kernels::Vector<T> normal{T(-A::sin(turn)), A::cos(turn)};   // u(pi/2 + alpha - beta)
  T base = T(pitch * A::cos(alpha));
  T involute_alpha = T(A::tan(alpha) - alpha);
  // The involute's point at radius r > base: pressure angle a = acos(base / r), polar angle
  // -beta + inv(a) - inv(alpha), inv(a) = tan a - a (tan a = sqrt(1 - c^2) / c, c = base / r).
  auto involute_point = [&](const T& r) {
    T c = T(base / r);
    T s = A::sqrt(T(constant<T>(1) - c * c));
    T angle = T(T(T(s / c) - A::atan2(s, c)) - T(beta + involute_alpha));
    return kernels::Vector<T>{T(r * A::cos(angle)), T(r * A::sin(angle))};
  };
  // The arc tangent at P to the normal's perpendicular through `end`: centre P + s n with
  // s = |d|^2 / (2 d.n), d = end - P.
  auto tangent_centre = [&](const kernels::Vector<T>& end) {
    kernels::Vector<T> d = end - pitch_point;
    T s = T(kernels::dot(d, d) / T(constant<T>(2) * kernels::dot(d, normal)));
    return pitch_point + kernels::scaled(s, normal);
  };
  InvoluteFlank<T> flank;
  kernels::Vector<T> tip = involute_point(tip_radius);
  if (radial) {
    // The involute starts on the base circle at polar angle -beta - inv(alpha); the radial
    // segment runs from the root circle there (the exact foot within the recorded rounding).
    T angle = T(-(beta + involute_alpha));
    kernels::Vector<T> direction = unit(angle);
    kernels::Vector<T> base_point = kernels::scaled(base, direction);
    flank.pieces = 3;
    flank.start = kernels::scaled(root_radius, direction);
    flank.ends[0] = base_point;
    flank.ends[1] = pitch_point;
    flank.ends[2] = tip;
    flank.centres[0] = base_point;   // a segment: no centre
    flank.centres[1] = tangent_centre(base_point);
    flank.centres[2] = tangent_centre(tip);
  } else {
    kernels::Vector<T> root = involute_point(root_radius);
    flank.pieces = 2;
    flank.start = root;
    flank.ends[0] = pitch_point;
    flank.ends[1] = tip;
    flank.centres[0] = tangent_centre(root);
    flank.centres[1] = tangent_centre(tip);
  }
  return flank;
}

/// Whether an involute fit's nominal expansion has the radial segment (3 pieces per flank: 8
/// edges per tooth, else 6).
inline bool involute_radial(const FeatureRecipe& feature) {
  return !feature.edge_counts.empty() && feature.teeth > 0 &&
         feature.edge_counts[0] == 8 * static_cast<std::size_t>(feature.teeth);
}

}  // namespace parametric_detail

template <class T>
void ParametricModel::template_edge(const FeatureRecipe& feature, std::size_t sub, std::size_t edge,
                                    const std::vector<T>& p, EdgeValue<T>& value) const {
  using namespace parametric_detail;
  using A = Arithmetic<T>;
  using V = kernels::Vector<T>;
  auto number = [&](const char* key) { return slot_value(feature.arguments.at(key).number, p); };
  auto point = [&](const char* key) { return point_value(feature.arguments.at(key).point, p); };
  const T zero = constant<T>(0);
  const std::vector<bool>& senses = feature.ccw.at(sub);
  // Sets the edge source -> target (an arc about `centre` when `arc`).
  auto set = [&](const V& source, const V& target, bool arc, const V& centre) {
    value.arc = arc;
    value.source = source;
    value.target = target;
    if (arc) {
      value.center = centre;
      value.radius_squared = squared_distance(source, centre);
      value.ccw = senses.at(edge);
    }
  };
  // A loop given as its start and its edges' targets / centres (arc when the centre is given).
  struct Step {
    V target;
    std::optional<V> centre;
  };
  auto from_list = [&](const V& start, const std::vector<Step>& steps) {
    const Step& step = steps.at(edge);
    const V& source = edge == 0 ? start : steps[edge - 1].target;
    set(source, step.target, step.centre.has_value(), step.centre ? *step.centre : source);
  };
  const std::string& name = feature.name;

  if (name == "geneva_driver") {
    V center = point("center");
    T span = number("lock_span");
    T phase = argument_or(feature, "phase", p, zero);
    T offset = argument_or(feature, "lock_offset", p, T(-(span / constant<T>(2))));
    if (sub == 0) {   // the pin
      V pin = center + kernels::scaled(number("pin_center_radius"), unit(phase));
      V start{T(pin.x + number("pin_radius")), pin.y};
      set(start, start, true, pin);
      return;
    }
    // The crescent on the side opposite the pin: -u(phase + offset) .. -u(phase + offset + span).
    V start = -unit(T(phase + offset)), end = -unit(T(T(phase + offset) + span));
    T outer = number("lock_outer_radius"), inner = number("lock_inner_radius");
    V outer_start = center + kernels::scaled(outer, start);
    if (feature.edge_counts.at(1) == 4)
      from_list(outer_start, {{center + kernels::scaled(outer, end), center},
                              {center + kernels::scaled(inner, end), std::nullopt},
                              {center + kernels::scaled(inner, start), center},
                              {outer_start, std::nullopt}});
    else
      from_list(outer_start, {{center + kernels::scaled(outer, end), center}, {center, std::nullopt}, {outer_start, std::nullopt}});
    return;
  }

  if (name == "geneva_wheel") {
    // Six edges per slot k: lock arc k, mouth R, wall R, bottom, wall L, mouth L (to lock k + 1).
    V center = point("center");
    long n = feature.teeth;
    long k = static_cast<long>(edge / 6);
    T half = T(number("slot_width") / constant<T>(2));
    T inner = number("slot_inner_radius"), outer = number("slot_outer_radius");
    T lock_distance = number("lock_center_radius"), lock_radius = number("lock_radius");
    T half_span = T(number("lock_span") / constant<T>(2));
    T phase = argument_or(feature, "phase", p, zero);
    // The walls reach the circle slot_outer_radius (the exact walls end within the rounding).
    T reach = A::sqrt(T(outer * outer - half * half));
    V lock_start{T(lock_distance - lock_radius * A::cos(half_span)), T(-(lock_radius * A::sin(half_span)))};
    V lock_end{lock_start.x, T(-lock_start.y)};
    V lock_center{lock_distance, zero};
    auto lock_turn = [&](long j) { return unit(T(phase + tooth_angle<T>(j, n))); };
    auto place = [&](const V& u, const V& local) { return center + turned(local, u); };
    V lock = lock_turn(k);
    V slot = unit(T(phase + T(constant<T>(2 * (k % n) + 1, n) * A::pi())));
    V vertices[7] = {place(lock, lock_start), place(lock, lock_end), place(slot, V{reach, T(-half)}),
                     place(slot, V{inner, T(-half)}), place(slot, V{inner, half}), place(slot, V{reach, half}),
                     place(lock_turn(k + 1), lock_start)};
    std::size_t j = edge % 6;
    if (j == 0) set(vertices[0], vertices[1], true, place(lock, lock_center));
    else if (j == 3) set(vertices[3], vertices[4], true, place(slot, V{inner, zero}));
    else set(vertices[j], vertices[j + 1], false, vertices[j]);
    return;
  }

  if (name == "escape_wheel") {
    // Per tooth k: [root arc from tooth k - 1's face root to the back root], [back to the
    // trailing top corner, top to the leading corner] or [back to the leading corner], face to
    // the face root; canonical for a wheel driven ccw, mirrored for cw, turned by phase.
    V center = point("center");
    long n = feature.teeth;
    bool root_arc = feature.arguments.count("back_angle") != 0;
    std::size_t per_tooth = feature.edge_counts.at(0) / static_cast<std::size_t>(n);
    bool top = per_tooth == (root_arc ? 4u : 3u);
    long k = static_cast<long>(edge / per_tooth);
    std::size_t j = edge % per_tooth;
    T tip = number("tip_radius"), root = number("root_radius");
    T phase = argument_or(feature, "phase", p, zero);
    T face = argument_or(feature, "face_angle", p, zero);
    auto dir = feature.arguments.find("dir");
    bool driven_ccw = dir != feature.arguments.end() && dir->second.word == "ccw";
    V phase_unit = unit(phase);
    auto at = [&](long tooth, const V& local) {
      V q = turned(local, unit(tooth_angle<T>(tooth, n)));
      if (!driven_ccw) q = mirrored(q);
      return center + turned(q, phase_unit);
    };
    V face_root = kernels::scaled(root, unit(T(-face)));
    std::vector<V> targets;
    if (root_arc) targets.push_back(at(k, kernels::scaled(root, unit(T(-number("back_angle"))))));
    if (top) targets.push_back(at(k, kernels::scaled(tip, unit(T(-number("tip_angle"))))));
    targets.push_back(at(k, V{tip, zero}));
    targets.push_back(at(k, face_root));
    V source = j == 0 ? at(k - 1, face_root) : targets[j - 1];
    set(source, targets[j], root_arc && j == 0, center);
    return;
  }

  if (name == "anchor") {
    // Canonical frame: pivot at the origin, +y from the wheel centre to the pivot.
    V pivot = point("center"), wheel = point("wheel_center");
    T wheel_radius = number("wheel_radius"), width = number("pallet_width");
    T lift = number("lift"), lock = number("lock");
    T extent = argument_or(feature, "pallet_extent", p, A::constant(Rational(174533, 500000)));
    T fork_length = number("fork_length"), half_fork = T(number("fork_width") / constant<T>(2));
    T half_slot = T(number("fork_slot_width") / constant<T>(2)), slot_depth = number("fork_slot_depth");
    V axis = pivot - wheel;
    T distance_squared = kernels::dot(axis, axis);
    T distance = A::sqrt(distance_squared);
    T tangent = A::sqrt(T(distance_squared - wheel_radius * wheel_radius));
    T inner = T(tangent - width / constant<T>(2)), outer = T(tangent + width / constant<T>(2));
    // the angle at the pivot between the wheel centre and the point of the wheel's tip circle
    // at distance rho: acos((D^2 + rho^2 - R^2) / (2 D rho))
    auto path_angle = [&](const T& rho) {
      T c = T(T(distance_squared + rho * rho - wheel_radius * wheel_radius) / T(constant<T>(2) * distance * rho));
      return A::atan2(A::sqrt(T(constant<T>(1) - c * c)), c);
    };
    T down = T(constant<T>(3, 2) * A::pi());
    T half_lift = T(lift / constant<T>(2)), half_lock = T(lock / constant<T>(2));
    T entry = T(T(down - path_angle(outer)) - half_lift + half_lock);
    T exit = T(T(down + path_angle(inner)) + half_lift - half_lock);
    auto polar = [&](const T& radius, const T& angle) { return kernels::scaled(radius, unit(angle)); };
    V fork_base_right{half_fork, A::sqrt(T(outer * outer - half_fork * half_fork))};
    V up = kernels::scaled(T(constant<T>(1) / distance), axis);
    V frame{up.y, T(-up.x)};
    auto at = [&](const V& local) { return pivot + turned(local, frame); };
    V origin = pivot;
    T slot_bottom = T(fork_length - slot_depth);
    from_list(at(polar(outer, T(exit - lift))),
              {{at(polar(outer, T(exit + extent))), origin},
               {at(fork_base_right), origin},
               {at(V{half_fork, fork_length}), std::nullopt},
               {at(V{half_slot, fork_length}), std::nullopt},
               {at(V{half_slot, slot_bottom}), std::nullopt},
               {at(V{T(-half_slot), slot_bottom}), std::nullopt},
               {at(V{T(-half_slot), fork_length}), std::nullopt},
               {at(V{T(-half_fork), fork_length}), std::nullopt},
               {at(V{T(-half_fork), fork_base_right.y}), std::nullopt},
               {at(polar(outer, T(entry - extent))), origin},
               {at(polar(outer, entry)), origin},
               {at(polar(inner, T(entry + lift))), std::nullopt},
               {at(polar(inner, T(entry - extent))), origin},
               {at(V{zero, T(-(T(distance - wheel_radius) / constant<T>(2)))}), std::nullopt},
               {at(polar(inner, T(exit + extent))), std::nullopt},
               {at(polar(inner, exit)), origin},
               {at(polar(outer, T(exit - lift))), std::nullopt}});
    return;
  }

  if (name == "balance") {
    // The disc and the impulse pin's circle merged at their crossings (mirror images in the
    // pin's axis), turned by phase.
    V center = point("center");
    T radius = number("radius"), pin_radius = number("pin_radius"), pin_distance = number("pin_center_radius");
    T along = T(T(pin_distance * pin_distance + radius * radius - pin_radius * pin_radius) /
                T(constant<T>(2) * pin_distance));
    T across = A::sqrt(T(radius * radius - along * along));
    V u = unit(argument_or(feature, "phase", p, zero));
    auto at = [&](const V& local) { return center + turned(local, u); };
    V meet = at(V{along, across});
    from_list(meet, {{at(V{along, T(-across)}), center}, {meet, at(V{pin_distance, zero})}});
    return;
  }

  if (name == "spur_gear") {
    // The involute fit: per tooth k, the right flank's pieces (root -> tip), the tip arc, the
    // left flank's (mirror images, tip -> root), the root arc to tooth k + 1.
    V center = point("center");
    long n = feature.teeth;
    InvoluteFlank<T> flank = involute_flank(feature, p, involute_radial(feature));
    std::size_t pieces = flank.pieces, per_tooth = 2 * pieces + 2;
    long k = static_cast<long>(edge / per_tooth);
    std::size_t j = edge % per_tooth;
    T phase = argument_or(feature, "phase", p, zero);
    auto place = [&](long tooth, const V& local) { return center + turned(local, unit(T(phase + tooth_angle<T>(tooth, n)))); };
    auto piece_start = [&](std::size_t i) { return i == 0 ? flank.start : flank.ends[i - 1]; };
    auto is_arc = [&](std::size_t i) { return !(pieces == 3 && i == 0); };
    const V& tip = flank.ends[pieces - 1];
    if (j < pieces) {
      set(place(k, piece_start(j)), place(k, flank.ends[j]), is_arc(j), place(k, flank.centres[j]));
    } else if (j == pieces) {
      set(place(k, tip), place(k, mirrored(tip)), true, center);
    } else if (j < 2 * pieces + 1) {
      std::size_t i = 2 * pieces - j;
      set(place(k, mirrored(flank.ends[i])), place(k, mirrored(piece_start(i))), is_arc(i),
          place(k, mirrored(flank.centres[i])));
    } else {
      set(place(k, mirrored(flank.start)), place(k + 1, flank.start), true, center);
    }
    return;
  }
  throw ModelError(feature.pointer, "feature template '" + name + "' has an exact parametric form only");
}

template <class T>
void ParametricModel::motion_value(std::size_t part, const std::vector<T>& p, kernels::Vector<T>& pivot,
                                   kernels::Vector<T>& direction) const {
  using namespace parametric_detail;
  const MotionRecipe& motion = parts_.at(part).motion;
  pivot = kernels::Vector<T>{Arithmetic<T>::constant(Rational(0)), Arithmetic<T>::constant(Rational(0))};
  direction = kernels::Vector<T>{Arithmetic<T>::constant(Rational(1)), Arithmetic<T>::constant(Rational(0))};
  if (motion.has_pivot) pivot = point_value(motion.pivot, p);
  if (motion.has_direction) {
    if (motion.direction_is_angle) {
      T a = slot_value(motion.direction_angle, p);
      direction = {Arithmetic<T>::cos(a), Arithmetic<T>::sin(a)};
    } else {
      T dx = slot_value(motion.direction_x, p), dy = slot_value(motion.direction_y, p);
      T length = Arithmetic<T>::sqrt(T(dx * dx + dy * dy));
      direction = {T(dx / length), T(dy / length)};
    }
  }
}

}  // namespace hipair::model_detail
