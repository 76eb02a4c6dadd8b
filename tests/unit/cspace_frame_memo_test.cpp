// CSpace::contact_frame's memo of the feature pairs' enclosed body geometries
// (src/cspace/cspace_queries.cpp, enclosed_geometries; switch cspace::frame_memo() in
// src/cspace/frame_memo.hpp): generated configurations on the example spaces, every feature pair,
// the spaces' queries interleaved (several spaces in the memo at once) and the spaces freed and
// rebuilt in turn: each frame (defined or not, the point's and the unit normal's enclosures, bound
// for bound) equals the frame made without the memo (the geometries enclosed at every call).
#include "cspace/frame_memo.hpp"
#include "cspace_test_support.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

using Switch = test::FlagSwitch<&cspace::frame_memo>;

// A part coordinate of an axis of kind `kind` from a chart value of a chart without a seam.
PartCoordinate coordinate_of(AxisKind kind, const Rational& value) {
  PartCoordinate c;
  c.kind = kind == AxisKind::rotation ? PartCoordinate::Kind::half_angle_tangent : PartCoordinate::Kind::offset;
  c.value = value;
  return c;
}

// The frame of `feature` at (x, y), printed exactly; "throws" / "none" where there is none.
std::string frame_text(const CSpace& space, FeatureId feature, const PartCoordinate& x, const PartCoordinate& y,
                       bool& defined) {
  std::optional<Contact> frame;
  try {
    frame = space.contact_frame(feature, x, y);
  } catch (const GeometryError&) {
    return "throws";
  }
  defined = frame.has_value();
  if (!frame) return "none";
  std::ostringstream out;
  out.precision(17);
  for (const auto* ranges : {&frame->point_range, &frame->normal})
    for (const CertifiedRange& r : *ranges) out << " [" << r.lower << ", " << r.upper << "]";
  return out.str();
}

TEST(CSpaceFrameMemo, FramesEqualTheFramesWithoutTheMemo) {
  std::mt19937_64 random(20261129);
  std::size_t compared = 0, defined_frames = 0;
  const std::size_t hits_before = cspace::frame_memo_hits();
  for (int round = 0; round < 3; ++round) {
    // each round builds the spaces anew (the memo must not match a freed space's successor)
    std::vector<std::unique_ptr<CSpace>> spaces = test::example_spaces();
    for (int query = 0; query < 400; ++query) {
      const CSpace& space = *spaces[random() % spaces.size()];
      // a configuration in a chart without a seam (its chart values are the part coordinates)
      std::optional<ChartPoint> p;
      for (int attempt = 0; attempt < 20 && !p; ++attempt) {
        ChartPoint q = test::random_tile_point(space, random);
        const CSpaceChart& chart = space.charts()[q.chart];
        if (!chart.x_half_turn && (space.dimension() == 1 || !chart.y_half_turn)) p = q;
      }
      if (!p) continue;
      const CSpaceChart& chart = space.charts()[p->chart];
      PartCoordinate x = coordinate_of(chart.x_kind, p->x);
      PartCoordinate y = space.dimension() == 2 ? coordinate_of(chart.y_kind, p->y) : PartCoordinate{};
      // twelve random feature pairs at this configuration, memo on and off, in a random order
      std::size_t pairs = space.feature_pairs().size();
      for (int k = 0; k < 12; ++k) {
        FeatureId feature(random() % pairs);
        bool first_on = random() % 2 == 0, d_on = false, d_off = false;
        std::string on, off;
        if (first_on) {
          { Switch s(true); on = frame_text(space, feature, x, y, d_on); }
          { Switch s(false); off = frame_text(space, feature, x, y, d_off); }
        } else {
          { Switch s(false); off = frame_text(space, feature, x, y, d_off); }
          { Switch s(true); on = frame_text(space, feature, x, y, d_on); }
        }
        ASSERT_EQ(on, off) << "round " << round << " query " << query << " feature pair "
                           << space.feature_pair(feature).label << " at chart " << p->chart << " (" << p->x << ", "
                           << p->y << ")";
        ++compared;
        if (d_on) ++defined_frames;
      }
    }
  }
  const std::size_t hits = cspace::frame_memo_hits() - hits_before;
  std::printf("frame memo: %zu frames compared, %zu defined, %zu from the memo\n", compared, defined_frames, hits);
  EXPECT_GT(defined_frames, compared / 4);
  EXPECT_GT(hits, compared / 4);
}

}  // namespace
}  // namespace hipair
