// Scale sweep: one mechanism with every length a multiple of a unit u, u = 10^k exactly for k
// from -300 to 400 (the range the model format admits). The configuration space and the
// kinematics of parts that only rotate do not depend on the unit, so at every scale:
//  - the C-space has the same charts, the same cells (kinds) and the same contact edges;
//  - exact point location gives the same answer at the same rational chart points, and that
//    answer agrees with the exact overlap oracle of the scaled model;
//  - the driven motion has the same events (kinds, contacts) at the same driver angles
//    (the two-lever mechanism; a lever against a fixed stop has no follower to drive).
// Before the builder and the slicer rescaled such models exactly, 1e400 mm parts lost every
// contact curve (doubles overflowed in the curve filters) and 1e-15 mm features crashed the
// inscribed-disk guesses (SIGFPE in mpq_set_d on a NaN).
#include "core/model_scale.hpp"
#include "curves/contact_curves.hpp"
#include "sliced/critical_angles.hpp"
#include "test_paths.hpp"
#include "cspace_test_support.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <string>

namespace hipair {
namespace {

using test::axis_of;
using test::random_tile_point;

// A crank turning about the origin and a rocker about (10u, 0); the rocker's left side has a
// notch whose depth is `notch` (in units of u; 0: no notch).
std::string levers_model(const std::string& notch) {
  const std::string x = "\"(9 + " + notch + ")*u\"";
  std::string left = notch == "0"
                         ? std::string(R"({ "line_to": ["9*u", 0], "label": "left side" })")
                         : R"({ "line_to": ["9*u", "3*u"], "label": "left side" }, { "line_to": [)" + x +
                               R"(, "3*u"], "label": "notch top" }, { "line_to": [)" + x +
                               R"(, "2*u"], "label": "notch" }, { "line_to": ["9*u", "2*u"], "label": "notch bottom" },
        { "line_to": ["9*u", 0], "label": "left side low" })";
  return R"({
  "hipair": 1, "name": "levers",
  "units": { "length": "mm", "angle": "deg" },
  "parameters": { "u": { "nominal": 1 } },
  "parts": [
    { "name": "crank", "motion": { "rotation": { "pivot": [0, 0] } }, "initial": { "angle": 180 },
      "loops": [ { "start": [0, "-u"], "edges": [
        { "line_to": ["9*u", "-u"], "label": "lower side" },
        { "arc_to": ["9*u", "u"], "center": ["9*u", 0], "dir": "ccw", "label": "tip" },
        { "line_to": [0, "u"], "label": "upper side" },
        { "arc_to": [0, "-u"], "center": [0, 0], "dir": "ccw", "label": "hub" } ] } ] },
    { "name": "rocker", "motion": { "rotation": { "pivot": ["10*u", 0] } }, "initial": { "angle": 0 },
      "loops": [ { "start": ["9*u", 0], "edges": [
        { "arc_to": ["11*u", 0], "center": ["10*u", 0], "dir": "ccw", "label": "hub" },
        { "line_to": ["11*u", "6*u"], "label": "right side" },
        { "arc_to": ["9*u", "6*u"], "center": ["10*u", "6*u"], "dir": "ccw", "label": "tip" },
        )" + left + R"( ] } ] }
  ],
  "pairs": [ { "parts": ["crank", "rocker"] } ]
})";
}

// A lever turning about the origin against a fixed stop block (a 1-D C-space).
const char* lever_stop_model = R"({
  "hipair": 1, "name": "lever-stop",
  "units": { "length": "mm", "angle": "deg" },
  "parameters": { "u": { "nominal": 1 } },
  "parts": [
    { "name": "lever", "motion": { "rotation": { "pivot": [0, 0] } }, "initial": { "angle": 0 },
      "loops": [ { "start": [0, "-4*u"], "edges": [
        { "line_to": ["60*u", "-4*u"] },
        { "arc_to": ["60*u", "4*u"], "center": ["60*u", 0], "dir": "ccw", "label": "tip" },
        { "line_to": [0, "4*u"], "label": "upper side" },
        { "arc_to": [0, "-4*u"], "center": [0, 0], "dir": "ccw" } ] } ] },
    { "name": "stop", "motion": "fixed",
      "loops": [ { "start": ["20*u", "6*u"], "edges": [
        { "line_to": ["40*u", "6*u"], "label": "stop face" }, { "line_to": ["40*u", "16*u"] },
        { "line_to": ["20*u", "16*u"] }, { "line_to": ["20*u", "6*u"] } ] } ] }
  ],
  "pairs": [ { "parts": ["lever", "stop"] } ]
})";

