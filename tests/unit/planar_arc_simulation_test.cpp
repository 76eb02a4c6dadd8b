// Held (sustained) contacts with circular arcs of a part free in the plane (docs/simulation.md,
// "Held contacts on arcs"): a disc on an incline slides at g sin a (frictionless) and rolls at
// (2/3) g sin a (solid disc, mu_s >= tan(a) / 3) on generated radii and inclines; a disc at rest
// on a floor stays at rest; a dropped spinning disc never gains energy (e <= 1); every recorded
// state's exact configuration is not blocked (exact point location in the pair's C-space); a disc
// in a round socket, a ring on a fixed pin and a block on its corners in a round bowl swing with
// their pendulum periods (complete elliptic integrals), sliding and rolling; a disc sliding off a
// round hump lifts off where its held force turns negative.
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>
#include <hipair/sliced.hpp>

#include <gtest/gtest.h>

#include "simulation_planar_support.hpp"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace hipair {
namespace {

using planar_test::Lcg;
using planar_test::num;

// A solid disc of radius r (mass m, I = m r^2 / 2, centre = pivot at the origin) above a flat
// fixed floor (top y = 0), gravity (gx, gy) (tilted gravity is the incline).
struct DiscScene {
  double r = 5, mass = 0.01, e = 0, y = 0, vx = 0, vy = 0, omega = 0, gx = 0, gy = -9810;
  double mu_static = 0, mu_kinetic = 0;
  std::string json() const {
    std::string friction = mu_static > 0 ? R"(, "friction": { "static": )" + num(mu_static) + R"(, "kinetic": )" +
                                               num(mu_kinetic) + " }"
                                         : "";
    return R"({ "hipair": 1, "name": "disc", "units": { "length": "mm", "angle": "rad" },
      "parts": [
        { "name": "floor", "motion": "fixed", "loops": [ { "start": [-2000, -20], "edges": [ { "line_to": [2000, -20] },
          { "line_to": [2000, 0] }, { "line_to": [-2000, 0], "label": "floor" }, { "line_to": [-2000, -20] } ] } ] },
        { "name": "disc", "motion": { "planar": { "pivot": [0, 0] } },
          "initial": { "x": 0, "y": )" + num(y) + R"( },
          "dynamics": { "mass": )" + num(mass) + R"(, "moment_of_inertia": )" + num(0.5 * mass * r * r) + R"( },
          "loops": [ { "circle": { "center": [0, 0], "radius": )" + num(r) + R"( }, "label": "rim" } ] } ],
      "pairs": [ { "parts": ["floor", "disc"], "restitution": )" + num(e) + friction + R"( } ],
      "simulation": { "gravity": [)" + num(gx) + ", " + num(gy) + R"(], "accuracy": 1e-10,
        "velocities": { "disc": { "x": )" + num(vx) + R"(, "y": )" + num(vy) + R"(, "angle": )" + num(omega) + R"( } } } })";
  }
  Model model() const { return read_model(json(), "<disc>"); }
};

// A disc of radius k/8 mm (k in [k0, k1], rounded) on an incline of a in [a0, a1] degrees
// (tilted gravity of 9810 mm/s^2).
DiscScene generated_disc(Lcg& rng, double k0, double k1, double a0, double a1) {
  DiscScene scene;
  scene.r = std::round(rng.uniform(k0, k1)) / 8;
  const double a = rng.uniform(a0, a1) * std::numbers::pi / 180;
  scene.gx = 9810 * std::sin(a);
  scene.gy = -9810 * std::cos(a);
  return scene;
}

std::size_t count(const std::vector<SimulationEvent>& events, SimulationEvent::Kind kind) {
  std::size_t n = 0;
  for (const auto& e : events) n += e.kind == kind;
  return n;
}

