// The parametric model: recording the formulas of a model's geometry (RecipeBuilder) and the
// exact evaluation at a parameter vector (ExactEvaluator), which repeats the reader's steps on
// the recorded slots. See parametric.hpp.
#include "model/parametric/parametric.hpp"
#include "model/parametric/certified_positive.hpp"
#include "model/parametric/dimensions.hpp"
#include "model/parametric/mpfi_arithmetic.hpp"
#include "model/parametric/number_traits.hpp"
#include "model/parametric/self_check.hpp"
#include "model/parametric/tie_arithmetic.hpp"

#include "model/exact_trig.hpp"
#include "model/expression.hpp"
#include "model/json_document.hpp"
#include "model/profile_tolerance.hpp"
#include "model/template_rules.hpp"
#include "model/reader.hpp"
#include "model/validate_geometry.hpp"

#include "core/model_scale.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>

namespace hipair::model_detail {
namespace {

Rational squared_distance(const Point& a, const Point& b) {
  Rational dx = a.x - b.x, dy = a.y - b.y;
  return dx * dx + dy * dy;
}

Quantity plus(Quantity q, const Rational& delta) {
  if (delta == 0) return q;
  if (q.exact) {
    q.rational += delta;
  } else {
    q.enclosure = *q.enclosure + Interval(delta);
  }
  return q;
}

// Exact evaluation of recorded slots at a deviation vector: the reader's steps.
class ExactEvaluator {
 public:
  ExactEvaluator(const Model& nominal, const std::vector<Slot>& parameter_nominals, bool degrees,
                 const std::vector<Rational>& deviations, std::vector<Rounding>& roundings)
      : nominal_(nominal), parameter_nominals_(parameter_nominals), degrees_(degrees),
        deviations_(deviations), roundings_(roundings), cache_(nominal.parameters.size()) {}

  Quantity parameter(std::size_t i) {
    if (cache_[i]) return *cache_[i];
    const Parameter& parameter = nominal_.parameters[i];
    const Slot& slot = parameter_nominals_[i];
    Quantity q = evaluate(slot);
    if (parameter.is_angle || q.is_angle) q = as_angle(q, degrees_, slot.pointer, slot.text);
    bool derived = mentions_parameters(slot.formula);
    if (!derived && deviations_[i] != 0) {
      q = Quantity::of(parameter.nominal + deviations_[i], parameter.is_angle);
    } else {
      q = plus(q, deviations_[i]);
    }
    cache_[i] = q;
    return q;
  }

  Quantity evaluate(const Slot& slot) {
    if (slot.literal) return Quantity::of(parse_literal(slot.text, slot.pointer));
    ExpressionContext context;
    context.degrees = degrees_;
    context.pointer = slot.pointer;
    context.parameter = [this, &slot](const std::string& name) {
      const Parameter* found = nominal_.find_parameter(name);
      if (!found) throw ModelError(slot.pointer, "unknown parameter '" + name + "'");
      return parameter(static_cast<std::size_t>(found - nominal_.parameters.data()));
    };
    return evaluate_expression(slot.text, context);
  }

  Rational number(const Slot& slot) { return to_rational(evaluate(slot), slot.pointer, slot.text, roundings_); }
  Quantity angle_quantity(const Slot& slot) { return as_angle(evaluate(slot), degrees_, slot.pointer, slot.text); }
  Rational angle(const Slot& slot) { return to_rational(angle_quantity(slot), slot.pointer, slot.text, roundings_); }

  Point point(const PointRecipe& recipe) {
    if (!recipe.polar) return Point{number(recipe.x), number(recipe.y)};
    Point center = point(*recipe.center);
    Rational radius = number(recipe.radius);
    Point unit = unit_vector(angle_quantity(recipe.angle), recipe.angle.pointer, recipe.angle.text, roundings_);
    return point_on_circle(center, radius, unit);
  }

  Point direction(const MotionRecipe& motion) {
    if (motion.direction_is_angle)
      return unit_vector(angle_quantity(motion.direction_angle), motion.direction_angle.pointer,
                         motion.direction_angle.text, roundings_);
    // the reader's construction (Reader::direction), on the recipe's slots
    Rational dx = number(motion.direction_x), dy = number(motion.direction_y);
    return unit_direction(dx, dy, motion.direction_x.pointer, motion.direction_x.text, motion.direction_y.text, roundings_);
  }

  std::vector<Rounding>& roundings() { return roundings_; }

 private:
  const Model& nominal_;
  const std::vector<Slot>& parameter_nominals_;
  bool degrees_;
  const std::vector<Rational>& deviations_;
  std::vector<Rounding>& roundings_;
  std::vector<std::optional<Quantity>> cache_;
};

// The loops of one part before orientation, from its recipe.
std::vector<Loop> exact_loops(const PartRecipe& recipe, ExactEvaluator& exact) {
  std::vector<Loop> loops;
  for (const LoopRecipe& loop_recipe : recipe.loops) {
    Loop loop;
    if (loop_recipe.circle) {
      Edge edge;
      edge.kind = Edge::Kind::arc;
      edge.center = exact.point(loop_recipe.center);
      Rational radius = exact.number(loop_recipe.radius);
      if (radius <= 0) throw ModelError(loop_recipe.radius.pointer, "a circle's radius must be positive");
      edge.source = Point{edge.center.x + radius, edge.center.y};
      edge.target = edge.source;
      edge.radius_squared = radius * radius;
      loop.edges.push_back(edge);
    } else {
      Point current = exact.point(loop_recipe.start);
      for (const EdgeRecipe& e : loop_recipe.edges) {
        Edge edge;
        edge.source = current;
        edge.target = exact.point(e.target);
        if (e.arc) {
          edge.kind = Edge::Kind::arc;
          edge.center = exact.point(e.center);
          edge.ccw = e.ccw;
          edge.radius_squared = squared_distance(edge.source, edge.center);
        }
        current = edge.target;
        loop.edges.push_back(edge);
      }
    }
    loops.push_back(std::move(loop));
  }
  for (const FeatureRecipe& feature : recipe.features) {
    std::map<std::string, TemplateValue> arguments;
    for (const auto& [key, argument] : feature.arguments) {
      switch (argument.kind) {
        case ArgumentKind::length: arguments.emplace(key, exact.number(argument.number)); break;
        case ArgumentKind::angle: arguments.emplace(key, exact.angle(argument.number)); break;
        case ArgumentKind::count: {
          Quantity q = exact.evaluate(argument.number);
          if (!q.is_rational()) throw ModelError(argument.number.pointer, "expected a positive whole number");
          arguments.emplace(key, q.rational);
          break;
        }
        case ArgumentKind::point: arguments.emplace(key, exact.point(argument.point)); break;
        case ArgumentKind::direction_word: arguments.emplace(key, argument.word); break;
      }
    }
    std::vector<Loop> expanded;
    try {
      expanded = expand_template(feature.name, arguments, feature.pointer, exact.roundings());
    } catch (const ModelError&) {
      throw;
    } catch (const Error& error) {
      throw ModelError(feature.pointer, error.what());
    }
    for (Loop& loop : expanded) loops.push_back(std::move(loop));
  }
  return loops;
}

}  // namespace

// Walks the document as the reader did and records every slot.
class RecipeBuilder {
 public:
  RecipeBuilder(ParametricModel& model, const JsonValue& root) : model_(model), root_(root) {}

  void build() {
    const Model& nominal = *model_.nominal_;
    model_.degrees_ = nominal.angle_unit == "deg";
    std::size_t n = nominal.parameters.size();
    model_.parameter_nominals_.resize(n);
    model_.derived_.assign(n, false);
    const JsonValue* parameters = root_.find("parameters");
    std::vector<Rational> zero(n, Rational(0));
    exact_ = std::make_unique<ExactEvaluator>(nominal, model_.parameter_nominals_, model_.degrees_, zero, roundings_);
    // First the slots (texts and formulas), then the unit conversions (which evaluate them).
    for (std::size_t i = 0; i < n && parameters; ++i) {
      const JsonValue& nominal_value = *parameters->find(nominal.parameters[i].name)->find("nominal");
      model_.parameter_nominals_[i] = raw_slot(nominal_value);
      auto overridden = model_.nominal_overrides_.find(nominal.parameters[i].name);
      if (overridden == model_.nominal_overrides_.end()) continue;
      // An overridden nominal is the exact value given, in mm or rad (an angle's is marked rad,
      // so that a degree file does not convert it).
      Slot& slot = model_.parameter_nominals_[i];
      slot.text = overridden->second.get_str() + (nominal.parameters[i].is_angle ? " rad" : "");
      slot.literal = false;
      slot.formula = parse_formula(slot.text, slot.pointer, [&](const std::string& name) -> std::size_t {
        throw ModelError(slot.pointer, "unknown parameter '" + name + "'");
      });
    }
    for (std::size_t i = 0; i < n && parameters; ++i) {
      Slot& slot = model_.parameter_nominals_[i];
      if (nominal.parameters[i].is_angle) slot.formula = angle_formula(slot);
      model_.derived_[i] = mentions_parameters(slot.formula);
    }
    const JsonValue& parts = *root_.find("parts");
    for (std::size_t k = 0; k < parts.items.size(); ++k) model_.parts_.push_back(part(parts.items[k], k));
  }

