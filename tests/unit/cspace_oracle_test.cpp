// Exact point location against the exact overlap oracle on the example mechanisms: at 10,000
// random rational configurations per pair (fixed seed; the builder also checks every face it
// classified from the blocked side of a contact edge with the oracle), free <=> apart, blocked <=>
// overlapping, and a configuration on an edge or a vertex is touching (on a real edge) or of
// the class of the surrounding cell (on a spurious edge, whose curve may still touch there).
#include "cspace_oracle_sampling.hpp"
#include "curves/contact_curves.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <random>

namespace hipair {
namespace {

struct Agreement {
  int free = 0, blocked = 0, on_contact = 0;
};

Agreement check_pair(const std::string& file, const std::string& first, const std::string& second, int samples,
                     std::uint64_t seed) {
  Agreement counts;
  std::filesystem::path path = std::filesystem::path(HIPAIR_EXAMPLES) / file;
  if (!std::filesystem::exists(path)) return counts;
  Model model = read_model_file(path);
  // faces classified from the blocked side of a contact edge are checked by the oracle too
  CSpaceBuildOptions options;
  options.check_face_classification = true;
  CSpace space = CSpace::build(model, first, second, options);
  const test::OracleSampler sampler(model, space);
  std::mt19937_64 random(seed);
  EXPECT_EQ(space.charts().size(), sampler.oracle_charts());
  for (int i = 0; i < samples; ++i) {
    const test::OracleSampler::Sample sample = sampler.next(random, {4, 64, 1000003});
    switch (sampler.expect_agrees(sample, file + " " + sampler.where(sample))) {
      case test::SampleClass::free: ++counts.free; break;
      case test::SampleClass::blocked: ++counts.blocked; break;
      case test::SampleClass::on_contact: ++counts.on_contact; break;
    }
  }
  return counts;
}

// Session 56 (hunt56): configurations next to contact space, where a filter or a rounded bound
// would err first. At every vertex with exact coordinates (a 1-D space: every vertex), the
// rational points d beyond its isolating interval on each side and diagonally, and on sampled
// edges at a rational abscissa the points d below and above the edge's exact ordinate, for
// d = 2^-20, 2^-64 and 2^-200: point location must agree with the exact overlap oracle exactly as
// at random points (a real edge or vertex: touching). Examples with polygons and arcs, fixed,
// rotating and translating parts, and a zero-backlash spur-gear pair.
int sign_at(const std::vector<mpz_class>& p, const Rational& x) {
  Rational value(0);
  for (std::size_t i = p.size(); i-- > 0;) value = value * x + Rational(p[i]);
  return sgn(value);
}

// [lo, hi] within `width` around the algebraic number (bisection on its polynomial's sign)
std::pair<Rational, Rational> refined(const AlgebraicNumber& a, const Rational& width) {
  if (a.exact) return {a.lower, a.lower};
  Rational lo = a.lower, hi = a.upper;
  const int lo_sign = sign_at(a.polynomial, lo);
  while (hi - lo > width) {
    Rational middle = (lo + hi) / 2;
    const int s = sign_at(a.polynomial, middle);
    if (s == 0) return {middle, middle};
    (s == lo_sign ? lo : hi) = middle;
  }
  return {lo, hi};
}

struct NearCounts {
  int points = 0, free = 0, blocked = 0, on_contact = 0;
};

NearCounts check_near_contact(const Model& model, const std::string& first, const std::string& second,
                              const CSpaceBuildOptions& options, int edge_samples, std::uint64_t seed) {
  NearCounts counts;
  CSpace space = CSpace::build(model, first, second, options);
  const test::OracleSampler sampler(model, space);
  auto check = [&](std::size_t chart, const Rational& x, const Rational& y, const char* where) {
    const CSpaceChart& box = space.charts()[chart];
    if (x < box.x_lo || x > box.x_hi || (space.dimension() == 2 && (y < box.y_lo || y > box.y_hi))) return;
    const test::OracleSampler::Sample sample = sampler.at(ChartPoint{chart, x, space.dimension() == 2 ? y : Rational(0)});
    ++counts.points;
    switch (sampler.expect_agrees(sample, std::string(where) + " " + sampler.where(sample))) {
      case test::SampleClass::free: ++counts.free; break;
      case test::SampleClass::blocked: ++counts.blocked; break;
      case test::SampleClass::on_contact: ++counts.on_contact; break;
    }
  };
  const Rational distances[] = {Rational(mpz_class(1), mpz_class(1) << 20), Rational(mpz_class(1), mpz_class(1) << 64),
                                Rational(mpz_class(1), mpz_class(1) << 200)};
  for (const CSpaceVertex& v : space.vertices())
    for (const Rational& d : distances) {
      auto [xl, xh] = refined(v.x, d / 4);
      if (space.dimension() == 1) {
        check(v.chart, Rational(xl - d), 0, "beside a 1-D vertex");
        check(v.chart, Rational(xh + d), 0, "beside a 1-D vertex");
        continue;
      }
      if (!v.y_exact) continue;
      auto [yl, yh] = refined(v.y, d / 4);
      for (int sx = -1; sx <= 1; ++sx)
        for (int sy = -1; sy <= 1; ++sy) {
          if ((sx == 0 && !v.x.exact) || (sy == 0 && !v.y.exact)) continue;
          Rational x = sx < 0 ? Rational(xl - d) : sx > 0 ? Rational(xh + d) : xl;
          Rational y = sy < 0 ? Rational(yl - d) : sy > 0 ? Rational(yh + d) : yl;
          check(v.chart, x, y, "around a vertex");
        }
    }
  std::mt19937_64 random(seed);
  for (int i = 0; space.dimension() == 2 && !space.edges().empty() && i < edge_samples; ++i) {
    const std::size_t e = random() % space.edges().size();
    const CSpaceEdge& edge = space.edges()[e];
    if (edge.vertical) continue;
    auto [al, ah] = refined(space.vertices()[edge.source].x, Rational(1, 1 << 30));
    auto [bl, bh] = refined(space.vertices()[edge.target].x, Rational(1, 1 << 30));
    if (!(ah < bl)) continue;
    Rational u(static_cast<long>(random() % 1000 + 1), 1002);
    u.canonicalize();
    Rational x = ah + u * (bl - ah);
    AlgebraicNumber y = space.evaluate_exact(e, x);
    for (const Rational& d : distances) {
      auto [yl, yh] = refined(y, d / 4);
      check(edge.chart, x, Rational(yl - d), "below an edge");
      check(edge.chart, x, Rational(yh + d), "above an edge");
      if (y.exact) check(edge.chart, x, yl, "on an edge");
    }
  }
  return counts;
}

NearCounts near_contact_example(const std::string& file, const std::string& first, const std::string& second, int edge_samples,
                                std::uint64_t seed) {
  Model model = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / file);
  return check_near_contact(model, first, second, CSpaceBuildOptions{}, edge_samples, seed);
}

TEST(CSpaceOracle, NearContactSpaceAgreesWithTheOracle) {
  struct Case {
    const char *file, *first, *second;
  };
  // rotation vs fixed (1-D, segments and arcs), rotation vs translation (arcs, polygon),
  // translation vs translation, rotation vs rotation (polygons and arcs)
  for (Case c : {Case{"lever-stop.json", "lever", "stop"}, Case{"scotch-yoke.json", "crank", "yoke"},
                 Case{"cam-follower.json", "cam", "follower"}, Case{"two-pin-wedge.json", "wedge", "plunger"},
                 Case{"cam-follower-lever.json", "follower", "lever"}, Case{"escapement.json", "anchor", "balance"}}) {
    SCOPED_TRACE(std::string(c.file) + " " + c.first + ":" + c.second);
    NearCounts n = near_contact_example(c.file, c.first, c.second, 150, 56);
    EXPECT_GT(n.points, 20);
    EXPECT_GT(n.free + n.blocked, 0);
  }
}

TEST(CSpaceOracle, NearContactOfAZeroBacklashGearPair) {
  // 7 and 19 teeth, backlash 0 at the exact centre distance (tests/fuzz/zero_backlash_gears.py):
  // its operating region (about 600 edges, 8 500 points, 1-3 s); hunt56 found no disagreement at
  // 134 478 points of a 12 x 20 pair's region, nor at 75 084 points of a whole 6 x 6 torus, either
  ReadOptions read;
  read.parameter_values["teeth-1"] = Rational(7);
  read.parameter_values["teeth-2"] = Rational(19);
  read.parameter_values["backlash"] = Rational(0);
  read.parameter_values["center-distance"] = Rational(2 * (7 + 19), 2);
  read.allow_out_of_tolerance = true;
  Model model = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / "spur-gears.json", read);
  CSpaceBuildOptions options;
  options.operating_region = true;
  NearCounts n = check_near_contact(model, "pinion", "gear", options, 400, 719);
  EXPECT_GT(n.points, 1000);
  EXPECT_GT(n.blocked, 0);
}

