// The public vertices' exact numbers (x, y, y_exact, y_lower, y_upper, y_curve, y_branch) of a
// 2-D space are written from the raw arrangement's vertices when the public vertices are first
// read (CSpace::vertices(), CSpace::vertex(); CSpace::Impl::vertex_numbers, session 43). The
// build no longer copies them. Checked here, on generated translating polygon pairs (grids of
// 1, 1/16, 1/97, scaled by 2^-100 and 2^100, collinear and touching cases, equal polygons) and
// on the degenerate corpus' rotating and mixed pairs (several charts):
//   - every public vertex equals its raw vertex field by field (the copy the build made before);
//   - independently of that mapping, every vertex lies in the certified box of each of its edges
//     (edges and boxes are written by the build from the raw vertices), an edge's source is
//     lexicographically at most its target, and a polygonal space's vertices are exact rationals;
//   - vertex(id) read first, before vertices(), gives the same numbers (and vertices() first);
//   - copies of a space share one set of numbers (the same storage), written once;
//   - several threads reading a fresh space's vertices at once all see the written numbers.
// The cells' samples (sample_x, sample_y) are likewise written when the cells are first read
// (CSpace::cells(), CSpace::cell(); CSpace::Impl::cell_samples, session 56): the build writes
// none (checked before the first read); each cell's sample is its first face's (in chart, then
// face order), and, independently of that, exact point location at the sample finds the cell.
#include "cspace/builder_impl.hpp"
#include "star_slider_pairs.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