 private:
  Slot raw_slot(const JsonValue& value) {
    Slot slot;
    slot.text = value.text;
    slot.pointer = value.pointer;
    slot.literal = value.is_number();
    const Model& nominal = *model_.nominal_;
    FormulaUnits units{model_.degrees_, [&nominal](std::size_t i) { return nominal.parameters[i].is_angle; }};
    slot.formula = slot.literal ? formula_constant(parse_literal(value.text, value.pointer))
                                : parse_formula(
                                      value.text, value.pointer,
                                      [&](const std::string& name) {
                                        const Parameter* found = nominal.find_parameter(name);
                                        if (!found) throw ModelError(value.pointer, "unknown parameter '" + name + "'");
                                        return static_cast<std::size_t>(found - nominal.parameters.data());
                                      },
                                      &units);
    return slot;
  }
  // A plain number used as an angle in a degree file is in degrees.
  FormulaPtr angle_formula(const Slot& slot) {
    Quantity q = exact_->evaluate(slot);
    if (!model_.degrees_ || q.is_angle) return slot.formula;
    return formula_node(Formula::Op::multiply,
                        {slot.formula, formula_node(Formula::Op::divide,
                                                    {formula_node(Formula::Op::pi, {}), formula_constant(180)})});
  }
  Slot number_slot(const JsonValue& value) { return raw_slot(value); }
  // A count argument's value at the nominal vector, or 0 when it depends on a toleranced
  // parameter (a tooth count cannot vary continuously: the template then stays exact only).
  // A template's tooth (slot) count: its value at nominal when no parameter it reads varies, else
  // 0 (the template then has no generic form: its edge count would vary over the box). Session
  // 62: a derived parameter varies only when it has its own tolerance or reads one that varies
  // (until then every derived parameter was taken as varying), and a varying count is recorded
  // with its pointer and parameters for the analysis's refusal (ParametricModel::require_generic).
  long fixed_count(const FeatureRecipe& feature, const char* key) {
    auto found = feature.arguments.find(key);
    if (found == feature.arguments.end()) return 0;
    const Model& nominal = *model_.nominal_;
    std::function<bool(std::size_t)> parameter_varies = [&](std::size_t i) {
      const Parameter& parameter = nominal.parameters[i];
      if (parameter.range.lo != parameter.range.hi) return true;
      if (!model_.derived_[i]) return false;
      bool reads = false;
      evaluate_formula<double>(*model_.parameter_nominals_[i].formula, [&](std::size_t j) {
        reads = reads || parameter_varies(j);
        return nominal.parameters[j].nominal.get_d();
      });
      return reads;
    };
    std::vector<std::string> varying;
    double value = evaluate_formula<double>(*found->second.number.formula, [&](std::size_t i) {
      if (parameter_varies(i) && std::find(varying.begin(), varying.end(), nominal.parameters[i].name) == varying.end())
        varying.push_back(nominal.parameters[i].name);
      return nominal.parameters[i].nominal.get_d();
    });
    if (varying.empty()) return std::lround(value);
    if (model_.count_refusal_.first.empty()) {
      std::string list;
      for (const std::string& name : varying) list += (list.empty() ? "'" : ", '") + name + "'";
      model_.count_refusal_ = {
          feature.pointer + "/" + key,
          std::string("the ") + (std::string(key) == "slots" ? "slot" : "tooth") + " count of feature template " +
              feature.name + " varies with toleranced parameter" + (varying.size() == 1 ? " " : "s ") + list +
              ": the tolerance analysis keeps a template's count fixed over the tolerance box (a count is no "
              "dimension: its generic form has a fixed number of " + (std::string(key) == "slots" ? "slots" : "teeth") +
              "); give " + (varying.size() == 1 ? "that parameter" : "those parameters") +
              " no tolerance and analyse each count on its own (e.g. --set " + varying.front() + "=N)"};
    }
    return 0;
  }
  // A spur_gear has the generic form with flank_radius (one arc per flank): the crossings of
  // the flank circle with the tip and root circles that the exact template takes (the one
  // nearer the pitch point) and the arc's turning sense, decided at nominal. The two-arc
  // involute fit (no flank_radius) places its arcs through involute points computed in double
  // and switches at the base circle: exact form only.
  bool spur_gear_sides(FeatureRecipe& feature) { return spur_gear_sides(model_, feature); }
 public:
  // A spur gear's flank sides chosen at the nominal vector in doubles (the generic form's
  // crossings); false when that form does not evaluate (the template is then exact only).
  // Scale-free choices: a model drawn at an extreme scale chooses them again on its rescaled
  // copy (ParametricModel::rescaled), where the doubles hold its lengths.
  static bool spur_gear_sides(const ParametricModel& model_, FeatureRecipe& feature) {
    if (!feature.arguments.count("flank_radius")) return false;
    std::vector<double> p = model_.parameter_values<double>(std::vector<double>(model_.parameter_count(), 0.0));
    auto nearer = [](const SpurFlank<double>& a, const SpurFlank<double>& b, bool tip) {
      const kernels::Vector<double>& x = tip ? a.tip : a.root;
      const kernels::Vector<double>& y = tip ? b.tip : b.root;
      return parametric_detail::squared_distance(x, a.pitch_point) <= parametric_detail::squared_distance(y, a.pitch_point);
    };
    SpurFlank<double> plus = model_.spur_flank(feature, p, 1, 1), minus = model_.spur_flank(feature, p, -1, -1);
    feature.tip_side = nearer(plus, minus, true) ? 1 : -1;
    feature.root_side = nearer(plus, minus, false) ? 1 : -1;
    SpurFlank<double> flank = model_.spur_flank(feature, p, feature.tip_side, feature.root_side);
    kernels::Vector<double> a = flank.root - flank.centre, b = flank.tip - flank.centre;
    feature.flank_ccw = a.x * b.y - a.y * b.x > 0;
    return std::isfinite(flank.tip.x) && std::isfinite(flank.root.x);
  }

  // Session 67 (scale67): the rescaling of a model whose parameters themselves lie beyond the
  // doubles (a raw `module` of 2e400 mm), by each parameter's length dimension (see below,
  // "Length dimensions of the parameters").
  static ParametricModel rescaled_by_dimension(const ParametricModel& model, long exponent);
  static ParametricModel rescaled_lengths(const ParametricModel& model, long exponent);
  static std::vector<long> scale_exponents(const ParametricModel& model);
  // Every template of a rescaled copy judged again by the reader's rule (has_generic_form): its
  // generic form evaluated in doubles at the file's scale may not have (session 56, scale56).
  static void judge_templates_again(ParametricModel& scaled) {
    scaled.generic_ = true;
    scaled.exact_only_feature_.clear();
    for (PartRecipe& part : scaled.parts_)
      for (FeatureRecipe& feature : part.features) {
        const bool generic = has_generic_form(scaled, feature);
        if (!generic && scaled.generic_) {
          scaled.generic_ = false;
          scaled.exact_only_feature_ = feature.name + " (" + feature.pointer + ")";
        }
      }
  }

  // Whether a template occurrence has the generic form: circle and pin; the toothed templates
  // with a tooth (slot) count that is not toleranced; spur_gear with flank_radius when its
  // crossings evaluate at nominal; the others once their nominal structure is recorded.
  static bool has_generic_form(const ParametricModel& model, FeatureRecipe& feature) {
    const std::string& name = feature.name;
    if (name == "circle" || name == "pin") return true;
    if (name == "ratchet_wheel") return feature.teeth > 0;
    if (name == "spur_gear" && feature.arguments.count("flank_radius"))
      return feature.teeth > 0 && spur_gear_sides(model, feature);
    if (feature.ccw.size() != feature.loop_count) return false;
    if (name == "geneva_driver" || name == "anchor" || name == "balance") return true;
    if (feature.teeth <= 0) return false;
    std::size_t n = static_cast<std::size_t>(feature.teeth), edges = feature.edge_counts[0];
    if (name == "geneva_wheel") return edges == 6 * n;
    if (name == "escape_wheel") return edges % n == 0 && edges / n >= 2 && edges / n <= 4;
    if (name == "spur_gear") return edges == 6 * n || edges == 8 * n;
    return false;
  }

 private:
  Slot angle_slot(const JsonValue& value) {
    Slot slot = raw_slot(value);
    slot.formula = angle_formula(slot);
    return slot;
  }

  PointRecipe point(const JsonValue& value) {
    PointRecipe recipe;
    if (value.is_array()) {
      recipe.x = number_slot(value.items[0]);
      recipe.y = number_slot(value.items[1]);
      return recipe;
    }
    const JsonValue& polar = *value.find("polar");
    recipe.polar = true;
    recipe.center = std::make_shared<PointRecipe>(point(*polar.find("center")));
    recipe.radius = number_slot(*polar.find("radius"));
    recipe.angle = angle_slot(*polar.find("angle"));
    return recipe;
  }

  PartRecipe part(const JsonValue& value, std::size_t index) {
    PartRecipe recipe;
    if (const JsonValue* loops = value.find("loops")) {
      for (const JsonValue& loop_value : loops->items) {
        LoopRecipe loop;
        if (const JsonValue* circle = loop_value.find("circle")) {
          loop.circle = true;
          loop.center = point(*circle->find("center"));
          loop.radius = number_slot(*circle->find("radius"));
        } else {
          loop.start = point(*loop_value.find("start"));
          for (const JsonValue& edge_value : loop_value.find("edges")->items) {
            EdgeRecipe edge;
            if (const JsonValue* line_to = edge_value.find("line_to")) {
              edge.target = point(*line_to);
            } else {
              edge.arc = true;
              edge.target = point(*edge_value.find("arc_to"));
              edge.center = point(*edge_value.find("center"));
              edge.ccw = edge_value.find("dir")->text == "ccw";
            }
            loop.edges.push_back(std::move(edge));
          }
        }
        recipe.loops.push_back(std::move(loop));
      }
    }
    if (const JsonValue* features = value.find("features")) {
      for (const JsonValue& feature_value : features->items) {
        const JsonMember& member = feature_value.members.front();
        FeatureRecipe feature;
        feature.name = member.key;
        feature.pointer = member.value.pointer;
        const TemplateSpec* spec = nullptr;
        for (const TemplateSpec& candidate : template_specs())
          if (candidate.name == member.key) spec = &candidate;
        for (const JsonMember& argument : member.value.members) {
          FeatureRecipe::Argument a;
          for (const ArgumentSpec& candidate : spec->arguments)
            if (candidate.key == argument.key) a.kind = candidate.kind;
          switch (a.kind) {
            case ArgumentKind::length:
            case ArgumentKind::count: a.number = number_slot(argument.value); break;
            case ArgumentKind::angle: a.number = angle_slot(argument.value); break;
            case ArgumentKind::point: a.point = point(argument.value); break;
            case ArgumentKind::direction_word: a.word = argument.value.text; break;
          }
          feature.arguments.emplace(argument.key, std::move(a));
        }
        if (feature.name == "ratchet_wheel" || feature.name == "spur_gear" || feature.name == "escape_wheel")
          feature.teeth = fixed_count(feature, "teeth");
        if (feature.name == "geneva_wheel") feature.teeth = fixed_count(feature, "slots");
        feature.loop_count = feature.name == "geneva_driver" ? 2 : 1;
        recipe.features.push_back(std::move(feature));
      }
    }
    const JsonValue& motion = *value.find("motion");
    if (motion.is_object()) {
      const JsonValue& body = motion.members.front().value;
      if (const JsonValue* pivot = body.find("pivot")) {
        recipe.motion.has_pivot = true;
        recipe.motion.pivot = point(*pivot);
      }
      if (const JsonValue* direction = body.find("direction")) {
        recipe.motion.has_direction = true;
        if (direction->is_array()) {
          recipe.motion.direction_x = number_slot(direction->items[0]);
          recipe.motion.direction_y = number_slot(direction->items[1]);
        } else {
          recipe.motion.direction_is_angle = true;
          recipe.motion.direction_angle = angle_slot(*direction);
        }
      }
    }
    // The exact form at the nominal vector is the part read, each loop as written or reversed
    // by the reader's orientation (self_check.hpp): which one is recorded.
    const Part& read = model_.nominal_->parts[index];
    Part mine;
    mine.loops = exact_loops(recipe, *exact_);
    // Each template's loops as expanded at nominal (template order and orientation): the
    // structure its generic form follows; then whether it has one.
    std::size_t next = recipe.loops.size();
    for (FeatureRecipe& feature : recipe.features) {
      for (std::size_t l = 0; l < feature.loop_count && next < mine.loops.size(); ++l, ++next) {
        feature.edge_counts.push_back(mine.loops[next].edges.size());
        std::vector<bool> senses;
        for (const Edge& edge : mine.loops[next].edges) senses.push_back(edge.ccw);
        feature.ccw.push_back(std::move(senses));
      }
      if (!has_generic_form(model_, feature) && model_.generic_) {
        model_.generic_ = false;
        model_.exact_only_feature_ = feature.name + " (" + feature.pointer + ")";
      }
    }
    if (mine.loops.size() != read.loops.size())
      throw ModelError(read.pointer, "internal error: the parametric form of the part has " +
                                         std::to_string(mine.loops.size()) + " loops, the model " +
                                         std::to_string(read.loops.size()));
    mine.motion = read.motion;
    if (recipe.motion.has_pivot) mine.motion.pivot = exact_->point(recipe.motion.pivot);
    if (recipe.motion.has_direction) mine.motion.direction = exact_->direction(recipe.motion);
    recipe.reversed = checked_loop_reversals(mine, read);
    return recipe;
  }

