// Minimal reproduction of a CGAL 5.5.1 failure (docs/cspace.md, "A CGAL failure and its guard"),
// CGAL alone, no HIPAIR code. Not part of the build; compile and run by hand:
//   g++ -std=c++17 -O1 -DCGAL_USE_GMP -DCGAL_USE_MPFR -DCGAL_USE_MPFI \
//       tests/arrangement/cgal_incremental_duplicate_vertex.cpp -lgmpxx -lgmp -lmpfr -lmpfi
//   ./a.out inc 01    -> "are_vertices_unique" check violation: (0, 0) is two vertices
//   ./a.out inc 0123  -> CGAL precondition violation
//   ./a.out agg 0123  -> valid (the sweep); ./a.out inc 10 -> valid (the other order)
// g1 and g2 are tangent at (0, 0), both with a vertical tangent there; curve 2 is that tangent
// line, curve 3 crosses through (0, 0).
#include <CGAL/Arr_algebraic_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Gmpz.h>

#include <iostream>
#include <string>
#include <vector>

using Traits = CGAL::Arr_algebraic_segment_traits_2<CGAL::Gmpz>;
using Arrangement = CGAL::Arrangement_2<Traits>;
using Polynomial_2 = Traits::Polynomial_2;
using Curve = Traits::Curve_2;

int main(int argc, char** argv) {
  Traits traits;
  const Polynomial_2 x = CGAL::shift(Polynomial_2(1), 1, 0), y = CGAL::shift(Polynomial_2(1), 1, 1);
  const std::vector<Polynomial_2> polynomials = {
      -x * x * y * y - x * x * y - 2 * x * x + 2 * x * y * y + 2 * x * y + 2 * x - 3 * y * y,
      -x * x * y * y - x * x * y + 10 * x * x + 2 * x * y * y + 38 * x * y + 2 * x + 24 * y * y,
      x,
      -3 * x * x * y + 2 * x * x - 2 * x * y * y + 3 * x * y - x + y * y + 3 * y};
  const std::string mode = argc > 1 ? argv[1] : "inc";
  const std::string order = argc > 2 ? argv[2] : "01";
  std::vector<Curve> curves;
  for (char c : order) curves.push_back(traits.construct_curve_2_object()(polynomials.at(c - '0')));
  Arrangement arrangement(&traits);
  if (mode == "agg") {
    CGAL::insert(arrangement, curves.begin(), curves.end());
  } else {
    for (const auto& curve : curves) CGAL::insert(arrangement, curve);
  }
  std::cout << "valid " << arrangement.is_valid() << ", " << arrangement.number_of_vertices() << " vertices\n";
  for (auto v = arrangement.vertices_begin(); v != arrangement.vertices_end(); ++v) {
    if (v->is_at_open_boundary()) continue;
    const auto p = v->point().to_double();
    std::cout << "  (" << p.first << ", " << p.second << ") degree " << v->degree() << "\n";
  }
  return 0;
}
