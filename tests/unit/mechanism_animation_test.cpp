// The animated mechanism drawing (render::mechanism_animation_svg, `hipair simulate --out`'s
// animation.svg): read back with a real XML parser (expat), it must be well-formed, carry one
// <animateTransform> per moving part, keyTimes rising from 0 to 1 at the frames' times, and
// values that are the simulated trajectory at those times; applied to the part drawn at its zero
// configuration, a frame's transform must give what the still drawing (mechanism_svg) draws at
// that frame's configuration: rotations about the part's pivot, translations along its axis.
#include "render/mechanism_svg.hpp"
#include "test_paths.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <expat.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

Model example(const std::string& name) {
  return read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / name);
}

struct Element {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::vector<std::size_t> ancestors;  // indices of the enclosing elements, outermost first
};

// Parses `xml` with expat; false (and the message) when it is not well-formed.
::testing::AssertionResult parse(const std::string& xml, std::vector<Element>* elements) {
  struct State {
    std::vector<Element>* elements;
    std::vector<std::size_t> open;
  } state{elements, {}};
  XML_Parser parser = XML_ParserCreate("UTF-8");
  XML_SetUserData(parser, &state);
  XML_SetElementHandler(
      parser,
      [](void* data, const XML_Char* name, const XML_Char** attributes) {
        auto* s = static_cast<State*>(data);
        Element e;
        e.name = name;
        for (const XML_Char** a = attributes; *a; a += 2) e.attributes[a[0]] = a[1];
        e.ancestors = s->open;
        s->open.push_back(s->elements->size());
        s->elements->push_back(std::move(e));
      },
      [](void* data, const XML_Char*) { static_cast<State*>(data)->open.pop_back(); });
  bool ok = XML_Parse(parser, xml.data(), static_cast<int>(xml.size()), 1) == XML_STATUS_OK;
  std::string message = ok ? "" : XML_ErrorString(XML_GetErrorCode(parser));
  long line = ok ? 0 : static_cast<long>(XML_GetCurrentLineNumber(parser));
  XML_ParserFree(parser);
  if (!ok) return ::testing::AssertionFailure() << "not well-formed: " << message << " at line " << line;
  return ::testing::AssertionSuccess();
}

std::vector<double> numbers(const std::string& text) {
  std::vector<double> out;
  std::string cleaned = text;
  for (char& c : cleaned)
    if (c == ',' || c == ';' || c == '(' || c == ')') c = ' ';
  std::istringstream in(cleaned);
  for (double v; in >> v;) out.push_back(v);
  return out;
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (std::size_t at; (at = text.find(separator, start)) != std::string::npos; start = at + 1)
    out.push_back(text.substr(start, at - start));
  out.push_back(text.substr(start));
  return out;
}

// The id of the nearest enclosing <g> with an id.
std::string enclosing_id(const std::vector<Element>& elements, const Element& e) {
  for (auto it = e.ancestors.rbegin(); it != e.ancestors.rend(); ++it) {
    auto id = elements[*it].attributes.find("id");
    if (id != elements[*it].attributes.end()) return id->second;
  }
  return "";
}

// The first point ("M x,y") of the path titled `part` (SVG user units).
std::array<double, 2> first_point(const std::vector<Element>& elements, const std::string& group_id) {
  for (std::size_t i = 0; i < elements.size(); ++i) {
    const Element& e = elements[i];
    if (e.name != "path") continue;
    bool inside = false;
    for (std::size_t a : e.ancestors) inside |= elements[a].attributes.count("id") && elements[a].attributes.at("id") == group_id;
    if (!inside) continue;
    std::vector<double> v = numbers(e.attributes.at("d").substr(1));
    return {v.at(0), v.at(1)};
  }
  ADD_FAILURE() << "no path in " << group_id;
  return {0, 0};
}

// Printing precision of the SVG writer (io::format_number): four decimals for numbers of at
// least 1e-2 (smaller ones carry seven significant digits), so a printed number is within half a
// unit of the fourth decimal of its value.
constexpr double printed = 0.5e-4;