namespace hipair {
namespace {

using test_loops::Points;

Points random_star(std::mt19937_64& random, int k, double cx, double cy, double radius, long q, const Rational& scale) {
  return test_loops::grid_star(random, k, cx, cy, radius, q, scale);
}

Points scaled(Points points, const Rational& scale, const Rational& dx = 0, const Rational& dy = 0) {
  for (auto& [x, y] : points) {
    x = x * scale + dx;
    y = y * scale + dy;
  }
  return points;
}

void expect_same(const AlgebraicNumber& n, const cspace::algebra::Real& r, const char* what) {
  EXPECT_EQ(n.exact, r.exact) << what;
  EXPECT_EQ(n.lower, r.lower) << what;
  EXPECT_EQ(n.upper, r.upper) << what;
  EXPECT_EQ(n.polynomial, r.polynomial) << what;
}

// The public vertices of `space` (read through `vertices`) against the raw vertices and the edges.
void expect_vertex_numbers(const CSpace& space, const std::vector<CSpaceVertex>& vertices, bool polygonal) {
  const CSpace::Impl& impl = implementation(space);
  ASSERT_EQ(space.dimension(), 2);
  ASSERT_EQ(vertices.size(), impl.vertex_local.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    SCOPED_TRACE("vertex " + std::to_string(i));
    const CSpaceVertex& vertex = vertices[i];
    auto [c, v] = impl.vertex_local[i];
    ASSERT_EQ(vertex.chart, c);
    const cspace::raw::Vertex& raw = impl.charts[c].arrangement.vertices[v];
    expect_same(vertex.x, raw.x, "x");
    EXPECT_EQ(vertex.y_exact, raw.y_exact);
    if (raw.y_exact) expect_same(vertex.y, raw.y, "y");
    EXPECT_EQ(vertex.y_lower, raw.y_lower);
    EXPECT_EQ(vertex.y_upper, raw.y_upper);
    EXPECT_EQ(vertex.y_curve, raw.y_curve.coefficients);
    EXPECT_EQ(vertex.y_branch, raw.y_branch);
    EXPECT_LE(vertex.x.lower, vertex.x.upper);
    EXPECT_LE(vertex.y_lower, vertex.y_upper);
    EXPECT_FALSE(vertex.y_curve.empty());
    if (polygonal) {
      EXPECT_TRUE(vertex.x.exact);
      EXPECT_TRUE(vertex.y_exact && vertex.y.exact);
      EXPECT_EQ(vertex.x.lower, vertex.x.upper);
      EXPECT_EQ(vertex.y_lower, vertex.y.lower);
      EXPECT_EQ(vertex.y_upper, vertex.y.lower);
    }
  }
  // independent of the vertex mapping: each end lies in its edge's certified box (written by
  // the build from the raw ends), and the source is the lexicographically smaller end
  for (std::size_t e = 0; e < space.edges().size(); ++e) {
    SCOPED_TRACE("edge " + std::to_string(e));
    const CSpaceEdge& edge = space.edges()[e];
    for (std::size_t end : {edge.source, edge.target}) {
      const CSpaceVertex& vertex = vertices[end];
      EXPECT_EQ(vertex.chart, edge.chart);
      EXPECT_LE(Rational(edge.x_chart.lower), vertex.x.upper);
      EXPECT_GE(Rational(edge.x_chart.upper), vertex.x.lower);
      EXPECT_LE(Rational(edge.y_chart.lower), vertex.y_upper);
      EXPECT_GE(Rational(edge.y_chart.upper), vertex.y_lower);
      EXPECT_NE(std::find(vertex.edges.begin(), vertex.edges.end(), e), vertex.edges.end());
    }
    const CSpaceVertex &s = vertices[edge.source], &t = vertices[edge.target];
    if (polygonal) {
      int by_x = (s.x.lower > t.x.lower) - (s.x.lower < t.x.lower);
      EXPECT_TRUE(by_x < 0 || (by_x == 0 && s.y.lower < t.y.lower));
      if (edge.vertical) EXPECT_EQ(s.x.lower, t.x.lower);
    }
  }
}

// A fresh space read three ways: vertex(id) first, then vertices() (the same numbers, one
// storage), and through a copy made before any read.
void check_space(const CSpace& space, bool polygonal, bool vertex_first = true) {
  CSpace copy = space;   // shares the implementation: one set of numbers for both
  const std::size_t n = space.statistics().vertices;
  if (!vertex_first) {   // vertices() read first
    expect_vertex_numbers(space, space.vertices(), polygonal);
  } else if (n > 0) {
    const CSpaceVertex& last = space.vertex(VertexId{n - 1});   // read first through vertex(id)
    const cspace::raw::Vertex& raw =
        implementation(space).charts[last.chart].arrangement.vertices[implementation(space).vertex_local[n - 1].second];
    expect_same(last.x, raw.x, "x read first through vertex(id)");
    EXPECT_EQ(last.y_curve, raw.y_curve.coefficients);
  }
  const std::vector<CSpaceVertex>& vertices = space.vertices();
  EXPECT_EQ(&vertices, &copy.vertices());
  expect_vertex_numbers(space, vertices, polygonal);
}

TEST(CSpaceVertexNumbers, GeneratedTranslatingPairsEqualTheRawVerticesAndLieOnTheirEdges) {
  std::mt19937_64 random(4343);
  int checked = 0;
  const Rational tiny = Rational(1) / (mpz_class(1) << 100), huge = Rational(mpz_class(1) << 100);
  for (int instance = 0; instance < 30; ++instance) {
    SCOPED_TRACE("instance " + std::to_string(instance));
    const test_loops::StarPair pair = test_loops::generated_star_pair(random, instance, instance % 7 == 6);   // 6: equal polygons
    if (std::optional<CSpace> space = test_loops::star_slider_space(pair.a, pair.b)) {
      check_space(*space, true, instance % 2 == 0);
      ++checked;
    }
  }
  EXPECT_GE(checked, 24);
  // collinear and parallel edges (overlapping contact curves), touching at a vertex, a
  // zero-clearance slot, equal squares; at scales 1, 2^-100 and 2^100
  const Points square{{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  const Points triangle{{0, 0}, {4, 0}, {1, 3}};
  const Points slot{{0, 0}, {6, 0}, {6, 1}, {4, 1}, {4, 3}, {2, 3}, {2, 1}, {0, 1}};   // a U of inner width 2
  const std::vector<std::pair<Points, Points>> cases{
      {square, scaled(square, 1, 5, 0)},         // equal heights: parallel edges slide along each other
      {square, scaled(square, 1, 2, 2)},         // corners touch at the start
      {square, square},                          // equal polygons
      {triangle, scaled(triangle, -1, 7, 3)},    // a vertex against a vertex, reflected
      {scaled(square, 1, 2, 1), slot},           // a square exactly as wide as the slot
      {scaled(triangle, Rational(1, 3)), scaled(square, Rational(7, 5), 3, -2)}};
  for (const Rational& s : {Rational(1), tiny, huge})
    for (std::size_t k = 0; k < cases.size(); ++k) {
      SCOPED_TRACE("case " + std::to_string(k) + " scale " + s.get_str().substr(0, 12));
      Model model = test_loops::slider_pair_model(scaled(cases[k].first, s), scaled(cases[k].second, s));
      CSpace space = CSpace::build(model, "a", "b");
      check_space(space, true, k % 2 == 0);
    }
}

TEST(CSpaceVertexNumbers, DegenerateCorpusSpacesOfSeveralChartsEqualTheRawVertices) {
  std::size_t spaces = 0, multi_chart = 0, algebraic = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(HIPAIR_TEST_DATA) / "degenerate")) {
    SCOPED_TRACE(entry.path().filename().string());
    Model model = read_model_file(entry.path());
    for (const CSpace& space : CSpace::build_all(model)) {
      if (space.dimension() != 2) continue;
      check_space(space, false);
      ++spaces;
      multi_chart += space.charts().size() > 1;
      for (const CSpaceVertex& v : space.vertices()) algebraic += !v.x.exact;
    }
  }
  EXPECT_GE(spaces, 5u);
  EXPECT_GE(multi_chart, 2u);   // rotating pairs: vertices of later charts mapped through vertex_global
  EXPECT_GE(algebraic, 1u);     // irrational vertices (their polynomial and isolating interval)
}

TEST(CSpaceVertexNumbers, ThreadsReadingAFreshSpaceAtOnceSeeTheWrittenNumbers) {
  std::mt19937_64 random(8);
  for (int instance = 0; instance < 6; ++instance) {
    const std::optional<CSpace> built = test_loops::random_star_slider_space(random);
    if (!built) continue;
    const CSpace& space = *built;
    std::vector<const CSpaceVertex*> seen(4, nullptr);
    std::vector<std::string> first_x(4);
    std::vector<std::thread> threads;
    for (std::size_t t = 0; t < 4; ++t)
      threads.emplace_back([&, t] {
        const CSpaceVertex& v = t % 2 ? space.vertex(VertexId{0}) : space.vertices().front();
        seen[t] = &v;
        first_x[t] = v.x.lower.get_str() + " " + v.y_lower.get_str() + " " + std::to_string(v.y_curve.size());
      });
    for (auto& thread : threads) thread.join();
    for (std::size_t t = 0; t < 4; ++t) {
      EXPECT_EQ(seen[t], &space.vertices().front());
      EXPECT_EQ(first_x[t], first_x[0]);
    }
    expect_vertex_numbers(space, space.vertices(), true);
  }
}

// The cells of `space` read first through cell(id) (`cell_first`) or cells(): every cell's sample
// is its first face's (in chart, then face order) and that face is sampled; exact point location
// at the sample finds the cell (free / blocked / touching inside it, or a spurious piece inside
// it); nothing was written before the first read; copies share the cells.
void check_cell_samples(const CSpace& space, bool cell_first) {
  const CSpace::Impl& impl = implementation(space);
  EXPECT_FALSE(impl.samples.all.load()) << "the build wrote the cells' samples";
  CSpace copy = space;
  const std::size_t n = space.statistics().cells;
  if (cell_first && n > 0) {
    const CSpaceCell& last = space.cell(CellId{n - 1});
    EXPECT_TRUE(impl.samples.all.load());
    EXPECT_EQ(&last, &space.cells().back());
  }
  const std::vector<CSpaceCell>& cells = space.cells();
  EXPECT_EQ(&cells, &copy.cells());
  ASSERT_EQ(cells.size(), n);
  std::vector<char> seen(n, 0);
  std::size_t located = 0;
  for (std::size_t c = 0; c < impl.charts.size(); ++c) {
    const cspace::ChartData& chart = impl.charts[c];
    for (std::size_t f = 0; f < chart.faces.size(); ++f) {
      const cspace::FaceData& face = chart.faces[f];
      if (face.kind == cspace::FaceKind::outside || face.cell >= n || seen[face.cell]) continue;
      seen[face.cell] = 1;
      const CSpaceCell& cell = cells[face.cell];
      SCOPED_TRACE("cell " + std::to_string(face.cell));
      EXPECT_TRUE(face.sampled);
      EXPECT_EQ(cell.sample_chart, c);
      EXPECT_EQ(cell.sample_x, face.sample_x);
      EXPECT_EQ(cell.sample_y, face.sample_y);
      const Location at = space.locate(ChartPoint{c, cell.sample_x, space.dimension() == 2 ? cell.sample_y : Rational(0)});
      EXPECT_EQ(at.cell, face.cell) << "the sample " << cell.sample_x.get_str() << ", " << cell.sample_y.get_str()
                                    << " is not inside its cell";
      if (at.kind == Location::Kind::free || at.kind == Location::Kind::blocked)
        EXPECT_EQ(at.kind == Location::Kind::free, cell.kind == CellKind::free);
      ++located;
    }
  }
  EXPECT_EQ(located, n);   // every cell has a first face
}

TEST(CSpaceVertexNumbers, CellSamplesWrittenOnFirstReadAreTheirFirstFacesAndLieInTheirCells) {
  std::mt19937_64 random(5656);
  int checked = 0;
  for (int instance = 0; instance < 16; ++instance) {
    SCOPED_TRACE("instance " + std::to_string(instance));
    const long q = instance % 3 == 0 ? 1 : instance % 3 == 1 ? 16 : 97;
    Points a = random_star(random, 3 + static_cast<int>(random() % 8), 0, 0, 3 + static_cast<double>(random() % 4), q, 1);
    Points b = instance % 5 == 4 ? a
                                 : random_star(random, 3 + static_cast<int>(random() % 8), static_cast<double>(random() % 7) - 3,
                                               static_cast<double>(random() % 7) - 3, 2 + static_cast<double>(random() % 5), q, 1);
    if (std::optional<CSpace> space = test_loops::star_slider_space(a, b)) {
      check_cell_samples(*space, instance % 2 == 0);
      ++checked;
    }
  }
  EXPECT_GE(checked, 12);
  // a non-convex slot with a square exactly its width (touching cells), at 2^-100
  const Points slot{{0, 0}, {6, 0}, {6, 1}, {4, 1}, {4, 3}, {2, 3}, {2, 1}, {0, 1}};
  const Points square{{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  const Rational tiny = Rational(1) / (mpz_class(1) << 100);
  check_cell_samples(CSpace::build(test_loops::slider_pair_model(scaled(square, tiny, 2 * tiny, tiny), scaled(slot, tiny)), "a", "b"), true);
  // the corpus: rotating and mixed pairs of several charts, 1-D spaces
  std::size_t spaces = 0, one_dimensional = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(HIPAIR_TEST_DATA) / "degenerate")) {
    SCOPED_TRACE(entry.path().filename().string());
    for (const CSpace& space : CSpace::build_all(read_model_file(entry.path()))) {
      check_cell_samples(space, spaces % 2 == 0);
      ++spaces;
      one_dimensional += space.dimension() == 1;
    }
  }
  EXPECT_GE(spaces, 5u);
  EXPECT_GE(one_dimensional, 1u);
}

TEST(CSpaceVertexNumbers, ThreadsReadingAFreshSpaceAtOnceSeeTheWrittenCellSamples) {
  std::mt19937_64 random(56);
  for (int instance = 0; instance < 6; ++instance) {
    const std::optional<CSpace> built = test_loops::random_star_slider_space(random);
    if (!built) continue;
    const CSpace& space = *built;
    std::vector<std::string> samples(4);
    std::vector<std::thread> threads;
    for (std::size_t t = 0; t < 4; ++t)
      threads.emplace_back([&, t] {
        const CSpaceCell& cell = t % 2 ? space.cell(CellId{0}) : space.cells().front();
        samples[t] = cell.sample_x.get_str() + " " + cell.sample_y.get_str();
      });
    for (auto& thread : threads) thread.join();
    for (std::size_t t = 1; t < 4; ++t) EXPECT_EQ(samples[t], samples[0]);
    EXPECT_EQ(samples[0], space.cells().front().sample_x.get_str() + " " + space.cells().front().sample_y.get_str());
  }
}

}  // namespace
}  // namespace hipair