  ParametricModel& model_;
  const JsonValue& root_;
  std::vector<Rounding> roundings_;
  std::unique_ptr<ExactEvaluator> exact_;
};

ParametricModel::Nominal ParametricModel::read_nominal(std::string_view json_text, std::string_view source_name,
                                                       const ReadOptions& options) {
  mpfr_prec_t bits = interval_bits;
  ReadOptions design = options;
  design.overrides_set_nominal = true;  // the parametric form varies parameters about their nominals
  Nominal nominal;
  nominal.model = std::make_shared<const Model>(read_model_escalating(json_text, source_name, design, &bits));
  nominal.precision_bits = bits;
  return nominal;
}

ParametricModel ParametricModel::read(std::string_view json_text, std::string_view source_name,
                                      const ReadOptions& options) {
  return read(json_text, source_name, options, read_nominal(json_text, source_name, options));
}

ParametricModel ParametricModel::read(std::string_view json_text, std::string_view source_name,
                                      const ReadOptions& options, Nominal nominal) {
  if (!nominal.model) throw ModelError("", "internal error: no model read for the parametric form");
  ParametricModel model;
  ReadOptions design = options;
  design.overrides_set_nominal = true;
  model.nominal_ = std::move(nominal.model);
  for (auto [name, value] : options.parameter_values) {
    value.canonicalize();
    model.nominal_overrides_[name] = value;
  }
  model.precision_bits_ = nominal.precision_bits;
  PrecisionScope precision(model.precision_bits_);  // every exact evaluation repeats the reader's at its precision
  model.text_ = std::string(json_text);
  JsonValue root = parse_json(json_text);
  RoundingBoundScope rounding_scope(model_rounding_bound(root));  // the file's bound
  model.profile_tolerances_ = root.is_object() && has_profile_tolerances(root);
  if (root.is_object() && has_profile_tolerances(root)) {
    // The same translation as the reader's: offset parameters and rewritten loop points.
    ReadOptions plain_options = design;  // as the reader's: overrides of declared parameters only
    const JsonValue* declared = root.find("parameters");
    std::erase_if(plain_options.parameter_values,
                  [&](const auto& entry) { return !declared || !declared->find(entry.first); });
    Model plain = read_model_root(strip_profile_tolerances(root), source_name, plain_options);
    translate_profile_tolerances(root, plain);
  }
  // The builder checks each part as it records it (self_check.hpp): the exact form at the
  // nominal vector is the part that was read (its loops as read or reversed).
  RecipeBuilder(model, root).build();
  return model;
}

ParametricModel ParametricModel::read_file(const std::filesystem::path& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
    throw IoError("cannot read model file '" + path.string() + "': it is a directory");
  std::ifstream file(path, std::ios::binary);
  if (!file) throw IoError("cannot open model file '" + path.string() + "'");
  std::ostringstream content;
  content << file.rdbuf();
  if (file.bad()) throw IoError("cannot read model file '" + path.string() + "'");
  return read(content.str(), path.string());
}

Model ParametricModel::exact_model(const std::vector<Rational>& deviations) const {
  if (unscaled_) {
    // rescaled by dimension (session 67): the deviations at the file's scale, the parameters of
    // the model divided so
    const std::vector<long> exponents = RecipeBuilder::scale_exponents(*this);
    if (std::all_of(exponents.begin(), exponents.end(), [](long k) { return k == 0; }))
      return decimal_scaled_model(unscaled_->exact_model(deviations), length_exponent_);
    std::vector<Rational> at_file_scale = deviations;
    for (std::size_t i = 0; i < at_file_scale.size() && i < exponents.size(); ++i)
      if (exponents[i] != 0) at_file_scale[i] *= power_of_ten_rational(exponents[i]);
    Model model = decimal_scaled_model(unscaled_->exact_model(at_file_scale), length_exponent_);
    scale_parameter_values(model.parameters, exponents);
    return model;
  }
  if (deviations.size() != parameter_count())
    throw ModelError("/parameters", "expected " + std::to_string(parameter_count()) +
                                        " parameter deviations, got " + std::to_string(deviations.size()));
  Model model = *nominal_;
  model.roundings.clear();
  RoundingBoundScope rounding_scope(model_rounding_bound(parse_json(text_)));
  PrecisionScope precision(precision_bits_);
  // Callers may pass mpq_class(a, b), which is not canonical: GMP's arithmetic needs canonical
  // operands (the rounding's continued fractions gave wrong results on such input).
  std::vector<Rational> canonical = deviations;
  for (Rational& deviation : canonical) deviation.canonicalize();
  ExactEvaluator exact(*nominal_, parameter_nominals_, degrees_, canonical, model.roundings);
  for (std::size_t i = 0; i < model.parameters.size(); ++i) {
    Parameter& parameter = model.parameters[i];
    Rational shift = to_rational(exact.parameter(i), parameter.pointer, parameter.name, model.roundings) -
                     parameter.nominal;
    parameter.nominal += shift;
    parameter.range.lo += shift;
    parameter.range.hi += shift;
  }
  for (std::size_t k = 0; k < model.parts.size(); ++k) {
    Part& part = model.parts[k];
    const PartRecipe& recipe = parts_[k];
    std::vector<Loop> loops = exact_loops(recipe, exact);
    for (std::size_t l = 0; l < loops.size(); ++l) {
      loops[l].pointer = nominal_->parts[k].loops[l].pointer;
      loops[l].is_hole = false;
      const auto& nominal_edges = nominal_->parts[k].loops[l].edges;
      // Labels and pointers as read (the nominal loop may be reversed).
      for (std::size_t e = 0; e < loops[l].edges.size(); ++e) {
        std::size_t m = recipe.reversed[l] ? loops[l].edges.size() - 1 - e : e;
        loops[l].edges[e].label = nominal_edges[m].label;
        loops[l].edges[e].pointer = nominal_edges[m].pointer;
      }
    }
    part.loops = std::move(loops);
    if (recipe.motion.has_pivot) part.motion.pivot = exact.point(recipe.motion.pivot);
    if (recipe.motion.has_direction) part.motion.direction = exact.direction(recipe.motion);
    validate_part_geometry(part);
  }
  return model;
}

// certified_positive.hpp says what it decides.
BoxVerdict certified_positive(const ParametricModel& model, const std::vector<bool>& derived,
                              const std::vector<Rational>& lo, const std::vector<Rational>& hi,
                              const std::vector<std::size_t>& read,
                              const std::function<Interval(const std::vector<Interval>&)>& margin, bool strict,
                              const MarginTies* ties) {
  const std::size_t n = lo.size();
  const std::vector<Parameter>& parameters = model.nominal().parameters;
  // the margin's enclosure over [a, b] (the ends exact rationals: enclosed outward)
  auto enclosure = [&](const std::vector<Rational>& a, const std::vector<Rational>& b) {
    std::vector<Interval> deviations(n);
    for (std::size_t i = 0; i < n; ++i) {
      if (a[i] == b[i]) deviations[i] = Interval(a[i]);
      else mpfi_interv_q(deviations[i].get(), a[i].get_mpq_t(), b[i].get_mpq_t());
    }
    try {
      std::vector<Interval> values = model.parameter_values<Interval>(deviations);
      for (std::size_t i = 0; i < n; ++i) {
        if (derived[i]) continue;
        const Rational low = parameters[i].nominal + a[i], high = parameters[i].nominal + b[i];
        if (low == high) values[i] = Interval(low);
        else mpfi_interv_q(values[i].get(), low.get_mpq_t(), high.get_mpq_t());
      }
      return std::optional<Interval>(margin(values));
    } catch (const Error&) {
      return std::optional<Interval>();   // does not evaluate there
    }
  };
  // +1: the margin certainly holds over the sub-box, -1: certainly fails somewhere, 0: open
  auto evaluate_sign = [&](const std::vector<Rational>& a, const std::vector<Rational>& b) {
    const std::optional<Interval> enclosed = enclosure(a, b);
    // A margin that does not evaluate at a point fails there; over a sub-box (an enclosure too
    // wide to evaluate) a strict check fails as before and a non-strict one is open: split
    // further. (Until session 64 the enclosure was [0, 0] there, which a non-strict check read as
    // holding.)
    if (!enclosed) return (strict || a == b) ? -1 : 0;
    const Interval& m = *enclosed;
    const int sign = m.sign();
    if (sign != 0 || !m.is_bounded()) return sign;
    if (strict) return mpfi_is_zero(m.get()) > 0 ? -1 : 0;   // exactly 0 over the sub-box: fails
    return mpfi_is_nonneg(m.get()) > 0 ? 1 : 0;
  };
  // the exact sign of the margin at the deviation vector c (nullopt: not exact there)
  auto exact_sign = [&](const std::vector<Rational>& c) -> std::optional<int> {
    std::vector<PiRational> deviations;
    for (const Rational& x : c) deviations.emplace_back(x);
    try {
      return ties->exact(model.parameter_values<PiRational>(deviations)).sign();
    } catch (const Error&) {
      return std::nullopt;
    }
  };
  // the sub-box [a, b] by the margin's monotony and its exact value at its smallest corner
  // (+1 holds, -1 fails, 0 open)
  auto monotone_sign = [&](const std::vector<Rational>& a, const std::vector<Rational>& b) {
    if (!ties) return 0;
    std::vector<Rational> corner = a;
    if (a != b) {
      std::vector<MpfiJet> deviations;
      for (std::size_t i = 0; i < n; ++i) {
        Interval v(a[i]);
        if (a[i] != b[i]) mpfi_interv_q(v.get(), a[i].get_mpq_t(), b[i].get_mpq_t());
        std::vector<Interval> unit(n, Interval(Rational(0)));
        unit[i] = Interval(Rational(1));
        deviations.emplace_back(std::move(v), std::move(unit));
      }
      MpfiJet m;
      try {
        m = ties->jet(model.parameter_values<MpfiJet>(deviations));
      } catch (const Error&) {
        return 0;
      }
      for (std::size_t i = 0; i < n; ++i) {
        if (a[i] == b[i] || i >= m.derivatives.size()) continue;
        const Interval& d = m.derivatives[i];
        if (!d.is_bounded()) return 0;
        if (mpfi_is_nonneg(d.get()) > 0) continue;                        // smallest at a[i]
        if (mpfi_is_nonpos(d.get()) > 0) corner[i] = b[i]; else return 0;  // at b[i], or no monotony
      }
    }
    const int enclosed = evaluate_sign(corner, corner);
    if (enclosed < 0) return -1;
    if (enclosed > 0) return 1;   // margin >= its value at the corner, certainly positive (or non-negative)
    const std::optional<int> s = exact_sign(corner);
    if (!s) return 0;
    return (strict ? *s > 0 : *s >= 0) ? 1 : -1;
  };
  constexpr std::size_t budget = 3000;   // sub-boxes per stage
  for (mpfr_prec_t bits : {160, 640, 2560}) {
    PrecisionScope precision(bits);
    // The box's corners first: a failing box mostly fails at one (the rules are monotone in most
    // of their arguments). A corner whose enclosure holds 0 at this precision (a margin vanishing
    // there: a box ending on a rule's bound) leaves the stage undecided: every sub-box holding
    // it encloses at least the corner's enclosure.
    bool corner_undecided = false;
    if (read.size() <= 6) {
      for (std::size_t mask = 0; mask < (std::size_t(1) << read.size()) && !corner_undecided; ++mask) {
        std::vector<Rational> corner = lo;
        for (std::size_t j = 0; j < read.size(); ++j)
          if (mask & (std::size_t(1) << j)) corner[read[j]] = hi[read[j]];
        int sign = evaluate_sign(corner, corner);
        if (sign == 0) sign = monotone_sign(corner, corner);
        if (sign < 0) return BoxVerdict::fails;
        corner_undecided = sign == 0;
      }
    }
    if (corner_undecided) continue;
    // the smallest share of a parameter's box a sub-box is split to at this precision
    const Rational finest(mpz_class(1), mpz_class(1) << static_cast<mp_bitcnt_t>(bits - 32));
    std::vector<std::pair<std::vector<Rational>, std::vector<Rational>>> stack{{lo, hi}};
    std::size_t evaluated = 0;
    bool undecided = false;
    while (!stack.empty() && !undecided) {
      auto [a, b] = std::move(stack.back());
      stack.pop_back();
      int sign = evaluate_sign(a, b);
      if (sign == 0) sign = monotone_sign(a, b);
      if (sign > 0) continue;
      if (sign < 0) return BoxVerdict::fails;
      std::optional<std::size_t> widest;
      Rational share(0);
      for (std::size_t i : read) {
        const Rational s = (b[i] - a[i]) / (hi[i] - lo[i]);
        if (s > share) {
          share = s;
          widest = i;
        }
      }
      if (++evaluated > budget || !widest || share < finest) {
        undecided = true;
        break;
      }
      const Rational middle = (a[*widest] + b[*widest]) / 2;
      std::vector<Rational> upper_a = a, lower_b = b;
      upper_a[*widest] = middle;
      lower_b[*widest] = middle;
      stack.emplace_back(std::move(upper_a), b);
      stack.emplace_back(a, std::move(lower_b));
    }
    if (!undecided) return BoxVerdict::holds;
  }
  return BoxVerdict::undecided;
}

namespace {

// The involute function inv(a) = tan a - a over an enclosure of a, by its values at a's ends
// where a lies in [0, 1.5) (it increases there: derivative tan^2 a); tan a - a in interval
// arithmetic loses the cancellation (session 58: near the root circle of a 62-tooth gear at
// 23 deg, 0.2 deg of pressure angle tolerance made the root point's polar angle 0.027 rad wide,
// 1.6 mm at its radius, against d.n = 0.17 mm). In doubles and (session 63) in MPFI.
kernels::Interval involute_enclosure(const kernels::Interval& a) {
  using I = kernels::Interval;
  using A = Arithmetic<I>;
  if (!(a.lo >= 0 && a.hi < 1.5)) return I(A::tan(a) - a);
  I low(a.lo, a.lo), high(a.hi, a.hi);
  return I((A::tan(low) - low).lo, (A::tan(high) - high).hi);
}

Interval involute_enclosure(const Interval& a) {
  using A = Arithmetic<Interval>;
  if (!a.is_bounded() || mpfi_is_nonneg(a.get()) <= 0 || mpfr_cmp_d(&a.get()->right, 1.5) >= 0) return A::tan(a) - a;
  Interval low, high;
  mpfi_set_fr(low.get(), &a.get()->left);   // (outward if a carries more bits: still about the end)
  mpfi_set_fr(high.get(), &a.get()->right);
  const Interval at_low = A::tan(low) - low, at_high = A::tan(high) - high;
  Interval result;
  mpfi_interv_fr(result.get(), &at_low.get()->left, &at_high.get()->right);
  return result;
}

// The flank arcs' turning senses of an involute spur gear kept over the exact box [lo, hi]
// (session 63; check_choices, where the doubles leave them open or cannot enclose them at all:
// lengths of 1e400 mm), in MPFI: `terms(values)` gives each arc's (d.n, n x d) (check_choices'
// flank_terms); their signs at the box's middle (160, 640, then 2560 bits) must give the nominal
// senses (`keeps(arc, sign of d.n, sign of n x d)`), and each term must keep its sign over the
// whole box (certified_positive, bisecting along `read`). A term vanishing at the middle, or not
// certainly of one sign over the box, refuses (false).
template <class Terms, class Keeps>
bool flank_senses_certified(const ParametricModel& model, const std::vector<bool>& derived, const std::vector<Rational>& lo,
                            const std::vector<Rational>& hi, const std::vector<std::size_t>& read, const Terms& terms,
                            const Keeps& keeps) {
  const std::size_t n = lo.size();
  const std::vector<Parameter>& parameters = model.nominal().parameters;
  std::vector<std::pair<int, int>> signs;
  for (mpfr_prec_t bits : {160, 640, 2560}) {
    PrecisionScope precision(bits);
    std::vector<Interval> deviations(n);
    std::vector<Rational> middle(n);
    for (std::size_t i = 0; i < n; ++i) {
      middle[i] = (lo[i] + hi[i]) / 2;
      deviations[i] = Interval(middle[i]);
    }
    signs.clear();
    try {
      std::vector<Interval> values = model.parameter_values<Interval>(deviations);
      for (std::size_t i = 0; i < n; ++i)
        if (!derived[i]) values[i] = Interval(Rational(parameters[i].nominal + middle[i]));
      for (const auto& [along, across] : terms(values)) signs.emplace_back(along.sign(), across.sign());
    } catch (const Error&) {
      return false;
    }
    if (std::all_of(signs.begin(), signs.end(), [](const auto& s) { return s.first != 0 && s.second != 0; })) break;
  }
  for (std::size_t j = 0; j < signs.size(); ++j)
    if (signs[j].first == 0 || signs[j].second == 0 || !keeps(j, signs[j].first, signs[j].second)) return false;
  for (std::size_t j = 0; j < signs.size(); ++j)
    for (int which : {0, 1}) {
      const int sign = which ? signs[j].second : signs[j].first;
      const BoxVerdict verdict = certified_positive(model, derived, lo, hi, read, [&](const std::vector<Interval>& q) {
        const auto t = terms(q);
        const Interval& term = which ? t.at(j).second : t.at(j).first;
        return sign > 0 ? term : Interval(-term);
      });
      if (verdict != BoxVerdict::holds) return false;
    }
  return true;
}

// The parameters varying in the box [lo, hi] that the feature's (present) arguments `keys` read,
// directly or through derived parameters (check_choices' rules and shape checks).
std::vector<std::size_t> varying_read(const FeatureRecipe& feature, const std::vector<const char*>& keys,
                                      const std::vector<Rational>& lo, const std::vector<Rational>& hi,
                                      const std::function<void(const Formula&, std::vector<char>&)>& mark_read,
                                      const std::function<void(const PointRecipe&, std::vector<char>&)>& mark_point) {
  using namespace parametric_detail;
  const std::size_t n = lo.size();
  std::vector<char> read(n, 0);
  for (const char* key : keys) {
    auto a = feature.arguments.find(key);
    if (a == feature.arguments.end()) continue;
    if (a->second.kind == ArgumentKind::point) mark_point(a->second.point, read);
    else if (a->second.number.formula) mark_read(*a->second.number.formula, read);
  }
  std::vector<std::size_t> indices;
  for (std::size_t i = 0; i < n; ++i)
    if (read[i] && lo[i] != hi[i]) indices.push_back(i);
  return indices;
}

// ParametricModel::check_choices' rules of the feature templates over the box (session 59; since
// session 61 the templates' own rules, template_rules.hpp, enclosed over the box): \throws
// ModelError naming the argument and the toleranced parameters the rule reads when a margin is
// not certainly positive over the box. A rule reading no parameter that varies in the box is
// held at nominal, where the template was expanded. Since session 62 a margin the doubles'
// enclosure over the (outward-rounded) box leaves undecided is decided over the exact box
// [lo_exact, hi_exact] in MPFI (certified_positive): a box valid up to 2^-k of a rule's bound, or
// drawn at 1e-300 or 1e400 mm, is kept; one reaching the bound or beyond it is refused.
void check_template_rules(
    const FeatureRecipe& feature, const std::vector<kernels::Interval>& p, const std::vector<Rational>& lo_exact,
    const std::vector<Rational>& hi_exact,
    const std::function<void(const Formula&, std::vector<char>&)>& mark_read,
    const std::function<void(const PointRecipe&, std::vector<char>&)>& mark_point, const ParametricModel& model,
    const std::vector<bool>& derived) {
  using namespace parametric_detail;
  const Model& nominal = model.nominal();
  TemplateRuleValues values;
  values.has = [&](const char* key) { return feature.arguments.count(key) > 0; };
  values.value = [&](const char* key) { return slot_value(feature.arguments.at(key).number, p); };
  values.point = [&](const char* key) { return point_value(feature.arguments.at(key).point, p); };
  values.count = feature.teeth;
  // the same rules over MPFI enclosures of the parameters' values over a sub-box (`exact` is
  // pointed at them while a margin is evaluated)
  const std::vector<Interval>* exact = nullptr;
  BasicTemplateRuleValues<Interval> certified;
  certified.has = values.has;
  certified.value = [&](const char* key) { return slot_value(feature.arguments.at(key).number, *exact); };
  certified.point = [&](const char* key) { return point_value(feature.arguments.at(key).point, *exact); };
  certified.count = feature.teeth;
  // the parameters varying in the box read by the rule's (present) arguments
  auto varying = [&](const std::vector<const char*>& keys) {
    return varying_read(feature, keys, lo_exact, hi_exact, mark_read, mark_point);
  };
  std::size_t index = 0;   // the rule's place in the template's order (the same in both number types)
  template_rules(feature.name, values, [&](const TemplateRule& rule) {
    const std::size_t place = index++;
    std::vector<std::size_t> read = varying(rule.reads);
    if (read.empty()) return;   // held at nominal, where the template was expanded
    if (rule.margin().lo > 0) return;
    // undecided in doubles: decided over the exact box
    BoxVerdict verdict = BoxVerdict::undecided;
    std::size_t at = 0;
    template_rules(feature.name, certified, [&](const BasicTemplateRule<Interval>& same) {
      if (at++ != place) return;
      verdict = certified_positive(model, derived, lo_exact, hi_exact, read, [&](const std::vector<Interval>& values_over) {
        exact = &values_over;
        return same.margin();
      });
    });
    if (verdict == BoxVerdict::holds) return;
    std::string list;
    for (std::size_t i : read) list += (list.empty() ? "'" : ", '") + nominal.parameters[i].name + "'";
    throw ModelError(feature.pointer + "/" + rule.key,
                     "the tolerance box may make feature template " + feature.name + " invalid: " + rule.rule +
                         " may fail for some parameter values within the box (toleranced parameter" +
                         (read.size() == 1 ? " " : "s ") + list +
                         "), where the template refuses the geometry; narrow " + (read.size() == 1 ? "its" : "their") +
                         " tolerance" + (read.size() == 1 ? "" : "s"));
  });
}

}  // namespace

void ParametricModel::require_generic() const {
  if (generic_) return;
  if (!count_refusal_.first.empty()) throw ModelError(count_refusal_.first, count_refusal_.second);
  throw ModelError("", "tolerance analysis needs the generic parametric form; feature template " + exact_only_feature_ +
                           " has an exact form only");
}

void ParametricModel::check_choices(const std::vector<double>& lo, const std::vector<double>& hi) const {
  const std::size_t n = parameter_count();
  if (lo.size() != n || hi.size() != n)
    throw ModelError("/parameters", "expected a box of " + std::to_string(n) + " parameter deviations");
  std::vector<Rational> lo_exact(n), hi_exact(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(lo[i]) || !std::isfinite(hi[i]))
      throw ModelError("/parameters/" + nominal_->parameters[i].name, "the tolerance box's deviations are not finite");
    lo_exact[i] = Rational(lo[i]);
    hi_exact[i] = Rational(hi[i]);
  }
  check_choices(lo_exact, hi_exact);
}

