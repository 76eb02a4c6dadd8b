// The cell structure of two C-spaces of the same pair compared field by field, indices included:
// the tests that build one space two ways (the polygon front end against the general one, a
// streamed build against a whole one) or move or scale the mechanism (the same space, other
// numbers) share it, and each compares the numbers (vertex coordinates, samples, supports) in
// its own way afterwards.
#pragma once

#include <hipair/cspace.hpp>

#include <gtest/gtest.h>

#include <string>

namespace hipair::test {

// Feature pairs (features, kind, blocked side), cells (kind, boundary, neighbours, faces,
// wrapping), vertices (chart, edges, curves, touching, contact change, chart boundary; not whether y is
// rational: a number) and edges
// (chart, ends, vertical, curves, role, cells, real) equal. ASSERTs on the counts: call it as
// ASSERT_NO_FATAL_FAILURE(expect_same_topology(...)) where later code indexes the spaces.
inline void expect_same_topology(const CSpace& a, const CSpace& b, const std::string& what) {
  ASSERT_EQ(a.feature_pairs().size(), b.feature_pairs().size()) << what;
  for (std::size_t i = 0; i < a.feature_pairs().size(); ++i) {
    const FeaturePair &p = a.feature_pairs()[i], &q = b.feature_pairs()[i];
    SCOPED_TRACE(what + ", feature pair " + std::to_string(i));
    EXPECT_EQ(p.first_part, q.first_part);
    EXPECT_EQ(p.first_feature, q.first_feature);
    EXPECT_EQ(p.second_part, q.second_part);
    EXPECT_EQ(p.second_feature, q.second_feature);
    EXPECT_EQ(p.kind, q.kind);
    EXPECT_EQ(p.blocked_sign, q.blocked_sign);
  }
  ASSERT_EQ(a.cells().size(), b.cells().size()) << what;
  for (std::size_t i = 0; i < a.cells().size(); ++i) {
    const CSpaceCell &p = a.cells()[i], &q = b.cells()[i];
    SCOPED_TRACE(what + ", cell " + std::to_string(i));
    EXPECT_EQ(p.kind, q.kind);
    EXPECT_EQ(p.boundary, q.boundary);
    EXPECT_EQ(p.neighbours, q.neighbours);
    EXPECT_EQ(p.faces, q.faces);
    EXPECT_EQ(p.wraps_x, q.wraps_x);
    EXPECT_EQ(p.wraps_y, q.wraps_y);
  }
  ASSERT_EQ(a.vertices().size(), b.vertices().size()) << what;
  for (std::size_t i = 0; i < a.vertices().size(); ++i) {
    const CSpaceVertex &p = a.vertices()[i], &q = b.vertices()[i];
    SCOPED_TRACE(what + ", vertex " + std::to_string(i));
    EXPECT_EQ(p.chart, q.chart);
    EXPECT_EQ(p.edges, q.edges);
    EXPECT_EQ(p.curves, q.curves);
    EXPECT_EQ(p.touching, q.touching);
    EXPECT_EQ(p.contact_change, q.contact_change);
    EXPECT_EQ(p.on_chart_boundary, q.on_chart_boundary);
  }
  ASSERT_EQ(a.edges().size(), b.edges().size()) << what;
  for (std::size_t i = 0; i < a.edges().size(); ++i) {
    const CSpaceEdge &p = a.edges()[i], &q = b.edges()[i];
    SCOPED_TRACE(what + ", edge " + std::to_string(i));
    EXPECT_EQ(p.chart, q.chart);
    EXPECT_EQ(p.source, q.source);
    EXPECT_EQ(p.target, q.target);
    EXPECT_EQ(p.vertical, q.vertical);
    EXPECT_EQ(p.curves, q.curves);
    EXPECT_EQ(p.role, q.role);
    EXPECT_EQ(p.left_cell, q.left_cell);
    EXPECT_EQ(p.right_cell, q.right_cell);
    EXPECT_EQ(p.real, q.real);
  }
}

}  // namespace hipair::test