// Simulates `model` and takes a frame at every multiple of dt (run_until stops there exactly).
std::vector<render::MechanismFrame> simulated_frames(const Model& model, double t_end, std::size_t count,
                                                     std::vector<SimulationState>* states) {
  Simulation s = Simulation::create(model);
  std::vector<render::MechanismFrame> frames;
  for (std::size_t k = 0; k <= count; ++k) {
    if (k > 0) s.run_until(t_end * static_cast<double>(k) / static_cast<double>(count));
    states->push_back(s.state());
    render::MechanismFrame frame;
    frame.time = s.state().time;
    for (std::size_t p = 0; p < model.parts.size(); ++p) {
      PartConfiguration c = model.parts[p].initial;
      if (model.parts[p].motion.kind == Motion::Kind::rotation) c.angle = Rational(s.state().position[p]);
      if (model.parts[p].motion.kind == Motion::Kind::translation) c.offset = Rational(s.state().position[p]);
      frame.configurations.push_back(c);
    }
    frames.push_back(frame);
  }
  return frames;
}

// Checks an animation of `frames` of `model` (see the file comment); *animated receives the
// number of <animateTransform> elements.
void check_animation(const Model& model, const std::vector<render::MechanismFrame>& frames, const std::string& svg,
                     std::size_t* animated) {
  std::vector<Element> elements;
  EXPECT_TRUE(parse(svg, &elements));
  std::size_t moving = 0;
  for (const Part& part : model.parts)
    moving += part.motion.kind == Motion::Kind::rotation || part.motion.kind == Motion::Kind::translation;
  std::vector<const Element*> animations;
  std::map<std::string, const Element*> name_animations;  // by part name
  for (const Element& e : elements)
    if (e.name == "animateTransform") {
      std::string group = enclosing_id(elements, e);
      if (group.rfind("name-", 0) == 0)
        name_animations[group.substr(5)] = &e;
      else
        animations.push_back(&e);
    }
  EXPECT_EQ(animations.size(), moving);
  // A translating (or planar) part's name rides with it: its shift in every frame is the part's
  // own displacement from the first frame; a rotating or fixed part's name does not move.
  for (const Part& part : model.parts) {
    bool carried = part.motion.kind == Motion::Kind::translation || part.motion.kind == Motion::Kind::planar;
    EXPECT_EQ(name_animations.count(part.name), carried ? 1u : 0u) << part.name;
  }
  for (const Element* a : animations) {
    std::string name = enclosing_id(elements, *a).substr(7);
    auto it = name_animations.find(name);
    if (it == name_animations.end() || a->attributes.at("type") != "translate") continue;
    std::vector<std::string> part_values = split(a->attributes.at("values"), ';');
    std::vector<std::string> name_values = split(it->second->attributes.at("values"), ';');
    ASSERT_EQ(part_values.size(), name_values.size()) << name;
    EXPECT_EQ(it->second->attributes.at("keyTimes"), a->attributes.at("keyTimes")) << name;
    std::vector<double> first = numbers(part_values.front());
    for (std::size_t f = 0; f < part_values.size(); ++f) {
      std::vector<double> p = numbers(part_values[f]), q = numbers(name_values[f]);
      ASSERT_EQ(q.size(), 2u);
      EXPECT_NEAR(q[0], p[0] - first[0], 3 * printed) << name << " frame " << f;
      EXPECT_NEAR(q[1], p[1] - first[1], 3 * printed) << name << " frame " << f;
    }
  }
  *animated = animations.size();
  double t0 = frames.front().time, span = frames.back().time - t0;
  for (const Element* a : animations) {
    std::string group = enclosing_id(elements, *a);
    ASSERT_EQ(group.rfind("motion-", 0), 0u) << group;
    std::string name = group.substr(7);
    std::size_t p = *model.find_part(name);
    const Part& part = model.parts[p];
    SCOPED_TRACE(name);
    EXPECT_EQ(a->attributes.at("attributeName"), "transform");
    EXPECT_EQ(a->attributes.at("calcMode"), "linear");
    EXPECT_EQ(a->attributes.at("repeatCount"), "indefinite");
    bool rotation = part.motion.kind == Motion::Kind::rotation;
    EXPECT_EQ(a->attributes.at("type"), rotation ? "rotate" : "translate");
    // keyTimes: 0 ... 1, increasing, one per frame, at the frames' times over the run
    std::vector<std::string> keys = split(a->attributes.at("keyTimes"), ';');
    std::vector<std::string> values = split(a->attributes.at("values"), ';');
    EXPECT_EQ(keys.size(), frames.size());
    EXPECT_EQ(values.size(), frames.size());
    if (keys.size() != frames.size() || values.size() != frames.size()) continue;
    EXPECT_EQ(keys.front(), "0");
    EXPECT_EQ(keys.back(), "1");
    for (std::size_t f = 0; f < keys.size(); ++f) {
      double key = std::stod(keys[f]);
      if (f > 0) EXPECT_GT(key, std::stod(keys[f - 1])) << "frame " << f;
      // printed with nine significant digits: within half a unit of the ninth, 0.5e-8 of the value
      EXPECT_NEAR(key, (frames[f].time - t0) / span, 0.5e-8 * key + 1e-15) << "frame " << f;
    }
    // the group's own transform is the first frame's (what a renderer without SMIL shows)
    const Element& g = elements[a->ancestors.back()];
    EXPECT_EQ(g.attributes.at("transform"), std::string(rotation ? "rotate(" : "translate(") + values.front() + ")");
    // values: the trajectory at the frames, and the still drawing's geometry
    std::array<double, 2> zero = first_point(elements, group);
    std::vector<double> pivot;
    for (std::size_t f = 0; f < frames.size(); f += std::max<std::size_t>(1, frames.size() / 12)) {
      std::vector<double> v = numbers(values[f]);
      const PartConfiguration& c = frames[f].configurations[p];
      std::vector<PartConfiguration> still_configurations = frames[f].configurations;
      std::vector<Element> still;
      ASSERT_TRUE(parse(render::mechanism_svg(model, still_configurations), &still));
      std::array<double, 2> expected = first_point(still, "part-" + name);
      std::array<double, 2> moved{};
      if (rotation) {
        ASSERT_EQ(v.size(), 3u);
        double angle = to_double(c.angle);
        EXPECT_NEAR(v[0], -angle * 180 / std::numbers::pi, printed + 1e-12 * std::abs(angle * 180 / std::numbers::pi))
            << "frame " << f;
        if (pivot.empty()) pivot = {v[1], v[2]};
        EXPECT_EQ(v[1], pivot[0]);   // one pivot for every frame
        EXPECT_EQ(v[2], pivot[1]);
        // SVG rotate(a, px, py): by a degrees (y down) about (px, py)
        double r = v[0] * std::numbers::pi / 180, cs = std::cos(r), sn = std::sin(r);
        double dx = zero[0] - v[1], dy = zero[1] - v[2];
        moved = {v[1] + cs * dx - sn * dy, v[2] + sn * dx + cs * dy};
        // printing: both points and the pivot within `printed` per coordinate, the angle within
        // `printed` degrees at the point's distance from the pivot
        double tolerance = 4 * printed + std::hypot(dx, dy) * printed * std::numbers::pi / 180;
        EXPECT_NEAR(moved[0], expected[0], tolerance) << "frame " << f;
        EXPECT_NEAR(moved[1], expected[1], tolerance) << "frame " << f;
      } else {
        ASSERT_EQ(v.size(), 2u);
        // along the axis: the translation is parallel to the motion's direction (y negated)
        double ux = to_double(part.motion.direction.x), uy = -to_double(part.motion.direction.y);
        EXPECT_NEAR(v[0] * uy - v[1] * ux, 0, 2 * printed) << "frame " << f;
        moved = {zero[0] + v[0], zero[1] + v[1]};
        EXPECT_NEAR(moved[0], expected[0], 3 * printed) << "frame " << f;
        EXPECT_NEAR(moved[1], expected[1], 3 * printed) << "frame " << f;
      }
    }
  }
}

