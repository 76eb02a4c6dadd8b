// Zero-clearance fits at kernel slice points (session 28): a crank carrying a pin of radius p at
// (R, 0) turns in the slot of a yoke that translates along y, the slot exactly 2p wide. With the
// yoke fixed at s (the other part) and the crank the follower, the pin fits exactly where
// R sin(theta) = s: in the chart t = tan(theta / 2), s t^2 - 2 R t + s = 0 (and in the chart
// around theta = pi its image), a square-free quadratic factor of the walls' contact polynomials,
// blocked space on both sides of each root. Generated over random R, p and t0 with a fixed seed:
//  - at s = 2 R t0 / (1 + t0^2) the roots t0 and 1/t0 are rational roots of a degree-2 factor;
//    the slicer must hold t0 exactly and mark it touching, and every exact point with blocked
//    space on both sides must be touching exactly when the exact oracle says so there;
//  - at a rational s with R^2 - s^2 no square the roots are irrational: the algebraic oracle
//    (curves/algebraic_overlap.hpp, parts with arcs since session 34) decides them. Checked
//    against the construction's closed form (touching exactly at the roots of the fit
//    polynomial, exactly) and the rational oracle at rationals 2^-100 either side of every
//    irrational point blocked on both sides (overlapping: the fit is isolated); none is left
//    undecided (SliceClassCounts::touching_undecided, reported by the analysis as a warning).
//  - on generated spur-gear pairs (no zero-clearance fit, many contact curves through blocked
//    space): no point is undecided (the one-contact sign test decides them), none is touching,
//    and where such a point is rational the exact oracle says the parts overlap there.
#include "kinematics/axis.hpp"
#include "algebra/rational_root.hpp"
#include "test_paths.hpp"

#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <random>
#include <string>

