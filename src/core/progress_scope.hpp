// A progress hook for the calling thread's inner work: a stage that reports progress (the
// tolerance command's bar, src/tolerance/progress.hpp) installs one with ProgressScope for the
// duration of a call whose interface has no hook (a C-space build: include/hipair/cspace.hpp's
// options stay as they are), and the work inside reports its own fraction done with
// report_progress. Fractions are the reporter's, in [0, 1]; the installer maps and filters them
// (StagedProgress passes on only growing values). Work on other threads reports nothing: the
// hook is the installing thread's. Without a scope, report_progress does nothing.
#pragma once

#include <functional>
#include <utility>

namespace hipair {

namespace progress_detail {
inline const std::function<void(double)>*& installed_hook() {
  thread_local const std::function<void(double)>* hook = nullptr;
  return hook;
}
}  // namespace progress_detail

/// Installs `hook` (empty: none, which also hides an outer scope's) for this thread until the
/// scope ends; the previous hook is restored then.
class ProgressScope {
 public:
  explicit ProgressScope(std::function<void(double)> hook)
      : hook_(std::move(hook)), previous_(progress_detail::installed_hook()) {
    progress_detail::installed_hook() = hook_ ? &hook_ : nullptr;
  }
  ~ProgressScope() { progress_detail::installed_hook() = previous_; }
  ProgressScope(const ProgressScope&) = delete;
  ProgressScope& operator=(const ProgressScope&) = delete;

 private:
  std::function<void(double)> hook_;
  const std::function<void(double)>* previous_;
};

/// Whether this thread has a hook (work may skip counting its units otherwise).
inline bool progress_wanted() { return progress_detail::installed_hook() != nullptr; }

/// Passes `fraction` (this work's own, in [0, 1]) to this thread's hook, if any.
inline void report_progress(double fraction) {
  if (const auto* hook = progress_detail::installed_hook()) (*hook)(fraction);
}

}  // namespace hipair