// The disc lands (a gap of 10^-3 mm, plastic) and is held on its rim; along the floor its speed
// grows at g sin a sliding (frictionless: it does not turn) and at (2/3) g sin a rolling
// (mu_s = 2 tan(a) / 3 + 0.2 > tan(a) / 3: the contact sticks, v = -omega r). Radii k/8 mm, k in
// [8, 160]; inclines 2..30 degrees. Accuracy: the run's 1e-10 (relative) on a quadratic motion,
// asserted at 1e-7 of G (the velocities differ over 20 ms; the landing's projection error is
// below the chord deviation delta over the time).
TEST(PlanarArcSimulation, DiscOnAnInclineSlidesAtGSinAAndRollsAtTwoThirdsGSinA) {
  Lcg rng{11};
  for (int c = 0; c < 8; ++c) {
    DiscScene scene = generated_disc(rng, 8, 160, 2, 30);
    const double a = std::atan2(scene.gx, -scene.gy), G = 9810;
    scene.y = scene.r + 1e-3;
    const bool rolls = c % 2 == 1;
    if (rolls) {
      scene.mu_static = 2 * std::tan(a) / 3 + 0.2;
      scene.mu_kinetic = scene.mu_static;
    }
    PlanarSimulation s = PlanarSimulation::create(scene.model());
    s.run_until(0.01);
    ASSERT_GE(count(s.events(), SimulationEvent::Kind::contact), 1u) << c;   // held on the rim
    const double t1 = s.state().time, v1 = s.state().vx;
    s.run_until(0.03);
    const double t2 = s.state().time, v2 = s.state().vx;
    const double expected = rolls ? 2 * scene.gx / 3 : scene.gx;
    EXPECT_NEAR((v2 - v1) / (t2 - t1), expected, 1e-7 * G) << c << " r " << scene.r << " a " << a;
    std::cerr << "incline case " << c << (rolls ? " rolling" : " sliding") << ": acceleration relative error "
              << (v2 - v1) / (t2 - t1) / expected - 1 << "\n";
    EXPECT_NEAR(s.state().y, scene.r, s.chord_deviation()) << c;
    if (rolls) EXPECT_NEAR(s.state().omega, -s.state().vx / scene.r, 1e-7 * std::abs(s.state().vx) + 1e-9) << c;
    else EXPECT_NEAR(s.state().omega, 0.0, 1e-9) << c;
    EXPECT_EQ(count(s.events(), SimulationEvent::Kind::lift_off), 0u) << c;
  }
}

// A disc set down on a flat floor (a gap of 10^-3 mm) without friction or with friction, spin 0:
// after landing it stays where it landed, its speed 0 (to the integration accuracy).
TEST(PlanarArcSimulation, DiscAtRestOnAFloorStaysAtRest) {
  Lcg rng{5};
  for (int c = 0; c < 4; ++c) {
    DiscScene scene;
    scene.r = std::round(rng.uniform(8, 160)) / 8;
    scene.y = scene.r + 1e-3;
    if (c % 2 == 1) scene.mu_static = scene.mu_kinetic = 0.5;
    PlanarSimulation s = PlanarSimulation::create(scene.model());
    s.run_until(0.2);
    EXPECT_NEAR(s.state().x, 0.0, 1e-9) << c;
    EXPECT_NEAR(s.state().y, scene.r, s.chord_deviation()) << c;
    EXPECT_NEAR(s.state().vx, 0.0, 1e-9) << c;
    EXPECT_NEAR(s.state().vy, 0.0, 1e-6) << c;
    EXPECT_NEAR(s.state().omega, 0.0, 1e-9) << c;
    EXPECT_EQ(count(s.events(), SimulationEvent::Kind::lift_off), 0u) << c;
  }
}

// A spinning disc thrown onto an incline (generated radius, incline, restitution in [0, 1],
// friction or none): its energy never grows (beyond the integration's 1e-9 per step of the
// energy scale and m g delta), and every recorded state's exact configuration is not blocked.
TEST(PlanarArcSimulation, ThrownDiscNeverGainsEnergyAndNeverPenetrates) {
  Lcg rng{29};
  std::size_t held_cases = 0;
  for (int c = 0; c < 6; ++c) {
    DiscScene scene = generated_disc(rng, 16, 120, 0, 20);
    const double G = 9810;
    scene.e = c < 2 ? 0.0 : rng.uniform(0, 1);
    if (c % 2 == 1) {
      scene.mu_static = rng.uniform(0.1, 0.8);
      scene.mu_kinetic = scene.mu_static * rng.uniform(0.5, 1);
    }
    scene.y = scene.r + rng.uniform(0.5, 5);
    scene.vx = rng.uniform(-40, 40);
    scene.omega = rng.uniform(-4, 4);
    const Model model = scene.model();
    PlanarSimulation s = PlanarSimulation::create(model);
    SlicedSpace space = SlicedSpace::build(model, "floor", "disc", SlicedBuildOptions{false, {}});
    const double e0 = s.energy();
    const double scale = (scene.mass * G * (scene.y + 2000) + 0.5 * scene.mass * scene.vx * scene.vx +
                          0.25 * scene.mass * scene.r * scene.r * scene.omega * scene.omega) / 1000;
    double previous = e0;
    while (s.state().time < 0.1 && !s.state().resting) {
      std::size_t before = s.steps();
      s.step(0.1);
      const double now = s.energy();
      const double tol = 1e-9 * static_cast<double>(s.steps() - before + 1) * scale +
                         scene.mass * G * s.chord_deviation() / 1000;
      EXPECT_LE(now, previous + tol) << c << " t = " << s.state().time;
      previous = std::min(previous, now);
      ASSERT_NE(space.locate(s.state().configuration).kind, SlicedLocation::Kind::blocked)
          << c << " t = " << s.state().time;
    }
    held_cases += count(s.events(), SimulationEvent::Kind::contact) > 0;
  }
  EXPECT_GE(held_cases, 3u);
}

