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
#pragma once

#include "kernels/vector.hpp"
#include "model/formula.hpp"
#include "model/templates.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
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
  static ParametricModel read(std::string_view json_text, std::string_view source_name = "<string>");
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

  /// The exact model at a deviation vector. \throws ModelError when the geometry is invalid
  /// there (loops crossing, ...), naming the pointer.
  Model exact_model(const std::vector<Rational>& deviations) const;

  /// The value of every parameter at a deviation vector, for number type T.
  template <class T>
  std::vector<T> parameter_values(const std::vector<T>& deviations) const;

  /// Part `part`'s geometry for number type T at the deviations.
  /// \throws ModelError when the part uses an exact-only feature template.
  template <class T>
  PartGeometry<T> part_geometry(std::size_t part, const std::vector<T>& deviations) const;

 private:
  std::shared_ptr<const Model> nominal_;
  std::string text_;
  bool degrees_ = false;
  std::vector<Slot> parameter_nominals_;
  std::vector<bool> derived_;
  std::vector<PartRecipe> parts_;
  bool generic_ = true;
  std::string exact_only_feature_;

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
  using namespace parametric_detail;
  const PartRecipe& recipe = parts_.at(part);
  std::vector<T> p = parameter_values(deviations);
  PartGeometry<T> geometry;
  auto circle = [&](const kernels::Vector<T>& center, const T& radius) {
    EdgeValue<T> edge;
    edge.arc = true;
    edge.center = center;
    edge.source = kernels::Vector<T>{T(center.x + radius), center.y};
    edge.target = edge.source;
    edge.radius_squared = T(radius * radius);
    edge.ccw = true;
    return std::vector<EdgeValue<T>>{edge};
  };
  for (const LoopRecipe& loop : recipe.loops) {
    if (loop.circle) {
      geometry.loops.push_back(circle(point_value(loop.center, p), slot_value(loop.radius, p)));
      continue;
    }
    std::vector<EdgeValue<T>> edges;
    kernels::Vector<T> current = point_value(loop.start, p);
    for (const EdgeRecipe& e : loop.edges) {
      EdgeValue<T> edge;
      edge.arc = e.arc;
      edge.source = current;
      edge.target = point_value(e.target, p);
      if (e.arc) {
        edge.center = point_value(e.center, p);
        edge.radius_squared = squared_distance(edge.source, edge.center);
        edge.ccw = e.ccw;
      }
      current = edge.target;
      edges.push_back(edge);
    }
    geometry.loops.push_back(std::move(edges));
  }
  for (const FeatureRecipe& feature : recipe.features) {
    if (feature.name != "circle" && feature.name != "pin")
      throw ModelError(feature.pointer, "feature template '" + feature.name +
                                            "' has an exact parametric form only (no derivatives or intervals yet)");
    geometry.loops.push_back(circle(point_value(feature.arguments.at("center").point, p),
                                    slot_value(feature.arguments.at("radius").number, p)));
  }
  for (std::size_t l = 0; l < geometry.loops.size() && l < recipe.reversed.size(); ++l) {
    if (!recipe.reversed[l]) continue;
    auto& edges = geometry.loops[l];
    std::reverse(edges.begin(), edges.end());
    for (EdgeValue<T>& edge : edges) {
      std::swap(edge.source, edge.target);
      edge.ccw = !edge.ccw;
    }
  }
  const MotionRecipe& motion = recipe.motion;
  if (motion.has_pivot) geometry.pivot = point_value(motion.pivot, p);
  if (motion.has_direction) {
    if (motion.direction_is_angle) {
      T a = slot_value(motion.direction_angle, p);
      geometry.direction = {Arithmetic<T>::cos(a), Arithmetic<T>::sin(a)};
    } else {
      T dx = slot_value(motion.direction_x, p), dy = slot_value(motion.direction_y, p);
      T length = Arithmetic<T>::sqrt(T(dx * dx + dy * dy));
      geometry.direction = {T(dx / length), T(dy / length)};
    }
  }
  return geometry;
}

}  // namespace hipair::model_detail
