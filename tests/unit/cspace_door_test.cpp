// The adaptor as the only door: the queries the library's own consumers use instead of the
// C-space internals — faces() (the C-space picture), curve_polynomial() (the kinematic slicer's
// velocity ratios) and part_overlap() (the certificate producers' oracle) — against the exact
// overlap oracle, exact point location and the edges' own cells.
#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>

#include "cam_and_block_model.hpp"
#include "oracle/overlap.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <random>
#include <set>
#include <string>

namespace hipair {
namespace {

std::filesystem::path example(const std::string& name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; }

Rational random_rational(std::mt19937_64& random, long range, long denominator) {
  Rational r(static_cast<long>(random() % (2 * range + 1)) - range, denominator);
  r.canonicalize();
  return r;
}

// A rational rotation (through a rational half-angle tangent) about a pivot, then a shift.
Placement random_placement(std::mt19937_64& random, const Point& pivot) {
  Rational t = random_rational(random, 3000, 1000);
  Rational w = 1 + t * t;
  Rational c = (1 - t * t) / w, s = 2 * t / w;
  Point shift{random_rational(random, 200, 100), random_rational(random, 200, 100)};
  return placement_about(pivot, c, s, shift);
}

// ------------------------------------------------------------------ part_overlap

TEST(CSpaceDoor, PartOverlapIsTheExactOracleWithWitnessesInsideBothParts) {
  std::mt19937_64 random(1010);
  int counts[3] = {0, 0, 0};
  for (const char* file : {"geneva.json", "ratchet.json", "cam-follower.json", "spur-gears.json"}) {
    Model model = read_model_file(example(file));
    for (const PairSpec& pair : model.pairs) {
      const Part& a = model.parts[pair.first];
      const Part& b = model.parts[pair.second];
      for (int i = 0; i < 25; ++i) {
        Placement pa = random_placement(random, a.motion.pivot), pb = random_placement(random, b.motion.pivot);
        if (i % 5 == 0) pb = pa;   // the same placement of both: often overlapping or touching
        PartOverlap door = part_overlap(a, pa, b, pb, true);
        cspace::RigidMap ma{pa.cos, pa.sin, pa.offset}, mb{pb.cos, pb.sin, pb.offset};
        cspace::OverlapOptions options;
        options.exact_only = true;   // the oracle's exact path, without its interval filter
        cspace::OverlapReport oracle = cspace::analyse_overlap(a, ma, b, mb, options);
        ASSERT_EQ(static_cast<int>(door.relation), static_cast<int>(oracle.relation)) << file << " " << i;
        ++counts[static_cast<int>(door.relation)];
        if (door.relation == PartRelation::overlapping && door.witness) {
          EXPECT_EQ(cspace::locate_point(a, ma, *door.witness), cspace::PointLocation::inside) << file;
          EXPECT_EQ(cspace::locate_point(b, mb, *door.witness), cspace::PointLocation::inside) << file;
        }
        if (door.relation != PartRelation::overlapping) EXPECT_FALSE(door.witness.has_value());
        // the placement maps body points as the oracle's rigid map does
        EXPECT_EQ(pa.apply(a.loops.at(0).edges.at(0).source), ma.apply(a.loops.at(0).edges.at(0).source));
      }
    }
  }
  EXPECT_GT(counts[0], 0);
  EXPECT_GT(counts[2], 0);
}

TEST(CSpaceDoor, PartOverlapRefusesAPlacementThatIsNotRigid) {
  Model model = read_model_file(example("geneva.json"));
  Placement skew;
  skew.cos = Rational(3, 5);
  skew.sin = Rational(3, 5);
  EXPECT_THROW(part_overlap(model.parts[0], skew, model.parts[1], Placement{}), NumericError);
  EXPECT_THROW(part_overlap(model.parts[0], Placement{}, model.parts[1], skew), NumericError);
}

// ------------------------------------------------------------------ faces

// Every face's boundary cycles are closed chains of the chart's edges with the face on their
// named side (the edges' own left/right cells), every edge bounds a face on each side inside
// the chart box, and the face's kind is its cell's.
void expect_faces_consistent(const CSpace& space) {
  const auto& edges = space.edges();
  std::map<std::size_t, int> sides;   // edge -> sides seen
  for (std::size_t c = 0; c < space.charts().size(); ++c) {
    for (const CSpaceFace& face : space.faces(c)) {
      EXPECT_EQ(face.chart, c);
      if (!face.classified) continue;
      ASSERT_TRUE(face.cell.valid());
      EXPECT_EQ(space.cell(face.cell).kind, face.kind);
      for (const auto& cycle : face.boundary) {
        ASSERT_FALSE(cycle.empty());
        for (std::size_t i = 0; i < cycle.size(); ++i) {
          auto [e, forward] = cycle[i];
          const CSpaceEdge& edge = space.edge(e);
          EXPECT_EQ(edge.chart, c);
          EXPECT_EQ(forward ? edge.left_cell : edge.right_cell, face.cell.index());
          ++sides[e.index()];
          auto [next, next_forward] = cycle[(i + 1) % cycle.size()];
          std::size_t end = forward ? edge.target : edge.source;
          std::size_t start = next_forward ? space.edge(next).source : space.edge(next).target;
          EXPECT_EQ(end, start) << "cycle not closed at edge " << e.index();
        }
      }
    }
  }
  if (!space.complete()) return;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    int expected = (edges[e].left_cell != no_index) + (edges[e].right_cell != no_index);
    EXPECT_EQ(sides[e], expected) << "edge " << e;
  }
}

TEST(CSpaceDoor, FacesAreClosedCyclesWithTheEdgesCellsOnTheirSides) {
  Model model = read_model_file(example("geneva.json"));
  CSpace space = CSpace::build(model, "driver", "wheel");
  ASSERT_EQ(space.dimension(), 2);
  std::size_t faces = 0;
  for (std::size_t c = 0; c < space.charts().size(); ++c) faces += space.faces(c).size();
  EXPECT_EQ(faces, space.statistics().faces);
  expect_faces_consistent(space);
  EXPECT_THROW(space.faces(space.charts().size()), GeometryError);
}

using test::cam_and_block;

TEST(CSpaceDoor, OneDimensionalFacesAreTheIntervalsBetweenContactPointsByExactLocation) {
  std::vector<CSpace> spaces = CSpace::build_all(read_model_file(example("cam-follower.json")));
  spaces.push_back(CSpace::build(read_model(cam_and_block), "cam", "block"));
  std::size_t checked = 0, blocked = 0;
  for (const CSpace& space : spaces) {
    if (space.dimension() != 1) continue;
    for (std::size_t c = 0; c < space.charts().size(); ++c) {
      const CSpaceChart& chart = space.charts()[c];
      std::vector<CSpaceFace> faces = space.faces(c);
      ASSERT_FALSE(faces.empty());
      EXPECT_FALSE(faces.front().lower.valid());
      EXPECT_FALSE(faces.back().upper.valid());
      for (std::size_t i = 0; i + 1 < faces.size(); ++i) EXPECT_EQ(faces[i].upper, faces[i + 1].lower);
      for (const CSpaceFace& face : faces) {
        if (!face.classified) continue;
        Rational lo = face.lower.valid() ? space.vertex(face.lower).x.upper : chart.x_lo;
        Rational hi = face.upper.valid() ? space.vertex(face.upper).x.lower : chart.x_hi;
        if (face.lower.valid() && space.vertex(face.lower).x.exact) lo = space.vertex(face.lower).x.lower;
        if (!(lo < hi)) continue;
        Rational mid = (lo + hi) / 2;
        Location where = space.locate(ChartPoint{c, mid, 0});
        Location::Kind expected = face.kind == CellKind::free      ? Location::Kind::free
                                  : face.kind == CellKind::blocked ? Location::Kind::blocked
                                                                   : Location::Kind::touching;
        EXPECT_EQ(where.kind, expected);
        EXPECT_EQ(where.cell, face.cell.index());
        ++checked;
        blocked += face.kind == CellKind::blocked;
      }
    }
  }
  EXPECT_GT(checked, 3u);
  EXPECT_GT(blocked, 0u);
}

// ------------------------------------------------------------------ curve_polynomial

// Evaluates c[i][j] x^i y^j exactly.
Rational evaluate(const std::vector<std::vector<mpz_class>>& c, const Rational& x, const Rational& y) {
  Rational sum = 0, xp = 1;
  for (const auto& row : c) {
    Rational yp = 1;
    for (const mpz_class& a : row) {
      sum += Rational(a) * xp * yp;
      yp *= y;
    }
    xp *= x;
  }
  return sum;
}

using test::square_and_plate;

TEST(CSpaceDoor, CurvePolynomialsVanishExactlyAtTheContactsAndOnlyForTheTouchingPairs) {
  Model model = read_model(square_and_plate);
  CSpace space = CSpace::build(model, "square", "plate");
  std::mt19937_64 random(77);
  int contacts = 0;
  for (int i = 0; i < 60; ++i) {
    Rational t = random_rational(random, 999, 1000);
    for (const Slice& slice : space.slice(SliceAxis::x, t)) {
      for (const Slice::Point& point : slice.points) {
        if (!point.at.exact) continue;
        ChartPoint q{slice.chart, t, point.at.lower};
        std::set<std::size_t> touching;
        for (const Contact& contact : space.contact_at(q)) touching.insert(contact.feature.index());
        ASSERT_FALSE(touching.empty());
        for (std::size_t f = 0; f < space.feature_pairs().size(); ++f) {
          auto polynomial = space.curve_polynomial(q.chart, FeatureId(f));
          if (touching.count(f)) {
            ASSERT_FALSE(polynomial.empty());
            EXPECT_EQ(sgn(evaluate(polynomial, q.x, q.y)), 0) << space.feature_pair(FeatureId(f)).label;
            ++contacts;
          }
        }
      }
    }
  }
  EXPECT_GT(contacts, 20);
  EXPECT_THROW(space.curve_polynomial(0, FeatureId(space.feature_pairs().size())), GeometryError);
  EXPECT_THROW(space.curve_polynomial(space.charts().size(), FeatureId(0)), GeometryError);
}

}  // namespace
}  // namespace hipair
