// Session 37: one vertex rule for every pair (docs/simulation.md, "Session 37 (sim37)"). At a
// contact change's C-space vertex the new contacts and the old one's rows are taken at the vertex
// for every pair; both contacts stay held only where their rows are independent over the pair's
// free coordinates (a wedge); otherwise the new contact takes over. Before, driver pairs kept
// the old contact whenever a new one was held and grew its slack threefold at each visit: the
// Geneva pin left its slot 1 wall L at the mouth's corner after 3 (accuracy 1e-9) to 8 (1e-3)
// contact/lift-off repeats of the corner, held on the wall's extension up to 5.2e-6 s past the
// vertex; and with the wedge rules of session 36 applied to every free pair, the Geneva pair
// driven by a motor torque repeated the corner change without end ("10000 steps in a row").

#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "test_paths.hpp"

namespace hipair {
namespace {

nlohmann::json geneva_json() {
  std::ifstream in(std::filesystem::path(HIPAIR_EXAMPLES) / "geneva-drive.json");
  return nlohmann::json::parse(in);
}

bool names(const SimulationEvent& e, const std::string& feature) {
  for (const std::string& f : e.features)
    if (f.find(feature) != std::string::npos) return true;
  return false;
}

// The wheel's speed with the pin on slot 1's wall L at driver angle psi, in closed form: the pin
// centre P = (d + c cos psi, c sin psi) (wheel pivot at the origin, driver pivot at (d, 0)) keeps
// the distance w = 5 - 4.5 from the slot's axis at wheel angle theta + pi/4, so
// theta = atan2(P) - pi/4 - asin(w / |P|) and theta' = omega (phi' + w rho' / (rho^2 sqrt(1 - w^2/rho^2))).
double wall_l_speed(double psi, double omega) {
  const double c = 56.5, d = 80, w = 0.5;
  const double rho2 = d * d + c * c + 2 * d * c * std::cos(psi), rho = std::sqrt(rho2);
  const double phi1 = (c * c + d * c * std::cos(psi)) / rho2;
  const double rho1 = -d * c * std::sin(psi) / rho;
  return omega * (phi1 + w * rho1 / (rho2 * std::sqrt(1 - w * w / rho2)));
}

// The pin leaves slot 1 at its mouth's corner in one contact change at one time, at every
// accuracy: the wall's contact ends (edge-end), the corner's is taken up and lifts off; the wheel
// then coasts (no load on it) at the closed-form speed of the wall contact at that driver angle,
// and strikes the driver's lock at the time of the 1e-9 run.
TEST(SimulationVertexRule, GenevaPinLeavesTheSlotAtItsMouthCornerOnce) {
  const std::string wall = "wheel slot 1 wall L", corner = "wheel corner of slot 1 wall L and slot 1 mouth L";
  double fine_lock = 0;
  for (double accuracy : {1e-9, 1e-6, 1e-3}) {
    SCOPED_TRACE(accuracy);
    SimulationOptions options;
    options.accuracy = accuracy;
    Simulation s = Simulation::create(read_model(geneva_json().dump(), "geneva-drive"), options);
    s.run_until(0.66);
    int ends = 0, contacts = 0, lifts = 0;
    double release = -1;
    for (const SimulationEvent& e : s.events()) {
      if (e.kind == SimulationEvent::Kind::edge_end && names(e, wall)) {
        ++ends;
        release = e.time;
      }
      if (e.kind == SimulationEvent::Kind::contact && names(e, corner)) ++contacts;
      if (e.kind == SimulationEvent::Kind::lift_off && names(e, corner)) ++lifts;
    }
    EXPECT_EQ(ends, 1);
    EXPECT_EQ(contacts, 1);
    EXPECT_EQ(lifts, 1);
    for (const SimulationEvent& e : s.events())
      if (names(e, corner)) EXPECT_EQ(e.time, release);
    ASSERT_GT(release, 0.6);
    // driver at 2 pi rad/s from angle 0; the wheel free and unloaded after the release
    const double omega = 2 * std::numbers::pi;
    EXPECT_NEAR(s.state().velocity[1], wall_l_speed(omega * release, omega), 5e-8);
    s.run_until(0.7);
    double lock = 0;
    for (const SimulationEvent& e : s.events())
      if (e.kind == SimulationEvent::Kind::impact && names(e, "wheel lock arc 2")) lock = e.time;
    ASSERT_GT(lock, 0.69);
    if (accuracy == 1e-9) fine_lock = lock;
    EXPECT_NEAR(lock, fine_lock, 1e-8);
  }
}

// The Geneva pair driven by a motor torque (both parts free: the driver has an inertia) runs
// through two drives at 1e-3 and 1e-9; main stopped at 0.6076 s with "10000 steps in a row did not
// move the time on" (session 36's wedge rules at the tangent corner change).
TEST(SimulationVertexRule, GenevaDrivenByAMotorTorqueRunsThroughTwoDrives) {
  nlohmann::json m = geneva_json();
  m["simulation"].erase("drivers");
  m["simulation"]["velocities"] = {{"driver", "2*pi"}};
  for (auto& part : m["parts"])
    if (part["name"] == "driver") part["dynamics"] = {{"moment_of_inertia", 100000}, {"torque", 100}};
  for (double accuracy : {1e-3, 1e-9}) {
    SCOPED_TRACE(accuracy);
    SimulationOptions options;
    options.accuracy = accuracy;
    options.max_steps = 20000;
    Simulation s = Simulation::create(read_model(m.dump(), "geneva-motor"), options);
    ASSERT_NO_THROW(s.run_until(2.0));
    int mouth_ends = 0;
    for (const SimulationEvent& e : s.events())
      if (e.kind == SimulationEvent::Kind::edge_end && (names(e, "slot 1 wall L") || names(e, "slot 2 wall L"))) ++mouth_ends;
    EXPECT_GE(mouth_ends, 2);
  }
}

}  // namespace
}  // namespace hipair
