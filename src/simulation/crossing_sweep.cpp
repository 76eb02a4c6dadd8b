#include "simulation/crossing_sweep.hpp"

#include <hipair/crossing_before.hpp>

#include <optional>

namespace hipair::simulation {

namespace {

// a crossing's bracket in doubles as the step takes it (a start in contact: 0); false for an
// answer without one
bool bracket(const MotionCrossing& c, double& lower, double& upper) {
  if (c.status != CrossingStatus::crossing && c.status != CrossingStatus::starts_in_contact) return false;
  lower = c.status == CrossingStatus::starts_in_contact ? 0.0 : c.u_lower.get_d();
  upper = c.status == CrossingStatus::starts_in_contact ? 0.0 : c.u_upper.get_d();
  return true;
}

}  // namespace

SweptCrossings sweep_crossings(const std::vector<const CSpace*>& spaces, const std::vector<MotionPath>& paths,
                               const CrossingOptions& options, double u_end, const CrossingLimitRule& limit_rule) {
  const std::size_t n = spaces.size();
  SweptCrossings out;
  out.answers.resize(n);
  out.stopped.assign(n, 0);
  std::vector<std::optional<CrossingQuery>> queries(n);
  double first_lower = u_end;
  bool found = false;
  Rational limit;
  auto take = [&](std::size_t pair) {
    out.answers[pair] = queries[pair]->answer();
    double lower, upper;
    if (bracket(out.answers[pair], lower, upper) && (!found || lower < first_lower)) {
      first_lower = lower;
      limit = limit_rule ? limit_rule(lower, upper) : Rational(upper);
      found = true;
    }
  };
  for (std::size_t pair = 0; pair < n; ++pair) {
    if (!spaces[pair]) continue;
    queries[pair].emplace(*spaces[pair], paths[pair], options);
    queries[pair]->step();   // the start
    if (queries[pair]->finished()) take(pair);
  }
  for (;;) {
    std::size_t first = n;
    for (std::size_t pair = 0; pair < n; ++pair)
      if (queries[pair] && !queries[pair]->finished() && (first == n || queries[pair]->next() < queries[first]->next()))
        first = pair;
    if (first == n || (found && queries[first]->next() > limit)) break;
    queries[first]->step();
    if (queries[first]->finished()) take(first);
  }
  for (std::size_t pair = 0; pair < n; ++pair)
    if (queries[pair] && !queries[pair]->finished()) ++out.limited;
  for (bool resumed = true; resumed;) {
    resumed = false;
    // the step's earliest crossing from the finished answers (as the step finds it)
    double final_lower = u_end, final_upper = u_end;
    for (std::size_t pair = 0; pair < n; ++pair) {
      double lower, upper;
      if (!queries[pair] || !queries[pair]->finished() || !bracket(out.answers[pair], lower, upper)) continue;
      if (lower < final_lower) {
        final_lower = lower;
        final_upper = upper;
      }
    }
    for (std::size_t pair = 0; pair < n; ++pair)
      if (queries[pair] && !queries[pair]->finished() && !(queries[pair]->next().get_d() > final_upper)) {
        ++out.resumed;
        queries[pair]->run();
        out.answers[pair] = queries[pair]->answer();
        resumed = true;
      }
  }
  for (std::size_t pair = 0; pair < n; ++pair)
    if (queries[pair] && !queries[pair]->finished()) {
      out.stopped[pair] = 1;
      out.answers[pair] = queries[pair]->answer();
    }
  return out;
}

}  // namespace hipair::simulation