namespace hipair::kinematics_detail {
namespace {

namespace algebra = cspace::algebra;

std::string quoted(const Rational& r) { return "\"" + r.get_str() + "\""; }

// The axis-parallel rectangle [x0, x1] x [y0, y1] as a model loop.
std::string rectangle(const Rational& x0, const Rational& y0, const Rational& x1, const Rational& y1) {
  auto point = [](const Rational& x, const Rational& y) { return "[" + quoted(x) + ", " + quoted(y) + "]"; };
  return "{ \"start\": " + point(x0, y0) + ", \"edges\": [ { \"line_to\": " + point(x1, y0) + " }, { \"line_to\": " +
         point(x1, y1) + " }, { \"line_to\": " + point(x0, y1) + " }, { \"line_to\": " + point(x0, y0) + " } ] }";
}

std::string crank_in_yoke(const Rational& R, const Rational& p) {
  const Rational half = R + p + 2, margin = p + 4;
  return R"({ "hipair": 1, "name": "crank-pin-in-exact-slot", "parts": [
      { "name": "crank", "motion": { "rotation": { "pivot": [0, 0] } },
        "loops": [ { "circle": { "center": [)" + quoted(R) + ", 0], \"radius\": " + quoted(p) + R"( } } ] },
      { "name": "yoke", "motion": { "translation": { "direction": [0, 1], "limits": [)" + quoted(-R - p - 1) + ", " +
         quoted(R + p + 1) + R"(] } },
        "loops": [ )" + rectangle(-half - 3, -margin, half + 3, margin) + ", " + rectangle(-half, -p, half, p) + R"( ] } ],
    "pairs": [ { "parts": ["crank", "yoke"] } ] })";
}

Rational random_rational(std::mt19937_64& random, long lo, long hi, long den) {
  Rational r(std::uniform_int_distribution<long>(lo * den, hi * den)(random), den);
  r.canonicalize();
  return r;
}

bool is_square(const Rational& r) {
  return r >= 0 && mpz_perfect_square_p(r.get_num_mpz_t()) && mpz_perfect_square_p(r.get_den_mpz_t());
}

struct Verdicts {
  int exact_touching = 0;    // exact points blocked on both sides that the oracle calls touching
  bool met_t0 = false;       // the point t0 of the chart around 0: exact and touching
  int claimed_touching = 0;  // points marked touching
  int irrational_touching = 0;   // irrational points marked touching (fits by the closed form)
  int irrational_blocked = 0;    // irrational points blocked on both sides, not touching
};

// The closed form of the fit in the crank's chart (t = tan((theta - c) / 2), c = pi on the
// half-turn chart): the pin's centre is level with the slot's, R sin(theta) = s, i.e.
// s t^2 - 2 R t + s = 0 (c = 0) or s t^2 + 2 R t + s = 0 (c = pi).
bool is_fit(const Rational& R, const Rational& s, const ChartAxis& chart, const algebra::Real& t) {
  const algebra::Polynomial fit = algebra::from_rationals({s, chart.half_turn ? Rational(2 * R) : Rational(-2 * R), s});
  return t.exact ? algebra::sign_at(fit, t.lower) == 0 : algebra::vanishes_at(fit, t);
}

// Every slice point of the crank's charts at the yoke's offset s: no point is undecided; a point
// with blocked space on both sides is touching exactly where the closed form says the pin fits,
// and the rational oracle agrees: at the point when it is exact, at rationals 2^-100 either side
// of it (overlapping) when it is irrational.
Verdicts check_slices(const Model& model, const PairSlicer& slicer, const Rational& R, const Rational& s, const Rational* t0) {
  Verdicts verdicts;
  cspace::PairAxes axes = cspace::pair_axes(model, 0, 1);
  const ChartAxis& yoke_chart = slicer.other_charts().at(0);
  for (std::size_t f = 0; f < slicer.follower_charts().size(); ++f) {
    const ChartAxis& crank_chart = slicer.follower_charts()[f];
    ChartSlice slice = slicer.slice(0, s, f);
    for (std::size_t i = 0; i < slice.points.size(); ++i) {
      const SlicePoint& point = slice.points[i];
      const std::string where = "s " + s.get_str() + " chart " + std::to_string(f) + " point " + point.value.description("t");
      verdicts.claimed_touching += point.touching;
      EXPECT_FALSE(point.undecided) << where;
      if (slice.kinds[i] != SliceKind::blocked || slice.kinds[i + 1] != SliceKind::blocked) {
        EXPECT_FALSE(point.touching) << where;
        continue;
      }
      EXPECT_EQ(point.touching, is_fit(R, s, crank_chart, point.value)) << where;
      if (!point.value.exact) {
        algebra::Real near = point.value;
        algebra::refine_dyadically(near, Rational(mpz_class(1), mpz_class(1) << 100));
        for (const Rational& q : {near.lower, near.upper})
          EXPECT_EQ(cspace::classify_overlap(model, axes, crank_chart, yoke_chart, cspace::ChartPoint{q, s}),
                    cspace::Overlap::overlapping)
              << where << " beside it at " << q.get_str();
        verdicts.irrational_touching += point.touching;
        verdicts.irrational_blocked += !point.touching;
        continue;
      }
      cspace::Overlap truth =
          cspace::classify_overlap(model, axes, crank_chart, yoke_chart, cspace::ChartPoint{point.value.lower, s});
      EXPECT_EQ(point.touching, truth == cspace::Overlap::touching) << where;
      verdicts.exact_touching += truth == cspace::Overlap::touching;
      if (t0 && !crank_chart.half_turn && point.value.lower == *t0 && point.touching) verdicts.met_t0 = true;
    }
  }
  return verdicts;
}

TEST(KernelSlicerZeroClearance, RootsOfQuadraticChannelFactorsAreDecidedTouching) {
  std::mt19937_64 random(2828);
  for (int instance = 0; instance < 6; ++instance) {
    const Rational R = random_rational(random, 5, 40, 7), p = random_rational(random, 1, 2, 5);
    SCOPED_TRACE("R " + R.get_str() + " p " + p.get_str());
    Model model = read_model(crank_in_yoke(R, p));
    std::unique_ptr<PairSlicer> slicer = make_kernel_slicer(model, 0, 0);
    ASSERT_TRUE(slicer->other_moves());
    for (int k = 0; k < 8; ++k) {
      // t0 in (-1, 1) \ {0}, not dyadic in general
      Rational t0 = random_rational(random, -1, 1, 3 + static_cast<long>(random() % 90));
      if (t0 == 0 || t0 == 1 || t0 == -1) continue;
      Rational s = 2 * R * t0 / (1 + t0 * t0);
      s.canonicalize();
      const std::size_t undecided_before = kernel_slice_class_counts(*slicer).touching_undecided;
      Verdicts verdicts = check_slices(model, *slicer, R, s, &t0);
      EXPECT_TRUE(verdicts.met_t0) << "t0 " << t0.get_str() << " s " << s.get_str();
      EXPECT_GE(verdicts.exact_touching, 2) << "t0 " << t0.get_str();   // t0 and 1/t0 (in the chart around pi)
      EXPECT_EQ(kernel_slice_class_counts(*slicer).touching_undecided, undecided_before) << "t0 " << t0.get_str();
    }
    // irrational roots: decided touching (the two roots of the chart around 0 or their images
    // in the chart around pi), nothing undecided
    for (int k = 0; k < 4; ++k) {
      Rational s = random_rational(random, 0, 1, 101) * R * Rational(9, 10);
      s.canonicalize();
      if (s == 0 || is_square(R * R - s * s)) continue;
      const std::size_t undecided_before = kernel_slice_class_counts(*slicer).touching_undecided;
      Verdicts verdicts = check_slices(model, *slicer, R, s, nullptr);
      EXPECT_GE(verdicts.irrational_touching, 2) << "s " << s.get_str();
      EXPECT_EQ(verdicts.claimed_touching, verdicts.irrational_touching) << "s " << s.get_str();
      EXPECT_EQ(kernel_slice_class_counts(*slicer).touching_undecided, undecided_before) << "s " << s.get_str();
    }
  }
}

TEST(KernelSlicerZeroClearance, GearMeshesCurvesThroughBlockedSpaceAreDecidedBlocked) {
  std::mt19937_64 random(2829);
  std::size_t blocked_both = 0, rational_checked = 0;
  for (int trial = 0; trial < 2; ++trial) {
    ReadOptions read;
    read.parameter_values["teeth-1"] = Rational(7 + static_cast<long>(random() % 5));
    read.parameter_values["teeth-2"] = Rational(8 + static_cast<long>(random() % 6));
    read.allow_out_of_tolerance = true;
    Model model = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / "spur-gears.json", read);
    cspace::PairAxes axes = cspace::pair_axes(model, model.pairs[0].first, model.pairs[0].second);
    std::unique_ptr<PairSlicer> slicer = make_kernel_slicer(model, 0, model.pairs[0].second);
    for (int k = 0; k < 12; ++k) {
      const std::size_t o = random() % std::max<std::size_t>(1, slicer->other_charts().size());
      const ChartAxis& other = slicer->other_charts().at(o);
      Rational value = other.lo + (other.hi - other.lo) * Rational(static_cast<long>(random() % 997), 997);
      value.canonicalize();
      for (std::size_t f = 0; f < slicer->follower_charts().size(); ++f) {
        ChartSlice slice = slicer->slice(o, value, f);
        for (std::size_t i = 0; i < slice.points.size(); ++i) {
          const SlicePoint& point = slice.points[i];
          EXPECT_FALSE(point.touching);
          if (slice.kinds[i] != SliceKind::blocked || slice.kinds[i + 1] != SliceKind::blocked) continue;
          ++blocked_both;
          std::optional<Rational> exact = algebra::rational_root(point.value);
          if (!exact) continue;
          ++rational_checked;
          // the pair's first part is the other one: (other, follower)
          EXPECT_EQ(cspace::classify_overlap(model, axes, other, slicer->follower_charts()[f], cspace::ChartPoint{value, *exact}),
                    cspace::Overlap::overlapping);
        }
      }
    }
    EXPECT_EQ(kernel_slice_class_counts(*slicer).touching_undecided, 0u);
  }
  EXPECT_GT(blocked_both, 20u);
}

// What the analysis says about them: the yoke driving the crank pin in its exact slot meets
// irrational touching points (R^2 - s^2 no square at most slices), all decided now: the crank is
// reported held in the fit (a touching piece whose ends satisfy the closed form R sin(theta) = s,
// to double precision), with no warning of undecided points; the same crank with a pin 1/10
// narrower has play: no touching piece, no such warning.
TEST(KernelSlicerZeroClearance, AnalysisOfTheExactSlotLeavesNoPointUndecided) {
  for (const Rational& shrink : {Rational(0), Rational(1, 10)}) {
    SCOPED_TRACE("pin narrower by " + shrink.get_str());
    const Rational R(5), p(1);
    std::string text = crank_in_yoke(R, p);
    // the pin's radius alone: the slot keeps its width 2p
    const std::string pin = "\"radius\": " + quoted(p);
    ASSERT_NE(text.find(pin), std::string::npos);
    text.replace(text.find(pin), pin.size(), "\"radius\": " + quoted(Rational(p - shrink)));
    Model model = read_model(text);
    KinematicsOptions options;
    options.driver = "yoke";
    options.range = std::make_pair(Rational(0), Rational(2));
    options.steps_per_cycle = 40;
    options.reversal = false;
    KinematicsResult result = analyze_kinematics(model, options);
    std::size_t undecided = 0;
    for (const std::string& w : result.warnings) undecided += w.find("were not decided") != std::string::npos;
    EXPECT_EQ(undecided, 0u);
    int touching = 0;
    for (const KinematicPiece& piece : result.pieces) {
      if (piece.mode != KinematicPiece::Mode::touching) continue;
      ++touching;
      for (const auto& [theta, s] : {std::pair{piece.start_position, piece.start.value()}, std::pair{piece.end_position, piece.end.value()}})
        EXPECT_NEAR(5 * std::sin(theta), s, 1e-9) << "theta " << theta;
    }
    EXPECT_EQ(touching > 0, shrink == 0);
  }
}

// The engine's reading ahead (session 29: narrower windows read off a wider slice instead of
// being sliced) keeps the slicer's verdicts as if each window had been sliced: a read slice
// flags exactly the undecided points the slicer counts when it slices that window itself (none
// since the irrational fits are decided), and marks touching exactly the points the direct
// slice marks. At irrational channel points of the exact slot, wide slices (whole charts and
// windows) and narrow windows around and between their points.
TEST(KernelSlicerZeroClearance, SlicesReadOffWiderOnesFlagTheFitsAndUndecidedPointsAsTheSlicerDoes) {
  std::mt19937_64 random(2929);
  std::size_t touching = 0, reads = 0;
  for (int instance = 0; instance < 3; ++instance) {
    const Rational R = random_rational(random, 5, 40, 7), p = random_rational(random, 1, 2, 5);
    Model model = read_model(crank_in_yoke(R, p));
    std::unique_ptr<PairSlicer> slicer = make_kernel_slicer(model, 0, 0);
    for (int k = 0; k < 6; ++k) {
      Rational s = random_rational(random, 0, 1, 101) * R * Rational(9, 10);
      s.canonicalize();
      for (std::size_t f = 0; f < slicer->follower_charts().size(); ++f) {
        const ChartAxis& chart = slicer->follower_charts()[f];
        ChartSlice wide = slicer->slice(0, s, f);
        for (int w = 0; w < 8; ++w) {
          Rational a = chart.lo + (chart.hi - chart.lo) * random_rational(random, 0, 1, 1 + static_cast<long>(random() % 500));
          Rational b = chart.lo + (chart.hi - chart.lo) * random_rational(random, 0, 1, 1 + static_cast<long>(random() % 500));
          if (b < a) std::swap(a, b);
          const ChartWindow window{a, b};
          std::optional<ChartSlice> read = restrict_chart_slice(wide, chart, &window);
          if (!read) continue;
          ++reads;
          const std::size_t before = kernel_slice_class_counts(*slicer).touching_undecided;
          ChartSlice direct = slicer->slice(0, s, f, &window);
          const std::size_t counted = kernel_slice_class_counts(*slicer).touching_undecided - before;
          const auto flagged = static_cast<std::size_t>(std::count_if(
              read->points.begin(), read->points.end(), [](const SlicePoint& point) { return point.undecided; }));
          EXPECT_EQ(flagged, counted) << "s " << s.get_str() << " window " << a.get_str() << " .. " << b.get_str();
          ASSERT_EQ(read->points.size(), direct.points.size());
          for (std::size_t i = 0; i < direct.points.size(); ++i) {
            EXPECT_EQ(read->points[i].touching, direct.points[i].touching) << "s " << s.get_str() << " point " << i;
            touching += direct.points[i].touching;
          }
        }
      }
    }
  }
  EXPECT_GT(reads, 50u);
  EXPECT_GT(touching, 10u);
}

}  // namespace
}  // namespace hipair::kinematics_detail
