// HIPAIR — the exact jam test of a set of contact rows against constant-speed drivers (session
// 69, jam69; film68's `refuse_jam`, shared by the pin-slot and the planar simulators). Internal
// to src/simulation.
#pragma once

#include <hipair/rational.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace hipair::simulation {

/// Contact rows whose normal speed is a_i . q' + d_i (>= 0: apart), q' the free coordinates'
/// rates and d_i the share of the prescribed motions (the constant-speed drivers' surface speeds
/// along the normal). No q' keeps every row's speed >= 0 exactly when (Farkas) some y >= 0 has
/// sum y_i a_i = 0 and sum y_i d_i < 0: the rows of that combination lock the free coordinates and
/// the drivers close them — a jam. Decided exactly (CGAL's exact LP, exact_feasible_point, on
/// y >= 0, sum y_i a_i = 0, sum y_i d_i = -1). Returns the rows with y_i > 0 of one such
/// combination, or nullopt when there is none (no jam). Every a_i has the same length.
std::optional<std::vector<std::size_t>> locking_rows(const std::vector<std::vector<Rational>>& a,
                                                     const std::vector<Rational>& d);

/// The jam's message after the simulator's "where": "the constant-speed driver 'cam' jams
/// 'follower' (a jam): no motion of the free parts keeps its N contacts [c1; c2; ...] (`decided`:
/// a nonnegative combination of their normals vanishes on every free coordinate and the driver
/// closes it), and a driver at constant speed cannot give way" — several drivers or parts listed
/// "'a', 'b' and 'c'"; `constant` false: "prescribed driver", "a prescribed driver cannot give
/// way". `decided`: "decided exactly" (the rows' exact normals), or how an approximate verdict was found.
std::string jam_message(const std::vector<std::string>& drivers, bool constant, const std::vector<std::string>& jammed,
                        std::size_t count, const std::vector<std::string>& contacts,
                        const std::string& decided = "decided exactly");

}  // namespace hipair::simulation
