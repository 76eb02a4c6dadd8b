// HIPAIR — the fixed-axis simulator's internal time unit at extreme speeds (docs/simulation.md,
// "Session 60 (geneva60)"). A mechanism whose fastest prescribed or initial speed is w rad/s
// runs through its motion in a time of order 1/w: at w = 1e10 rad/s the steps the accuracy asks
// for fall below the resolution of the time t in doubles, and every absolute threshold of the
// event handling that carries a time or a speed (a rest speed, a step's length, a separation
// speed) meets quantities 1e10 times smaller or larger than at 1 rad/s. Without springs,
// dampers or loads the motion as a function of w t is the same at every w; with them it is the
// motion of the model with its loads scaled by 1/w^2 (damping 1/w). The simulator therefore
// integrates in a time unit of 2^-e s, 2^e the power of two of the fastest speed, so that its
// internal speeds are of order 1 at every w: every conversion at the boundary (seconds per time
// unit, mN per force unit, gravity) is multiplied by a power of two, exactly, and the run at
// w is the run of an ordinary speed. Runs whose fastest speed is below 2^12 rad/s (or mm/s)
// keep e = 0 and their doubles (a slow driver leaves the time scale to the loads).
#pragma once

#include <hipair/model.hpp>

#include <algorithm>
#include <cmath>

namespace hipair::simulation {

/// From 2^12 rad/s (or mm/s) on, the internal time unit is rescaled.
inline constexpr int rescaled_speed_exponent = 12;
/// The largest exponent: the force scale (mN per force unit) times 2^-2e stays a normal double
/// (>= 1e-3 * 2^-1000) and so do gravity and the loads it scales.
inline constexpr int largest_time_exponent = 500;

/// The fastest speed of `spec` in rad/s or mm/s (`seconds_per`: seconds per time unit of the
/// model): its drivers' constant speeds and profile points and its initial velocities; 0 for
/// none.
inline double fastest_speed(const SimulationSpec& spec, double seconds_per) {
  double fastest = 0;
  for (const auto& driver : spec.drivers) {
    fastest = std::max(fastest, std::abs(driver.speed.get_d()));
    for (const auto& point : driver.profile) fastest = std::max(fastest, std::abs(point.second.get_d()));
  }
  for (const auto& velocity : spec.velocities) fastest = std::max(fastest, std::abs(velocity.value.get_d()));
  return fastest / seconds_per;
}

/// The exponent e of the internal time unit 2^-e s for a fastest speed `speed` (rad/s or mm/s):
/// 0 below 2^12 or for a non-finite speed, else ilogb(speed), so that the internal speed
/// speed 2^-e lies in [1, 2); at most largest_time_exponent (a driver beyond 2^500 rad/s is
/// refused unless its part's reach is below 1e-150 mm: its internal speed stays far inside the
/// doubles).
inline int time_exponent(double speed) {
  if (!std::isfinite(speed) || !(speed >= std::ldexp(1.0, rescaled_speed_exponent))) return 0;
  return std::min(std::ilogb(speed), largest_time_exponent);
}

}  // namespace hipair::simulation
