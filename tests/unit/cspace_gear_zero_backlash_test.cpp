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
#include <hipair/kernel_slice.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/pin_slot.hpp>

#include <gtest/gtest.h>

#include <filesystem>
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

}  // namespace
}  // namespace hipair
