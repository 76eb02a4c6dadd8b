// The C-space adaptor's own access to the internals behind hipair::CSpace (internal: only
// src/cspace includes it; every other layer uses the public queries of hipair/cspace.hpp).
#pragma once

#include <hipair/cspace.hpp>

#include <memory>

namespace hipair {

struct CSpaceAccess {
  static const CSpace::Impl& implementation(const CSpace& space);
  static CSpace make(std::shared_ptr<const CSpace::Impl> impl);
  /// The owning pointer (an identity that outlives reuse of the address: first_crossing's
  /// per-thread start anchors keep a weak_ptr to it).
  static const std::shared_ptr<const CSpace::Impl>& shared(const CSpace& space) { return space.impl_; }
};

/// The internals of a built space. \throws GeometryError for an empty (default) CSpace.
inline const CSpace::Impl& implementation(const CSpace& space) { return CSpaceAccess::implementation(space); }
/// A CSpace sharing `impl`.
inline CSpace make_cspace(std::shared_ptr<const CSpace::Impl> impl) { return CSpaceAccess::make(std::move(impl)); }

}  // namespace hipair
