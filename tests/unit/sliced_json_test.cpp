// The JSON of a 3-DOF pair's sliced C-space (`hipair cspace --json`, src/cli/cspace_sliced.cpp)
// read back: every connection's exact witnesses (crossings[].witnesses, parallel to
// crossings[].connections) parsed from their exact rationals and located exactly in (x, y, θ):
// free, in the free cell of the interval the connection names on each side, and the pure
// rotation between them certified free (motion_free) as the connection claims. And the default
// choice of full-size slices of the stack (render::sliced_default_full_size).
#include <hipair/model.hpp>
#include <hipair/rational.hpp>
#include <hipair/sliced.hpp>

#include "cli/cspace_sliced.hpp"
#include "render/sliced_svg.hpp"
#include "sliced_peg_in_hole.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace hipair {
namespace {

using nlohmann::json;

using test::peg_in_hole;

SlicedConfiguration read_configuration(const json& j) {
  SlicedConfiguration q;
  q.x = parse_rational(j.at("x").get<std::string>());
  q.y = parse_rational(j.at("y").get<std::string>());
  q.angle.half_turn = j.at("half_turn").get<bool>();
  if (!q.angle.half_turn) q.angle.t = parse_rational(j.at("t").get<std::string>());
  return q;
}

void expect_witnesses_as_claimed(const SlicedSpace& space, std::size_t* checked, std::size_t* through_half_turn) {
  json doc = json::parse(cli::sliced_json(space, false));
  const json& crossings = doc.at("crossings");
  ASSERT_EQ(crossings.size(), space.crossings().size());
  for (const json& crossing : crossings) {
    const json& connections = crossing.at("connections");
    const json& witnesses = crossing.at("witnesses");
    ASSERT_EQ(witnesses.size(), connections.size());
    const std::size_t left_slice = crossing.at("left_slice"), right_slice = crossing.at("right_slice");
    for (std::size_t k = 0; k < connections.size(); ++k) {
      const std::size_t left_cell = connections[k][0], right_cell = connections[k][1];
      SlicedConfiguration left = read_configuration(witnesses[k].at("left"));
      SlicedConfiguration right = read_configuration(witnesses[k].at("right"));
      const bool flip = witnesses[k].at("through_half_turn");
      SCOPED_TRACE("critical " + std::to_string(crossing.at("critical").get<std::size_t>()) + " connection " +
                   std::to_string(k) + ": " + witnesses[k].dump());
      // the same offset on both sides (a pure rotation)
      EXPECT_EQ(left.x, right.x);
      EXPECT_EQ(left.y, right.y);
      SlicedLocation a = space.locate(left), b = space.locate(right);
      ASSERT_EQ(a.kind, SlicedLocation::Kind::free);
      ASSERT_EQ(b.kind, SlicedLocation::Kind::free);
      EXPECT_EQ(a.interval, left_slice);
      EXPECT_EQ(a.cell, left_cell);
      EXPECT_EQ(b.interval, right_slice);
      EXPECT_EQ(b.cell, right_cell);
      // the rotation across the critical angle is free throughout (ends included)
      EXPECT_TRUE(space.motion_free(SlicedMotion{left, right, flip, {}}));
      ++*checked;
      if (flip) ++*through_half_turn;
    }
  }
}

TEST(SlicedJson, WitnessesOfAPegInAHoleLocateAsClaimed) {
  // a 10 mm peg in a 12 mm hole (examples/models/peg-in-hole.json)
  SlicedSpace space = SlicedSpace::build(peg_in_hole("5", "6"), "plate", "peg");
  std::size_t checked = 0, flips = 0;
  expect_witnesses_as_claimed(space, &checked, &flips);
  // 12 critical angles, each crossed by the outside at least, and by the cell in the hole
  // where it continues; one crossing is the half turn
  ASSERT_EQ(space.critical_angles().size(), 12u);
  EXPECT_GE(checked, 12u);
  EXPECT_GE(flips, 1u);

  // the default full-size slices: the two sides of the critical angle nearest theta = 0 where
  // a free cell ends or starts: where the free square in the hole closes, the smaller root of
  // the fit polynomial 2 - 20 t + 22 t^2 (t = (10 - sqrt 56)/22, theta = 13.05 degrees; sign
  // either), with the outside only on one side and the outside and the hole on the other
  std::vector<std::size_t> chosen = render::sliced_default_full_size(space);
  ASSERT_EQ(chosen.size(), 2u);
  const SlicedCrossing* change = nullptr;
  for (const auto& c : space.crossings())
    if (std::minmax(c.left_interval, c.right_interval) == std::minmax(chosen[0], chosen[1])) change = &c;
  ASSERT_NE(change, nullptr) << "the chosen slices are not neighbours";
  // degrees is the display value (2 decimals shown): 0.005 degree is its stated precision
  const double expected = 2 * std::atan((10 - std::sqrt(56.0)) / 22) * 180 / 3.14159265358979323846;
  EXPECT_NEAR(std::fabs(space.critical_angles()[change->critical].degrees), expected, 0.005);
  EXPECT_EQ(space.intervals()[change->left_interval].free_cells.size() +
                space.intervals()[change->right_interval].free_cells.size(),
            3u);
  EXPECT_EQ(change->ending.size() + change->starting.size(), 1u);
}

TEST(SlicedJson, WitnessesOfAWideHoleLocateAsClaimed) {
  // a 10 mm peg in a 14.15 mm hole turns freely: the hole's cell continues across every angle
  SlicedSpace space = SlicedSpace::build(peg_in_hole("5", "7.075"), "plate", "peg");
  std::size_t checked = 0, flips = 0;
  expect_witnesses_as_claimed(space, &checked, &flips);
  EXPECT_GE(checked, 2u * space.critical_angles().size());
  // no change of structure: the default full-size slices fall back to the most free cells
  std::vector<std::size_t> chosen = render::sliced_default_full_size(space);
  ASSERT_EQ(chosen.size(), 2u);
  for (std::size_t i : chosen) EXPECT_EQ(space.intervals()[i].free_cells.size(), 2u);
}

}  // namespace
}  // namespace hipair
