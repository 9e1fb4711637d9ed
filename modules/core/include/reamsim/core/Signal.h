#pragma once
// Minimal observer list with RAII subscriptions (no Qt). Single-threaded.
// Re-entrancy rules, relied on by Document:
//  - an observer disconnected during an emission is not called again, not even later in that emission;
//  - an observer connected during an emission is first called by the next emission;
//  - a Subscription may outlive its Signal (disconnecting then does nothing).
#include <cstdint>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace reamsim {

namespace detail {
struct SignalStateBase {
  virtual ~SignalStateBase() = default;
  virtual void disconnect(std::uint64_t slotId) = 0;
};
}  // namespace detail

// Owning handle of one connection: destroying or reset()ing it disconnects. Move-only.
class [[nodiscard]] Subscription {
 public:
  Subscription() = default;
  Subscription(std::weak_ptr<detail::SignalStateBase> state, std::uint64_t slotId)
      : state_(std::move(state)), slotId_(slotId) {}
  Subscription(Subscription&& o) noexcept : state_(std::move(o.state_)), slotId_(o.slotId_) { o.slotId_ = 0; }
  Subscription& operator=(Subscription&& o) noexcept {
    if (this != &o) {
      reset();
      state_ = std::move(o.state_);
      slotId_ = o.slotId_;
      o.slotId_ = 0;
    }
    return *this;
  }
  Subscription(const Subscription&) = delete;
  Subscription& operator=(const Subscription&) = delete;
  ~Subscription() { reset(); }

  void reset() {
    if (auto s = state_.lock(); s && slotId_ != 0) s->disconnect(slotId_);
    state_.reset();
    slotId_ = 0;
  }
  bool connected() const { return slotId_ != 0 && !state_.expired(); }

 private:
  std::weak_ptr<detail::SignalStateBase> state_;
  std::uint64_t slotId_ = 0;
};

template <class... Args>
class Signal {
 public:
  using Callback = std::function<void(Args...)>;

  Subscription connect(Callback callback) {
    auto slot = std::make_shared<Slot>(Slot{state_->nextId++, std::move(callback), true});
    state_->slots.push_back(slot);
    return Subscription(state_, slot->id);
  }

  void emit(const Args&... args) const {
    // Hold the state and each slot by shared_ptr: callbacks may connect (reallocating the vector) or
    // disconnect (erasing slots) while we iterate.
    const std::shared_ptr<State> state = state_;
    const std::size_t count = state->slots.size();  // observers added during this emission wait
    ++state->emitting;
    struct Guard {
      State& s;
      ~Guard() {
        if (--s.emitting == 0) s.compact();
      }
    } guard{*state};
    for (std::size_t i = 0; i < count && i < state->slots.size(); ++i) {
      const std::shared_ptr<Slot> slot = state->slots[i];
      if (slot->active) slot->callback(args...);
    }
  }

  std::size_t observerCount() const {
    std::size_t n = 0;
    for (const auto& s : state_->slots) n += s->active ? 1 : 0;
    return n;
  }

 private:
  struct Slot {
    std::uint64_t id;
    Callback callback;
    bool active;
  };
  struct State final : detail::SignalStateBase {
    std::vector<std::shared_ptr<Slot>> slots;
    std::uint64_t nextId = 1;
    int emitting = 0;
    void disconnect(std::uint64_t slotId) override {
      for (auto& s : slots)
        if (s->id == slotId) s->active = false;
      if (emitting == 0) compact();  // during an emission, erasing would shift the indices being walked
    }
    void compact() {
      std::vector<std::shared_ptr<Slot>> kept;
      kept.reserve(slots.size());
      for (auto& s : slots)
        if (s->active) kept.push_back(std::move(s));
      slots = std::move(kept);
    }
  };
  std::shared_ptr<State> state_ = std::make_shared<State>();
};

}  // namespace reamsim
