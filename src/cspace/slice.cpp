// C-space slicer: 1-D slices of a built hipair::CSpace for the kinematic analysis, read from
// its contact edges and cells (public API plus the implementation accessors).
#include "kinematics/slice.hpp"

#include <hipair/error.hpp>

namespace hipair::kinematics_detail {

std::unique_ptr<PairSlicer> make_cspace_slicer(const Model&, const CSpace&, std::size_t, std::size_t) {
  throw GeometryError("C-space slices are not available yet");
}

}  // namespace hipair::kinematics_detail
