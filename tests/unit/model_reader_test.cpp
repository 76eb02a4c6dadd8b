// The model reader end to end: exact numbers, parameters and overrides, roundings,
// motions, pairs, orientation of loops and holes.
#include "core/sha256.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace {

using hipair::Model;
using hipair::Point;
using hipair::Rational;

Rational q(const char* text) { return hipair::parse_rational(text); }

// A model with one part `plate` whose loops are `loops_json`, plus optional extras.
std::string model_with(const std::string& loops_json, const std::string& extra = "",
                       const std::string& motion = "\"fixed\"") {
  return R"({"hipair": 1, "name": "t", )" + extra + R"("parts": [{"name": "plate", "motion": )" + motion +
         R"(, "loops": )" + loops_json + "}]}";
}

const std::string unit_square = R"([{"start": [0, 0], "edges": [{"line_to": [1, 0]}, {"line_to": [1, 1]}, {"line_to": [0, 1]}, {"line_to": [0, 0]}]}])";

std::string error_pointer(const std::string& text, const hipair::ReadOptions& options = {}) {
  try {
    hipair::read_model(text, "<test>", options);
  } catch (const hipair::ModelError& error) {
    return error.pointer() + " | " + error.reason();
  }
  return "accepted";
}

// Twice the signed area of a polygonal loop (exact).
Rational twice_polygon_area(const hipair::Loop& loop) {
  Rational sum = 0;
  for (const hipair::Edge& edge : loop.edges) sum += edge.source.x * edge.target.y - edge.target.x * edge.source.y;
  return sum;
}

TEST(ModelReader, DecimalsAreExactEvenWhereADoubleIsNot) {
  Model model = hipair::read_model(model_with(R"([{"start": [0.1, 1e-30], "edges": [
      {"line_to": [46.683, 1e-30]}, {"line_to": [46.683, 9007199254740993]},
      {"line_to": ["0.1", "9007199254740993"]}, {"line_to": [0.1, 1e-30]}]}])"));
  const auto& edges = model.parts[0].loops[0].edges;
  EXPECT_EQ(edges[0].source, (Point{Rational(1, 10), q("1e-30")}));
  EXPECT_EQ(edges[0].target.x, Rational(46683, 1000));
  EXPECT_EQ(edges[1].target.y, Rational(mpz_class("9007199254740993")));
  EXPECT_NE(edges[1].target.y, Rational(9007199254740992.0));
  EXPECT_EQ(edges[0].source.y * q("1e30"), Rational(1));
  EXPECT_TRUE(model.roundings.empty());
}

TEST(ModelReader, HashIsSha256OfTheBytesAndSourceIsKept) {
  std::string text = model_with(unit_square);
  Model model = hipair::read_model(text, "square.json");
  EXPECT_EQ(model.content_hash, hipair::detail::sha256_hex(text));
  EXPECT_EQ(model.content_hash.size(), 64u);
  EXPECT_EQ(model.source, "square.json");
  EXPECT_EQ(model.name, "t");
  EXPECT_EQ(model.angle_unit, "rad");
  Model other = hipair::read_model(text + " ");
  EXPECT_NE(other.content_hash, model.content_hash);
}