Model at_scale(const std::string& text, int k) {
  ReadOptions options;
  mpz_class power;
  mpz_ui_pow_ui(power.get_mpz_t(), 10, static_cast<unsigned long>(k < 0 ? -k : k));
  options.parameter_values["u"] = k < 0 ? Rational(mpz_class(1), power) : Rational(power);
  options.allow_out_of_tolerance = true;
  return read_model(text, "scaled", options);
}

struct Structure {
  std::vector<CellKind> cells;
  std::size_t contact_edges = 0;
  std::vector<Location::Kind> located;   // at the sample points
};

const std::vector<int> scales = {-300, -200, -100, -30, -15, 0, 15, 30, 100, 200, 300, 400};

// Builds the C-space at every scale; compares with the unit scale and the oracle.
void sweep_cspace(const std::string& text, const std::string& a, const std::string& b) {
  std::optional<Structure> reference;
  std::vector<ChartPoint> points;
  std::vector<CSpaceChart> reference_charts;
  for (int k : scales) {
    SCOPED_TRACE("scale 1e" + std::to_string(k));
    Model model = at_scale(text, k);
    CSpace space = CSpace::build(model, a, b);
    ASSERT_TRUE(space.complete());
    if (points.empty()) {
      std::mt19937_64 random(29);
      for (int i = 0; i < 150; ++i) {
        points.push_back(random_tile_point(space, random));
      }
      reference_charts = space.charts();
    }
    // rotation charts: the same boxes in half-angle tangents
    ASSERT_EQ(space.charts().size(), reference_charts.size());
    for (std::size_t t = 0; t < reference_charts.size(); ++t) {
      EXPECT_EQ(space.charts()[t].x_lo, reference_charts[t].x_lo);
      EXPECT_EQ(space.charts()[t].x_hi, reference_charts[t].x_hi);
    }
    Structure s;
    for (const CSpaceCell& cell : space.cells()) s.cells.push_back(cell.kind);
    if (space.dimension() == 2)
      for (const CSpaceEdge& edge : space.edges()) s.contact_edges += edge.role == EdgeRole::contact;
    else
      s.contact_edges = space.vertices().size();   // 1-D: the contact configurations
    // The oracle reads the model through doubles in its filters (src/oracle/overlap.cpp, fixed
    // separately); overlap does not depend on the unit, so it is asked about the exactly
    // rescaled copy (the identity within 1e-9 .. 1e18 mm).
    std::vector<std::size_t> both{*model.find_part(a), *model.find_part(b)};
    Model oracle_model = scaled_model(model, normalising_shift(model, both));
    cspace::PairAxes axes = cspace::pair_axes(oracle_model, both[0], both[1]);
    int free = 0, blocked = 0;
    for (const ChartPoint& q : points) {
      Location location = space.locate(q);
      s.located.push_back(location.kind);
      const CSpaceChart& chart = space.charts()[q.chart];
      cspace::Overlap overlap = cspace::classify_overlap(
          oracle_model, axes, axis_of(chart.x_kind, chart.x_half_turn, chart.x_lo, chart.x_hi),
          axis_of(chart.y_kind, chart.y_half_turn, chart.y_lo, chart.y_hi), cspace::ChartPoint{q.x, q.y});
      if (location.kind == Location::Kind::free) {
        EXPECT_EQ(overlap, cspace::Overlap::apart) << "at " << q.x << ", " << q.y;
        ++free;
      } else if (location.kind == Location::Kind::blocked) {
        EXPECT_EQ(overlap, cspace::Overlap::overlapping) << "at " << q.x << ", " << q.y;
        ++blocked;
      }
    }
    EXPECT_GT(free, 0);
    EXPECT_GT(blocked, 0);
    EXPECT_GT(s.contact_edges, 0u);
    if (!reference) {
      reference = s;
      continue;
    }
    EXPECT_EQ(s.cells, reference->cells);
    EXPECT_EQ(s.contact_edges, reference->contact_edges);
    EXPECT_EQ(s.located, reference->located);
  }
}

