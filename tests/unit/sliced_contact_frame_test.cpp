// sliced_contact_frame (include/hipair/sliced.hpp): the kernels' contact point and normal of a
// 3-DOF feature pair, against the posed geometry computed here independently, exactly, on
// generated rational configurations (both charts' angles, the half turn included).
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/sliced.hpp>

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace hipair {
namespace {

const char* kModel = R"({ "hipair": 1, "name": "frames", "units": { "length": "mm", "angle": "rad" },
  "parts": [
    { "name": "base", "motion": "fixed", "loops": [ { "start": [-7, -3], "edges": [
        { "line_to": [11, -1] }, { "line_to": [9, 6] }, { "line_to": [-7, -3] } ] } ] },
    { "name": "peg", "motion": { "planar": { "pivot": [1, 2] } }, "initial": { "x": 40, "y": 0, "angle": 0 },
      "loops": [ { "start": [0, 0], "edges": [ { "line_to": [4, 1] }, { "line_to": [2, 5] }, { "line_to": [0, 0] } ] } ] } ] })";

Rational ratio(std::uint64_t& s, int range) {
  s = s * 6364136223846793005ULL + 1442695040888963407ULL;
  Rational r(static_cast<long>((s >> 33) % (2 * range * 64)) - range * 64, 64);
  r.canonicalize();
  return r;
}

TEST(SlicedContactFrame, VertexSegmentFramesArePosedExactly) {
  Model model = read_model(kModel, "<frames>");
  const Part& base = model.parts[0];
  const Part& peg = model.parts[1];
  const Point pivot = peg.motion.pivot;
  std::uint64_t seed = 9;
  for (int c = 0; c < 40; ++c) {
    SlicedConfiguration q;
    q.x = ratio(seed, 20);
    q.y = ratio(seed, 20);
    q.angle.half_turn = c % 10 == 9;
    q.angle.t = ratio(seed, 3);
    // the rotation, exact: (1 - t^2, 2t) / (1 + t^2), or the half turn
    Rational t = q.angle.t, w = 1 + t * t;
    Rational cs = q.angle.half_turn ? Rational(-1) : Rational((1 - t * t) / w);
    Rational sn = q.angle.half_turn ? Rational(0) : Rational(2 * t / w);
    auto posed = [&](const Point& p) {
      Rational dx = p.x - pivot.x, dy = p.y - pivot.y;
      return Point{Rational(pivot.x + cs * dx - sn * dy + q.x), Rational(pivot.y + sn * dx + cs * dy + q.y)};
    };
    for (std::size_t e = 0; e < 3; ++e)
      for (std::size_t v = 0; v < 3; ++v) {
        // a fixed segment against a vertex of the peg: the posed vertex, the segment's outward
        // (right) normal, from the fixed part into the peg
        SlicedFeaturePair a{{0, 0, e, FeatureKind::segment}, {1, 0, v, FeatureKind::vertex}, ""};
        SlicedContactFrame fa = sliced_contact_frame(model, a, q);
        ASSERT_TRUE(fa.defined);
        const Edge& se = base.loops[0].edges[e];
        EXPECT_EQ(fa.point, posed(peg.loops[0].edges[v].source));
        Point d{Rational(se.target.x - se.source.x), Rational(se.target.y - se.source.y)};
        EXPECT_EQ(fa.normal.x * d.x + fa.normal.y * d.y, 0);
        EXPECT_EQ(fa.normal.x * -d.y + fa.normal.y * d.x < 0, true);   // opposite to the left normal
        // a fixed vertex against a segment of the peg: the vertex, the posed segment's inward
        // (left) normal
        SlicedFeaturePair b{{0, 0, v, FeatureKind::vertex}, {1, 0, e, FeatureKind::segment}, ""};
        SlicedContactFrame fb = sliced_contact_frame(model, b, q);
        ASSERT_TRUE(fb.defined);
        EXPECT_EQ(fb.point, base.loops[0].edges[v].source);
        const Edge& pe = peg.loops[0].edges[e];
        Point p0 = posed(pe.source), p1 = posed(pe.target);
        Point pd{Rational(p1.x - p0.x), Rational(p1.y - p0.y)};
        EXPECT_EQ(fb.normal.x * pd.x + fb.normal.y * pd.y, 0);
        EXPECT_EQ(fb.normal.x * -pd.y + fb.normal.y * pd.x > 0, true);   // along the left normal
        // vertex against vertex: no contact of its own
        SlicedFeaturePair vv{{0, 0, v, FeatureKind::vertex}, {1, 0, e, FeatureKind::vertex}, ""};
        EXPECT_FALSE(sliced_contact_frame(model, vv, q).defined);
      }
  }
  SlicedFeaturePair swapped{{1, 0, 0, FeatureKind::vertex}, {0, 0, 0, FeatureKind::segment}, ""};
  EXPECT_THROW(sliced_contact_frame(model, swapped, SlicedConfiguration{}), GeometryError);
}