// A solid disc of radius r in a round socket of radius R (a circular hole in a fixed block;
// its centre at the origin), the disc's centre on the circle of radius rho = R - r at angle phi0
// from the bottom (10^-4 mm inside it). Held on the socket's wall it is a pendulum of length rho:
// sliding (frictionless, the disc does not turn) its period is 4 sqrt(rho / g) K(sin(phi0 / 2));
// rolling (no slip, I = m r^2 / 2) 4 sqrt(3 rho / (2 g)) K(sin(phi0 / 2)) (K the complete elliptic
// integral of the first kind). The curvature terms (the centripetal n' . V) decide both.
std::string socket_json(double r, double R, double phi0, double mu, double e) {
  const double rho = R - r - 1e-4;
  const std::string friction = mu > 0 ? R"(, "friction": { "static": )" + num(mu) + R"(, "kinetic": )" + num(mu) + " }" : "";
  return R"({ "hipair": 1, "name": "socket", "units": { "length": "mm", "angle": "rad" },
      "parts": [
        { "name": "block", "motion": "fixed", "loops": [ { "start": [-100, -100], "edges": [ { "line_to": [100, -100] },
          { "line_to": [100, 100] }, { "line_to": [-100, 100] }, { "line_to": [-100, -100] } ] },
          { "circle": { "center": [0, 0], "radius": )" + num(R) + R"( }, "label": "socket" } ] },
        { "name": "disc", "motion": { "planar": { "pivot": [0, 0] } },
          "initial": { "x": )" + num(rho * std::sin(phi0)) + R"(, "y": )" + num(-rho * std::cos(phi0)) + R"( },
          "dynamics": { "mass": 0.01, "moment_of_inertia": )" + num(0.5 * 0.01 * r * r) + R"( },
          "loops": [ { "circle": { "center": [0, 0], "radius": )" + num(r) + R"( }, "label": "rim" } ] } ],
      "pairs": [ { "parts": ["block", "disc"], "restitution": )" + num(e) + friction + R"( } ],
      "simulation": { "gravity": [0, -9810], "accuracy": 1e-10 } })";
}

// The times at which vx changes sign from + to - (linear interpolation between states).
std::vector<double> swings(PlanarSimulation& s, double t_end) {
  std::vector<double> at;
  double t0 = s.state().time, v0 = s.state().vx;
  while (s.state().time < t_end) {
    s.step(t_end);
    const double t1 = s.state().time, v1 = s.state().vx;
    if (v0 > 0 && v1 <= 0) at.push_back(t0 + (t1 - t0) * v0 / (v0 - v1));
    t0 = t1;
    v0 = v1;
  }
  return at;
}

