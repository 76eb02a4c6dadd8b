// Whole turns of an unlimited rotating coordinate, removed exactly (session 61, issue 11).
//
// The fixed-axis simulator carries each rotating coordinate in a double. A driver or a wheel that
// turns without end grows without bound, and the double loses one bit of the angle within the turn
// for every doubling: at 18 929 rad one unit in the last place is 3.6e-12 rad, coarser than the
// contact handling's own scales (a contact taken up within 1e-12 chart units of a vertex, nudges
// of a few units in the last place), and the Geneva drive at 10^6 rad/s jammed there. The
// simulator therefore takes the whole turns out of such a coordinate at step boundaries: the
// physical angle is r + 2 pi n with r the double it integrates and n an exact integer kept beside
// it. reduce_turns computes (n, r) from an exact rational angle with pi to as many bits as the
// angle's size needs (MPFR at |x|'s exponent + 128 bits), so r is the angle's residue rounded once
// to the nearest double (not the double residue std::remainder(x, 2 pi) of a rounded 2 pi, which
// is off by n x 2.4e-16 rad); add_turns gives back r + 2 pi n rounded once, for the published state.
#pragma once

#include <hipair/rational.hpp>

namespace hipair::simulation {

struct ReducedAngle {
  Rational turns;   // n, an integer
  double angle;     // r, the nearest double to x - 2 pi n, with |x - 2 pi n| <= pi
};

// x = 2 pi n + r, n = the nearest integer to x / (2 pi)
ReducedAngle reduce_turns(const Rational& x);

// x - 2 pi n, rounded once to the nearest double (n an integer)
double minus_turns(const Rational& x, const Rational& turns);

// r + 2 pi n rounded once to the nearest double (n an integer; r when n = 0 or r is not finite)
double add_turns(double r, const Rational& turns);

}  // namespace hipair::simulation