void ParametricModel::check_choices(const std::vector<Rational>& lo_exact, const std::vector<Rational>& hi_exact) const {
  using I = kernels::Interval;
  using namespace parametric_detail;
  std::size_t n = parameter_count();
  if (lo_exact.size() != n || hi_exact.size() != n)
    throw ModelError("/parameters", "expected a box of " + std::to_string(n) + " parameter deviations");
  // the doubles' box about the exact one (outward) for the enclosures in doubles; the rules'
  // margins they leave undecided are decided over the exact box (check_template_rules)
  std::vector<double> lo(n), hi(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (hi_exact[i] < lo_exact[i])
      throw ModelError("/parameters/" + nominal_->parameters[i].name, "the tolerance box's deviations are not ascending");
    lo[i] = I::enclose(lo_exact[i]).lo;
    hi[i] = I::enclose(hi_exact[i]).hi;
  }
  std::vector<I> box(n);
  for (std::size_t i = 0; i < n; ++i) box[i] = I(lo[i], hi[i]);
  std::vector<I> p = parameter_values(box);
  // whether a formula reads a parameter that varies in the box (directly or through a derived one)
  std::function<bool(const Formula&)> varies = [&](const Formula& f) -> bool {
    if (f.op == Formula::Op::parameter)
      return lo_exact[f.parameter] != hi_exact[f.parameter] || (derived_[f.parameter] && varies(*parameter_nominals_[f.parameter].formula));
    for (const FormulaPtr& argument : f.arguments)
      if (varies(*argument)) return true;
    return false;
  };
  // The toleranced parameters (varying in the box) that a slot's or a point's formula reads,
  // directly or through derived parameters, by name.
  std::function<void(const Formula&, std::vector<char>&)> mark_read = [&](const Formula& f, std::vector<char>& read) {
    if (f.op == Formula::Op::parameter) {
      read[f.parameter] = 1;
      if (derived_[f.parameter]) mark_read(*parameter_nominals_[f.parameter].formula, read);
    }
    for (const FormulaPtr& argument : f.arguments) mark_read(*argument, read);
  };
  std::function<void(const PointRecipe&, std::vector<char>&)> mark_point = [&](const PointRecipe& point,
                                                                                 std::vector<char>& read) {
    if (!point.polar) {
      mark_read(*point.x.formula, read);
      mark_read(*point.y.formula, read);
      return;
    }
    mark_point(*point.center, read);
    mark_read(*point.radius.formula, read);
    mark_read(*point.angle.formula, read);
  };
  for (const PartRecipe& part : parts_)
    for (const FeatureRecipe& feature : part.features) {
      // The template's own rules over the whole box (session 59): the exact expansion refuses
      // values that break them ("must be less than tip_radius", ...), and before this only the
      // nominal vector was expanded, so a box reaching past a rule was analysed on a generic form
      // the template has no shape for. Each rule is an enclosure over the box that must be
      // certainly positive (the templates' own margins kept); rules whose arguments read no
      // parameter varying in the box held at nominal, where the template was expanded.
      try {
        check_template_rules(feature, p, lo_exact, hi_exact, mark_read, mark_point, *this, derived_);
      } catch (const ModelError&) {
        throw;
      } catch (const Error& error) {
        throw ModelError(feature.pointer, "the tolerance box may make feature template " + feature.name +
                                              " invalid: its rules do not evaluate over the box (" + error.what() + ")");
      }
      if (feature.ccw.empty()) continue;
      auto refuse = [&](const std::string& key, const std::string& what) {
        throw ModelError(feature.pointer + (key.empty() ? "" : "/" + key),
                         "the tolerance box may change the shape of feature template " + feature.name + ": " + what +
                             "; the generic form follows the nominal shape, so this box is refused (narrow the "
                             "tolerances of the parameters it depends on)");
      };
      // the parameters varying in the box that the arguments `keys` read (directly or through
      // derived parameters)
      auto reads = [&](std::initializer_list<const char*> keys) {
        return varying_read(feature, std::vector<const char*>(keys), lo_exact, hi_exact, mark_read, mark_point);
      };
      // Whether margin(parameter values) is positive (strict) or non-negative over the whole box
      // (session 63): its enclosure in doubles over the outward-rounded box first (every ordinary
      // box is decided there), else over the exact box in MPFI (certified_positive: a box ending
      // exactly on a non-strict bound, or 2^-k from any bound, or lengths of 1e-300 or 1e400 mm
      // beyond the doubles). `margin` is generic: called with the doubles' enclosures and with MPFI ones.
      auto certain = [&](const std::vector<std::size_t>& read, bool strict, const auto& margin) {
        try {
          const I m = margin(p);
          if (strict ? m.lo > 0 : m.lo >= 0) return true;
        } catch (const Error&) {
        }
        const MarginTies ties{[&](const std::vector<MpfiJet>& q) { return MpfiJet(margin(q)); },
                              [&](const std::vector<PiRational>& q) { return PiRational(margin(q)); }};
        return certified_positive(
                   *this, derived_, lo_exact, hi_exact, read,
                   [&](const std::vector<Interval>& q) { return Interval(margin(q)); }, strict, &ties) == BoxVerdict::holds;
      };
      auto slot_margin = [&](const char* key) {
        const Slot* slot = &feature.arguments.at(key).number;
        return [slot](const auto& q) { return slot_value(*slot, q); };
      };
      try {
        // values the template itself refuses (session 58, hunt58: an escape wheel's face_angle of
        // 0 +- 0.05 deg was analysed, though every negative value in the box is refused by the
        // reader, "must not be negative"); the exact expansion has no shape there to follow
        auto refuse_below = [&](const char* key, bool strict, const char* what) {
          if (!feature.arguments.count(key)) return;
          if (!certain(reads({key}), strict, slot_margin(key)))
            refuse(key, std::string(key) + " may become " + (strict ? "zero or negative" : "negative") +
                            " within the box, which the template refuses (" + what + ")");
        };
        if (feature.name == "escape_wheel") {
          refuse_below("face_angle", false, "must not be negative");
          refuse_below("tip_angle", false, "must not be negative");
        } else if (feature.name == "anchor") {
          refuse_below("lift", true, "must be positive");
          refuse_below("lock", false, "must not be negative");
          refuse_below("pallet_extent", true, "must be positive");
        }
        if (feature.name == "escape_wheel" && feature.teeth > 0 && feature.arguments.count("tip_angle")) {
          std::size_t per_tooth = feature.edge_counts.at(0) / static_cast<std::size_t>(feature.teeth);
          bool top = per_tooth == (feature.arguments.count("back_angle") ? 4u : 3u);
          if (top && !certain(reads({"tip_angle"}), true, slot_margin("tip_angle")))
            refuse("tip_angle", "tip_angle may reach 0 within the box (the nominal teeth have flat tops)");
          if (!top && varies(*feature.arguments.at("tip_angle").number.formula))
            refuse("tip_angle", "tip_angle is 0 at nominal (pointed teeth) and varies within the box");
        } else if (feature.name == "geneva_driver" && feature.edge_counts.size() == 2) {
          bool inner_arc = feature.edge_counts[1] == 4;
          if (!inner_arc) {
            // 0 at nominal: kept exactly when its formula reads no parameter varying in the box
            const Slot& slot = feature.arguments.at("lock_inner_radius").number;
            if (varies(*slot.formula))
              refuse("lock_inner_radius", "lock_inner_radius is 0 at nominal (a sector) and varies within the box");
            continue;
          }
          if (!certain(reads({"lock_inner_radius"}), true, slot_margin("lock_inner_radius")))
            refuse("lock_inner_radius", "lock_inner_radius may reach 0 within the box (the nominal crescent has an inner arc)");
        } else if (feature.name == "spur_gear" && !feature.arguments.count("flank_radius")) {
          const bool radial = involute_radial(feature);
          const auto pressure = feature.arguments.find("pressure_angle");
          auto number = [&](const char* key, const auto& q) { return slot_value(feature.arguments.at(key).number, q); };
          auto alpha_of = [&](const auto& q) {
            using T = typename std::decay_t<decltype(q)>::value_type;
            using A = Arithmetic<T>;
            return pressure != feature.arguments.end() ? slot_value(pressure->second.number, q)
                                                       : T(A::constant(Rational(1, 9)) * A::pi());
          };
          // base - root radius: positive over the box where the nominal flank has its radial
          // segment (the root inside the base circle), negative where it has none
          auto base_margin = [&](const auto& q) {
            using T = typename std::decay_t<decltype(q)>::value_type;
            using A = Arithmetic<T>;
            const T pitch = number("pitch_radius", q);
            const T margin = T(pitch * A::cos(alpha_of(q)) - T(pitch - number("dedendum", q)));
            return radial ? margin : T(-margin);
          };
          if (!certain(reads({"pitch_radius", "dedendum", "pressure_angle"}), true, base_margin))
            refuse("dedendum", std::string("the root circle may cross the base circle within the box (at nominal it lies ") +
                                   (radial ? "inside" : "outside") + " it: the flank " +
                                   (radial ? "has" : "has no") + " radial segment)");
          // Each flank arc is tangent at the pitch point P to the normal's perpendicular, centre
          // c = P + s n with s = |d|^2 / (2 d.n), d = (far end) - P: its turning sense from the
          // far end to P is sign(d.n) sign(n x d), from P to the far end the opposite (enclosed
          // so, without the dependency of c on d). flank_terms: (d.n, n x d) of the flank's arcs
          // over a box, for the doubles' enclosures and for MPFI ones.
          const std::size_t first = radial ? 1 : 0, pieces = radial ? 3 : 2;
          auto flank_terms = [&](const auto& q) {
            using T = typename std::decay_t<decltype(q)>::value_type;
            using A = Arithmetic<T>;
            const T pitch_q = number("pitch_radius", q), alpha_q = alpha_of(q);
            const T beta = T(number("tooth_thickness", q) / T(pitch_q + pitch_q));
            const kernels::Vector<T> normal{T(-A::sin(T(alpha_q - beta))), A::cos(T(alpha_q - beta))};
            const kernels::Vector<T> pitch_point{T(pitch_q * A::cos(beta)), T(-T(pitch_q * A::sin(beta)))};
            const T base_q = T(pitch_q * A::cos(alpha_q));
            const T start_angle = T(beta + involute_enclosure(alpha_q));   // the involute starts at polar angle -start_angle
            auto involute_point = [&](const T& r) {
              const T c = T(base_q / r);
              const T a = A::atan2(A::sqrt(T(A::constant(Rational(1)) - T(c * c))), c);   // the pressure angle at r
              const T angle = T(involute_enclosure(a) - start_angle);
              return kernels::Vector<T>{T(r * A::cos(angle)), T(r * A::sin(angle))};
            };
            // far ends of the pieces: the lower arc's (root, or base point), the upper's
            const kernels::Vector<T> lower_end =
                radial ? kernels::Vector<T>{T(base_q * A::cos(T(-start_angle))), T(base_q * A::sin(T(-start_angle)))}
                       : involute_point(T(pitch_q - number("dedendum", q)));
            const kernels::Vector<T> upper_end = involute_point(T(pitch_q + number("addendum", q)));
            std::vector<std::pair<T, T>> terms;
            for (std::size_t i = first; i < pieces; ++i) {
              const kernels::Vector<T> d = (i + 2 == pieces ? lower_end : upper_end) - pitch_point;   // the lower arc runs to P
              terms.emplace_back(kernels::dot(d, normal), kernels::cross(normal, d));
            }
            return terms;
          };
          // the sense of piece i from the signs of its terms
          auto sense_of = [&](std::size_t i, int along, int across) {
            const bool sense = (along > 0) == (across > 0);   // sign(d.n) sign(n x d) > 0
            return i + 2 == pieces ? sense : !sense;
          };
          const std::vector<std::size_t> moving =
              reads({"pitch_radius", "addendum", "dedendum", "tooth_thickness", "pressure_angle"});
          // In doubles: where the enclosures over a box leave a sign open, the box is bisected
          // (its varying parameters in turn, 2^14 boxes at most; the involute function
          // inv(a) = tan a - a enclosed by its values at the ends of a's enclosure, involute_enclosure:
          // session 58). A box the doubles leave open (or cannot enclose: lengths beyond them) is
          // decided in MPFI below.
          enum class Senses { kept, changed, open };
          std::function<Senses(std::vector<I>&, int)> senses_in_doubles = [&](std::vector<I>& sub, int depth) -> Senses {
            std::vector<std::pair<I, I>> terms;
            try {
              terms = flank_terms(parameter_values(sub));
            } catch (const Error&) {
              return Senses::open;
            }
            bool open = false;
            for (std::size_t j = 0; j < terms.size(); ++j) {
              const I &along = terms[j].first, &across = terms[j].second;
              if (!std::isfinite(along.lo) || !std::isfinite(along.hi) || !std::isfinite(across.lo) ||
                  !std::isfinite(across.hi))
                return Senses::open;   // beyond the doubles
              if (!((along.lo > 0 || along.hi < 0) && (across.lo > 0 || across.hi < 0))) {
                open = true;
                continue;
              }
              if (sense_of(first + j, along.lo > 0 ? 1 : -1, across.lo > 0 ? 1 : -1) != feature.ccw.at(0).at(first + j))
                return Senses::changed;   // certainly changed
            }
            if (!open) return Senses::kept;
            if (moving.empty() || depth >= 14) return Senses::open;
            std::size_t k = moving[static_cast<std::size_t>(depth) % moving.size()];
            I whole = sub[k];
            double middle = 0.5 * (whole.lo + whole.hi);
            // both halves: one certainly changed settles it, though the other be left open
            sub[k] = I(whole.lo, middle);
            const Senses lower = senses_in_doubles(sub, depth + 1);
            Senses upper = Senses::kept;
            if (lower != Senses::changed) {
              sub[k] = I(middle, whole.hi);
              upper = senses_in_doubles(sub, depth + 1);
            }
            sub[k] = whole;
            if (lower == Senses::changed || upper == Senses::changed) return Senses::changed;
            return lower == Senses::open || upper == Senses::open ? Senses::open : Senses::kept;
          };
          std::vector<I> whole_box = box;
          const Senses in_doubles = senses_in_doubles(whole_box, 0);
          if (in_doubles == Senses::changed)
            refuse("", "a flank arc's turning sense may change within the box (the arc degenerates)");
          if (in_doubles == Senses::open && !flank_senses_certified(*this, derived_, lo_exact, hi_exact, moving, flank_terms,
                                                                   [&](std::size_t j, int along, int across) {
                                                                     return sense_of(first + j, along, across) ==
                                                                            feature.ccw.at(0).at(first + j);
                                                                   }))
            refuse("", "a flank arc's turning sense may change within the box (the arc degenerates)");
        }
      } catch (const ModelError&) {
        throw;
      } catch (const Error& error) {
        refuse("", std::string("its generic form does not evaluate over the box (") + error.what() + ")");
      }
    }
}

