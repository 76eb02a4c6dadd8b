// Storage recycled per thread for the Taylor models' coefficient vectors (session 70, tol70).
//
// The certified band's Taylor-model jets (jet.hpp, taylor_model.hpp) make a new coefficient
// vector at almost every operation — a product, a scaling, a sum into a fresh model — and free
// one as soon as the operand temporaries die: on the 100-parameter gear train's chain a model
// carries a coefficient for each of up to ~100 variables (1.6 kB), past glibc's per-thread cache
// of small blocks (tcache: up to 1 032 bytes), so that every such vector went through malloc's
// general bins (malloc and free ≈ 14 % of the chain kernel test's time, session 69's profile).
// This allocator keeps freed blocks on per-thread free lists by power-of-two size class and hands
// them out again: only memory management changes, never a value (the same operations on the same
// operands: outputs bit for bit).
//
// Blocks freed by another thread than the one that took them join the freeing thread's lists
// (they came from ::operator new like every other; nothing is per-thread about a block). A
// thread's lists are bounded (`kept` blocks per class) and released at the thread's exit; a block
// freed after that (a static memo destroyed at program exit) goes straight to ::operator delete.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <new>

namespace hipair::tolerance_detail {

namespace recycling_detail {

struct Block {
  Block* next;
};
/// Classes of 64, 128, ... 2^(6 + classes - 1) bytes; larger blocks are not recycled.
constexpr std::size_t smallest_shift = 6;
constexpr std::size_t classes = 14;   // up to 512 kB
/// Blocks kept per class and thread (at most 256 of the largest class ≈ 128 MB would be too
/// many: the bound is on bytes, see limit()).
constexpr std::size_t kept_bytes = std::size_t(4) << 20;   // 4 MB per class and thread
constexpr std::size_t limit(std::size_t k) {
  std::size_t n = kept_bytes >> (smallest_shift + k);
  return n < 4 ? 4 : n;
}

struct Lists {
  Block* head[classes];
  std::uint32_t count[classes];
};
// Trivially destructible (zero-initialised, never destroyed): readable at any time in the thread.
inline thread_local Lists lists{};
inline thread_local bool closed = false;

inline void release_all() noexcept {
  for (std::size_t k = 0; k < classes; ++k) {
    while (Block* b = lists.head[k]) {
      lists.head[k] = b->next;
      ::operator delete(static_cast<void*>(b));
    }
    lists.count[k] = 0;
  }
}
// Its destructor (registered at the thread's first use of it) releases the lists at the thread's exit.
struct Release {
  Release() noexcept {}   // NOLINT(modernize-use-equals-default): non-trivial, so that it is constructed and registered
  ~Release() {
    closed = true;
    release_all();
  }
  Release(const Release&) = delete;
  Release& operator=(const Release&) = delete;
  bool used = false;
};
inline thread_local Release release;

/// The class of a block of `bytes` (> 0), or `classes` when not recycled; its size in `size`.
inline std::size_t class_of(std::size_t bytes, std::size_t& size) {
  std::size_t rounded = std::bit_ceil(bytes < (std::size_t(1) << smallest_shift) ? (std::size_t(1) << smallest_shift) : bytes);
  std::size_t k = static_cast<std::size_t>(std::countr_zero(rounded)) - smallest_shift;
  size = rounded;
  return k;
}

inline void* take(std::size_t bytes) {
  std::size_t size = 0;
  std::size_t k = class_of(bytes, size);
  if (k >= classes) return ::operator new(bytes);
  // (a whole class's size even once closed: another thread may recycle the block)
  if (closed) return ::operator new(size);
  if (Block* b = lists.head[k]) {
    lists.head[k] = b->next;
    --lists.count[k];
    return b;
  }
  release.used = true;   // constructs the thread's Release on its first use, registering its destructor
  return ::operator new(size);
}

inline void give(void* p, std::size_t bytes) noexcept {
  std::size_t size = 0;
  std::size_t k = class_of(bytes, size);
  if (k >= classes || closed || lists.count[k] >= limit(k)) {
    ::operator delete(p);
    return;
  }
  Block* b = static_cast<Block*>(p);
  b->next = lists.head[k];
  lists.head[k] = b;
  ++lists.count[k];
}

}  // namespace recycling_detail

/// std::allocator's interface over recycling_detail::take / give (stateless: every instance equal).
template <class T>
struct RecyclingAllocator {
  using value_type = T;
  RecyclingAllocator() noexcept = default;
  template <class U>
  RecyclingAllocator(const RecyclingAllocator<U>&) noexcept {}   // NOLINT(google-explicit-constructor)
  T* allocate(std::size_t n) {
    if (n == 0) n = 1;
    return static_cast<T*>(recycling_detail::take(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept { recycling_detail::give(p, (n == 0 ? 1 : n) * sizeof(T)); }
  friend bool operator==(const RecyclingAllocator&, const RecyclingAllocator&) noexcept { return true; }
  friend bool operator!=(const RecyclingAllocator&, const RecyclingAllocator&) noexcept { return false; }
};

}  // namespace hipair::tolerance_detail