TEST(ModelReader, ParametersWithTolerancesRangesAndDistributions) {
  Model model = hipair::read_model(model_with(unit_square, R"("units": {"angle": "deg"}, "parameters": {
      "r": {"nominal": "d / 2", "tolerance": 0.01},
      "d": {"nominal": 9, "tolerance": [-0.02, 0], "distribution": {"normal": {"sigma": "0.02/3"}}},
      "span": {"nominal": 90, "angle": true, "range": [89.5, 90.5], "distribution": "uniform"},
      "fixed-one": {"nominal": "r + 1"}},)"));
  ASSERT_EQ(model.parameters.size(), 4u);
  const hipair::Parameter* r = model.find_parameter("r");
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->nominal, Rational(9, 2));
  EXPECT_EQ(r->range.lo, q("4.49"));
  EXPECT_EQ(r->range.hi, q("4.51"));
  EXPECT_EQ(r->pointer, "/parameters/r");
  EXPECT_EQ(model.parameters[0].name, "r");  // file order
  const hipair::Parameter* d = model.find_parameter("d");
  EXPECT_EQ(d->range.lo, q("8.98"));
  EXPECT_EQ(d->range.hi, Rational(9));
  EXPECT_EQ(d->distribution, hipair::Parameter::Distribution::normal);
  EXPECT_EQ(*d->sigma, Rational(1, 150));
  const hipair::Parameter* span = model.find_parameter("span");
  EXPECT_TRUE(span->is_angle);
  EXPECT_EQ(span->distribution, hipair::Parameter::Distribution::uniform);
  EXPECT_EQ(span->nominal, Rational(573204, 364913));  // the simplest rational within 1e-12 of pi/2
  EXPECT_LT(span->range.lo, span->nominal);
  const hipair::Parameter* fixed = model.find_parameter("fixed-one");
  EXPECT_EQ(fixed->range.lo, fixed->range.hi);
  EXPECT_EQ(fixed->nominal, Rational(11, 2));
  EXPECT_EQ(model.find_parameter("nope"), nullptr);
  // Roundings: span's nominal and both range ends (degrees are irrational in rad).
  std::size_t parameter_roundings = 0;
  for (const hipair::Rounding& rounding : model.roundings)
    if (rounding.pointer.rfind("/parameters/span", 0) == 0) ++parameter_roundings;
  EXPECT_EQ(parameter_roundings, 3u);
}

TEST(ModelReader, OverridesReplaceParameterValuesWithinTolerance) {
  std::string text = model_with(R"([{"circle": {"center": [0, 0], "radius": "r"}}])",
                                R"("parameters": {"r": {"nominal": 5, "tolerance": 0.1}},)");
  hipair::ReadOptions options;
  options.parameter_values["r"] = q("5.05");
  Model model = hipair::read_model(text, "<t>", options);
  EXPECT_EQ(model.parts[0].loops[0].edges[0].radius_squared, q("5.05") * q("5.05"));
  EXPECT_EQ(model.find_parameter("r")->nominal, Rational(5));
  options.parameter_values["r"] = q("5.2");
  EXPECT_EQ(error_pointer(text, options).substr(0, 16), "/parameters/r | ");
  EXPECT_NE(error_pointer(text, options).find("outside its tolerance range"), std::string::npos);
  options.allow_out_of_tolerance = true;
  EXPECT_EQ(hipair::read_model(text, "<t>", options).parts[0].loops[0].edges[0].radius_squared,
            q("5.2") * q("5.2"));
  options.parameter_values["unknown"] = 1;
  EXPECT_NE(error_pointer(text, options).find("unknown parameter 'unknown'"), std::string::npos);
}

TEST(ModelReader, RoundingsAreRecordedWithPointerExpressionAndBound) {
  Model model = hipair::read_model(model_with(
      R"json([{"start": [0, 0], "edges": [{"line_to": ["sqrt(2)", 0]}, {"line_to": ["sqrt(2)", 1]}, {"line_to": [0, 1]}, {"line_to": [0, 0]}]}])json"));
  ASSERT_EQ(model.roundings.size(), 2u);
  EXPECT_EQ(model.roundings[0].pointer, "/parts/0/loops/0/edges/0/line_to/0");
  EXPECT_EQ(model.roundings[0].expression, "sqrt(2)");
  EXPECT_EQ(model.roundings[0].value, Rational(1607521, 1136689));  // simplest within 1e-12 of sqrt(2)
  EXPECT_EQ(model.roundings[0].bound, q("1e-12"));
  EXPECT_EQ(model.roundings[1].pointer, "/parts/0/loops/0/edges/1/line_to/0");
}

