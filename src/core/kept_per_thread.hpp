// Objects kept per thread for reuse: a query made and freed thousands of times (the simulation's
// crossing queries) hands its block or its scratch objects back here instead of to the allocator,
// and the next query on the thread takes them again. At most N per thread; T::dispose(T*) frees
// one for good (when N are kept already, or at the thread's exit). What a taken object still
// holds is the previous user's: the taker resets whatever it reads before writing.
// One handed back on another thread joins that thread's objects. A thread's objects are disposed
// of at its exit; one handed back after that (a static destroyed late) is disposed of at once.
#pragma once

#include <array>
#include <cstddef>

namespace hipair {

template <class T, std::size_t N>
class KeptPerThread {
 public:
  // a kept object, or nullptr (none kept)
  static T* take() noexcept {
    Slots& kept = slots_;
    return kept.count > 0 ? kept.item[--kept.count] : nullptr;
  }
  // kept (true), or left to the caller to dispose of (false: N kept, or the thread is ending)
  static bool keep(T* p) noexcept {
    Slots& kept = slots_;
    if (kept.closed || kept.count == N) return false;
    (void)&release_;   // (its first use on this thread registers the release at the thread's exit)
    kept.item[kept.count++] = p;
    return true;
  }
  static std::size_t kept() noexcept { return slots_.count; }

 private:
  // (trivially destructible: usable until the thread's very end; `release_` empties it first)
  struct Slots {
    std::array<T*, N> item;
    std::size_t count;
    bool closed;
  };
  struct Release {
    ~Release() {
      Slots& kept = slots_;
      kept.closed = true;
      while (kept.count > 0) T::dispose(kept.item[--kept.count]);
    }
  };
  static thread_local Slots slots_;
  static thread_local Release release_;
};

template <class T, std::size_t N>
thread_local typename KeptPerThread<T, N>::Slots KeptPerThread<T, N>::slots_{};
template <class T, std::size_t N>
thread_local typename KeptPerThread<T, N>::Release KeptPerThread<T, N>::release_;

}  // namespace hipair
