// The C-space adaptor's own access to the internals behind hipair::CSpace (internal: only
// src/cspace includes it; every other layer uses the public queries of hipair/cspace.hpp).
#pragma once

#include <hipair/cspace.hpp>

#include <memory>

namespace hipair {

struct CSpaceAccess {
  static const CSpace::Impl& implementation(const CSpace& space);
  static CSpace make(std::shared_ptr<const CSpace::Impl> impl);
};

/// The internals of a built space. \throws GeometryError for an empty (default) CSpace.
inline const CSpace::Impl& implementation(const CSpace& space) { return CSpaceAccess::implementation(space); }
/// A CSpace sharing `impl`.
inline CSpace make_cspace(std::shared_ptr<const CSpace::Impl> impl) { return CSpaceAccess::make(std::move(impl)); }

}  // namespace hipair
