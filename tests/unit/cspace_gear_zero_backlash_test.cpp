// Spur gears at zero backlash (session 65, perf65; issue 14's 19 x 40 pair that hunt64 found
// slow): is "BLOCKED at the start" the exact answer? With exact involutes at zero backlash the
// teeth would touch on both flanks (touching, a channel of zero width). The model's flanks are
// circular arcs fitted to the involute (templates_gears.cpp), so at zero backlash they either
// clear or interfere, depending on the tooth counts: the 19 x 40 pair interferes (its start
// overlaps and no position of the gear is free or touching at the pinion's start angle), the
// 17 x 17 pair clears. The exact kernel slice at the pinion's start is checked against the
// exact overlap predicate (part_overlap) at generated rational gear angles over both of the
// gear's charts: a blocked interval holds only overlapping configurations, a free one only
// configurations where the parts are apart; at zero backlash the 19 x 40 slice has no free and
// no touching interval (on both gear charts; the other pairs on the chart about 0). The backlash-0.1 pair with the same tooth counts is the control (a free
// interval around the start, apart there).
#include "test_paths.hpp"
#include "test_seed.hpp"

#include <hipair/cspace.hpp>
#include <hipair/cspace_region.hpp>
#include <hipair/error.hpp>
#include <hipair/kernel_slice.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/pin_slot.hpp>

#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <functional>
#include <optional>
#include <random>
#include <string>