// ---------------------------------------------------------------- length dimensions (session 67)
//
// A model whose parameters themselves lie beyond the doubles (a raw `module` of 2e400 mm) cannot
// be analysed by dividing its length slots alone (formula_scaled: the parameter's double is
// already infinite). rescaled() then rescales the parameters themselves: each parameter's length
// dimension d is inferred from its uses (a length slot has dimension 1, an angle, a count and a
// direction word 0; a sum's terms, min, max, abs and atan2's arguments share one dimension; a
// product adds its factors', a quotient subtracts, a power multiplies, sqrt halves; sin, cos and
// tan take and give 0; a parameter declared as an angle is 0; a derived parameter has its
// formula's). Constants and pi take the dimension their place asks (a constant added to a length
// is a length; a constant factor is a pure number). A parameter no use constrains is
// dimensionless. Each parameter's values (nominal, tolerance range, sigma) are then multiplied
// by 10^(-E d) exactly, each constant standing for a length^d by 10^(-E d), and every formula
// evaluates, for every number type, to its value at the file's scale times 10^(-E d): exactly
// the model divided by 10^E, with its parameters in units of (10^E mm)^d.
namespace {

struct Dimension {
  enum Kind { unknown, free, known } kind = unknown;
  long d = 0;
  long value() const { return kind == known ? d : 0; }
};

std::string dimension_text(long d) {
  if (d == 0) return "a dimensionless value (an angle, a count or a ratio)";
  if (d == 1) return "a length";
  if (d == 2) return "an area (a length squared)";
  return "a length to the power " + std::to_string(d);
}

// Where a slot's formula is used: a length (1), a dimensionless value (0), or a direction's
// component (-1: both components share one dimension, which the slot's own formula gives).
struct DimensionUse {
  FormulaPtr formula;
  int kind = 1;
  std::string pointer, text;
};

// Every slot of a part's recipe with its use (1 a length, 0 dimensionless, -1 a direction's
// component): the one walk of the slots for the dimension inference, rescaled_by_dimension and
// rescaled_lengths (which divides the length ones, kind 1).
template <class Visit>
void visit_slots(PartRecipe& part, Visit&& visit) {
  std::function<void(PointRecipe&)> point = [&](PointRecipe& p) {
    if (!p.polar) {
      visit(p.x, 1);
      visit(p.y, 1);
      return;
    }
    auto center = std::make_shared<PointRecipe>(*p.center);
    point(*center);
    p.center = center;
    visit(p.radius, 1);
    visit(p.angle, 0);
  };
  for (LoopRecipe& loop : part.loops) {
    if (loop.circle) {
      point(loop.center);
      visit(loop.radius, 1);
      continue;
    }
    point(loop.start);
    for (EdgeRecipe& edge : loop.edges) {
      point(edge.target);
      if (edge.arc) point(edge.center);
    }
  }
  for (FeatureRecipe& feature : part.features)
    for (auto& [key, argument] : feature.arguments) switch (argument.kind) {
        case ArgumentKind::length: visit(argument.number, 1); break;
        case ArgumentKind::angle:
        case ArgumentKind::count: visit(argument.number, 0); break;
        case ArgumentKind::point: point(argument.point); break;
        case ArgumentKind::direction_word: break;
      }
  if (part.motion.has_pivot) point(part.motion.pivot);
  if (part.motion.has_direction) {
    if (part.motion.direction_is_angle) {
      visit(part.motion.direction_angle, 0);
    } else {
      visit(part.motion.direction_x, -1);
      visit(part.motion.direction_y, -1);
    }
  }
}

class DimensionSolver {
 public:
  explicit DimensionSolver(const std::vector<Parameter>& parameters)
      : parameters_(parameters), dims_(parameters.size()), where_(parameters.size()) {
    for (std::size_t i = 0; i < parameters.size(); ++i)
      if (parameters[i].is_angle) set(i, 0, "declared as an angle");
  }