TEST(ModelReader, LoopsAreOrientedAndHolesFoundByNesting) {
  // Outer square clockwise, a hole counter-clockwise, an island inside the hole clockwise.
  Model model = hipair::read_model(model_with(R"([
      {"start": [0, 0], "edges": [{"line_to": [0, 10]}, {"line_to": [10, 10]}, {"line_to": [10, 0]}, {"line_to": [0, 0]}]},
      {"start": [2, 2], "edges": [{"line_to": [8, 2]}, {"line_to": [8, 8]}, {"line_to": [2, 8]}, {"line_to": [2, 2]}]},
      {"start": [4, 4], "edges": [{"line_to": [4, 6]}, {"line_to": [6, 6]}, {"line_to": [6, 4]}, {"line_to": [4, 4]}]}])"));
  const auto& loops = model.parts[0].loops;
  ASSERT_EQ(loops.size(), 3u);
  EXPECT_FALSE(loops[0].is_hole);
  EXPECT_TRUE(loops[1].is_hole);
  EXPECT_FALSE(loops[2].is_hole);
  EXPECT_GT(twice_polygon_area(loops[0]), 0);
  EXPECT_LT(twice_polygon_area(loops[1]), 0);
  EXPECT_GT(twice_polygon_area(loops[2]), 0);
  EXPECT_EQ(twice_polygon_area(loops[0]), Rational(200));
  // Reversed loops keep their edges' pointers and stay connected.
  for (const hipair::Loop& loop : loops)
    for (std::size_t i = 0; i < loop.edges.size(); ++i)
      EXPECT_EQ(loop.edges[i].target, loop.edges[(i + 1) % loop.edges.size()].source);
  EXPECT_EQ(loops[0].edges[0].pointer, "/parts/0/loops/0/edges/3");
}

TEST(ModelReader, ArcLoopsAndCircleHolesAreOriented) {
  // A D shape given clockwise with a circular hole given as a shorthand (counter-clockwise).
  Model model = hipair::read_model(model_with(R"([
      {"start": [-5, 0], "edges": [{"arc_to": [5, 0], "center": [0, 0], "dir": "cw"}, {"line_to": [-5, 0]}]},
      {"circle": {"center": [0, 2], "radius": 1}, "label": "bore"}])"));
  const auto& loops = model.parts[0].loops;
  EXPECT_FALSE(loops[0].is_hole);
  EXPECT_TRUE(loops[1].is_hole);
  // The D: the arc over the top must now run counter-clockwise from (5, 0) to (-5, 0).
  const hipair::Edge* arc = nullptr;
  for (const auto& edge : loops[0].edges)
    if (edge.is_arc()) arc = &edge;
  ASSERT_NE(arc, nullptr);
  EXPECT_TRUE(arc->ccw);
  EXPECT_EQ(arc->source, (Point{Rational(5), Rational(0)}));
  EXPECT_EQ(arc->radius_squared, Rational(25));
  // The hole runs clockwise as a full circle.
  ASSERT_EQ(loops[1].edges.size(), 1u);
  EXPECT_TRUE(loops[1].edges[0].is_full_circle());
  EXPECT_FALSE(loops[1].edges[0].ccw);
  EXPECT_EQ(loops[1].edges[0].label, "bore");
  EXPECT_EQ(loops[1].edges[0].radius_squared, Rational(1));
}

TEST(ModelReader, PolarPointsLieExactlyOnTheirCircle) {
  Model model = hipair::read_model(model_with(R"([
      {"start": {"polar": {"center": [1, 2], "radius": 7, "angle": "10 deg"}}, "edges": [
        {"arc_to": {"polar": {"center": [1, 2], "radius": 7, "angle": "100 deg"}}, "center": [1, 2], "dir": "ccw"},
        {"line_to": {"polar": {"center": [1, 2], "radius": 7, "angle": "10 deg"}}}]}])"));
  const hipair::Edge& arc = model.parts[0].loops[0].edges[0];
  Rational dx = arc.source.x - 1, dy = arc.source.y - 2;
  EXPECT_EQ(dx * dx + dy * dy, Rational(49));
  EXPECT_NEAR(hipair::to_double(arc.source.x), 1 + 7 * std::cos(M_PI / 18), 1e-10);
  EXPECT_FALSE(model.roundings.empty());
}