namespace hipair {
namespace {

Model gears(long z1, long z2, const Rational& backlash) {
  ReadOptions read;
  read.parameter_values["teeth-1"] = Rational(z1);
  read.parameter_values["teeth-2"] = Rational(z2);
  read.parameter_values["backlash"] = backlash;
  read.allow_out_of_tolerance = true;
  return read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / "spur-gears.json", read);
}

// The relation of the pinion at angle 0 and the gear at chart value u of its chart (about 0, or
// about pi with `half`): tan(theta / 2) = u, or -1 / u about pi.
PartRelation relation_at(const Model& model, const Rational& u, bool half) {
  const Part& pinion = model.parts[*model.find_part("pinion")];
  const Part& gear = model.parts[*model.find_part("gear")];
  PartCoordinate coordinate{PartCoordinate::Kind::half_angle_tangent, u};
  if (half && sgn(u) == 0) coordinate = PartCoordinate{PartCoordinate::Kind::half_turn, Rational(0)};
  if (half && sgn(u) != 0) coordinate.value = Rational(-1 / u);
  return part_overlap(pinion, Placement{}, gear, part_placement(gear, coordinate)).relation;
}

// The sign of u - a for the algebraic number a (exactly: a is the unique root of its square-free
// polynomial in (lower, upper), so p changes sign there once and u's side is the side of the end
// where p has p(u)'s sign).
int compare(const Rational& u, const AlgebraicNumber& a) {
  if (a.exact) return sgn(Rational(u - a.lower));
  if (u <= a.lower) return -1;
  if (u >= a.upper) return 1;
  auto value = [&](const Rational& x) {
    Rational sum(0);
    for (std::size_t i = a.polynomial.size(); i-- > 0;) sum = sum * x + Rational(a.polynomial[i]);
    return sgn(sum);
  };
  const int at_u = value(u);
  if (at_u == 0) return 0;
  return at_u == value(a.lower) ? -1 : 1;
}

struct Counts {
  int free = 0, blocked = 0, touching = 0, checked = 0;
};

// The slice of the gear at the pinion's angle 0 on the gear's chart `half`, every interval's
// class against the predicate at `samples` generated rationals of [-1, 1] (and 0).
Counts check_slice(const Model& model, bool half, int samples, std::mt19937_64& random) {
  const std::size_t pinion = *model.find_part("pinion"), gear = *model.find_part("gear");
  std::optional<KernelSlice> slice = kernel_slice(model, pinion, gear, Rational(0), false, Rational(0), half);
  Counts counts;
  EXPECT_TRUE(slice.has_value());
  if (!slice) return counts;
  EXPECT_EQ(slice->kinds.size(), slice->points.size() + 1);
  for (KernelSlice::Kind kind : slice->kinds) {
    counts.free += kind == KernelSlice::Kind::free;
    counts.blocked += kind == KernelSlice::Kind::blocked;
    counts.touching += kind == KernelSlice::Kind::touching;
  }
  std::uniform_int_distribution<long> numerator(-1000003, 1000003);
  for (int i = 0; i <= samples; ++i) {
    Rational u = i == 0 ? Rational(0) : Rational(numerator(random), 1000003);
    u.canonicalize();
    // the interval holding u: after every point whose isolating interval lies below u
    std::size_t k = 0;
    bool ambiguous = false;
    for (const KernelSlice::Point& p : slice->points) {
      const int side = compare(u, p.at);
      if (side > 0) ++k;
      ambiguous = side == 0;
      if (side <= 0) break;
    }
    if (ambiguous) continue;
    const KernelSlice::Kind kind = slice->kinds[k];
    const PartRelation relation = relation_at(model, u, half);
    SCOPED_TRACE("gear chart value " + u.get_str() + (half ? " (about pi)" : ""));
    if (kind == KernelSlice::Kind::blocked) EXPECT_EQ(relation, PartRelation::overlapping);
    if (kind == KernelSlice::Kind::free) EXPECT_EQ(relation, PartRelation::apart);
    if (kind == KernelSlice::Kind::touching) EXPECT_NE(relation, PartRelation::overlapping);
    ++counts.checked;
  }
  return counts;
}

TEST(GearZeroBacklash, NineteenByFortyOverlapsAtTheStartAndNoGearPositionIsFree) {
  std::mt19937_64 random(test::test_seed(65));
  Model model = gears(19, 40, Rational(0));
  // the start (both at angle 0): interiors meet, by the exact predicate
  EXPECT_EQ(relation_at(model, Rational(0), false), PartRelation::overlapping);
  for (bool half : {false, true}) {
    SCOPED_TRACE(half ? "gear chart about pi" : "gear chart about 0");
    Counts counts = check_slice(model, half, 60, random);
    EXPECT_EQ(counts.free, 0);
    EXPECT_EQ(counts.touching, 0);
    EXPECT_GT(counts.blocked, 0);
    EXPECT_GT(counts.checked, 50);
  }
}

TEST(GearZeroBacklash, SlicesAtTheStartAgreeWithThePredicate) {
  std::mt19937_64 random(test::test_seed(6517));
  // the control with backlash (a free interval around the start), a zero-backlash pair whose
  // arcs clear (17 x 17) and one whose arcs interfere (18 x 27)
  struct Case {
    long z1, z2;
    Rational backlash;
    bool start_free;
  };
  for (const Case& c : {Case{19, 40, Rational(1, 10), true}, Case{17, 17, Rational(0), true}, Case{18, 27, Rational(0), false}}) {
    SCOPED_TRACE(std::to_string(c.z1) + " x " + std::to_string(c.z2) + " backlash " + c.backlash.get_str());
    Model model = gears(c.z1, c.z2, c.backlash);
    EXPECT_EQ(relation_at(model, Rational(0), false) != PartRelation::overlapping, c.start_free);
    Counts counts = check_slice(model, false, 40, random);
    EXPECT_EQ(counts.free > 0, c.start_free);
    EXPECT_GT(counts.checked, 30);
  }
}

// The operating region's refusal of an overlapping start before its build (perf65's, in the
// CLI until session 66) is the library's: every entry that builds a region seeded at the
// model's initial configuration (CSpace::build, build_all, build_pairs as simulate calls it,
// build_operating_region_along from a path starting there, as analyze and the tolerance
// analysis call it) refuses it with the same message, before building: 19 x 40 and generated
// zero-backlash pairs whose start overlaps by the exact predicate. Until session 66 the library
// built these regions (19 x 40: 38 s) and returned them. The control: 17 x 17 at zero backlash
// (start free by the predicate) is built.
TEST(GearZeroBacklash, EveryRegionEntryRefusesAnOverlappingStartBeforeItsBuild) {
  std::mt19937_64 random(test::test_seed(66));
  std::uniform_int_distribution<long> teeth(6, 16);
  std::vector<std::array<long, 2>> pairs;
  for (int k = 0; k < 3; ++k) {
    const long z = teeth(random);
    pairs.push_back({z, k % 2 == 0 ? z : 2 * z});
  }
  pairs.push_back({19, 40});   // last: a region built around it takes 38 s
  int refused = 0;
  for (const auto& [z1, z2] : pairs) {
    SCOPED_TRACE(std::to_string(z1) + " x " + std::to_string(z2) + " at zero backlash");
    Model model = gears(z1, z2, Rational(0));
    if (relation_at(model, Rational(0), false) != PartRelation::overlapping) continue;
    ++refused;
    const std::string message =
        "operating region of 'pinion' and 'gear': the parts certainly overlap at the seed configuration (their "
        "interiors meet at the initial configuration, by the exact overlap predicate: there is no channel to build)";
    CSpaceBuildOptions options;
    options.operating_region = true;
    auto expect_refused = [&](const std::string& entry, const std::function<void()>& call) {
      SCOPED_TRACE(entry);
      try {
        call();
        ADD_FAILURE() << "built a region around an overlapping start";
      } catch (const GeometryError& e) {
        EXPECT_EQ(std::string(e.what()), message);
      }
    };
    expect_refused("CSpace::build", [&] { CSpace::build(model, "pinion", "gear", options); });
    expect_refused("CSpace::build_all", [&] { CSpace::build_all(model, options); });
    expect_refused("build_operating_region_along", [&] {
      build_operating_region_along(model, "pinion", "gear", {{0.0, 0.0}, {0.01, -0.01}});
    });
    CSpaceBuildOptions seeded = options;
    seeded.region_seed = std::array<double, 2>{0.0, 0.0};   // the start, given
    expect_refused("CSpace::build, seed given", [&] { CSpace::build(model, "pinion", "gear", seeded); });
    std::vector<PairBuild> builds = CSpace::build_pairs(model, options);
    ASSERT_EQ(builds.size(), 1u);
    EXPECT_EQ(builds[0].status, PairBuild::Status::failed);
    EXPECT_EQ(builds[0].error, message);
    if (HasFailure()) return;   // (a build around the start: the next pairs' would be as slow)
  }
  EXPECT_GE(refused, 1);
  // the control: a free start (by the predicate) is built
  Model clear = gears(17, 17, Rational(0));
  ASSERT_NE(relation_at(clear, Rational(0), false), PartRelation::overlapping);
  CSpaceBuildOptions options;
  options.operating_region = true;
  CSpace space = CSpace::build(clear, "pinion", "gear", options);
  EXPECT_FALSE(space.complete());
  EXPECT_GT(space.statistics().region_tiles, 0u);
}

}  // namespace
}  // namespace hipair
