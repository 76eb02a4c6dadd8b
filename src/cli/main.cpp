#include "cli/commands.hpp"

#include <hipair/error.hpp>
#include <hipair/rational.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <new>

#include <malloc.h>

// The command's operator new and delete: blocks of up to 512 bytes are kept for reuse in
// per-thread free lists by size class (16-byte steps) instead of going back to malloc at
// once. CGAL's algebraic kernel creates and releases millions of small handles and vectors;
// glibc's per-thread cache holds only 7 blocks per size, so most releases took malloc's slow
// path (measured on the Geneva C-space build: docs/performance.md). Every block comes from
// malloc and goes back to free() when its class already keeps 64 KB, at thread exit, or
// when it was not allocated here (its class follows malloc's usable size, so any block
// malloc handed out is safe to reuse for the class it is filed under).
namespace {

constexpr std::size_t block_step = 16;
constexpr std::size_t block_classes = 32;   // blocks up to 512 bytes
constexpr std::size_t class_bytes = std::size_t{64} << 10;

struct BlockNode {
  BlockNode* next;
};

// Trivially destructible: usable during thread and process exit, after the guard emptied it.
struct BlockLists {
  BlockNode* heads[block_classes];
  std::size_t counts[block_classes];
  bool registered;
  bool closed;
};
thread_local BlockLists block_lists{};

struct BlockListsGuard {
  ~BlockListsGuard() {
    BlockLists& lists = block_lists;
    lists.closed = true;
    for (std::size_t c = 0; c < block_classes; ++c) {
      while (BlockNode* node = lists.heads[c]) {
        lists.heads[c] = node->next;
        std::free(node);
      }
      lists.counts[c] = 0;
    }
  }
};
thread_local BlockListsGuard block_lists_guard;

void* allocate_block(std::size_t size) {
  if (size == 0) size = 1;
  if (size <= block_step * block_classes) {
    BlockLists& lists = block_lists;
    const std::size_t c = (size + block_step - 1) / block_step - 1;
    if (BlockNode* node = lists.heads[c]) {
      lists.heads[c] = node->next;
      --lists.counts[c];
      return node;
    }
    size = (c + 1) * block_step;
  }
  for (;;) {
    if (void* p = std::malloc(size)) return p;
    std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}

void release_block(void* p) noexcept {
  if (!p) return;
  BlockLists& lists = block_lists;
  if (!lists.closed) {
    const std::size_t usable = malloc_usable_size(p);
    if (usable >= block_step) {
      if (!lists.registered) {
        lists.registered = true;
        (void)&block_lists_guard;   // constructs the guard: the lists are emptied at thread exit
      }
      const std::size_t c = std::min(usable / block_step, block_classes) - 1;
      if (lists.counts[c] * (c + 1) * block_step < class_bytes) {
        auto* node = static_cast<BlockNode*>(p);
        node->next = lists.heads[c];
        lists.heads[c] = node;
        ++lists.counts[c];
        return;
      }
    }
  }
  std::free(p);
}

}  // namespace

void* operator new(std::size_t size) { return allocate_block(size); }
void* operator new[](std::size_t size) { return allocate_block(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return allocate_block(size);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return allocate_block(size);
  } catch (...) {
    return nullptr;
  }
}
void operator delete(void* p) noexcept { release_block(p); }
void operator delete[](void* p) noexcept { release_block(p); }
void operator delete(void* p, std::size_t) noexcept { release_block(p); }
void operator delete[](void* p, std::size_t) noexcept { release_block(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { release_block(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { release_block(p); }

int main(int argc, char** argv) {
  // out of memory inside GMP (and MPFR, CGAL) becomes std::bad_alloc: exit 4, not an abort
  hipair::use_throwing_gmp_allocation();
  CLI::App app{
      "HIPAIR: exact contact analysis of planar mechanisms from configuration spaces.\n"
      "Models are JSON files (see docs/model-format.md)."};
  app.set_version_flag("--version", "hipair 0.1.0");
  app.require_subcommand(1);
  hipair::cli::Action action;
  hipair::cli::register_validate(app, action);
  hipair::cli::register_show(app, action);
  hipair::cli::register_analyze(app, action);
  hipair::cli::register_certify(app, action);
  hipair::cli::register_cspace(app, action);
  hipair::cli::register_tolerance(app, action);
  hipair::cli::register_simulate(app, action);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    return action ? action() : 0;
  } catch (const hipair::ModelError& e) {
    std::cerr << "hipair: error: " << e.what() << "\n";
    return 2;
  } catch (const hipair::Error& e) {
    std::cerr << "hipair: error: " << e.what() << "\n";
    return 3;
  } catch (const std::bad_alloc&) {
    std::cerr << "hipair: error: out of memory (the computation needs more memory than the process may use)\n";
    return 4;
  } catch (const std::exception& e) {
    std::cerr << "hipair: internal error: " << e.what() << "\n";
    return 5;
  }
}
