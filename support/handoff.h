// When the two threads of a bounded single-producer, single-consumer queue wait and wake.
// Woken for every item, a thread sleeps again after one: each item a context switch on each
// side, and a condition variable notified while its waiter's condition is still false wakes it
// for nothing. So a full queue's producer sleeps until the consumer has taken half of it, an
// empty queue's consumer until two items (or the end) are there, and each side is notified
// once, when the other's condition becomes true. The compile's pipelines hand over thousands
// of chunks a second (driver/stages, readback/program_reader, support/text_channel):
// docs/performance.md has the context switches and the time this saves.
//
// The caller keeps the queue and its mutex; these calls are made under that mutex, and the
// ones that notify unlock it first.
#pragma once

#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <mutex>

namespace clpc {

class Handoff {
 public:
  explicit Handoff(size_t depth) : depth_(depth), resume_(depth / 2), ready_at_(std::min<size_t>(2, depth)) {}

  // Producer, before adding: while the queue holds `depth` items, sleeps until it holds half
  // (or `gone()`: the consumer has stopped).
  template <class Size, class Gone>
  void wait_for_room(std::unique_lock<std::mutex>& g, Size size, Gone gone) {
    if (size() < depth_) return;
    room_.wait(g, [&] { return gone() || size() <= resume_; });
  }
  // Producer, after adding: the queue now holds `size`; unlocks.
  void added(std::unique_lock<std::mutex>& g, size_t size) {
    g.unlock();
    if (size == ready_at_) ready_.notify_one();
  }
  // Consumer, before taking: while the queue is empty, sleeps until it holds two items (or
  // `ended()`: nothing more will come, or the producer has stopped).
  template <class Size, class Ended>
  void wait_for_items(std::unique_lock<std::mutex>& g, Size size, Ended ended) {
    if (size() > 0) return;
    ready_.wait(g, [&] { return ended() || size() >= ready_at_; });
  }
  // Consumer, after taking: the queue now holds `size`; unlocks.
  void taken(std::unique_lock<std::mutex>& g, size_t size) {
    g.unlock();
    if (size == resume_) room_.notify_one();
  }
  // Either side stopped, or the producer ended: whoever waits, wakes (call after setting the
  // flag that `gone()` or `ended()` reads, with the mutex released).
  void wake_both() {
    room_.notify_all();
    ready_.notify_all();
  }

 private:
  size_t depth_, resume_, ready_at_;
  std::condition_variable room_, ready_;
};

}  // namespace clpc
