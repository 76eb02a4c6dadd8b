// Per-thread switches and counters of the exact fast paths (memos, filters, limits: each header
// that declares one says what it switches, e.g. cspace/angle_memo.hpp): a switch is on by
// default and a test turns it off on its own thread to compare the answers with and without the
// fast path; a counter counts how often the fast path answered on this thread (tests,
// profiling). `Tag` makes each switch and counter its own thread_local variable.
#pragma once

#include <cstddef>

namespace hipair {

template <class Tag>
bool& thread_switch() {
  thread_local bool on = true;
  return on;
}

template <class Tag>
std::size_t& thread_counter() {
  thread_local std::size_t count = 0;
  return count;
}

}  // namespace hipair
