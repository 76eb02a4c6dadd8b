// The contact frames of the simulator's Coulomb rows, remembered within a step
// (simulation.cpp, Simulation::Impl::friction_of; docs/simulation.md#friction).
//
// friction_of asks CSpace::contact_frame for every feature pair of a held (or struck) frictional
// contact at the configuration of the call: an exact frame (the configuration's doubles are
// rationals) whose cost dominates the friction rows. A step asks it several times at the same
// configuration: the step-start complementarity problem and the held (bilateral) forces at the
// start, the integrator's first stage there, the accepted trial's last stage and the forces at
// its end, the impacts at a crossing. The frame is a function of the pair's C-space (built once,
// immutable), the feature pair and the two part coordinates, which friction_of derives from the
// doubles of the pair's two coordinates alone; so an entry keyed by (pair, feature pair, the bit
// patterns of those doubles) is the frame itself, and what friction_of takes from it (the
// midpoints of the point's and the unit normal's certified enclosures, or "no frame": undefined
// or throwing) is stored as it would be computed. The cache is emptied at each step's start
// (entries never go stale; emptying only bounds it) and when it grows past `capacity`.
//
// Switch simulation::frame_cache() (on by default; tests turn it off on their thread to compare
// runs bit for bit, SimulationFrameCache.*); counters frame_cache_hits(), frame_cache_misses().
#pragma once

#include "core/thread_switch.hpp"

#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace hipair::simulation {

struct FrameCacheTag;
inline bool& frame_cache() { return thread_switch<FrameCacheTag>(); }
// Switch simulation::frame_doubles() (on by default): friction_of makes a missed frame by
// contact_frame_ranges (hipair/contact_frame_doubles.hpp: the same ranges from the
// configuration's doubles, no rationals) instead of CSpace::contact_frame; tests turn it off on
// their thread to compare runs bit for bit (SimulationFrameDoubles.*).
struct FrameDoublesTag;
inline bool& frame_doubles() { return thread_switch<FrameDoublesTag>(); }
struct FrameCacheHitsTag;
inline std::size_t& frame_cache_hits() { return thread_counter<FrameCacheHitsTag>(); }
struct FrameCacheMissesTag;
inline std::size_t& frame_cache_misses() { return thread_counter<FrameCacheMissesTag>(); }

// What friction_of takes from one contact frame.
struct FrameSample {
  bool defined = false;                // false: contact_frame gave no frame or threw
  double point[2] = {0, 0};            // mid of the point's certified enclosure
  double normal[2] = {0, 0};           // mid of the unit normal's certified enclosure
};

class FrameCache {
 public:
  static constexpr std::size_t capacity = 512;

  // The sample of (pair, feature) at part coordinates x, y (y: 0 for a 1-D pair): remembered,
  // or compute() (a FrameSample) remembered now. With the switch off, always compute().
  template <class Compute>
  FrameSample get(std::size_t pair, std::size_t feature, double x, double y, const Compute& compute) {
    if (!frame_cache()) return compute();
    const std::uint64_t bx = std::bit_cast<std::uint64_t>(x), by = std::bit_cast<std::uint64_t>(y);
    for (const Entry& e : entries_)
      if (e.x == bx && e.y == by && e.feature == feature && e.pair == pair) {
        ++frame_cache_hits();
        return e.sample;
      }
    ++frame_cache_misses();
    FrameSample sample = compute();
    if (entries_.size() >= capacity) entries_.clear();
    entries_.push_back(Entry{pair, feature, bx, by, sample});
    return sample;
  }
  void clear() { entries_.clear(); }
  std::size_t size() const { return entries_.size(); }

 private:
  struct Entry {
    std::size_t pair, feature;
    std::uint64_t x, y;
    FrameSample sample;
  };
  std::vector<Entry> entries_;
};

}  // namespace hipair::simulation
