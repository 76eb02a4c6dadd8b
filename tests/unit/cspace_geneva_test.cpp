// The Geneva pair of the paper's Figure 2: the free space is ONE cell, a channel that wraps
// around the torus in both directions, bounded by horizontal contact segments (the locking
// arcs hold the wheel at a constant angle) and diagonal ones (the pin drives the slots).
#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <filesystem>

#include "test_paths.hpp"

namespace hipair {
namespace {

bool contains(const std::string& text, const std::string& word) { return text.find(word) != std::string::npos; }

TEST(CSpaceGeneva, FreeSpaceIsOneChannelAroundTheTorus) {
  std::filesystem::path path = std::filesystem::path(HIPAIR_EXAMPLES) / "geneva.json";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "examples/models/geneva.json missing";
  Model model = read_model_file(path);
  CSpace space = CSpace::build(model, "driver", "wheel");
  ASSERT_EQ(space.dimension(), 2);
  EXPECT_EQ(space.charts().size(), 4u);   // two rotations without limits: 2 x 2 charts
  std::size_t free = no_index;
  int free_cells = 0;
  for (std::size_t c = 0; c < space.cells().size(); ++c)
    if (space.cells()[c].kind == CellKind::free) {
      free = c;
      ++free_cells;
    }
  ASSERT_EQ(free_cells, 1);
  const CSpaceCell& channel = space.cells()[free];
  EXPECT_TRUE(channel.wraps_x);
  EXPECT_TRUE(channel.wraps_y);
  int horizontal_locking = 0, diagonal_pin_slot = 0;
  for (std::size_t e : channel.boundary) {
    const CSpaceEdge& edge = space.edges()[e];
    ASSERT_TRUE(edge.real);
    ASSERT_FALSE(edge.curves.empty());
    const auto& c = space.edge_polynomial_coefficients(e);
    bool horizontal = c.size() == 1;   // no x: constant wheel angle
    for (std::size_t k : edge.curves) {
      const std::string& label = space.feature_pairs()[k].label;
      if (horizontal && contains(label, "lock arc") && contains(label, "driver") && contains(label, "wheel"))
        ++horizontal_locking;
      if (!horizontal && !edge.vertical && contains(label, "pin") && contains(label, "slot") &&
          edge.x_chart.upper - edge.x_chart.lower > 1e-3 && edge.y_chart.upper - edge.y_chart.lower > 1e-3)
        ++diagonal_pin_slot;
    }
  }
  EXPECT_GT(horizontal_locking, 0);
  EXPECT_GT(diagonal_pin_slot, 0);
  // the initial configuration (both angles 0) is free or in contact, and lies in the channel
  Location start = space.locate(PartCoordinate{PartCoordinate::Kind::half_angle_tangent, Rational(0)},
                                PartCoordinate{PartCoordinate::Kind::half_angle_tangent, Rational(0)});
  EXPECT_NE(start.kind, Location::Kind::blocked);
  if (start.kind == Location::Kind::free) {
    EXPECT_EQ(start.cell, free);
  }
  // every blocked cell borders the channel
  for (const auto& cell : space.cells())
    if (cell.kind == CellKind::blocked) EXPECT_FALSE(cell.neighbours.empty());
}

}  // namespace
}  // namespace hipair