TEST(PlanarArcSimulation, DiscInARoundSocketSwingsWithThePendulumPeriodSlidingAndRolling) {
  Lcg rng{7};
  for (int c = 0; c < 4; ++c) {
    const double r = std::round(rng.uniform(16, 80)) / 8, R = r + std::round(rng.uniform(40, 400)) / 8;
    const double phi0 = rng.uniform(0.1, 1.0), g = 9810;
    const bool rolls = c % 2 == 1;
    const Model model = read_model(socket_json(r, R, phi0, rolls ? 2.0 : 0.0, 0), "<socket>");
    PlanarSimulation s = PlanarSimulation::create(model);
    const double rho = R - r, k = std::sin(phi0 / 2);
    const double period = 4 * std::sqrt((rolls ? 1.5 : 1.0) * rho / g) * std::comp_ellint_1(k);
    const std::vector<double> at = swings(s, 3.2 * period);
    ASSERT_GE(at.size(), 3u) << c;
    ASSERT_GE(count(s.events(), SimulationEvent::Kind::contact), 1u) << c;
    const double measured = (at.back() - at.front()) / static_cast<double>(at.size() - 1);
    // the start 10^-4 mm inside the wall changes the amplitude by at most 10^-4 / rho rad (the
    // period's relative slope d ln T / d phi0 is below phi0 / 4 for phi0 <= 1); the swings' times
    // are interpolated linearly between states and integrated at 1e-10: 10^-6 for both
    EXPECT_NEAR(measured / period, 1.0, 1e-4 / rho * phi0 / 4 + 1e-6) << c << " r " << r << " R " << R << " phi0 " << phi0;
    EXPECT_EQ(count(s.events(), SimulationEvent::Kind::lift_off), 0u) << c;
    if (rolls) EXPECT_EQ(count(s.events(), SimulationEvent::Kind::slip), 0u) << c;
    std::cerr << "socket case " << c << (rolls ? " rolling" : " sliding") << ": period " << measured << " s, closed form "
              << period << " s, relative error " << measured / period - 1 << ", " << s.steps() << " steps\n";
  }
}

