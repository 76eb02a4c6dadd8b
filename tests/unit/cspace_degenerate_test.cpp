// Degenerate corpus (tests/data/degenerate): tangent circles (an isolated contact point),
// coincident and collinear edges, concentric arcs (contact everywhere), a zero-clearance fit,
// vertex on vertex, features touching along a whole interval. Every pair builds without a
// crash and exact point location agrees with the exact overlap oracle; special
// configurations are checked exactly.
#include "cspace_oracle_sampling.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <random>

namespace hipair {
namespace {

std::filesystem::path corpus() { return std::filesystem::path(HIPAIR_TEST_DATA) / "degenerate"; }

// Point location against the oracle at random rational configurations of every pair.
void agree_with_oracle(const Model& model, const CSpace& space, int samples, std::uint64_t seed) {
  const test::OracleSampler sampler(model, space);
  std::mt19937_64 random(seed);
  for (int i = 0; i < samples; ++i) {
    const test::OracleSampler::Sample sample = sampler.next(random, {3, 32, 100003});
    sampler.expect_agrees(sample, sampler.where(sample));
  }
}

TEST(CSpaceDegenerate, EveryCorpusModelBuildsAndAgreesWithTheOracle) {
  int models = 0;
  for (const auto& entry : std::filesystem::directory_iterator(corpus())) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().filename().string());
    Model model = read_model_file(entry.path());
    std::vector<CSpace> spaces;
    ASSERT_NO_THROW(spaces = CSpace::build_all(model));
    EXPECT_FALSE(spaces.empty());
    for (const CSpace& space : spaces) {
      EXPECT_FALSE(space.cells().empty());
      agree_with_oracle(model, space, 1500, 17);
    }
    ++models;
  }
  EXPECT_GE(models, 7);
}

TEST(CSpaceDegenerate, TangentCirclesTouchAtOneIsolatedConfiguration) {
  Model model = read_model_file(corpus() / "tangent-circles.json");
  CSpace space = CSpace::build(model, "left", "right");
  // theta = 0, phi = pi: the only contact; nearby configurations are free
  Location touch = space.locate(PartCoordinate{PartCoordinate::Kind::half_angle_tangent, Rational(0)},
                                PartCoordinate{PartCoordinate::Kind::half_turn, Rational(0)});
  EXPECT_EQ(touch.kind, Location::Kind::vertex);
  Location near = space.locate(PartCoordinate{PartCoordinate::Kind::half_angle_tangent, Rational(1, 1000000)},
                               PartCoordinate{PartCoordinate::Kind::half_turn, Rational(0)});
  EXPECT_EQ(near.kind, Location::Kind::free);
  int free = 0;
  for (const auto& cell : space.cells()) free += cell.kind == CellKind::free;
  EXPECT_EQ(free, 1);
}

TEST(CSpaceDegenerate, ConcentricArcsTouchEverywhere) {
  Model model = read_model_file(corpus() / "concentric-arcs.json");
  CSpace space = CSpace::build(model, "shaft", "bearing");
  ASSERT_EQ(space.dimension(), 1);
  ASSERT_EQ(space.cells().size(), 1u);
  EXPECT_EQ(space.cells()[0].kind, CellKind::touching);
  EXPECT_TRUE(space.cells()[0].wraps_x);
}

TEST(CSpaceDegenerate, IntervalContactIsATouchingCell) {
  Model model = read_model_file(corpus() / "interval-contact.json");
  CSpace space = CSpace::build(model, "sector", "block");
  int touching = 0;
  for (const auto& cell : space.cells()) touching += cell.kind == CellKind::touching;
  EXPECT_GE(touching, 1);
  // theta = pi: the sector spans [180, 270] deg, exactly the block's arc
  Location full = space.locate(PartCoordinate{PartCoordinate::Kind::half_turn, Rational(0)});
  ASSERT_NE(full.cell, no_index);
  EXPECT_EQ(space.cells()[full.cell].kind, CellKind::touching);
}

TEST(CSpaceDegenerate, VertexOnVertexAtRationalConfigurations) {
  Model model = read_model_file(corpus() / "vertex-on-vertex.json");
  CSpace space = CSpace::build(model, "a", "b");
  // a's apex (1, 1) meets b's corner (1, 1) at s = 0, r = 0
  Location meet = space.locate(PartCoordinate{PartCoordinate::Kind::offset, Rational(0)},
                               PartCoordinate{PartCoordinate::Kind::offset, Rational(0)});
  EXPECT_TRUE(meet.kind == Location::Kind::vertex || meet.kind == Location::Kind::edge);
}

}  // namespace
}  // namespace hipair
