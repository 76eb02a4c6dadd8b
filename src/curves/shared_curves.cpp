// Contact curves shared between the curve generators of one thread while a
// SharedContactCurves lives (include/hipair/shared_curves.hpp).
#include <hipair/shared_curves.hpp>

#include "core/model_equal.hpp"
#include "curves/formed_store.hpp"

#include <vector>

namespace hipair {

struct SharedContactCurves::Impl {
  struct Group {
    std::shared_ptr<const Model> model;   // a copy: the generators' own models may go first
    cspace::PairAxes axes;
    bool cull_blocked_space = true;
    std::shared_ptr<cspace::FormedStore> store;
  };
  std::mutex mutex;   // the groups (a store has its own mutex for its curves)
  std::vector<Group> groups;
  std::shared_ptr<std::atomic<std::size_t>> reused = std::make_shared<std::atomic<std::size_t>>(0);
  Impl* previous = nullptr;   // the scope that was innermost on this thread before this one
  Impl** head = nullptr;      // the creating thread's innermost scope (its thread_local)
};

namespace {
thread_local SharedContactCurves::Impl* innermost = nullptr;
}  // namespace

SharedContactCurves::SharedContactCurves() : impl_(std::make_unique<Impl>()) {
  impl_->previous = innermost;
  impl_->head = &innermost;
  innermost = impl_.get();
}

// Unlinked from its thread's chain of scopes wherever it is in it (a scope need not be the
// innermost when it ends).
SharedContactCurves::~SharedContactCurves() {
  for (Impl** link = impl_->head; *link; link = &(*link)->previous)
    if (*link == impl_.get()) {
      *link = impl_->previous;
      break;
    }
}

std::size_t SharedContactCurves::reused() const { return impl_->reused->load(); }

std::size_t SharedContactCurves::groups() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->groups.size();
}

namespace cspace {

std::shared_ptr<FormedStore> formed_store(const Model& model, const PairAxes& axes, bool cull_blocked_space) {
  SharedContactCurves::Impl* scope = innermost;
  if (!scope) return std::make_shared<FormedStore>();
  std::lock_guard<std::mutex> lock(scope->mutex);
  std::shared_ptr<const Model> copy;
  for (const SharedContactCurves::Impl::Group& group : scope->groups) {
    if (!copy && same_model(*group.model, model)) copy = group.model;
    if (copy == group.model && group.axes.first == axes.first && group.axes.second == axes.second &&
        group.axes.first_moves == axes.first_moves && group.axes.second_moves == axes.second_moves &&
        group.cull_blocked_space == cull_blocked_space)
      return group.store;
  }
  if (!copy) copy = std::make_shared<const Model>(model);
  auto store = std::make_shared<FormedStore>();
  store->reused = scope->reused;
  scope->groups.push_back({std::move(copy), axes, cull_blocked_space, store});
  return store;
}

}  // namespace cspace
}  // namespace hipair
