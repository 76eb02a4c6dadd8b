// HIPAIR — kernels::contact_frame in exact rationals, defined wherever the frame is (session 73).
//
// contact_frame (contact_geometry.hpp) of two arcs divides by the squared distance of their
// centres. Concentric arcs of one radius (a pin in a hole of exactly its radius, at the fit)
// touch along the whole circle: no contact point or normal, and in GMP rationals the division by
// zero traps (SIGFPE). Enclosures and doubles divide without trapping (an unbounded interval,
// inf / NaN), so only the exact callers need this guard: CSpace::contact_at, exact_contact_frame
// and sliced_contact_frame.
#pragma once

#include "kernels/contact_geometry.hpp"

#include <gmpxx.h>

namespace hipair::kernels {

/// Whether features fa (of the part at pose a) and fb (at pose b) are two arcs whose centres
/// coincide, decided exactly.
inline bool concentric_arcs(const Pose<mpq_class>& a, const FeatureGeometry<mpq_class>& fa, const Pose<mpq_class>& b,
                            const FeatureGeometry<mpq_class>& fb) {
  if (fa.shape != FeatureShape::arc || fb.shape != FeatureShape::arc) return false;
  const Vector<mpq_class> d = world_point(b, fb.center) - world_point(a, fa.center);
  return sgn(d.x) == 0 && sgn(d.y) == 0;
}

/// contact_frame in rationals; undefined (frame.defined false) for concentric arcs.
inline ContactFrame<mpq_class> contact_frame_rational(const Pose<mpq_class>& a, const FeatureGeometry<mpq_class>& fa,
                                                      const Pose<mpq_class>& b, const FeatureGeometry<mpq_class>& fb) {
  if (concentric_arcs(a, fa, b, fb)) return ContactFrame<mpq_class>{};
  return contact_frame(a, fa, b, fb);
}

}  // namespace hipair::kernels