TEST(ModelReader, MotionsAndDirections) {
  auto motion_of = [](const std::string& motion_json, const std::string& extra = "") {
    return hipair::read_model(model_with(unit_square, extra, motion_json)).parts[0].motion;
  };
  hipair::Motion fixed = motion_of("\"fixed\"");
  EXPECT_EQ(fixed.kind, hipair::Motion::Kind::fixed);
  EXPECT_EQ(fixed.degrees_of_freedom(), 0);
  hipair::Motion translation = motion_of(R"({"translation": {"direction": [3, 4], "limits": [-1, 2.5]}})");
  EXPECT_EQ(translation.direction, (Point{Rational(3, 5), Rational(4, 5)}));
  EXPECT_EQ(translation.translation_limits->hi, Rational(5, 2));
  EXPECT_EQ(translation.degrees_of_freedom(), 1);
  EXPECT_EQ(translation.pointer, "/parts/0/motion");
  Model diagonal = hipair::read_model(model_with(unit_square, "", R"({"translation": {"direction": [1, 1]}})"));
  const Point& u = diagonal.parts[0].motion.direction;
  EXPECT_EQ(u.x * u.x + u.y * u.y, Rational(1));
  EXPECT_NEAR(hipair::to_double(u.x), std::sqrt(0.5), 1e-11);
  ASSERT_EQ(diagonal.roundings.size(), 1u);
  EXPECT_EQ(diagonal.roundings[0].pointer, "/parts/0/motion/translation/direction");
  Model left = hipair::read_model(model_with(unit_square, "", R"({"translation": {"direction": [-2, -1]}})"));
  const Point& w = left.parts[0].motion.direction;
  EXPECT_EQ(w.x * w.x + w.y * w.y, Rational(1));
  EXPECT_NEAR(hipair::to_double(w.x), -2 / std::sqrt(5.0), 1e-11);
  EXPECT_NEAR(hipair::to_double(w.y), -1 / std::sqrt(5.0), 1e-11);
  hipair::Motion by_angle = motion_of(R"({"translation": {"direction": 90}})", R"("units": {"angle": "deg"},)");
  EXPECT_EQ(by_angle.direction, (Point{Rational(0), Rational(1)}));
  hipair::Motion rotation = motion_of(R"({"rotation": {"pivot": [0.5, 0.5], "limits": ["-pi/2", "pi/2"]}})");
  EXPECT_EQ(rotation.pivot, (Point{Rational(1, 2), Rational(1, 2)}));
  EXPECT_EQ(rotation.angle_limits->hi, Rational(573204, 364913));  // simplest within 1e-12 of pi/2
  EXPECT_EQ(rotation.degrees_of_freedom(), 1);
  hipair::Motion planar = motion_of(R"({"planar": {"pivot": [0, 0]}})");
  EXPECT_EQ(planar.degrees_of_freedom(), 3);
  hipair::Motion pin_slot = motion_of(R"({"pin_slot": {"pivot": [0, 0], "direction": [0, 2], "angle_limits": [-1, 1], "limits": [0, 3]}})");
  EXPECT_EQ(pin_slot.degrees_of_freedom(), 2);
  EXPECT_EQ(pin_slot.direction, (Point{Rational(0), Rational(1)}));
  EXPECT_EQ(pin_slot.angle_limits->lo, Rational(-1));
  EXPECT_EQ(pin_slot.translation_limits->hi, Rational(3));
}

