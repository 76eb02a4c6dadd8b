// The mean-value composition of an assembly chain's certified band (chain.cpp compose_over;
// docs/tolerance.md "Assembly chains", session 22): the arithmetic on the enclosures, apart
// from where they come from, so that tests can drive it with chains of their own.
//
// V_k(p), pair k's output as a function of the parameters alone, its driver t_k = phi_k(V_k-1(p))
// moved by the pair before: over a box B with centre c,
//   V_k(p) in V_k(c) + sum_i D_k,i [B_i - c_i],
//   D_k,i = G_k,i + G_k,t phi_k' D_k-1,i   (D_1,i = G_1,i),
// with G_k,i, G_k,t enclosing dv_k/dp_i and dv_k/dt_k over B x Y_k x T_k (any region holding
// (p, V_k(p), t_k(p)) for every p in B) and phi_k' enclosing phi_k' over Y_k-1: the chain rule
// gives D_k,i as an enclosure of dV_k/dp_i over B, and the mean-value theorem on the segment
// from c to p the form. Every operation is outward rounded (kernels::Interval).
#pragma once

#include "tolerance/solver.hpp"

#include <algorithm>
#include <vector>

namespace hipair::tolerance_detail {

/// The box's centre (a double inside it) and B_i - c_i per parameter, outward rounded (exactly
/// 0 for a parameter that does not vary in the box).
inline void box_offsets(const Box& box, std::vector<double>& center, std::vector<Interval>& offsets) {
  std::size_t n = box.lo.size();
  center.assign(n, 0.0);
  offsets.assign(n, Interval(0));
  for (std::size_t p = 0; p < n; ++p) {
    center[p] = 0.5 * (box.lo[p] + box.hi[p]);
    if (!(center[p] >= box.lo[p] && center[p] <= box.hi[p])) center[p] = box.lo[p];   // overflow of lo + hi
    if (box.hi[p] > box.lo[p])
      offsets[p] = kernels::hull(Interval::point(box.lo[p]) - Interval::point(center[p]),
                                 Interval::point(box.hi[p]) - Interval::point(center[p]));
  }
}

/// D_k from the pair's own partials `g` (dv_k/dp_i), `g_t` (dv_k/dt_k), the driver's chart
/// derivative `factor` (phi_k') and D_k-1 (`previous`; null for the chain's first pair).
inline std::vector<Interval> chain_rule(const std::vector<Interval>& g, const Interval& g_t, const Interval& factor,
                                        const std::vector<Interval>* previous) {
  std::vector<Interval> d(g);
  if (previous) {
    Interval through = g_t * factor;
    for (std::size_t p = 0; p < d.size(); ++p) d[p] = d[p] + through * (*previous)[p];
  }
  return d;
}

/// V_k(c) + sum_i D_k,i [B_i - c_i].
inline Interval mean_value_form(const Interval& at_center, const std::vector<Interval>& d,
                                const std::vector<Interval>& offsets) {
  Interval form = at_center;
  for (std::size_t p = 0; p < d.size(); ++p)
    if (!(offsets[p].lo == 0.0 && offsets[p].hi == 0.0)) form = form + d[p] * offsets[p];
  return form;
}

/// R_k's own widening at a widened pair (session 27; chain.cpp compose_over): the follower
/// y_k(p) on the pushed side `side` (+1 or -1) of its holder's root h_k(p), within the
/// envelope, h_k(p) within the holder's enclosure, so y_k(p) - h_k(p) lies in
/// [0, envelope.hi - holder.lo] (side +1) or [envelope.lo - holder.hi, 0] (side -1): added to R.
inline Interval widened_remainder(const Interval& r, const Interval& envelope, const Interval& holder, int side) {
  if (side > 0) return r + Interval(0.0, (Interval::point(envelope.hi) - Interval::point(holder.lo)).hi);
  return r + Interval((Interval::point(envelope.lo) - Interval::point(holder.hi)).lo, 0.0);
}

/// The case split's bound at a widened pair (session 45, chain.cpp compose_over; a function of
/// its enclosures since session 46, so that tests can drive it with chains of their own). Pair
/// k's follower y_k(p) lies between its holder's root h_k(p) and the envelope's far end E (on
/// its pushed side); the pairs s = k+1 .. L after it hold their followers at their holders'
/// roots, y_s = g_s(p, t_s), t_s = phi_s(y_s-1) with phi_s increasing. `slopes`: enclosures of
/// dy_s/dt_s for s = k+1 .. L, each over box x the hull of the two cases' driver ranges x the
/// roots there; `lower` / `upper`: the last pair's enclosures over the box in the case
/// y_k = h_k(p) and in the case y_k = E. If every slope excludes 0, each g_s(p, .) is monotone
/// over its hull region and, by induction along the chain (pair s's driver for any y_k between
/// h_k(p) and E lies between its values in the two cases, so in the hull), the last pair's
/// holder root lies between its values in the two cases: in hull(lower, upper). A slope that
/// may vanish lets the root reach beyond both cases (an extremum between them): no bound
/// (false). `bridge`: the last pair's envelope over its hull region; where it extends on side
/// +1 (-1) the follower may lie beyond its holder on that side, within the bridge, so the hull
/// bounds only the other side (either side, when the side is not certain: the bridge alone).
/// `met` receives the bound (possibly empty: lo > hi).
inline bool case_split_bound(const std::vector<Interval>& slopes, const Interval& lower, const Interval& upper,
                             const Interval& bridge, bool bridge_extended, int bridge_side, Interval& met) {
  for (const Interval& slope : slopes)
    if (!(slope.lo > 0 || slope.hi < 0)) return false;
  const Interval cases = kernels::hull(lower, upper);
  met = Interval(std::max(bridge.lo, bridge_extended && bridge_side < 0 ? bridge.lo : cases.lo),
                 std::min(bridge.hi, bridge_extended && bridge_side > 0 ? bridge.hi : cases.hi));
  if (bridge_extended && bridge_side != 1 && bridge_side != -1) met = bridge;
  return true;
}

}  // namespace hipair::tolerance_detail