  Dimension infer(const Formula& f) const {
    using Op = Formula::Op;
    auto arg = [&](std::size_t k) { return infer(*f.arguments[k]); };
    switch (f.op) {
      case Op::constant:
      case Op::pi: return {Dimension::free, 0};
      case Op::parameter:
        return dims_[f.parameter] ? Dimension{Dimension::known, *dims_[f.parameter]} : Dimension{};
      case Op::add:
      case Op::subtract:
      case Op::min:
      case Op::max:
      case Op::abs:
      case Op::negate: {
        bool unknown = false;
        for (std::size_t k = 0; k < f.arguments.size(); ++k) {
          Dimension a = arg(k);
          if (a.kind == Dimension::known) return a;
          unknown = unknown || a.kind == Dimension::unknown;
        }
        return unknown ? Dimension{} : Dimension{Dimension::free, 0};
      }
      case Op::multiply:
      case Op::divide: {
        Dimension a = arg(0), b = arg(1);
        if (a.kind == Dimension::unknown || b.kind == Dimension::unknown) return {};
        if (a.kind == Dimension::free && b.kind == Dimension::free) return {Dimension::free, 0};
        return {Dimension::known, f.op == Op::multiply ? a.value() + b.value() : a.value() - b.value()};
      }
      case Op::power: {
        Dimension a = arg(0);
        if (a.kind != Dimension::known) return a;
        return {Dimension::known, a.d * f.exponent};
      }
      case Op::sqrt: {
        Dimension a = arg(0);
        if (a.kind != Dimension::known) return a;
        if (a.d % 2 != 0) return {};
        return {Dimension::known, a.d / 2};
      }
      case Op::sin:
      case Op::cos:
      case Op::tan:
      case Op::atan2: return {Dimension::known, 0};
    }
    return {};
  }