// A disk in a hole of exactly its radius (session 73): at the fit the two circles are concentric,
// touching along the whole circle, so the arc pair has no contact point or normal (undefined; the
// kernels' frame divided by the centres' squared distance, 0 there, and GMP's division by zero
// trapped: SIGFPE); moved off the fit by any rational step the frame is defined again, on the line
// of the centres. Generated: radii, centres, pivots, angles (the half turn too), scales 1, 10^-300
// and 10^300.
TEST(SlicedContactFrame, ConcentricArcsOfOneRadiusHaveNoFrameAndAnyOtherPlacementHasOne) {
  const Rational big(mpz_class("1" + std::string(300, '0')));
  const std::vector<Rational> scales = {Rational(1), Rational(1) / big, big};
  std::uint64_t seed = 73;
  for (int c = 0; c < 30; ++c) {
    const Rational scale = scales[static_cast<std::size_t>(c) % 3];
    Rational r = ratio(seed, 4);
    r = r < 0 ? Rational(-r + Rational(1, 8)) : Rational(r + Rational(1, 8));
    const Rational hx = ratio(seed, 20), hy = ratio(seed, 20), cx = ratio(seed, 20), cy = ratio(seed, 20);
    const Point pivot{ratio(seed, 20), ratio(seed, 20)};
    auto text = [&](const Rational& v) {
      Rational w = v * scale;
      w.canonicalize();
      return "\"" + w.get_str() + "\"";
    };
    auto point = [&](const Rational& x, const Rational& y) { return "[" + text(x) + ", " + text(y) + "]"; };
    const Rational side = 3 * r;
    const std::string json = R"({ "hipair": 1, "name": "disk-in-hole", "units": { "length": "mm", "angle": "rad" },
      "parts": [
        { "name": "plate", "motion": "fixed", "loops": [
          { "start": )" + point(hx - side, hy - side) + R"(, "edges": [ { "line_to": )" + point(hx + side, hy - side) +
                             R"( }, { "line_to": )" + point(hx + side, hy + side) + R"( }, { "line_to": )" +
                             point(hx - side, hy + side) + R"( }, { "line_to": )" + point(hx - side, hy - side) + R"( } ] },
          { "start": )" + point(hx + r, hy) + R"(, "edges": [ { "arc_to": )" + point(hx + r, hy) + R"(, "center": )" +
                             point(hx, hy) + R"(, "dir": "cw" } ] } ] },
        { "name": "disk", "motion": { "planar": { "pivot": )" + point(pivot.x, pivot.y) + R"( } },
          "loops": [ { "circle": { "center": )" + point(cx, cy) + R"(, "radius": )" + text(r) + R"( } } ] } ] })";
    SCOPED_TRACE("case " + std::to_string(c) + ": " + json);
    const Model model = read_model(json, "<disk-in-hole>");
    ASSERT_EQ(model.parts[0].loops.size(), 2u);
    ASSERT_TRUE(model.parts[0].loops[1].is_hole);
    const Point P = model.parts[1].motion.pivot, C = model.parts[1].loops[0].edges[0].center;
    const Point H = model.parts[0].loops[1].edges[0].center;
    SlicedConfiguration q;
    q.angle.half_turn = c % 10 == 9;
    q.angle.t = ratio(seed, 3);
    const Rational t = q.angle.t, w = 1 + t * t;
    const Rational cs = q.angle.half_turn ? Rational(-1) : Rational((1 - t * t) / w);
    const Rational sn = q.angle.half_turn ? Rational(0) : Rational(2 * t / w);
    // the shift that puts the disk's centre on the hole's: H = P + R (C - P) + (x, y)
    const Rational dx = C.x - P.x, dy = C.y - P.y;
    q.x = H.x - P.x - (cs * dx - sn * dy);
    q.y = H.y - P.y - (sn * dx + cs * dy);
    const SlicedFeaturePair hole_disk{{0, 1, 0, FeatureKind::arc}, {1, 0, 0, FeatureKind::arc}, ""};
    EXPECT_FALSE(sliced_contact_frame(model, hole_disk, q).defined);
    for (int step = 0; step < 2; ++step) {
      // off the fit by a nonzero rational step (along x, then along y): defined, its normal along
      // the line of the centres
      SlicedConfiguration off = q;
      const Rational along = ratio(seed, 2) * scale / 64, nonzero = scale / 128;
      off.x += step == 0 ? Rational(along + nonzero) : along;
      off.y += step == 0 ? along : Rational(along - nonzero);
      const SlicedContactFrame f = sliced_contact_frame(model, hole_disk, off);
      ASSERT_TRUE(f.defined);
      const Rational ddx = off.x - q.x, ddy = off.y - q.y;   // the disk's centre minus the hole's
      EXPECT_EQ(f.normal.x * ddy - f.normal.y * ddx, 0);
      EXPECT_TRUE(f.normal.x != 0 || f.normal.y != 0);
    }
  }
}

}  // namespace
}  // namespace hipair