TEST(MechanismAnimation, GenevaFramesAreTheSimulatedTrajectory) {
  Model model = example("geneva-drive.json");
  std::vector<SimulationState> states;
  std::vector<render::MechanismFrame> frames = simulated_frames(model, 1.0, 50, &states);
  // the frames are the simulation's states at the frame times themselves
  for (std::size_t k = 0; k < states.size(); ++k) EXPECT_EQ(states[k].time, 1.0 * static_cast<double>(k) / 50);
  render::MechanismAnimationOptions options;
  options.duration = 4;
  options.marks.push_back({0.3947, 30, 20, "impact"});
  std::string svg = render::mechanism_animation_svg(model, frames, options);
  std::size_t animated = 0;
  check_animation(model, frames, svg, &animated);
  EXPECT_EQ(animated, 2u);
  // the wheel really turns a quarter in the run (the values are not all the first frame's)
  EXPECT_NEAR(states.back().position[1] - states.front().position[1], -std::numbers::pi / 2, 0.03);
  // a time readout per frame, the first one visible without animation
  std::vector<Element> elements;
  ASSERT_TRUE(parse(svg, &elements));
  std::size_t readouts = 0, visible = 0, marks = 0;
  for (const Element& e : elements) {
    std::string group = enclosing_id(elements, e);
    if (e.name == "g" && group == "time") {
      ++readouts;
      visible += e.attributes.at("visibility") == "visible";
    }
    if (e.name == "circle" && group == "marks") ++marks;
  }
  EXPECT_EQ(readouts, frames.size());
  EXPECT_EQ(visible, 1u);
  EXPECT_EQ(marks, 1u);
}