// The driven motion at every scale against the unit scale.
void sweep_kinematics(const std::string& text, const std::string& driver) {
  KinematicsOptions options;
  options.driver = driver;
  options.steps_per_cycle = 360;
  options.reversal = false;
  std::optional<KinematicsResult> reference;
  for (int k : scales) {
    SCOPED_TRACE("scale 1e" + std::to_string(k));
    KinematicsResult result = analyze_kinematics(at_scale(text, k), options);
    if (k == 0) reference = result;
  }
  for (int k : scales) {
    SCOPED_TRACE("scale 1e" + std::to_string(k));
    KinematicsResult result = analyze_kinematics(at_scale(text, k), options);
    ASSERT_EQ(result.events.size(), reference->events.size());
    for (std::size_t e = 0; e < result.events.size(); ++e) {
      const KinematicEvent &got = result.events[e], &want = reference->events[e];
      EXPECT_EQ(got.kind, want.kind);
      EXPECT_EQ(got.part, want.part);
      EXPECT_EQ(got.before, want.before);
      EXPECT_EQ(got.after, want.after);
      EXPECT_NEAR(got.at.value(), want.at.value(), 1e-9);
      EXPECT_NEAR(got.position, want.position, 1e-9);
    }
    EXPECT_EQ(result.jam.has_value(), reference->jam.has_value());
    if (result.jam && reference->jam) EXPECT_NEAR(result.jam->at.value(), reference->jam->at.value(), 1e-9);
    EXPECT_NEAR(result.reached, reference->reached, 1e-9);
    ASSERT_EQ(result.pieces.size(), reference->pieces.size());
    for (std::size_t p = 0; p < result.pieces.size(); ++p) {
      EXPECT_EQ(result.pieces[p].mode, reference->pieces[p].mode);
      EXPECT_EQ(result.pieces[p].contacts, reference->pieces[p].contacts);
      EXPECT_NEAR(result.pieces[p].end_position, reference->pieces[p].end_position, 1e-9);
    }
  }
}

TEST(ScaleSweep, TwoLeversCSpace) { sweep_cspace(levers_model("0"), "crank", "rocker"); }

TEST(ScaleSweep, TwoLeversKinematics) { sweep_kinematics(levers_model("0"), "crank"); }

TEST(ScaleSweep, LeverAndStopCSpace) { sweep_cspace(lever_stop_model, "lever", "stop"); }

// A notch 1e-16 of the part's size deep (below the doubles' resolution at the part's
// coordinates): the inscribed-disk guesses must not turn it into a NaN, at any scale.
TEST(ScaleSweep, SubResolutionNotch) {
  for (const char* depth : {"1/10000000000000000", "1/1000000000000000000000000000000"})
    for (int k : {-300, 0, 400}) {
      SCOPED_TRACE(std::string("notch ") + depth + " at scale 1e" + std::to_string(k));
      Model model = at_scale(levers_model(depth), k);
      CSpace space = CSpace::build(model, "crank", "rocker");
      std::size_t contact = 0;
      for (const CSpaceEdge& edge : space.edges()) contact += edge.role == EdgeRole::contact;
      EXPECT_GT(contact, 0u);
      EXPECT_NO_THROW(analyze_kinematics(model));
    }
}

