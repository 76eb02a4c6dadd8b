// The adaptor's queries for simulation and tolerancing against the exact overlap oracle and
// closed forms: contact points and normals (exact, on both posed features), the eccentric
// cam's contact normal and lift derivative, the Geneva wheel's velocity ratio, first crossings
// along motions across the theta = +-pi/2 seams, random motions against dense exact sampling
// (no missed crossing), blocked sides, slices, and build_pairs keeping every good pair.
#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include "cam_and_block_model.hpp"
#include "curves/contact_curves.hpp"
#include "curves/pose.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>
#include <set>
#include <algorithm>
#include <array>
#include <string>

namespace hipair {
namespace {

std::filesystem::path example(const std::string& name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; }

PartCoordinate tangent(const Rational& t) { return {PartCoordinate::Kind::half_angle_tangent, t}; }
PartCoordinate offset(const Rational& s) { return {PartCoordinate::Kind::offset, s}; }

bool within(const CertifiedRange& r, double v, double slack = 1e-9) {
  double scale = std::max(1.0, std::fabs(v));
  return r.lower - slack * scale <= v && v <= r.upper + slack * scale;
}

double middle(const CertifiedRange& r) { return 0.5 * (r.lower + r.upper); }

// The x extent of a non-vertical edge from its end vertices (CSpaceEdge::x_chart is a
// certified superset, not the extent).
CertifiedRange x_extent(const CSpace& space, const CSpaceEdge& edge) {
  return {space.vertices()[edge.source].x.approximate(), space.vertices()[edge.target].x.approximate()};
}

using test::cam_and_block;

using test::square_and_plate;

// Exact world position of a body point of `part` at a chart point of `space`.
Point posed(const Model& model, const CSpace& space, const std::string& part_name, const Point& p, const ChartPoint& q) {
  const CSpaceChart& chart = space.charts()[q.chart];
  std::size_t index = 0;
  while (model.parts[index].name != part_name) ++index;
  const Part& part = model.parts[index];
  bool is_x = part_name == space.x_part(), is_y = !is_x && part_name == space.y_part();
  if (!is_x && !is_y) return p;
  cspace::ChartAxis axis;
  bool rotation = is_x ? chart.x_kind == AxisKind::rotation : chart.y_kind == AxisKind::rotation;
  axis.kind = rotation ? cspace::ChartAxis::Kind::rotation : cspace::ChartAxis::Kind::translation;
  axis.half_turn = is_x ? chart.x_half_turn : chart.y_half_turn;
  return cspace::world_map(part, true, axis, is_x ? q.x : q.y).apply(p);
}

// The contact lies exactly on both posed features, and its normal is exactly perpendicular
// to a segment feature / radial to an arc feature.
void expect_on_both_features(const Model& model, const CSpace& space, const ChartPoint& q, const Contact& contact) {
  ASSERT_TRUE(contact.exact);
  const FeaturePair& pair = space.feature_pair(contact.feature);
  Point point{contact.point[0], contact.point[1]};
  Point normal{contact.normal_direction[0], contact.normal_direction[1]};
  EXPECT_TRUE(sgn(normal.x) != 0 || sgn(normal.y) != 0);
  for (const FeatureIdentity* f : {&pair.first, &pair.second}) {
    const Part& part = model.parts.at(f->part);
    const Edge& edge = part.loops.at(f->loop).edges.at(f->edge);
    switch (f->kind) {
      case FeatureKind::vertex:
        EXPECT_EQ(posed(model, space, part.name, edge.source, q), point) << pair.label;
        break;
      case FeatureKind::segment: {
        Point a = posed(model, space, part.name, edge.source, q), b = posed(model, space, part.name, edge.target, q);
        Point d = cspace::difference(b, a), v = cspace::difference(point, a);
        EXPECT_EQ(sgn(cspace::cross(d, v)), 0) << pair.label;
        Rational along = cspace::dot(d, v);
        EXPECT_GE(sgn(along), 0) << pair.label;
        EXPECT_LE(along, cspace::dot(d, d)) << pair.label;
        EXPECT_EQ(sgn(cspace::dot(d, normal)), 0) << pair.label;
        break;
      }
      case FeatureKind::arc: {
        Point k = posed(model, space, part.name, edge.center, q);
        Point v = cspace::difference(point, k);
        EXPECT_EQ(cspace::dot(v, v), edge.radius_squared) << pair.label;
        EXPECT_EQ(sgn(cspace::cross(v, normal)), 0) << pair.label;
        break;
      }
    }
  }
  // the certified unit normal encloses the exact direction's
  double nx = normal.x.get_d(), ny = normal.y.get_d(), length = std::hypot(nx, ny);
  EXPECT_TRUE(within(contact.normal[0], nx / length, 1e-12));
  EXPECT_TRUE(within(contact.normal[1], ny / length, 1e-12));
}

// ------------------------------------------------------------------ contact_at, derivatives

TEST(CSpaceAdaptorQueries, EccentricCamContactNormalAndLiftDerivativesAreTheClosedForms) {
  Model model = read_model_file(example("cam-follower.json"));
  CSpace space = CSpace::build(model, "cam", "follower");
  ASSERT_EQ(space.x_part(), "cam");
  std::mt19937_64 random(10);
  std::uniform_int_distribution<int> numerator(-900, 900);
  int checked = 0, derivatives = 0;
  for (int i = 0; i < 40; ++i) {
    Rational t(numerator(random), 1000);
    t.canonicalize();
    Rational w = 1 + t * t;
    Rational s = 16 * t / w;   // the flat face on the cam's top: s = e sin(theta)
    s.canonicalize();
    auto q = space.to_chart(tangent(t), offset(s));
    ASSERT_TRUE(q);
    std::vector<Contact> contacts = space.contact_at(*q);
    const Contact* face = nullptr;
    for (const Contact& c : contacts) {
      const FeaturePair& pair = space.feature_pair(c.feature);
      if (pair.first.kind == FeatureKind::arc && pair.second.kind == FeatureKind::segment && pair.second.edge == 0)
        face = &c;
      expect_on_both_features(model, space, *q, c);
    }
    ASSERT_NE(face, nullptr) << "t = " << t;
    // closed form: the point (e cos(theta), R + s); the normal from the cam into the follower +y
    Rational px = 8 * (1 - t * t) / w, py = 25 + s;
    px.canonicalize();
    py.canonicalize();
    EXPECT_EQ(face->point[0], px);
    EXPECT_EQ(face->point[1], py);
    EXPECT_EQ(sgn(face->normal_direction[0]), 0);
    EXPECT_GT(sgn(face->normal_direction[1]), 0);
    EXPECT_TRUE(within(face->normal[1], 1.0, 0));
    ++checked;
    // ds/dtheta = e cos(theta), d2s/dtheta2 = -e sin(theta), on the face's contact edge
    Location where = space.locate(*q);
    if (where.kind != Location::Kind::edge) continue;
    EdgeDerivatives d = space.derivatives(EdgeId(where.edge), q->x);
    double theta = 2 * std::atan(t.get_d());
    EXPECT_TRUE(within(d.coordinate_dy, 8 * std::cos(theta))) << middle(d.coordinate_dy) << " t = " << t;
    EXPECT_TRUE(within(d.coordinate_d2y, -8 * std::sin(theta))) << middle(d.coordinate_d2y);
    EXPECT_LT(d.coordinate_dy.upper - d.coordinate_dy.lower, 1e-9);
    // chart slope of s = 16 t / (1 + t^2): 16 (1 - t^2) / (1 + t^2)^2
    double tt = t.get_d();
    EXPECT_TRUE(within(d.dy, 16 * (1 - tt * tt) / ((1 + tt * tt) * (1 + tt * tt))));
    ++derivatives;
  }
  EXPECT_EQ(checked, 40);
  EXPECT_GT(derivatives, 30);
}

TEST(CSpaceAdaptorQueries, ContactAtRationalContactConfigurationsIsExactlyOnBothFeatures) {
  struct Case {
    Model model;
    std::string first, second;
  };
  std::vector<Case> cases;
  cases.push_back({read_model_file(example("cam-follower.json")), "cam", "follower"});
  cases.push_back({read_model_file(example("scotch-yoke.json")), "crank", "yoke"});
  cases.push_back({read_model(square_and_plate), "square", "plate"});
  int contacts = 0;
  std::set<ContactKind> kinds;
  for (const Case& c : cases) {
    CSpace space = CSpace::build(c.model, c.first, c.second);
    for (std::size_t e = 0; e < space.edges().size(); ++e) {
      const CSpaceEdge& edge = space.edges()[e];
      if (!edge.real || edge.vertical) continue;
      CertifiedRange extent = x_extent(space, edge);
      if (extent.upper - extent.lower < 1e-6) continue;
      for (int i = 1; i < 8; ++i) {
        Rational x(extent.lower + (extent.upper - extent.lower) * i / 8.0);
        AlgebraicNumber y = space.evaluate_exact(e, x);
        if (!y.exact) continue;
        ChartPoint q{edge.chart, x, y.lower};
        std::vector<Contact> found = space.contact_at(q);
        EXPECT_FALSE(found.empty()) << c.model.name << " edge " << e;
        bool on_edge_curve = false;
        for (const Contact& contact : found) {
          expect_on_both_features(c.model, space, q, contact);
          on_edge_curve = on_edge_curve || std::find(edge.curves.begin(), edge.curves.end(),
                                                     contact.feature.index()) != edge.curves.end();
          kinds.insert(space.feature_pair(contact.feature).kind);
          ++contacts;
        }
        EXPECT_TRUE(on_edge_curve) << c.model.name << " edge " << e;
        // contact_at is exact: off the curve by a rational epsilon, the edge's pair is gone
        ChartPoint off{edge.chart, x, Rational(y.lower + Rational(1, 1000000))};
        for (const Contact& contact : space.contact_at(off))
          EXPECT_TRUE(std::find(edge.curves.begin(), edge.curves.end(), contact.feature.index()) == edge.curves.end());
      }
    }
  }
  EXPECT_GT(contacts, 100);
  EXPECT_GE(kinds.size(), 3u);   // arc-segment, vertex-segment, segment-vertex
}

TEST(CSpaceAdaptorQueries, GenevaVelocityRatioFromDerivativesIsTheClosedForm) {
  Model model = read_model_file(example("geneva.json"));
  CSpace space = CSpace::build(model, "driver", "wheel");
  ASSERT_EQ(space.x_part(), "driver");
  const Part& driver = model.parts[0];
  const Part& wheel = model.parts[1];
  int checked = 0;
  for (std::size_t e = 0; e < space.edges().size(); ++e) {
    const CSpaceEdge& edge = space.edges()[e];
    if (!edge.real || edge.vertical || edge.curves.size() != 1) continue;
    const FeaturePair& pair = space.feature_pairs()[edge.curves[0]];
    if (pair.kind != ContactKind::arc_segment) continue;
    CertifiedRange extent = x_extent(space, edge);
    if (extent.upper - extent.lower < 1e-4) continue;
    // the pin (an arc of the driver) tangent to a slot wall (a segment of the wheel):
    // G(theta, phi) = cross(u(theta), P(phi) - Ow) = const, so
    // dtheta/dphi = cross(u, J (P - Od)) / dot(u, P - Ow)
    const Edge& pin = driver.loops.at(pair.first.loop).edges.at(pair.first.edge);
    const Edge& wall = wheel.loops.at(pair.second.loop).edges.at(pair.second.edge);
    ASSERT_TRUE(pin.is_arc());
    ASSERT_FALSE(wall.is_arc());
    const CSpaceChart& chart = space.charts()[edge.chart];
    for (double f : {0.3, 0.5, 0.7}) {
      Rational x(extent.lower + (extent.upper - extent.lower) * f);
      EdgeDerivatives d = space.derivatives(EdgeId(e), x);
      double phi = chart.x_to_coordinate(x.get_d()), theta = chart.y_to_coordinate(d.y.approximate());
      double odx = driver.motion.pivot.x.get_d(), ody = driver.motion.pivot.y.get_d();
      double owx = wheel.motion.pivot.x.get_d(), owy = wheel.motion.pivot.y.get_d();
      double cx = pin.center.x.get_d() - odx, cy = pin.center.y.get_d() - ody;
      double px = odx + std::cos(phi) * cx - std::sin(phi) * cy, py = ody + std::sin(phi) * cx + std::cos(phi) * cy;
      double wx = Rational(wall.target.x - wall.source.x).get_d(), wy = Rational(wall.target.y - wall.source.y).get_d();
      double ux = std::cos(theta) * wx - std::sin(theta) * wy, uy = std::sin(theta) * wx + std::cos(theta) * wy;
      double jx = -(py - ody), jy = px - odx;
      double closed = (ux * jy - uy * jx) / (ux * (px - owx) + uy * (py - owy));
      EXPECT_TRUE(within(d.coordinate_dy, closed, 1e-8))
          << "edge " << e << ": " << middle(d.coordinate_dy) << " vs " << closed;
      EXPECT_LT(d.coordinate_dy.upper - d.coordinate_dy.lower, 1e-9);
      ++checked;
    }
  }
  EXPECT_GE(checked, 12);
}

TEST(CSpaceAdaptorQueries, FeatureIdentityAndBlockedSideAgreeWithTheModelAndTheOracle) {
  Model model = read_model_file(example("geneva.json"));
  CSpace space = CSpace::build(model, "driver", "wheel");
  for (const FeaturePair& pair : space.feature_pairs()) {
    EXPECT_EQ(model.parts.at(pair.first.part).name, pair.first_part);
    EXPECT_EQ(model.parts.at(pair.second.part).name, pair.second_part);
    EXPECT_EQ(pair.blocked_sign, -1);
    for (const FeatureIdentity* f : {&pair.first, &pair.second}) {
      const Edge& edge = model.parts[f->part].loops.at(f->loop).edges.at(f->edge);
      if (f->kind == FeatureKind::arc) EXPECT_TRUE(edge.is_arc());
      if (f->kind == FeatureKind::segment) EXPECT_FALSE(edge.is_arc());
    }
    std::string kind(to_string(pair.kind));
    auto name = [](FeatureKind k) { return k == FeatureKind::vertex ? "vertex" : k == FeatureKind::arc ? "arc" : "segment"; };
    EXPECT_EQ(kind, std::string(name(pair.first.kind)) + "-" + name(pair.second.kind));
  }
  cspace::PairAxes axes = cspace::pair_axes(model, 0, 1);
  int sides = 0;
  for (std::size_t e = 0; e < space.edges().size(); ++e) {
    const CSpaceEdge& edge = space.edges()[e];
    BlockedSide side = space.blocked_side(EdgeId(e));
    if (!edge.real || edge.role != EdgeRole::contact) continue;
    ASSERT_NE(side, BlockedSide::none) << "edge " << e;
    if (edge.vertical) continue;
    CertifiedRange extent = x_extent(space, edge);
    if (extent.upper - extent.lower < 1e-4) continue;
    double xd = 0.5 * (extent.lower + extent.upper);
    CertifiedValue y = space.evaluate(e, xd);
    const CSpaceChart& chart = space.charts()[edge.chart];
    cspace::ChartAxis ax{cspace::ChartAxis::Kind::rotation, chart.x_half_turn, chart.x_lo, chart.x_hi};
    cspace::ChartAxis ay{cspace::ChartAxis::Kind::rotation, chart.y_half_turn, chart.y_lo, chart.y_hi};
    // just above and just below the edge (left = above for a non-vertical edge)
    Rational above(y.value + y.error + 1e-9), below(y.value - y.error - 1e-9), x(xd);
    cspace::Overlap over = cspace::classify_overlap(model, axes, ax, ay, cspace::ChartPoint{x, above});
    cspace::Overlap under = cspace::classify_overlap(model, axes, ax, ay, cspace::ChartPoint{x, below});
    if (side == BlockedSide::left) {
      EXPECT_EQ(over, cspace::Overlap::overlapping) << "edge " << e;
      EXPECT_EQ(under, cspace::Overlap::apart) << "edge " << e;
    } else {
      EXPECT_EQ(under, cspace::Overlap::overlapping) << "edge " << e;
      EXPECT_EQ(over, cspace::Overlap::apart) << "edge " << e;
    }
    ++sides;
  }
  EXPECT_GT(sides, 20);
  EXPECT_THROW(space.edge(EdgeId()), GeometryError);
  EXPECT_THROW(space.cell(CellId(space.cells().size())), GeometryError);
}

// ------------------------------------------------------------------ first crossing along a motion

TEST(CSpaceAdaptorQueries, FirstCrossingAcrossTheSeamAtConstantAngularVelocity) {
  Model model = read_model(cam_and_block);
  CSpace space = CSpace::build(model, "cam", "block");
  ASSERT_EQ(space.dimension(), 1);
  // clockwise at 1 rad per unit of u from theta = 0: through theta = -pi/2 (a seam) to the
  // contact at theta = -pi - pi/6 (sin(theta) = 1/2), u* = 7 pi / 6
  MotionPath path;
  path.x = AxisPath{AxisPath::Kind::angle, {Rational(0), Rational(-1)}};
  path.u_end = 4;
  MotionCrossing c = space.first_crossing(path);
  ASSERT_EQ(c.status, CrossingStatus::crossing);
  EXPECT_FALSE(c.grazing);
  double expected = 7 * std::numbers::pi / 6;
  EXPECT_LE(c.u_lower.get_d(), expected + 1e-15);
  EXPECT_GE(c.u_upper.get_d(), expected - 1e-15);
  EXPECT_LT(Rational(c.u_upper - c.u_lower).get_d(), 1e-11);
  ASSERT_FALSE(c.features.empty());
  EXPECT_EQ(space.feature_pair(c.features.front()).kind, ContactKind::arc_segment);
  EXPECT_TRUE(space.charts()[c.chart].x_half_turn);   // beyond the seam
  EXPECT_TRUE(within(c.point[0], 8 * std::cos(-expected), 1e-9));
  EXPECT_TRUE(within(c.point[1], 14, 1e-9));
  EXPECT_TRUE(within(c.normal[0], 0, 1e-9));
  EXPECT_TRUE(within(c.normal[1], 1, 1e-9));
  EXPECT_TRUE(c.cell_entered.valid());

  // counter-clockwise from theta = 2.7 (the chart around pi, free: 8 sin(2.7) < 4) through
  // 3 pi / 2 (a seam) to theta = 2 pi + pi / 6
  path.x = AxisPath{AxisPath::Kind::angle, {Rational(27, 10), Rational(1)}};
  path.u_end = 6;
  c = space.first_crossing(path);
  ASSERT_EQ(c.status, CrossingStatus::crossing);
  EXPECT_FALSE(c.grazing);
  expected = 2 * std::numbers::pi + std::numbers::pi / 6 - 2.7;
  EXPECT_LE(c.u_lower.get_d(), expected + 1e-14);
  EXPECT_GE(c.u_upper.get_d(), expected - 1e-14);
  EXPECT_FALSE(space.charts()[c.chart].x_half_turn);

  // in half-angle tangents: t = -u turns clockwise through the seam at u = 1 and never reaches
  // the block (theta stays in (-pi, 0]); the query continues across the seam instead of throwing
  path.x = AxisPath{AxisPath::Kind::half_tangent, {Rational(0), Rational(-1)}};
  path.u_end = 50;
  c = space.first_crossing(path);
  EXPECT_EQ(c.status, CrossingStatus::none);
  // and t = u hits it at theta = pi / 6, t = tan(pi / 12)
  path.x = AxisPath{AxisPath::Kind::half_tangent, {Rational(0), Rational(1)}};
  c = space.first_crossing(path);
  ASSERT_EQ(c.status, CrossingStatus::crossing);
  EXPECT_LE(c.u_lower.get_d(), std::tan(std::numbers::pi / 12) + 1e-14);
  EXPECT_GE(c.u_upper.get_d(), std::tan(std::numbers::pi / 12) - 1e-14);

  // a start in contact
  path.x = AxisPath{AxisPath::Kind::angle, {Rational(0), Rational(1)}};
  path.u_begin = 1;   // theta = 1 > pi / 6: the cam overlaps the block
  path.u_end = 2;
  EXPECT_EQ(space.first_crossing(path).status, CrossingStatus::starts_in_contact);
}

// The exact overlap oracle at a configuration in half-angle tangent t0 (centre 0) and offset s.
cspace::Overlap oracle(const Model& model, const cspace::PairAxes& axes, const Rational& t0, const Rational& s) {
  bool beyond = t0 > 1 || t0 < -1;
  cspace::ChartAxis x{cspace::ChartAxis::Kind::rotation, beyond, Rational(-1), Rational(1)};
  cspace::ChartAxis y{cspace::ChartAxis::Kind::translation, false, Rational(-100), Rational(100)};
  Rational t = beyond ? Rational(-1 / t0) : t0;
  t.canonicalize();
  return cspace::classify_overlap(model, axes, x, y, cspace::ChartPoint{t, s});
}

TEST(CSpaceAdaptorQueries, RandomMotionsNeverMissACrossingOfDenseExactSampling) {
  Model model = read_model_file(example("cam-follower.json"));
  CSpace space = CSpace::build(model, "cam", "follower");
  cspace::PairAxes axes = cspace::pair_axes(model, 0, 1);
  std::mt19937_64 random(2024);
  std::uniform_int_distribution<int> start_t(-3000, 3000), speed_t(-4000, 4000), start_s(-1100, 1100),
      speed_s(-1500, 1500);
  int crossings = 0, certain = 0, free_runs = 0, outside = 0, motions = 0;
  const int samples = 300;
  while (motions < 150) {
    Rational t0(start_t(random), 1000), a(speed_t(random), 1000), s0(start_s(random), 100), b(speed_s(random), 100);
    t0.canonicalize(), a.canonicalize(), s0.canonicalize(), b.canonicalize();
    if (oracle(model, axes, t0, s0) != cspace::Overlap::apart) continue;
    ++motions;
    MotionPath path;
    path.x = AxisPath{AxisPath::Kind::half_tangent, {t0, a}};
    path.y = AxisPath{AxisPath::Kind::offset, {s0, b}};
    MotionCrossing c = space.first_crossing(path);
    ASSERT_NE(c.status, CrossingStatus::starts_in_contact);
    Rational limit = c.status == CrossingStatus::none ? Rational(1) : c.u_lower;
    // every sample before the reported crossing is free (none is missed)...
    int first_not_free = -1;
    for (int k = 0; k <= samples; ++k) {
      Rational u(k, samples);
      Rational t = t0 + a * u, s = s0 + b * u;
      t.canonicalize(), s.canonicalize();
      if (s < -12 || s > 12) break;   // beyond the follower's limits: outside the space
      if (oracle(model, axes, t, s) != cspace::Overlap::apart) {
        first_not_free = k;
        break;
      }
    }
    if (first_not_free >= 0) {
      EXPECT_NE(c.status, CrossingStatus::none) << "missed: t0 " << t0 << " a " << a << " s0 " << s0 << " b " << b;
      EXPECT_LE(limit, Rational(first_not_free, samples)) << "t0 " << t0 << " a " << a << " s0 " << s0 << " b " << b;
    }
    // ... and a certified crossing really leaves the free cell by u_upper
    if (c.status == CrossingStatus::crossing) {
      ++crossings;
      if (!c.grazing) {
        ++certain;
        Rational t = t0 + a * c.u_upper, s = s0 + b * c.u_upper;
        t.canonicalize(), s.canonicalize();
        Location there = space.locate(tangent(t), offset(s));
        bool left = there.kind != Location::Kind::free || there.cell != c.cell_left.index();
        EXPECT_TRUE(left) << "t0 " << t0 << " a " << a << " s0 " << s0 << " b " << b;
      }
    }
    if (c.status == CrossingStatus::none) ++free_runs;
    if (c.status == CrossingStatus::outside_region) ++outside;
  }
  EXPECT_GT(certain, 10);
  EXPECT_GT(free_runs + outside, 3);
  RecordProperty("crossings", crossings);
}

TEST(CSpaceAdaptorQueries, RandomAngleMotionsAcrossSeamsAgreeWithSampling) {
  Model model = read_model_file(example("cam-follower.json"));
  CSpace space = CSpace::build(model, "cam", "follower");
  cspace::PairAxes axes = cspace::pair_axes(model, 0, 1);
  std::mt19937_64 random(77);
  std::uniform_int_distribution<int> angle(-3141, 3141), speed(-9000, 9000), start_s(-1100, 1100);
  int motions = 0, crossings = 0;
  while (motions < 60) {
    Rational theta0(angle(random), 1000), omega(speed(random), 1000), s0(start_s(random), 100);
    theta0.canonicalize(), omega.canonicalize(), s0.canonicalize();
    auto t_of = [&](double theta) {
      double t = std::tan(theta / 2);
      return Rational(t);
    };
    if (oracle(model, axes, t_of(theta0.get_d()), s0) != cspace::Overlap::apart) continue;
    ++motions;
    MotionPath path;
    path.x = AxisPath{AxisPath::Kind::angle, {theta0, omega}};   // up to 1.4 turns: seams
    path.y = AxisPath{AxisPath::Kind::offset, {s0}};
    MotionCrossing c = space.first_crossing(path);
    ASSERT_NE(c.status, CrossingStatus::starts_in_contact);
    // samples (posed within 1e-15 rad) well before the crossing are free; the follower's face
    // meets the cam where s = 8 sin(theta): the first sample past it overlaps or touches
    double limit = c.status == CrossingStatus::none ? 1.0 : c.u_lower.get_d() - 1e-9;
    for (int k = 0; k <= 400; ++k) {
      double u = k / 400.0;
      if (u >= limit) break;
      double theta = theta0.get_d() + omega.get_d() * u;
      EXPECT_EQ(oracle(model, axes, t_of(theta), s0), cspace::Overlap::apart) << "u " << u;
    }
    if (c.status == CrossingStatus::crossing) {
      ++crossings;
      EXPECT_FALSE(c.grazing);
      EXPECT_LT(Rational(c.u_upper - c.u_lower).get_d(), 1e-9);
      double u = c.u_upper.get_d(), theta = theta0.get_d() + omega.get_d() * u;
      // the contact at the crossing: the cam's top at the face (s = e sin theta), or another feature
      ASSERT_FALSE(c.features.empty());
      if (space.feature_pair(c.features.front()).first.kind == FeatureKind::arc &&
          space.feature_pair(c.features.front()).second.edge == 0)
        EXPECT_NEAR(s0.get_d(), 8 * std::sin(theta), 1e-9);
    }
  }
  EXPECT_GT(crossings, 5);
}

// The exact overlap oracle of the Geneva pair at half-angle tangents (t1, t2) (centre 0).
cspace::Overlap torus_oracle(const Model& model, const cspace::PairAxes& axes, const Rational& t1, const Rational& t2) {
  auto axis = [](const Rational& t, Rational& chart_value) {
    bool beyond = t > 1 || t < -1;
    chart_value = beyond ? Rational(-1 / t) : t;
    chart_value.canonicalize();
    return cspace::ChartAxis{cspace::ChartAxis::Kind::rotation, beyond, Rational(-1), Rational(1)};
  };
  Rational x, y;
  cspace::ChartAxis ax = axis(t1, x), ay = axis(t2, y);
  return cspace::classify_overlap(model, axes, ax, ay, cspace::ChartPoint{x, y});
}

TEST(CSpaceAdaptorQueries, RandomGenevaMotionsOnTheTorusNeverMissACrossing) {
  Model model = read_model_file(example("geneva.json"));
  CSpace space = CSpace::build(model, "driver", "wheel");
  cspace::PairAxes axes = cspace::pair_axes(model, 0, 1);
  // start configurations: rational points of the free channel (the free cell's sample, and
  // random points located free)
  std::mt19937_64 random(99);
  std::uniform_int_distribution<int> coordinate(-2500, 2500), speed(-600, 600);
  int motions = 0, certain = 0, free_runs = 0, tries = 0;
  const int samples = 400;
  while (motions < 30 && ++tries < 200000) {
    Rational t1(coordinate(random), 1000), t2(coordinate(random), 1000);
    t1.canonicalize(), t2.canonicalize();
    if (torus_oracle(model, axes, t1, t2) != cspace::Overlap::apart) continue;
    Rational a(speed(random), 1000), b(speed(random), 1000);
    // gear-ratio-like motions in tangents: quadratic in u for the wheel
    Rational b2(speed(random), 4000);
    a.canonicalize(), b.canonicalize(), b2.canonicalize();
    ++motions;
    MotionPath path;
    path.x = AxisPath{AxisPath::Kind::half_tangent, {t1, a}};
    path.y = AxisPath{AxisPath::Kind::half_tangent, {t2, b, b2}};
    MotionCrossing c = space.first_crossing(path);
    ASSERT_NE(c.status, CrossingStatus::starts_in_contact);
    ASSERT_NE(c.status, CrossingStatus::outside_region);
    Rational limit = c.status == CrossingStatus::none ? Rational(2) : c.u_lower;
    for (int k = 0; k <= samples; ++k) {
      Rational u(k, samples);
      Rational x = t1 + a * u, y = t2 + b * u + b2 * u * u;
      x.canonicalize(), y.canonicalize();
      if (torus_oracle(model, axes, x, y) != cspace::Overlap::apart) {
        EXPECT_NE(c.status, CrossingStatus::none) << "missed at u = " << u;
        EXPECT_LE(limit, u) << "t1 " << t1 << " t2 " << t2 << " a " << a << " b " << b << " b2 " << b2;
        break;
      }
    }
    if (c.status == CrossingStatus::crossing && !c.grazing) {
      ++certain;
      Rational x = t1 + a * c.u_upper, y = t2 + b * c.u_upper + b2 * c.u_upper * c.u_upper;
      x.canonicalize(), y.canonicalize();
      Location there = space.locate(tangent(x), tangent(y));
      EXPECT_TRUE(there.kind != Location::Kind::free || there.cell != c.cell_left.index());
      EXPECT_TRUE(c.edge.valid());
      ASSERT_FALSE(c.features.empty());
    }
    if (c.status == CrossingStatus::none) ++free_runs;
  }
  EXPECT_EQ(motions, 30);
  EXPECT_GE(certain, 25);   // certified: the cell at u_upper is not the start's
  RecordProperty("free_runs", free_runs);
}

TEST(CSpaceAdaptorQueries, FirstCrossingOverOperatingRegionTilesAgreesWithTheWholeSpace) {
  Model model = read_model_file(example("geneva.json"));
  CSpace whole = CSpace::build(model, "driver", "wheel");
  CSpaceBuildOptions options;
  options.operating_region = true;
  options.region_tiles = 8;
  CSpace region = CSpace::build(model, "driver", "wheel", options);
  ASSERT_FALSE(region.complete());
  std::mt19937_64 random(31);
  std::uniform_int_distribution<int> coordinate(-2500, 2500), speed(-1500, 1500);
  int motions = 0, crossings = 0, outside = 0, tries = 0;
  while (motions < 30 && ++tries < 200000) {
    Rational t1(coordinate(random), 1000), t2(coordinate(random), 1000);
    t1.canonicalize(), t2.canonicalize();
    if (region.locate(tangent(t1), tangent(t2)).kind != Location::Kind::free) continue;
    Rational a(speed(random), 1000), b(speed(random), 1000);
    a.canonicalize(), b.canonicalize();
    ++motions;
    MotionPath path;
    path.x = AxisPath{AxisPath::Kind::half_tangent, {t1, a}};
    path.y = AxisPath{AxisPath::Kind::half_tangent, {t2, b}};
    MotionCrossing in_region = region.first_crossing(path);
    MotionCrossing in_whole = whole.first_crossing(path);
    ASSERT_EQ(in_whole.status == CrossingStatus::crossing || in_whole.status == CrossingStatus::none, true);
    if (in_region.status == CrossingStatus::outside_region) {
      ++outside;
      // nothing before the region's border: the whole space's crossing is not earlier
      if (in_whole.status == CrossingStatus::crossing) EXPECT_GE(in_whole.u_upper, in_region.u_lower);
      continue;
    }
    ASSERT_EQ(in_region.status, in_whole.status) << "t1 " << t1 << " t2 " << t2 << " a " << a << " b " << b;
    if (in_region.status == CrossingStatus::crossing) {
      ++crossings;
      // the two certified brackets hold the same first contact
      EXPECT_LE(in_region.u_lower, in_whole.u_upper);
      EXPECT_LE(in_whole.u_lower, in_region.u_upper);
      std::set<std::string> labels;
      for (FeatureId f : in_whole.features) labels.insert(whole.feature_pair(f).label);
      bool shared = false;
      for (FeatureId f : in_region.features) shared = shared || labels.count(region.feature_pair(f).label) > 0;
      EXPECT_TRUE(shared);
    }
  }
  EXPECT_EQ(motions, 30);
  EXPECT_GT(crossings, 15);
  RecordProperty("outside", outside);
}

// ------------------------------------------------------------------ slices, polylines, build_pairs

TEST(CSpaceAdaptorQueries, SlicesAgreeWithTheOracle) {
  Model model = read_model_file(example("geneva.json"));
  CSpace space = CSpace::build(model, "driver", "wheel");
  cspace::PairAxes axes = cspace::pair_axes(model, 0, 1);
  std::mt19937_64 random(5);
  std::uniform_int_distribution<int> value(-999, 999);
  int intervals = 0;
  for (int i = 0; i < 6; ++i) {
    for (SliceAxis axis : {SliceAxis::x, SliceAxis::y}) {
      Rational v(value(random), 1000);
      std::vector<Slice> slices = space.slice(axis, v);
      EXPECT_EQ(slices.size(), 4u);   // every chart: all four boxes are [-1, 1]^2
      for (const Slice& s : slices) {
        ASSERT_EQ(s.intervals.size(), s.points.size() + 1);
        const CSpaceChart& chart = space.charts()[s.chart];
        cspace::ChartAxis ax{cspace::ChartAxis::Kind::rotation, chart.x_half_turn, chart.x_lo, chart.x_hi};
        cspace::ChartAxis ay{cspace::ChartAxis::Kind::rotation, chart.y_half_turn, chart.y_lo, chart.y_hi};
        for (std::size_t k = 0; k < s.intervals.size(); ++k) {
          const Slice::Interval& in = s.intervals[k];
          cspace::ChartPoint q = axis == SliceAxis::x ? cspace::ChartPoint{v, in.sample} : cspace::ChartPoint{in.sample, v};
          cspace::Overlap o = cspace::classify_overlap(model, axes, ax, ay, q);
          if (in.kind == CellKind::free) EXPECT_EQ(o, cspace::Overlap::apart);
          if (in.kind == CellKind::blocked) EXPECT_EQ(o, cspace::Overlap::overlapping);
          if (k > 0) EXPECT_FALSE(s.intervals[k - 1].cell == in.cell && s.intervals[k - 1].kind == in.kind);
          ++intervals;
        }
        for (const Slice::Point& p : s.points) EXPECT_FALSE(p.features.empty());
      }
    }
  }
  EXPECT_GT(intervals, 24);
  // a drawing of every real edge stays within its certified box
  for (std::size_t e = 0; e < space.edges().size(); ++e) {
    const CSpaceEdge& edge = space.edges()[e];
    if (!edge.real) continue;
    EdgePolyline line = space.edge_polyline(EdgeId(e), 9);
    EXPECT_TRUE(line.approximate);
    EXPECT_GE(line.points.size(), 2u);
    EXPECT_LT(line.error, 1e-12);
    for (const auto& p : line.points) {
      EXPECT_TRUE(within(edge.x_chart, p[0], 1e-12));
      EXPECT_TRUE(within(edge.y_chart, p[1], 1e-12));
    }
  }
}

TEST(CSpaceAdaptorQueries, BuildPairsKeepsEveryGoodPairWhenOneFails) {
  Model model = read_model_file(example("cam-follower.json"));
  CSpaceBuildOptions options;
  options.operating_region = true;                 // 2-D pairs only: the cam and the follower
  options.region_seed = std::array<double, 2>{0, 500};   // beyond the follower's limits: fails
  std::vector<PairBuild> builds = CSpace::build_pairs(model, options);
  ASSERT_EQ(builds.size(), 2u);
  EXPECT_EQ(builds[0].first_part, "cam");
  EXPECT_EQ(builds[0].status, PairBuild::Status::failed);
  EXPECT_NE(builds[0].error.find("outside the motion limits"), std::string::npos) << builds[0].error;
  EXPECT_EQ(builds[0].space, nullptr);
  EXPECT_EQ(builds[1].first_part, "follower");
  ASSERT_EQ(builds[1].status, PairBuild::Status::built);
  ASSERT_NE(builds[1].space, nullptr);
  EXPECT_EQ(builds[1].space->dimension(), 1);
  EXPECT_FALSE(builds[1].space->cells().empty());
  EXPECT_THROW(CSpace::build_all(model, options), GeometryError);
}

}  // namespace
}  // namespace hipair