  // Pushes "f has dimension d" into its parameters.
  void require(const Formula& f, long d) {
    using Op = Formula::Op;
    switch (f.op) {
      case Op::constant:
      case Op::pi: return;
      case Op::parameter: set(f.parameter, d, where_now_); return;
      case Op::add:
      case Op::subtract:
      case Op::min:
      case Op::max:
      case Op::abs:
      case Op::negate:
        for (const FormulaPtr& a : f.arguments) require(*a, d);
        return;
      case Op::multiply:
      case Op::divide: {
        Dimension a = infer(*f.arguments[0]), b = infer(*f.arguments[1]);
        const bool product = f.op == Op::multiply;
        if (a.kind != Dimension::unknown)
          require(*f.arguments[1], product ? d - a.value() : a.value() - d);
        else if (b.kind != Dimension::unknown)
          require(*f.arguments[0], product ? d - b.value() : d + b.value());
        return;
      }
      case Op::power:
        if (f.exponent != 0 && d % f.exponent == 0) require(*f.arguments[0], d / f.exponent);
        return;
      case Op::sqrt: require(*f.arguments[0], 2 * d); return;
      case Op::sin:
      case Op::cos:
      case Op::tan: require(*f.arguments[0], 0); return;
      case Op::atan2: {
        Dimension a = infer(*f.arguments[0]), b = infer(*f.arguments[1]);
        if (a.kind == Dimension::known) require(*f.arguments[1], a.d);
        if (b.kind == Dimension::known) require(*f.arguments[0], b.d);
        return;
      }
    }
  }

  void at(const std::string& pointer) { where_now_ = pointer; }
  bool changed() {
    bool c = changed_;
    changed_ = false;
    return c;
  }
  const std::optional<long>& dim(std::size_t i) const { return dims_[i]; }
  void set(std::size_t i, long d, const std::string& where) {
    if (!dims_[i]) {
      dims_[i] = d;
      where_[i] = where;
      changed_ = true;
      return;
    }
    if (*dims_[i] == d) return;
    const Parameter& p = parameters_[i];
    throw ModelError(p.pointer, "parameter '" + p.name + "' is used as " + dimension_text(*dims_[i]) + " (" + where_[i] +
                                    ") and as " + dimension_text(d) + " (" + where + "): its length dimension is "
                                    "inconsistent, so its values cannot be rescaled to the unit the tolerance analysis "
                                    "of this model runs in (its parameters lie beyond the doubles)");
  }

 private:
  const std::vector<Parameter>& parameters_;
  std::vector<std::optional<long>> dims_;
  std::vector<std::string> where_;
  std::string where_now_;
  bool changed_ = false;
};

// The formula with each constant (and pi) standing for a length^d multiplied by 10^(-E d)
// (`unit` = 10^-E), given the parameters' dimensions (`solver`, all known): at parameters
// rescaled by their dimensions it evaluates to the formula's value times 10^(-E d).
FormulaPtr dimension_scaled(const FormulaPtr& formula, long d, const Rational& unit, const DimensionSolver& solver) {
  using Op = Formula::Op;
  const Formula& f = *formula;
  auto power = [&](long k) {
    Rational r(1);
    for (long j = 0; j < std::labs(k); ++j) r *= unit;
    return k >= 0 ? r : Rational(1 / r);
  };
  auto with = [&](std::vector<long> dims) {
    std::vector<FormulaPtr> arguments;
    bool same = true;
    for (std::size_t k = 0; k < f.arguments.size(); ++k) {
      arguments.push_back(dimension_scaled(f.arguments[k], dims[std::min(k, dims.size() - 1)], unit, solver));
      same = same && arguments.back() == f.arguments[k];
    }
    if (same) return formula;
    auto node = std::make_shared<Formula>(f);
    node->arguments = std::move(arguments);
    return FormulaPtr(node);
  };
  // A literal standing for a length^d, d != 0 (a constant, pi, "(80)*(1e400)" in a loop's
  // point; session 68): multiplied by 10^(-E d) as the session-54 path divides a length
  // (formula_scaled: of a product of literals the factor whose value times the scale is nearest
  // 1, so "(80)*(1e400)" becomes 80 * 1, not 80e-400 * 1e400, which overflows the doubles).
  if (d != 0 && !mentions_parameters(formula)) {
    bool unused = false;
    return formula_scaled(formula, power(d), unused);
  }
  switch (f.op) {
    case Op::constant:
    case Op::pi: return formula;
    case Op::parameter: return formula;
    case Op::add:
    case Op::subtract:
    case Op::min:
    case Op::max:
    case Op::abs:
    case Op::negate: return with({d});
    case Op::multiply:
    case Op::divide: {
      Dimension a = solver.infer(*f.arguments[0]), b = solver.infer(*f.arguments[1]);
      const bool product = f.op == Op::multiply;
      if (a.kind == Dimension::known) return with({a.d, product ? d - a.d : a.d - d});
      if (b.kind == Dimension::known) return with({product ? d - b.d : d + b.d, b.d});
      return with({d, 0});
    }
    case Op::power: return f.exponent == 0 ? formula : with({d / f.exponent});
    case Op::sqrt: return with({2 * d});
    case Op::sin:
    case Op::cos:
    case Op::tan: return with({0});
    case Op::atan2: {
      Dimension a = solver.infer(*f.arguments[0]), b = solver.infer(*f.arguments[1]);
      return with({a.kind == Dimension::known ? a.d : b.value()});
    }
  }
  return formula;
}

// Whether a parameter's value (nominal, range and its width, sigma) is no normal double far from
// its limits: beyond 1e300 or below 1e-300 in magnitude (and not 0).
bool beyond(const Rational& v) {
  static const Rational huge = power_of_ten_rational(300), tiny = power_of_ten_rational(-300);
  const Rational a = abs(v);
  return sgn(a) != 0 && (a > huge || a < tiny);
}
bool parameters_beyond_doubles(const std::vector<Parameter>& parameters) {
  for (const Parameter& p : parameters)
    if (beyond(p.nominal) || beyond(p.range.lo) || beyond(p.range.hi) || beyond(Rational(p.range.hi - p.range.lo)) ||
        (p.sigma && beyond(*p.sigma)))
      return true;
  return false;
}

// Multiplies each parameter's values by 10^(-exponents[i]) exactly.
void scale_parameters(std::vector<Parameter>& parameters, const std::vector<long>& exponents) {
  for (std::size_t i = 0; i < parameters.size() && i < exponents.size(); ++i) {
    if (exponents[i] == 0) continue;
    const Rational factor = power_of_ten_rational(-exponents[i]);
    Parameter& p = parameters[i];
    p.nominal *= factor;
    p.range.lo *= factor;
    p.range.hi *= factor;
    if (p.sigma) *p.sigma *= factor;
  }
}

// Fills the solver from the model's uses; \throws ModelError at an inconsistent parameter or slot.
void solve_dimensions(DimensionSolver& solver, const std::vector<Parameter>& parameters,
                      const std::vector<Slot>& parameter_nominals, const std::vector<bool>& derived,
                      const std::vector<PartRecipe>& parts) {
  std::vector<DimensionUse> uses;
  for (PartRecipe part : parts)
    visit_slots(part, [&](Slot& s, int kind) {
      if (s.formula) uses.push_back({s.formula, kind, s.pointer, s.text});
    });
  const std::size_t n = parameters.size();
  for (;;) {
    do {
      for (const DimensionUse& use : uses) {
        solver.at(use.pointer + " '" + use.text + "'");
        long d = use.kind;
        if (use.kind < 0) {
          Dimension own = solver.infer(*use.formula);
          if (own.kind != Dimension::known) continue;
          d = own.d;
        }
        solver.require(*use.formula, d);
      }
      for (std::size_t i = 0; i < n; ++i) {
        if (!derived[i]) continue;
        solver.at(parameters[i].pointer + " (the expression defining it)");
        if (solver.dim(i)) {
          solver.require(*parameter_nominals[i].formula, *solver.dim(i));
        } else {
          Dimension own = solver.infer(*parameter_nominals[i].formula);
          if (own.kind == Dimension::known) solver.set(i, own.d, parameters[i].pointer + " (the expression defining it)");
        }
      }
    } while (solver.changed());
    // a parameter no use constrains: dimensionless, and the rest propagated again
    std::size_t i = 0;
    while (i < n && solver.dim(i)) ++i;
    if (i == n) break;
    solver.set(i, 0, parameters[i].pointer + " (no use fixes its dimension)");
  }
  // every use consistent: a slot whose formula mixes dimensions no parameter carries
  for (const DimensionUse& use : uses) {
    Dimension own = solver.infer(*use.formula);
    if (own.kind == Dimension::unknown || (use.kind >= 0 && own.kind == Dimension::known && own.d != use.kind))
      throw ModelError(use.pointer, "'" + use.text + "': this value should be " + dimension_text(std::max(use.kind, 0)) +
                                        " but its formula mixes parameters of other length dimensions, so the model "
                                        "cannot be rescaled to the unit its tolerance analysis runs in (its parameters "
                                        "lie beyond the doubles)");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!derived[i]) continue;
    Dimension own = solver.infer(*parameter_nominals[i].formula);
    if (own.kind == Dimension::unknown || (own.kind == Dimension::known && own.d != *solver.dim(i)))
      throw ModelError(parameters[i].pointer, "the expression defining parameter '" + parameters[i].name +
                                                  "' mixes parameters of other length dimensions, so its values cannot "
                                                  "be rescaled to the unit the tolerance analysis runs in");
  }
}

}  // namespace

