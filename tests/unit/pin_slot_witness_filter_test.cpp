// The pin-slot stack's witness filter (PinSlotBuildOptions::witness_filter: a witness segment
// certified free by certified double intervals of the two boundaries before its exact 1-D
// C-space) changes nothing: on the film advance's film/follower pair and on generated
// translating blocks against pin-slot bars, the connections (cells, witnesses), changes and
// groups with and without it are identical, and the filter does decide some witnesses.
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/pin_slot.hpp>

#include "sliced/witness_filter.hpp"

#include "polygon_loop_json.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using test_loops::loop_json;
using test_loops::star;

std::size_t expect_same_stacks(const Model& model, const std::string& other, const std::string& pin, std::size_t slices) {
  PinSlotBuildOptions options;
  options.slices = slices;
  options.critical_values = false;
  PinSlotSpace filtered = PinSlotSpace::build(model, other, pin, options);
  options.witness_filter = false;
  PinSlotSpace exact = PinSlotSpace::build(model, other, pin, options);
  const auto& a = filtered.connections();
  const auto& b = exact.connections();
  EXPECT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k) {
    SCOPED_TRACE("connection " + std::to_string(k));
    EXPECT_EQ(a[k].kind, b[k].kind);
    EXPECT_EQ(a[k].lower, b[k].lower);
    EXPECT_EQ(a[k].lower_cell, b[k].lower_cell);
    EXPECT_EQ(a[k].upper_cell, b[k].upper_cell);
    EXPECT_EQ(a[k].witness_slide, b[k].witness_slide);
    EXPECT_EQ(a[k].witness_other.value, b[k].witness_other.value);
  }
  EXPECT_EQ(filtered.changes().size(), exact.changes().size());
  EXPECT_EQ(filtered.groups(), exact.groups());
  EXPECT_EQ(filtered.statistics().witness_spaces, exact.statistics().witness_spaces);
  EXPECT_EQ(exact.statistics().witness_filtered, 0u);
  return filtered.statistics().witness_filtered;
}

TEST(PinSlotWitnessFilter, ConnectionsEqualTheExactWitnessSpaces) {
  std::size_t decided = 0;
  {
    SCOPED_TRACE("film advance");
    const Model model = read_model_file(std::string(HIPAIR_EXAMPLES) + "/film-advance.json");
    decided += expect_same_stacks(model, "film", "follower", 6);
  }
  std::mt19937_64 random(1313);
  for (int round = 0; round < 12; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    // a block translating along y past a bar on a pin-slot motion (near and touching cases)
    const std::string block = loop_json(star(random, 4 + static_cast<int>(random() % 4), 11 + 0.5 * (round % 3), 0, 1.5, false));
    const std::string bar = loop_json(star(random, 4 + static_cast<int>(random() % 3), 5, 0, 1.0, false));
    Model model = read_model(R"({ "hipair": 1, "name": "generated", "parts": [
      { "name": "block", "motion": { "translation": { "direction": [0, 1], "limits": [-6, 6] } }, "loops": [ )" + block + R"( ] },
      { "name": "bar", "motion": { "pin_slot": { "pivot": [0, 0], "direction": [1, 0], "angle_limits": [)" + std::string(round < 6 ? "-20, 20" : "-70, 70") + R"(],
        "limits": [-2, 3] } }, "loops": [ )" + bar + R"( ] } ] })");
    // few slices over a wide angle range: block corners sweep through between slices, so
    // some witness segments are not free (a filter claiming them free fails)
    decided += expect_same_stacks(model, "block", "bar", round < 6 ? 6 : 2 + round % 3);
  }
  EXPECT_GT(decided, 0u);   // the filter is not vacuous
}

// The filter against the exact overlap oracle: whenever it says the boundaries stay apart over
// [a, b], the exact relation of the parts at 9 rational tau in [a, b] (ends included) is the
// same throughout and never touching. Generated polygons near each other, narrow and wide
// ranges; a filter that claims "apart" wrongly fails here.
TEST(PinSlotWitnessFilter, ApartMeansTheExactRelationIsConstant) {
  std::mt19937_64 random(2613);
  int claimed = 0, refused = 0;
  for (int round = 0; round < 300; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    const std::string fixed_loop = loop_json(star(random, 3 + static_cast<int>(random() % 5), 9, 0, 1.5, random() % 4 == 0));
    const std::string turning_loop = loop_json(star(random, 3 + static_cast<int>(random() % 5), 4, 0, 1.5, false));
    Model model = read_model(R"({ "hipair": 1, "name": "generated", "parts": [
      { "name": "a", "motion": "fixed", "loops": [ )" + fixed_loop + R"( ] },
      { "name": "b", "motion": "fixed", "loops": [ )" + turning_loop + R"( ] } ] })");
    const Part& fixed = model.parts[0];
    const Part& turning = model.parts[1];
    const Point pivot{Rational(0), Rational(0)};
    Rational shift_x(static_cast<long>(random() % 24), 8);
    shift_x.canonicalize();
    const Point shift{shift_x, Rational(0)};
    Rational a(static_cast<long>(random() % 64) - 32, 64);
    Rational b = a + Rational(1 + static_cast<long>(random() % 16), round % 2 == 0 ? 256 : 16);
    a.canonicalize();
    b.canonicalize();
    const bool apart = pinslot::boundaries_certainly_apart(fixed, turning, pivot, shift, a, b);
    (apart ? claimed : refused) += 1;
    if (!apart) continue;
    std::optional<PartRelation> first;
    for (int k = 0; k <= 8; ++k) {
      Rational t = a + (b - a) * Rational(k, 8);
      t.canonicalize();
      Rational d = 1 + t * t, c = (1 - t * t) / d, s = 2 * t / d;
      c.canonicalize();
      s.canonicalize();
      // shifted, then turned about the pivot: x -> R (x + shift)
      Placement placement = placement_about(pivot, c, s, Point{Rational(c * shift.x - s * shift.y), Rational(s * shift.x + c * shift.y)});
      PartRelation relation = part_overlap(fixed, Placement{}, turning, placement).relation;
      EXPECT_NE(relation, PartRelation::touching);
      if (!first) first = relation;
      EXPECT_EQ(relation, *first) << "tau " << t.get_d();
    }
  }
  EXPECT_GT(claimed, 30);   // neither vacuous
  EXPECT_GT(refused, 30);
}

}  // namespace
}  // namespace hipair