// A w x h block in a frictionless round bowl of radius R (a circular hole in a fixed block, centre
// O at the origin) with both bottom corners on the bowl (vertex-arc contacts, held): it moves as
// a rigid rotation about O, a physical pendulum with d = sqrt(R^2 - w^2 / 4) - h / 2 (O to the
// centre of mass) and I_O = m (w^2 + h^2) / 12 + m d^2: period 4 sqrt(I_O / (m g d)) K(sin(phi0 / 2)).
// Released at phi0 (10^-4 mm inside), generated sizes; energy conserved after the landing.
TEST(PlanarArcSimulation, BlockInARoundBowlSwingsAsAPhysicalPendulumOnItsCorners) {
  Lcg rng{19};
  for (int c = 0; c < 3; ++c) {
    const double R = std::round(rng.uniform(160, 400)) / 8, w = std::round(rng.uniform(0.8, 1.6) * R * 8) / 8;
    const double h = std::round(rng.uniform(0.1, 0.3) * R * 8) / 8, phi0 = rng.uniform(0.1, 0.8), g = 9810, m = 0.01;
    const double d = std::sqrt(R * R - w * w / 4) - h / 2, I = m * (w * w + h * h) / 12;
    const double dd = d - 1e-4;
    const std::string json = R"({ "hipair": 1, "name": "bowl", "units": { "length": "mm", "angle": "rad" },
      "parts": [
        { "name": "bowl", "motion": "fixed", "loops": [ { "start": [-100, -100], "edges": [ { "line_to": [100, -100] },
          { "line_to": [100, 100] }, { "line_to": [-100, 100] }, { "line_to": [-100, -100] } ] },
          { "circle": { "center": [0, 0], "radius": )" + num(R) + R"( }, "label": "bowl" } ] },
        { "name": "block", "motion": { "planar": { "pivot": [0, 0] } },
          "initial": { "x": )" + num(dd * std::sin(phi0)) + R"(, "y": )" + num(-dd * std::cos(phi0)) + R"(, "angle": )" + num(phi0) + R"( },
          "dynamics": { "mass": )" + num(m) + R"(, "moment_of_inertia": )" + num(I) + R"( },
          "loops": [ { "start": [)" + num(-w / 2) + ", " + num(-h / 2) + R"(], "edges": [ { "line_to": [)" + num(w / 2) + ", " +
                             num(-h / 2) + R"(] }, { "line_to": [)" + num(w / 2) + ", " + num(h / 2) + R"(] }, { "line_to": [)" +
                             num(-w / 2) + ", " + num(h / 2) + R"(] }, { "line_to": [)" + num(-w / 2) + ", " + num(-h / 2) + R"(] } ] } ] } ],
      "pairs": [ { "parts": ["bowl", "block"], "restitution": 0 } ],
      "simulation": { "gravity": [0, -9810], "accuracy": 1e-6 } })";
    const Model model = read_model(json, "<bowl>");
    PlanarSimulation s = PlanarSimulation::create(model);
    SlicedSpace space = SlicedSpace::build(model, "bowl", "block", SlicedBuildOptions{false, {}});
    const double period = 4 * std::sqrt((I + m * d * d) / (m * g * d)) * std::comp_ellint_1(std::sin(phi0 / 2));
    s.run_until(0.002);   // landed on both corners
    ASSERT_GE(count(s.events(), SimulationEvent::Kind::contact), 1u) << c;
    const double e1 = s.energy();
    const std::vector<double> at = swings(s, 2.2 * period);
    ASSERT_GE(at.size(), 2u) << c;
    const double measured = (at.back() - at.front()) / static_cast<double>(at.size() - 1);
    // as for the socket: the start 10^-4 mm inside (amplitude error 10^-4 / d); the run's accuracy
    // 10^-6 (its chord deviation delta is 10^4 times the socket's: 1e-10 would take minutes) over
    // about two periods and the interpolation: 10^-5
    EXPECT_NEAR(measured / period, 1.0, 1e-4 / d * phi0 / 4 + 1e-5) << c << " R " << R << " w " << w << " h " << h;
    // frictionless and held: the energy stays (the integration's 1e-6 per step, the projection
    // onto the gaps: m g delta)
    EXPECT_NEAR(s.energy(), e1, 1e-6 * static_cast<double>(s.steps()) * m * g * R / 1000 + m * g * s.chord_deviation() / 1000)
        << c;
    EXPECT_NE(space.locate(s.state().configuration).kind, SlicedLocation::Kind::blocked) << c;
    EXPECT_EQ(count(s.events(), SimulationEvent::Kind::lift_off), 0u) << c;
    std::cerr << "bowl case " << c << ": period " << measured << " s, closed form " << period << " s, relative error "
              << measured / period - 1 << ", energy drift " << s.energy() - e1 << " N mm\n";
  }
}

// The reverse pair: a ring (a part with a round hole of radius R, outer radius R + 4, centre of
// mass at the hole's centre, I given) hung on a fixed pin of radius r (a fixed convex arc inside
// the part's concave arc). Frictionless it slides without turning: period 4 sqrt(rho / g) K(k);
// rolling (the hole rolls on the pin, turning rho / R per radian of swing) the kinetic energy
// is (m rho^2 + I rho^2 / R^2) phi'^2 / 2: period 4 sqrt(rho (1 + I / (m R^2)) / g) K(k).
TEST(PlanarArcSimulation, RingOnAFixedPinSwingsWithThePendulumPeriodSlidingAndRolling) {
  Lcg rng{23};
  for (int c = 0; c < 4; ++c) {
    const double r = std::round(rng.uniform(16, 80)) / 8, R = r + std::round(rng.uniform(40, 400)) / 8;
    const double phi0 = rng.uniform(0.1, 1.0), g = 9810, m = 0.01, I = m * R * R * rng.uniform(0.5, 1.5);
    const bool rolls = c % 2 == 1;
    const double rho = R - r, start = rho - 1e-4;
    const std::string friction = rolls ? R"(, "friction": { "static": 2, "kinetic": 2 })" : "";
    const std::string json = R"({ "hipair": 1, "name": "ring", "units": { "length": "mm", "angle": "rad" },
      "parts": [
        { "name": "pin", "motion": "fixed", "loops": [ { "circle": { "center": [0, 0], "radius": )" + num(r) + R"( }, "label": "pin" } ] },
        { "name": "ring", "motion": { "planar": { "pivot": [0, 0] } },
          "initial": { "x": )" + num(start * std::sin(phi0)) + R"(, "y": )" + num(-start * std::cos(phi0)) + R"( },
          "dynamics": { "mass": )" + num(m) + R"(, "moment_of_inertia": )" + num(I) + R"( },
          "loops": [ { "circle": { "center": [0, 0], "radius": )" + num(R + 4) + R"( }, "label": "rim" },
                     { "circle": { "center": [0, 0], "radius": )" + num(R) + R"( }, "label": "hole" } ] } ],
      "pairs": [ { "parts": ["pin", "ring"], "restitution": 0)" + friction + R"( } ],
      "simulation": { "gravity": [0, -9810], "accuracy": 1e-10 } })";
    PlanarSimulation s = PlanarSimulation::create(read_model(json, "<ring>"));
    const double period = 4 * std::sqrt(rho * (rolls ? 1 + I / (m * R * R) : 1.0) / g) * std::comp_ellint_1(std::sin(phi0 / 2));
    const std::vector<double> at = swings(s, 2.2 * period);
    ASSERT_GE(at.size(), 2u) << c;
    ASSERT_GE(count(s.events(), SimulationEvent::Kind::contact), 1u) << c;
    const double measured = (at.back() - at.front()) / static_cast<double>(at.size() - 1);
    // as for the socket (amplitude error 10^-4 / rho, interpolation and integration 10^-6)
    EXPECT_NEAR(measured / period, 1.0, 1e-4 / rho * phi0 / 4 + 1e-6) << c << " r " << r << " R " << R << " phi0 " << phi0;
    EXPECT_EQ(count(s.events(), SimulationEvent::Kind::lift_off), 0u) << c;
    if (!rolls) EXPECT_NEAR(s.state().angle, 0.0, 1e-9) << c;
    std::cerr << "ring case " << c << (rolls ? " rolling" : " sliding") << ": period " << measured << " s, closed form " << period
              << " s, relative error " << measured / period - 1 << "\n";
  }
}

// Lift-off: a disc (radius r) released near the top of a fixed round hump (radius R) slides
// down it frictionless (not turning); its centre runs on the circle rho = R + r and the held
// force m (g cos phi - v^2 / rho) turns negative at cos phi = (2/3) cos phi0 (energy:
// v^2 = 2 g rho (cos phi0 - cos phi)), where the contact breaks (a lift_off event).
TEST(PlanarArcSimulation, DiscSlidingOffARoundHumpLiftsOffAtTwoThirdsOfTheStartCosine) {
  Lcg rng{31};
  for (int c = 0; c < 4; ++c) {
    const double r = std::round(rng.uniform(16, 80)) / 8, R = std::round(rng.uniform(40, 400)) / 8;
    const double phi0 = rng.uniform(0.05, 0.5), rho = R + r, start = rho + 1e-4;
    const std::string json = R"({ "hipair": 1, "name": "hump", "units": { "length": "mm", "angle": "rad" },
      "parts": [
        { "name": "hump", "motion": "fixed", "loops": [ { "circle": { "center": [0, 0], "radius": )" + num(R) + R"( }, "label": "hump" } ] },
        { "name": "disc", "motion": { "planar": { "pivot": [0, 0] } },
          "initial": { "x": )" + num(start * std::sin(phi0)) + R"(, "y": )" + num(start * std::cos(phi0)) + R"( },
          "dynamics": { "mass": 0.01, "moment_of_inertia": )" + num(0.5 * 0.01 * r * r) + R"( },
          "loops": [ { "circle": { "center": [0, 0], "radius": )" + num(r) + R"( }, "label": "rim" } ] } ],
      "pairs": [ { "parts": ["hump", "disc"], "restitution": 0 } ],
      "simulation": { "gravity": [0, -9810], "accuracy": 1e-10 } })";
    PlanarSimulation s = PlanarSimulation::create(read_model(json, "<hump>"));
    std::size_t lift = std::string::npos;
    while (lift == std::string::npos && s.state().time < 2) {
      s.step(2);
      for (std::size_t i = 0; i < s.events().size(); ++i)
        if (s.events()[i].kind == SimulationEvent::Kind::lift_off) lift = i;
    }
    ASSERT_NE(lift, std::string::npos) << c;
    ASSERT_GE(count(s.events(), SimulationEvent::Kind::contact), 1u) << c;
    const double cos_phi = s.state().y / std::hypot(s.state().x, s.state().y);
    // the 10^-4 mm drop adds 2 g 10^-4 to v^2: cos phi lower by at most (2/3) 10^-4 / rho;
    // the lift-off located by bisection on the force (relative tolerance 1e-9): 10^-6
    EXPECT_NEAR(cos_phi, 2 * std::cos(phi0) / 3, 1e-4 / rho + 1e-6) << c << " r " << r << " R " << R << " phi0 " << phi0;
    EXPECT_NEAR(s.state().omega, 0.0, 1e-9) << c;
    std::cerr << "hump case " << c << ": lift-off at cos phi " << cos_phi << ", closed form " << 2 * std::cos(phi0) / 3
              << ", error " << cos_phi - 2 * std::cos(phi0) / 3 << "\n";
  }
}

}  // namespace
}  // namespace hipair
