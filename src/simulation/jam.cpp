// HIPAIR — the exact jam test of contact rows against constant-speed drivers (jam.hpp).
#include "simulation/jam.hpp"

#include "simulation/exact_lp.hpp"

#include <sstream>

namespace hipair::simulation {

std::optional<std::vector<std::size_t>> locking_rows(const std::vector<std::vector<Rational>>& a,
                                                     const std::vector<Rational>& d) {
  if (a.empty() || a.size() != d.size()) return std::nullopt;
  ExactLinearSystem lp;
  lp.variables = a.size();
  lp.nonnegative.assign(a.size(), true);
  for (std::size_t k = 0; k < a.front().size(); ++k) {   // sum y_i a_ik = 0 on every free coordinate
    std::vector<Rational> row;
    bool any = false;
    for (const std::vector<Rational>& r : a) {
      row.push_back(r[k]);
      any = any || sgn(r[k]) != 0;
    }
    if (!any) continue;
    lp.rows.push_back(std::move(row));
    lp.rhs.emplace_back(0);
    lp.equality.push_back(true);
  }
  lp.rows.push_back(d);   // sum y_i d_i = -1 (< 0, scaled)
  lp.rhs.emplace_back(-1);
  lp.equality.push_back(true);
  const std::optional<std::vector<Rational>> y = exact_feasible_point(lp);
  if (!y) return std::nullopt;
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < y->size(); ++i)
    if (sgn((*y)[i]) > 0) out.push_back(i);
  return out;
}

namespace {

std::string quoted(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i)
    out += (i ? (i + 1 == names.size() ? "' and '" : "', '") : "'") + names[i];
  return out + "'";
}

}  // namespace

std::string jam_message(const std::vector<std::string>& drivers, bool constant, const std::vector<std::string>& jammed,
                        std::size_t count, const std::vector<std::string>& contacts, const std::string& decided) {
  std::ostringstream out;
  out << "the " << (constant ? "constant-speed" : "prescribed") << " driver" << (drivers.size() > 1 ? "s " : " ")
      << quoted(drivers) << (drivers.size() > 1 ? " jam " : " jams ") << quoted(jammed)
      << " (a jam): no motion of the free parts keeps its " << count << " contacts [";
  for (std::size_t i = 0; i < contacts.size(); ++i) out << (i ? "; " : "") << contacts[i];
  out << "] (" << decided << ": a nonnegative combination of their normals vanishes on every free "
      << "coordinate and the driver closes it), and " << (constant ? "a driver at constant speed" : "a prescribed driver")
      << " cannot give way";
  return out.str();
}

}  // namespace hipair::simulation
