#pragma once

// An optional value kept out of line, for the per-entity records that every step reads (Entity,
// ControlState): with hundreds of entities the records no longer fit in a core's cache, and a
// step costs the cache lines it reads of each. A field that few entities ever set, but that
// every step tests, takes 16 bytes (a pointer and a flag) in the record's hot part instead of
// the whole value. The interface is std::optional's (the parts the engine uses), so that
// callers read it as one.

#include <memory>
#include <optional>
#include <type_traits>
#include <utility>

namespace corsa::engine::detail {

/// An optional T on the heap. Copies copy the value (a record holding it stays copyable). The
/// storage, once made, is kept for the next value: a value set and reset every step (a pose
/// command) allocates once.
template <class T>
class OutOfLine {
 public:
  OutOfLine() = default;
  OutOfLine(std::nullopt_t) {}  // NOLINT: converts as std::optional does
  OutOfLine(const OutOfLine& other) {
    if (other.engaged_) {
      *this = *other.storage_;
    }
  }
  OutOfLine(OutOfLine&& other) noexcept
      : storage_(std::move(other.storage_)), engaged_(std::exchange(other.engaged_, false)) {}
  OutOfLine& operator=(const OutOfLine& other) {
    if (this != &other) {
      if (other.engaged_) {
        *this = *other.storage_;
      } else {
        reset();
      }
    }
    return *this;
  }
  OutOfLine& operator=(OutOfLine&& other) noexcept {
    storage_ = std::move(other.storage_);
    engaged_ = std::exchange(other.engaged_, false);
    return *this;
  }
  OutOfLine& operator=(std::nullopt_t) {
    reset();
    return *this;
  }
  template <class U>
  requires(!std::is_same_v<std::remove_cvref_t<U>, OutOfLine> &&
           !std::is_same_v<std::remove_cvref_t<U>, std::nullopt_t> &&
           std::is_assignable_v<T&, U&&>) OutOfLine&
  operator=(U&& value) {
    if (storage_) {
      *storage_ = std::forward<U>(value);
    } else {
      storage_ = std::make_unique<T>(std::forward<U>(value));
    }
    engaged_ = true;
    return *this;
  }

  template <class... Args>
  T& emplace(Args&&... args) {
    storage_ = std::make_unique<T>(std::forward<Args>(args)...);
    engaged_ = true;
    return *storage_;
  }
  void reset() { engaged_ = false; }

  bool has_value() const { return engaged_; }
  explicit operator bool() const { return engaged_; }
  T& operator*() { return *storage_; }
  const T& operator*() const { return *storage_; }
  T* operator->() { return storage_.get(); }
  const T* operator->() const { return storage_.get(); }

 private:
  std::unique_ptr<T> storage_;  ///< the last value's storage, kept for the next
  bool engaged_ = false;        ///< whether it holds a value
};

}  // namespace corsa::engine::detail