TEST(ModelReader, InitialConfigurationAndDynamics) {
  Model model = hipair::read_model(model_with(unit_square, R"("units": {"angle": "deg"},)",
      R"({"pin_slot": {"pivot": [0, 0], "direction": [1, 0]}}, "initial": {"angle": 0, "offset": 1.5},
         "dynamics": {"mass": 0.25, "moment_of_inertia": 3, "torsional_spring": {"stiffness": 2, "rest": 90},
                      "linear_spring": {"stiffness": 0.5}, "torque": -1, "force": [0, -9.81], "damping": 0.1})"));
  const hipair::Part& part = model.parts[0];
  EXPECT_EQ(part.initial.offset, Rational(3, 2));
  EXPECT_EQ(part.initial.angle, Rational(0));
  ASSERT_TRUE(part.dynamics.has_value());
  EXPECT_EQ(*part.dynamics->mass, Rational(1, 4));
  EXPECT_EQ(part.dynamics->torsional_spring->rest, Rational(573204, 364913));  // simplest within 1e-12 of pi/2
  EXPECT_EQ(part.dynamics->linear_spring->rest, Rational(0));
  EXPECT_EQ(*part.dynamics->torque, Rational(-1));
  EXPECT_EQ(part.dynamics->force->y, q("-9.81"));
}

TEST(ModelReader, DefaultPairsSkipFixedFixedAndExplicitPairsAreKept) {
  const std::string part = R"({"name": "%", "motion": #, "loops": [{"circle": {"center": [@, 0], "radius": 1}}]})";
  auto make = [&](const char* name, const char* motion, int x) {
    std::string text = part;
    text.replace(text.find('%'), 1, name);
    text.replace(text.find('#'), 1, motion);
    text.replace(text.find('@'), 1, std::to_string(x));
    return text;
  };
  std::string parts = "[" + make("frame", "\"fixed\"", 0) + "," + make("base", "\"fixed\"", 10) + "," +
                      make("wheel", R"({"rotation": {"pivot": [20, 0]}})", 20) + "]";
  Model model = hipair::read_model(R"({"hipair": 1, "name": "p", "parts": )" + parts + "}");
  EXPECT_FALSE(model.pairs_explicit);
  ASSERT_EQ(model.pairs.size(), 2u);
  EXPECT_EQ(model.pairs[0].first, 0u);
  EXPECT_EQ(model.pairs[0].second, 2u);
  EXPECT_EQ(model.pairs[1].first, 1u);
  EXPECT_EQ(*model.find_part("wheel"), 2u);
  EXPECT_FALSE(model.find_part("nothing").has_value());
  Model explicit_pairs = hipair::read_model(R"({"hipair": 1, "name": "p", "parts": )" + parts +
                                            R"(, "pairs": [{"parts": ["wheel", "base"], "friction": 0.15, "restitution": 1}]})");
  EXPECT_TRUE(explicit_pairs.pairs_explicit);
  ASSERT_EQ(explicit_pairs.pairs.size(), 1u);
  EXPECT_EQ(explicit_pairs.pairs[0].first, 2u);
  EXPECT_EQ(explicit_pairs.pairs[0].second, 1u);
  EXPECT_EQ(*explicit_pairs.pairs[0].friction, q("0.15"));
  EXPECT_EQ(*explicit_pairs.pairs[0].restitution, Rational(1));
  EXPECT_EQ(explicit_pairs.pairs[0].pointer, "/pairs/0");
}

TEST(ModelReader, FeatureTemplatesExpandIntoCheckedLoops) {
  Model model = hipair::read_model(model_with(unit_square.substr(0, unit_square.size() - 1) +
                                              R"(, {"start": [5, 5], "edges": [{"line_to": [6, 5]}, {"line_to": [5, 6]}, {"line_to": [5, 5]}]}])"));
  EXPECT_EQ(model.parts[0].loops.size(), 2u);
  std::string with_feature = R"({"hipair": 1, "name": "f", "parts": [{"name": "frame", "motion": "fixed",
      "features": [{"pin": {"center": [3, 4], "radius": 1.5}}]}]})";
  Model pinned = hipair::read_model(with_feature);
  ASSERT_EQ(pinned.parts[0].features.size(), 1u);
  EXPECT_EQ(pinned.parts[0].features[0], "pin");
  ASSERT_FALSE(pinned.parts[0].loops.empty());
  const hipair::Edge& edge = pinned.parts[0].loops[0].edges[0];
  EXPECT_TRUE(edge.is_arc());
  EXPECT_EQ(edge.radius_squared, Rational(9, 4));
  EXPECT_EQ(edge.label, "pin");
  // Expanded loops are validated like written ones: two pins crossing each other.
  std::string crossing = R"({"hipair": 1, "name": "f", "parts": [{"name": "frame", "motion": "fixed",
      "features": [{"pin": {"center": [3, 4], "radius": 1.5}}, {"pin": {"center": [4, 4], "radius": 1.5}}]}]})";
  EXPECT_NE(error_pointer(crossing).find("cross or touch"), std::string::npos);
}

TEST(ModelReader, FilesThatCannotBeReadAreIoErrors) {
  try {
    hipair::read_model_file("/nonexistent/dir/model.json");
    FAIL();
  } catch (const hipair::IoError& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent/dir/model.json"), std::string::npos);
  }
  EXPECT_THROW(hipair::read_model_file(std::filesystem::temp_directory_path()), hipair::IoError);
}

}  // namespace
