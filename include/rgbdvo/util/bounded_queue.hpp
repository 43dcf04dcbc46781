#pragma once
// A bounded queue between a producer that must not wait (a camera's callbacks) and a slower
// consumer (the odometry). When full, Push drops the oldest item so the newest always gets in
// ("newest wins": the odometry skips frames rather than falling ever further behind) and counts
// the drop; PushWait instead waits for room (for replays, where nothing should be lost).
// Memory is bounded by the capacity either way.

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>
#include <stdexcept>

namespace rgbdvo {

template <class T>
class BoundedQueue {
 public:
  explicit BoundedQueue(size_t capacity) : capacity_(capacity) {
    if (capacity == 0) throw std::invalid_argument("queue capacity must be > 0");
  }

  // Never blocks. Returns true when an older item was dropped to make room.
  bool Push(T item) {
    bool dropped = false;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (items_.size() >= capacity_) {
        items_.pop_front();
        ++dropped_;
        dropped = true;
      }
      items_.push_back(std::move(item));
    }
    not_empty_.notify_one();
    return dropped;
  }

  // Waits for room, up to `timeout`; false (item not queued) on timeout or when closed.
  bool PushWait(T item, std::chrono::milliseconds timeout) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      if (!not_full_.wait_for(lock, timeout,
                              [&] { return closed_ || items_.size() < capacity_; }) ||
          closed_)
        return false;
      items_.push_back(std::move(item));
    }
    not_empty_.notify_one();
    return true;
  }

  // The oldest item; waits up to `timeout`. nullopt on timeout, or when closed and empty.
  std::optional<T> Pop(std::chrono::milliseconds timeout) {
    std::optional<T> out;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      if (!not_empty_.wait_for(lock, timeout, [&] { return closed_ || !items_.empty(); }) ||
          items_.empty())
        return std::nullopt;
      out = std::move(items_.front());
      items_.pop_front();
    }
    not_full_.notify_one();
    return out;
  }

  // No more items will come: waiting consumers wake up; items already queued can still be
  // popped; further pushes are refused by PushWait (Push still never blocks).
  void Close() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      closed_ = true;
    }
    not_empty_.notify_all();
    not_full_.notify_all();
  }

  bool closed() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return closed_;
  }
  bool closed_and_empty() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return closed_ && items_.empty();
  }
  size_t dropped() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return dropped_;
  }
  size_t size() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return items_.size();
  }

 private:
  const size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable not_empty_, not_full_;
  std::deque<T> items_;
  size_t dropped_ = 0;
  bool closed_ = false;
};

}  // namespace rgbdvo
