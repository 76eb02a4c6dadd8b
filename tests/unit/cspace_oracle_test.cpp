// Exact point location against the exact overlap oracle on the example mechanisms: at 10,000
// random rational configurations per pair (fixed seed; the builder also checks every face it
// classified from the blocked side of a contact edge with the oracle), free <=> apart, blocked <=>
// overlapping, and a configuration on an edge or a vertex is touching (on a real edge) or of
// the class of the surrounding cell (on a spurious edge, whose curve may still touch there).
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
  cspace::PairAxes axes = cspace::pair_axes(model, *model.find_part(first), *model.find_part(second));
  cspace::ChartLayout layout = cspace::chart_layout(model, axes);
  std::mt19937_64 random(seed);
  const std::size_t y_count = space.dimension() == 2 ? layout.y_charts.size() : 1;
  EXPECT_EQ(space.charts().size(), layout.x_charts.size() * y_count);
  for (int i = 0; i < samples; ++i) {
    std::size_t c = random() % space.charts().size();
    const CSpaceChart& chart = space.charts()[c];
    auto pick = [&](const Rational& lo, const Rational& hi) {
      // a rational with a small denominator (hits edges and vertices now and then) or a
      // random one
      Rational u = random() % 4 == 0 ? Rational(static_cast<long>(random() % 65), 64)
                                      : Rational(mpz_class(static_cast<unsigned long>(random() % 1000003)), 1000003);
      u.canonicalize();
      return Rational(lo + u * (hi - lo));
    };
    ChartPoint q{c, pick(chart.x_lo, chart.x_hi), space.dimension() == 2 ? pick(chart.y_lo, chart.y_hi) : Rational(0)};
    Location location = space.locate(q);
    cspace::ChartAxis y_axis = space.dimension() == 2 ? layout.y_charts[c % y_count] : cspace::ChartAxis{};
    cspace::Overlap overlap =
        cspace::classify_overlap(model, axes, layout.x_charts[c / y_count], y_axis, cspace::ChartPoint{q.x, q.y});
    switch (location.kind) {
      case Location::Kind::free:
        EXPECT_EQ(overlap, cspace::Overlap::apart) << file << " chart " << c << " at " << q.x << ", " << q.y;
        ++counts.free;
        break;
      case Location::Kind::blocked:
        EXPECT_EQ(overlap, cspace::Overlap::overlapping) << file << " chart " << c << " at " << q.x << ", " << q.y;
        ++counts.blocked;
        break;
      case Location::Kind::edge:
      case Location::Kind::vertex: {
        bool real = false;
        if (location.kind == Location::Kind::edge) {
          real = space.edges()[location.edge].real;
        } else if (space.dimension() == 1) {
          real = location.cell == no_index;
        } else {
          for (std::size_t e : space.vertices()[location.vertex].edges) real = real || space.edges()[e].real;
        }
        if (real) {
          EXPECT_EQ(overlap, cspace::Overlap::touching) << file << " chart " << c << " at " << q.x << ", " << q.y;
        } else if (location.cell != no_index && overlap != cspace::Overlap::touching) {
          bool free = space.cells()[location.cell].kind == CellKind::free;
          EXPECT_EQ(overlap, free ? cspace::Overlap::apart : cspace::Overlap::overlapping);
        }
        ++counts.on_contact;
        break;
      }
      case Location::Kind::outside:
        ADD_FAILURE() << "a configuration inside a chart box is outside the C-space";
        break;
    }
  }
  return counts;
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