TEST(CSpaceOracle, GenevaDriverWheel) {
  Agreement a = check_pair("geneva.json", "driver", "wheel", 10000, 1);
  if (a.free + a.blocked + a.on_contact == 0) GTEST_SKIP() << "examples/models/geneva.json missing";
  EXPECT_GT(a.free, 0);
  EXPECT_GT(a.blocked, 0);
}

TEST(CSpaceOracle, ScotchYokeCrankYoke) {
  Agreement a = check_pair("scotch-yoke.json", "crank", "yoke", 10000, 2);
  if (a.free + a.blocked + a.on_contact == 0) GTEST_SKIP() << "examples/models/scotch-yoke.json missing";
  EXPECT_GT(a.free, 0);
  EXPECT_GT(a.blocked, 0);
}

TEST(CSpaceOracle, RatchetWheelPawl) {
  Agreement a = check_pair("ratchet.json", "wheel", "pawl", 10000, 3);
  if (a.free + a.blocked + a.on_contact == 0) GTEST_SKIP() << "examples/models/ratchet.json missing";
  EXPECT_GT(a.free, 0);
  EXPECT_GT(a.blocked, 0);
}

TEST(CSpaceOracle, EscapementWheelAnchor) {
  Agreement a = check_pair("escapement.json", "escape-wheel", "anchor", 3000, 5);
  if (a.free + a.blocked + a.on_contact == 0) GTEST_SKIP() << "examples/models/escapement.json missing";
  EXPECT_GT(a.free, 0);
  EXPECT_GT(a.blocked, 0);
}

TEST(CSpaceOracle, CamFollower) {
  Agreement a = check_pair("cam-follower.json", "cam", "follower", 10000, 4);
  if (a.free + a.blocked + a.on_contact == 0) GTEST_SKIP() << "examples/models/cam-follower.json missing";
  EXPECT_GT(a.free, 0);
  EXPECT_GT(a.blocked, 0);
}

}  // namespace
}  // namespace hipair