TEST(MechanismAnimation, TranslatingFollowerMovesAlongItsAxis) {
  // cam-drive: a cam turning at constant speed and a spring-loaded follower on a straight axis
  Model model = example("cam-drive.json");
  std::vector<SimulationState> states;
  std::vector<render::MechanismFrame> frames = simulated_frames(model, 0.03, 30, &states);
  render::MechanismAnimationOptions options;
  options.duration = 3;
  options.drawing.labels = true;
  std::string svg = render::mechanism_animation_svg(model, frames, options);
  std::size_t animated = 0;
  check_animation(model, frames, svg, &animated);
  EXPECT_EQ(animated, 2u);
  EXPECT_NE(svg.find("type=\"translate\""), std::string::npos);
}

TEST(MechanismAnimation, EscapementHasOneAnimationPerMovingPart) {
  Model model = example("escapement.json");
  std::vector<SimulationState> states;
  std::vector<render::MechanismFrame> frames = simulated_frames(model, 0.05, 20, &states);
  render::MechanismAnimationOptions options;
  options.duration = 2;
  std::size_t moving = 0;
  for (const Part& part : model.parts) moving += part.motion.kind != Motion::Kind::fixed;
  std::size_t animated = 0;
  check_animation(model, frames, render::mechanism_animation_svg(model, frames, options), &animated);
  EXPECT_EQ(animated, moving);
}

TEST(MechanismAnimation, BadFramesAreRefused) {
  Model model = example("geneva-drive.json");
  render::MechanismFrame frame;
  frame.configurations = {model.parts[0].initial, model.parts[1].initial};
  render::MechanismAnimationOptions options;
  options.duration = 1;
  EXPECT_THROW(render::mechanism_animation_svg(model, {frame}, options), Error);
  render::MechanismFrame later = frame;
  later.time = 0;   // not after the first
  EXPECT_THROW(render::mechanism_animation_svg(model, {frame, later}, options), Error);
  later.time = 1;
  later.configurations.pop_back();
  EXPECT_THROW(render::mechanism_animation_svg(model, {frame, later}, options), Error);
  later.configurations.push_back(model.parts[1].initial);
  options.duration = 0;
  EXPECT_THROW(render::mechanism_animation_svg(model, {frame, later}, options), Error);
  options.duration = 1;
  EXPECT_NO_THROW(render::mechanism_animation_svg(model, {frame, later}, options));
}

}  // namespace
}  // namespace hipair

