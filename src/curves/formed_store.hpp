// The exact contact curves a curve generator has formed, by feature pair and half-turn flags
// (internal; see include/hipair/shared_curves.hpp for when generators share one store).
#pragma once

#include "curves/contact_curves.hpp"

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <unordered_map>

namespace hipair::cspace {

/// One feature pair's answer in a chart kind: its curve, or kept == false when it has none
/// (no contact kernel, a non-zero constant, never valid).
struct FormedCurve {
  bool kept = false;
  ContactCurve curve;
  std::uint64_t maker = 0;   ///< the number of the generator that formed it (counts reuse by another)
};

/// Formed curves keyed by (feature pair index << 2) | half-turn bits; thread safe through
/// `mutex`. `reused` counts curves found that another generator formed.
struct FormedStore {
  std::mutex mutex;
  std::unordered_map<std::uint64_t, std::shared_ptr<const FormedCurve>> curves;
  std::shared_ptr<std::atomic<std::size_t>> reused = std::make_shared<std::atomic<std::size_t>>(0);
};

/// The store a generator for the pair `axes` of `model` with blocked-space setting
/// `cull_blocked_space` uses: the one of an equal model, pair and setting held by the innermost
/// SharedContactCurves alive on this thread, else a new store of its own.
std::shared_ptr<FormedStore> formed_store(const Model& model, const PairAxes& axes, bool cull_blocked_space);

}  // namespace hipair::cspace