namespace {

// The exponents k_i of a copy rescaled by dimension, solved once by rescaled_by_dimension and
// kept with the copy: the deleter of its `unscaled_` pointer holds them (std::get_deleter finds
// them on every copy of the copy; a copy of rescaled_lengths has none: all k_i 0). Held there
// rather than in a member so that parametric.hpp, included by most of the tree, is unchanged.
struct DimensionScaled {
  std::vector<long> exponents;
  void operator()(const ParametricModel* model) const { delete model; }
};

}  // namespace

std::vector<long> RecipeBuilder::scale_exponents(const ParametricModel& model) {
  if (const DimensionScaled* scaled = std::get_deleter<DimensionScaled>(model.unscaled_)) return scaled->exponents;
  return std::vector<long>(model.parameter_count(), 0);
}

ParametricModel RecipeBuilder::rescaled_by_dimension(const ParametricModel& model, long exponent) {
  const std::vector<Parameter>& parameters = model.nominal_->parameters;
  DimensionSolver solver(parameters);
  solve_dimensions(solver, parameters, model.parameter_nominals_, model.derived_, model.parts_);
  const std::size_t n = parameters.size();
  std::vector<long> exponents(n);
  for (std::size_t i = 0; i < n; ++i) exponents[i] = *solver.dim(i) * exponent;
  const Rational unit = power_of_ten_rational(-exponent);
  ParametricModel scaled = model;
  scaled.length_exponent_ = exponent;
  Model nominal = decimal_scaled_model(*model.nominal_, exponent);
  scale_parameters(nominal.parameters, exponents);
  // the exponents the copy's parameters are in: all 0 when no parameter value moved (every
  // length parameter 0), as session 67's scale_exponents compared them
  bool moved = false;
  for (std::size_t i = 0; i < n; ++i) {
    const Parameter &mine = nominal.parameters[i], &read = parameters[i];
    moved = moved || mine.nominal != read.nominal || mine.range.lo != read.range.lo || mine.range.hi != read.range.hi;
  }
  if (!moved) std::fill(exponents.begin(), exponents.end(), 0);
  scaled.unscaled_ = std::shared_ptr<const ParametricModel>(new ParametricModel(model), DimensionScaled{exponents});
  scaled.nominal_ = std::make_shared<const Model>(std::move(nominal));
  for (std::size_t i = 0; i < n; ++i)
    if (scaled.derived_[i])
      scaled.parameter_nominals_[i].formula =
          dimension_scaled(scaled.parameter_nominals_[i].formula, *solver.dim(i), unit, solver);
  std::vector<const Slot*> lengths;
  for (PartRecipe& part : scaled.parts_)
    visit_slots(part, [&](Slot& s, int kind) {
      if (!s.formula) return;
      long d = kind;
      if (kind < 0) d = solver.infer(*s.formula).value();
      s.formula = dimension_scaled(s.formula, d, unit, solver);
      if (kind == 1) lengths.push_back(&s);
    });
  // the templates judged again on the copy, as rescaled() does
  judge_templates_again(scaled);
  const std::vector<double> values = scaled.parameter_values<double>(std::vector<double>(n, 0.0));
  for (const Slot* slot : lengths) {
    const double v = parametric_detail::slot_value(*slot, values);
    if (std::isfinite(v) && (v == 0 || std::abs(v) >= 2.2250738585072014e-308) && std::abs(v) <= 1e300) continue;
    // a literal left beyond the doubles (session 68): taken as a pure number, its dimension not
    // determined by the uses (it multiplies a parameter no other use fixes)
    std::function<bool(const Formula&)> literal_beyond = [&](const Formula& f) {
      if (f.op == Formula::Op::constant) return beyond(f.value);
      return std::any_of(f.arguments.begin(), f.arguments.end(), [&](const FormulaPtr& a) { return literal_beyond(*a); });
    };
    throw ModelError(slot->pointer, "'" + slot->text + "': the tolerance analysis of this model runs in units of 1e" +
                                        std::to_string(exponent) + " mm, its parameters rescaled by their length "
                                        "dimensions, and this length does not evaluate there in doubles (its value "
                                        "lies more than 1e300 times from the model's size)" +
                                        (literal_beyond(*slot->formula)
                                             ? std::string("; a literal in it is beyond the doubles there: its length "
                                                           "dimension is not determined by its uses (it multiplies a "
                                                           "parameter that no other use fixes), write it as a factor "
                                                           "of a length parameter")
                                             : std::string()));
  }
  return scaled;
}

std::vector<long> parameter_scale_exponents(const ParametricModel& model) { return RecipeBuilder::scale_exponents(model); }

void scale_parameter_values(std::vector<Parameter>& parameters, const std::vector<long>& exponents) {
  scale_parameters(parameters, exponents);
}

ParametricModel ParametricModel::rescaled(long exponent) const {
  if (exponent == 0 || unscaled_) return *this;
  const std::string unit = "1e" + std::to_string(exponent) + " mm";
  if (profile_tolerances_)
    throw ModelError("/parts", "profile tolerances of a model drawn at this scale: its lengths are analysed in units of " +
                                   unit + " (they lie outside about 1e-9 .. 1e9 mm), and a profile tolerance's offset "
                                   "parameter is a length in mm that is not rescaled; give the tolerance as a parameter "
                                   "of the points instead");
  // Session 67: parameters whose values lie beyond about 1e-300 .. 1e300 (a raw `module` of
  // 2e400 mm, a tolerance of 2e-302 mm) are rescaled by their length dimensions, so that the copy
  // is exactly the model divided by 10^E, parameters included (RecipeBuilder::rescaled_by_dimension).
  // Where their dimensions are inconsistent, the lengths alone are divided as before if that
  // evaluates, else the inconsistency is the refusal.
  if (parameters_beyond_doubles(nominal_->parameters)) {
    try {
      return RecipeBuilder::rescaled_by_dimension(*this, exponent);
    } catch (const ModelError&) {
      try {
        return RecipeBuilder::rescaled_lengths(*this, exponent);
      } catch (const ModelError&) {
      }
      throw;
    }
  }
  return RecipeBuilder::rescaled_lengths(*this, exponent);
}

// The lengths' slots divided by 10^E (formula_scaled), the parameters kept as read (session 54).
ParametricModel RecipeBuilder::rescaled_lengths(const ParametricModel& model, long exponent) {
  const std::string unit = "1e" + std::to_string(exponent) + " mm";
  ParametricModel scaled = model;
  scaled.unscaled_ = std::make_shared<const ParametricModel>(model);
  scaled.length_exponent_ = exponent;
  scaled.nominal_ = std::make_shared<const Model>(decimal_scaled_model(*model.nominal_, exponent));
  // the length slots (visit_slots' kind 1, as the dimension inference walks them) divided
  const Rational factor = power_of_ten_rational(-exponent);
  std::vector<const Slot*> checked;
  for (PartRecipe& part : scaled.parts_)
    visit_slots(part, [&](Slot& s, int kind) {
      if (kind != 1) return;
      bool parameter = false;
      s.formula = formula_scaled(s.formula, factor, parameter);
      checked.push_back(&s);
    });
  // The templates' generic forms evaluated in doubles at the file's scale (a spur gear's flank
  // crossings at 1e-300 mm underflow: "exact form only"), so every template is judged again on
  // the copy, by the reader's rule (session 56, scale56).
  judge_templates_again(scaled);
  // Each length at the nominal vector, in doubles: finite and normal (or 0) once divided. A
  // formula that keeps the scale (a parameter of about 1e400 mm used as a length) cannot be
  // evaluated so: refused at its slot.
  std::vector<double> values = scaled.parameter_values<double>(std::vector<double>(model.parameter_count(), 0.0));
  for (const Slot* slot : checked) {
    double v = parametric_detail::slot_value(*slot, values);
    if (std::isfinite(v) && (v == 0 || std::abs(v) >= 2.2250738585072014e-308) && std::abs(v) <= 1e300) continue;
    char shown[40];
    std::snprintf(shown, sizeof shown, "%.3g", v);
    throw ModelError(slot->pointer, "'" + slot->text + "': the tolerance analysis of this model runs in units of " + unit +
                                        " (its lengths lie outside about 1e-9 .. 1e9 mm), and this length's formula does "
                                        "not evaluate there in doubles (" +
                                        (std::isfinite(v) ? std::string(shown) : std::string("beyond the doubles")) +
                                        " in that unit): a parameter of about that size used as a length? Write such "
                                        "lengths as factors of the scale at their uses, e.g. \"(radius)*(1e400)\"");
  }
  return scaled;
}

}  // namespace hipair::model_detail