namespace hipair {
namespace {

// The spring of spring-block.json (ceiling (0, 80) to the block's corner (10, 5)) drawn in every
// frame: one polyline per spring whose <animate> has one points value per frame, each a
// zig-zag of the same point count from the fixed attachment to the block's corner posed at that
// frame. The drawing scale is a power of ten (normalisation); the coordinates are written to
// four decimals, so the ends' differences match within two half units of the fourth decimal.
TEST(MechanismAnimation, SpringIsDrawnBetweenItsAttachmentsInEveryFrame) {
  Model model = example("spring-block.json");
  ASSERT_EQ(model.simulation->couplings.size(), 1u);
  std::vector<render::MechanismFrame> frames;
  std::vector<std::array<double, 3>> poses;
  for (int f = 0; f < 9; ++f) {
    double x = -40 + 7.5 * f, y = 20 - 3.25 * f * f / 4, angle = 0.37 * f - 0.9 * std::sin(f);
    poses.push_back({x, y, angle});
    render::MechanismFrame frame;
    frame.time = 0.05 * f;
    frame.configurations = {model.parts[0].initial, model.parts[1].initial};
    frame.configurations[1].x = Rational(x);
    frame.configurations[1].y = Rational(y);
    frame.configurations[1].angle = Rational(angle);
    frames.push_back(frame);
  }
  render::MechanismAnimationOptions options;
  options.duration = 2;
  std::string svg = render::mechanism_animation_svg(model, frames, options);
  std::vector<Element> elements;
  ASSERT_TRUE(parse(svg, &elements));
  std::vector<std::size_t> springs, animates;
  for (std::size_t i = 0; i < elements.size(); ++i) {
    if (elements[i].name == "polyline" && elements[i].attributes["class"] == "spring") springs.push_back(i);
    if (elements[i].name == "animate" && !elements[i].ancestors.empty() &&
        elements[elements[i].ancestors.back()].name == "polyline")
      animates.push_back(i);
  }
  ASSERT_EQ(springs.size(), 1u);
  ASSERT_EQ(animates.size(), 1u);
  EXPECT_EQ(elements[animates[0]].attributes["attributeName"], "points");
  std::vector<std::string> values = split(elements[animates[0]].attributes["values"], ';');
  ASSERT_EQ(values.size(), frames.size());
  EXPECT_EQ(values.front(), elements[springs[0]].attributes["points"]);  // unanimated: the first frame
  const double tolerance = 1e-4 * (1 + 1e-9);
  std::vector<double> first = numbers(values.front());
  double scale = 0;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    std::vector<double> p = numbers(values[f]);
    ASSERT_EQ(p.size(), first.size()) << "frame " << f;
    ASSERT_EQ(p.size(), 32u);   // 16 points: ends, lead ends, 12 zigs
    // the fixed end (the ceiling's point) stays
    EXPECT_EQ(p[30], first[30]);
    EXPECT_EQ(p[31], first[31]);
    auto [x, y, angle] = poses[f];
    double wx = x + std::cos(angle) * 10 - std::sin(angle) * 5 - 0, wy = y + std::sin(angle) * 10 + std::cos(angle) * 5 - 80;
    double dx = p[0] - p[30], dy = -(p[1] - p[31]);   // drawing y is negated
    if (f == 0) scale = std::pow(10.0, std::round(std::log10(std::hypot(dx, dy) / std::hypot(wx, wy))));
    EXPECT_NEAR(dx, scale * wx, tolerance) << "frame " << f;
    EXPECT_NEAR(dy, scale * wy, tolerance) << "frame " << f;
  }
  // the planar block's name rides with the block: shifted by the block's own shift from frame 0
  const std::string block = model.parts[1].name;
  const Element *shift = nullptr, *name_shift = nullptr;
  for (const Element& e : elements) {
    if (e.name != "animateTransform") continue;
    std::string group = enclosing_id(elements, e);
    if (group == "motion-" + block + "-shift") shift = &e;
    if (group == "name-" + block) name_shift = &e;
  }
  ASSERT_NE(shift, nullptr);
  ASSERT_NE(name_shift, nullptr);
  std::vector<std::string> block_values = split(shift->attributes.at("values"), ';');
  std::vector<std::string> name_values = split(name_shift->attributes.at("values"), ';');
  ASSERT_EQ(name_values.size(), frames.size());
  ASSERT_EQ(block_values.size(), frames.size());
  std::vector<double> block_first = numbers(block_values.front());
  for (std::size_t f = 0; f < frames.size(); ++f) {
    std::vector<double> b = numbers(block_values[f]), q = numbers(name_values[f]);
    ASSERT_EQ(q.size(), 2u);
    EXPECT_NEAR(q[0], b[0] - block_first[0], 3 * printed) << "frame " << f;
    EXPECT_NEAR(q[1], b[1] - block_first[1], 3 * printed) << "frame " << f;
  }
  // the still drawing (hipair show) draws it too
  std::string still = render::mechanism_svg(model, frames.front().configurations);
  EXPECT_NE(still.find("class=\"spring\""), std::string::npos);
}

}  // namespace
}  // namespace hipair
