// The bundled mechanisms' C-spaces located on their special lines against the exact overlap
// predicate: every vertical edge (a rational angle's half-angle tangent or offset where a vertex
// meets a flank, a chart seam, a tangent joint of a part's outline) sampled across its extent,
// and every exact vertex. Random configurations are checked elsewhere (cspace_oracle tests);
// these are the configurations where a point location that reads a vertex's ordinate wrongly,
// or a piece that reaches across a tangent, shows (session 14 found both on translating pairs).
#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "test_paths.hpp"

namespace hipair {
namespace {

// The placement of `part` at chart coordinate v of an axis (rotation: half-angle tangent t, or
// t of the half-turn chart, theta = pi + 2 atan t; translation: offset along the direction).
Placement placement_at(const Part& part, AxisKind kind, bool half_turn, const Rational& v) {
  if (kind == AxisKind::translation) {
    Placement p;
    p.offset = Point{Rational(part.motion.direction.x * v), Rational(part.motion.direction.y * v)};
    return p;
  }
  const Rational d = 1 + v * v;
  Rational c = (1 - v * v) / d, s = 2 * v / d;
  if (half_turn) {
    c = -c;
    s = -s;
  }
  return placement_about(part.motion.pivot, c, s, Point{Rational(0), Rational(0)});
}

const Part& part_named(const Model& model, const std::string& name) {
  for (const Part& part : model.parts)
    if (part.name == name) return part;
  throw std::runtime_error("no part " + name);
}

class CSpaceExampleLines : public testing::TestWithParam<std::string> {};

TEST_P(CSpaceExampleLines, VerticalEdgesAndVerticesLocateAsTheOverlapPredicateSays) {
  const Model model = read_model_file(std::string(HIPAIR_SOURCE_DIR) + "/examples/models/" + GetParam() + ".json");
  const std::vector<CSpace> spaces = CSpace::build_all(model);
  int checked = 0, touching = 0;
  for (const CSpace& space : spaces) {
    if (space.dimension() != 2) continue;
    SCOPED_TRACE(space.x_part() + " : " + space.y_part());
    const Part& x_part = part_named(model, space.x_part());
    const Part& y_part = part_named(model, space.y_part());
    std::vector<ChartPoint> points;
    for (std::size_t e = 0; e < space.edges().size(); ++e) {
      const CSpaceEdge& edge = space.edges()[e];
      if (!edge.vertical) continue;
      const auto& f = space.edge_polynomial_coefficients(e);   // c0 + c1 x
      if (f.size() != 2 || f[1].empty() || f[1][0] == 0) continue;
      Rational x(mpz_class(-f[0][0]), f[1][0]);
      x.canonicalize();
      for (int k = 0; k <= 8; ++k) {
        const double y = edge.y_chart.lower + (edge.y_chart.upper - edge.y_chart.lower) * k / 8;
        if (!std::isfinite(y)) continue;
        Rational q(std::lround(y * 4096), 4096);
        q.canonicalize();
        points.push_back(ChartPoint{edge.chart, x, q});
      }
    }
    for (const CSpaceVertex& v : space.vertices())
      if (v.x.exact && v.y_exact && v.y.exact) points.push_back(ChartPoint{v.chart, v.x.lower, v.y.lower});
    int wrong = 0;
    for (const ChartPoint& point : points) {
      const CSpaceChart& chart = space.charts()[point.chart];
      Location l;
      try {
        l = space.locate(point);
      } catch (const Error& e) {
        if (++wrong <= 3) ADD_FAILURE() << "locate (" << point.x << ", " << point.y << ") chart " << point.chart << ": " << e.what();
        continue;
      }
      if (l.kind == Location::Kind::outside) continue;
      const bool free = l.kind == Location::Kind::free ||
                        ((l.kind == Location::Kind::edge || l.kind == Location::Kind::vertex) && l.cell != no_index &&
                         space.cells()[l.cell].kind == CellKind::free);
      const bool blocked = l.kind == Location::Kind::blocked ||
                           ((l.kind == Location::Kind::edge || l.kind == Location::Kind::vertex) && l.cell != no_index &&
                            space.cells()[l.cell].kind == CellKind::blocked);
      const bool contact = !free && !blocked;
      const PartRelation relation =
          part_overlap(x_part, placement_at(x_part, chart.x_kind, chart.x_half_turn, point.x), y_part,
                       placement_at(y_part, chart.y_kind, chart.y_half_turn, point.y))
              .relation;
      const bool agrees = relation == PartRelation::apart         ? free
                          : relation == PartRelation::overlapping ? blocked
                                                                  : contact;
      if (!agrees && ++wrong <= 3)
        ADD_FAILURE() << "chart " << point.chart << " at (" << point.x << ", " << point.y << "): located "
                      << static_cast<int>(l.kind) << ", the parts are "
                      << (relation == PartRelation::apart ? "apart" : relation == PartRelation::overlapping ? "overlapping" : "touching");
      ++checked;
      touching += relation == PartRelation::touching;
    }
    EXPECT_EQ(wrong, 0);
  }
  std::cout << GetParam() << ": " << checked << " configurations on special lines, " << touching << " touching\n";
  EXPECT_GT(checked, 0);
}

INSTANTIATE_TEST_SUITE_P(Examples, CSpaceExampleLines,
                         testing::Values("geneva", "geneva-drive", "escapement", "ratchet", "cam-follower",
                                         "cam-follower-lever", "cam-drive", "two-pin-wedge", "scotch-yoke", "lift-chain",
                                         "cam-shim-stack"),
                         [](const testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

}  // namespace
}  // namespace hipair