// The kinematic analysis of a mechanism with a length coordinate (the scotch yoke: a crank
// turning a translating yoke in a fixed guide) times 10^k r, k = -300, 400 (r a random rational in
// [1/2, 2)), is refused (its positions are lengths, its resolutions absolute: session 47), with one
// message naming the part that translates and the part whose lengths are out of range (issue 13,
// session 51; base51's message named neither).
TEST(ScaleSweep, AnalysisOfAHugeOrTinyTranslatingMechanismIsRefusedNamingItsParts) {
  const Model yoke = read_model_file(std::string(HIPAIR_EXAMPLES) + "/scotch-yoke.json");
  std::mt19937_64 random(5152);
  EXPECT_NO_THROW(analyze_kinematics(yoke));
  for (int k : {-300, 400}) {
    mpz_class ten;
    mpz_ui_pow_ui(ten.get_mpz_t(), 10, static_cast<unsigned long>(k < 0 ? -k : k));
    Rational factor = (k < 0 ? Rational(mpz_class(1), ten) : Rational(ten)) * Rational(static_cast<long>(500 + random() % 1500), 1000);
    factor.canonicalize();
    Model model = yoke;
    for (Part& part : model.parts) part = sliced::scaled_part(part, factor);
    SCOPED_TRACE("scale 1e" + std::to_string(k));
    try {
      analyze_kinematics(model);
      ADD_FAILURE() << "analysed";
    } catch (const GeometryError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("part 'yoke' (/parts/1) translates"), std::string::npos) << message;
      EXPECT_NE(message.find("and part '"), std::string::npos) << message;
      EXPECT_NE(message.find(") reaches about 2^"), std::string::npos) << message;
      EXPECT_NE(message.find("reaches about 2^" + std::string(k < 0 ? "-" : "1")), std::string::npos) << message;
    }
  }
}

// A polygon cam turning about the origin and a flat-faced follower translating along y (limits
// -2u .. 12u): a rotation-translation pair without arcs, which is built as written at any scale
// (no normalisation: its translation chart is in mm, and at 10^-305 its culler's grid cells
// fall below the smallest normal double).
const char* polygon_cam_model = R"({
  "hipair": 1, "name": "polygon-cam",
  "units": { "length": "mm", "angle": "deg" },
  "parameters": { "u": { "nominal": 1 } },
  "parts": [
    { "name": "cam", "motion": { "rotation": { "pivot": [0, 0] } },
      "loops": [ { "start": ["3*u", 0], "edges": [
        { "line_to": ["u", "2*u"] }, { "line_to": ["-2*u", "u"] }, { "line_to": ["-2*u", "-2*u"] },
        { "line_to": ["u", "-5*u/2"] }, { "line_to": ["3*u", 0] } ] } ] },
    { "name": "follower", "motion": { "translation": { "direction": [0, 1], "limits": ["-2*u", "12*u"] } },
      "loops": [ { "start": ["-4*u", "3*u"], "edges": [
        { "line_to": ["4*u", "3*u"] }, { "line_to": ["4*u", "4*u"] }, { "line_to": ["u/2", "4*u"] },
        { "line_to": ["u/2", "9*u"] }, { "line_to": ["-u/2", "9*u"] }, { "line_to": ["-u/2", "4*u"] },
        { "line_to": ["-4*u", "4*u"] }, { "line_to": ["-4*u", "3*u"] } ] } ] } ],
  "pairs": [ { "parts": ["cam", "follower"] } ] })";

// The Geneva pair, the escapement's anchor against its balance and its banking pins, and the
// polygon cam and follower above, times 10^-305 and 10^-320 exactly (decimal_scaled_model): the
// same cells (kinds), the same number of contact edges and, at 80 generated rational chart points
// (translation coordinates times the same power of ten), the same exact location as the unscaled
// pair's, each free or blocked answer confirmed by the overlap oracle on the scaled model
// (session 56, scale56: the culler's grid below DBL_MIN). The escape wheel against the anchor
// (4 s a build) is left to scaled_escapement_analyze.
TEST(ScaleSweep, ExamplePairsBelowTheSmallestNormalDoubleLocateAsUnscaled) {
  struct Pair {
    const char* file;
    const char* first;
    const char* second;
  };
  const Pair pairs[] = {{"geneva.json", "driver", "wheel"},
                        {"escapement.json", "anchor", "balance"},
                        {"escapement.json", "anchor", "banking"},
                        {nullptr, "cam", "follower"}};
  for (const Pair& pair : pairs) {
    const Model unscaled = pair.file ? read_model_file(std::string(HIPAIR_EXAMPLES) + "/" + pair.file)
                                     : at_scale(polygon_cam_model, 0);
    const CSpace reference = CSpace::build(unscaled, pair.first, pair.second);
    ASSERT_TRUE(reference.complete());
    std::mt19937_64 random(5602);
    std::vector<ChartPoint> points;
    for (int i = 0; i < 80; ++i) points.push_back(random_tile_point(reference, random));
    std::size_t reference_edges = 0;
    for (const CSpaceEdge& edge : reference.edges()) reference_edges += edge.role == EdgeRole::contact;
    for (long k : {-305L, -320L}) {
      SCOPED_TRACE(std::string(pair.file ? pair.file : "polygon cam") + " " + pair.first + "/" + pair.second + " x 1e" + std::to_string(k));
      const Model model = decimal_scaled_model(unscaled, -k);
      const Rational factor = power_of_ten_rational(k);
      const CSpace space = CSpace::build(model, pair.first, pair.second);
      ASSERT_TRUE(space.complete());
      ASSERT_EQ(space.cells().size(), reference.cells().size());
      for (std::size_t c = 0; c < space.cells().size(); ++c) EXPECT_EQ(space.cells()[c].kind, reference.cells()[c].kind);
      std::size_t edges = 0;
      for (const CSpaceEdge& edge : space.edges()) edges += edge.role == EdgeRole::contact;
      // (the polygon cam at 10^-320: its translation chart, ~2^-1060 mm wide, holds cells no finer
      // than the subnormal spacing 2^-1074, so the cull keeps its curves in wider windows, which
      // split the same contact curves at more vertices: 30 edges for 10)
      if (pair.file == nullptr && k == -320)
        EXPECT_GE(edges, reference_edges);
      else
        EXPECT_EQ(edges, reference_edges);
      ASSERT_EQ(space.charts().size(), reference.charts().size());
      std::vector<std::size_t> both{*model.find_part(pair.first), *model.find_part(pair.second)};
      const Model oracle_model = scaled_model(model, normalising_shift(model, both));
      const cspace::PairAxes axes = cspace::pair_axes(oracle_model, both[0], both[1]);
      int free = 0, blocked = 0;
      for (const ChartPoint& p : points) {
        const CSpaceChart& chart = space.charts()[p.chart];
        auto scaled = [&](AxisKind kind, const Rational& v) {
          return kind == AxisKind::translation ? Rational(v * factor) : v;
        };
        const ChartPoint q{p.chart, scaled(chart.x_kind, p.x), scaled(chart.y_kind, p.y)};
        const Location want = reference.locate(p), got = space.locate(q);
        EXPECT_EQ(got.kind, want.kind) << "at " << p.x << ", " << p.y << " of chart " << p.chart;
        EXPECT_EQ(got.cell, want.cell) << "at " << p.x << ", " << p.y << " of chart " << p.chart;
        if (got.kind != Location::Kind::free && got.kind != Location::Kind::blocked) continue;
        const cspace::Overlap overlap = cspace::classify_overlap(
            oracle_model, axes, axis_of(chart.x_kind, chart.x_half_turn, chart.x_lo, chart.x_hi),
            axis_of(chart.y_kind, chart.y_half_turn, chart.y_lo, chart.y_hi), cspace::ChartPoint{q.x, q.y});
        EXPECT_EQ(overlap, got.kind == Location::Kind::free ? cspace::Overlap::apart : cspace::Overlap::overlapping)
            << "at " << q.x << ", " << q.y;
        (got.kind == Location::Kind::free ? free : blocked) += 1;
      }
      EXPECT_GT(free + blocked, 0);
    }
  }
}

}  // namespace
}  // namespace hipair
