// A queue in one growing array used round: push at the back, pop at the front, index from
// the front. Its slots are reused, so a window that slides over millions of elements (verify's
// window of program segments) allocates only while it grows, where std::deque allocates and
// frees a node for each element of some hundreds of bytes.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace clpc {

template <class T>
class Ring {
 public:
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  T& operator[](size_t i) { return slots_[(head_ + i) & (slots_.size() - 1)]; }
  const T& operator[](size_t i) const { return slots_[(head_ + i) & (slots_.size() - 1)]; }
  T& front() { return (*this)[0]; }

  // A slot at the back, holding whatever it held before (the caller fills it).
  T& push_back_slot() {
    if (size_ == slots_.size()) grow();
    ++size_;
    return (*this)[size_ - 1];
  }
  void pop_back() { --size_; }
  void pop_front() {
    head_ = (head_ + 1) & (slots_.size() - 1);
    --size_;
  }

 private:
  void grow() {
    std::vector<T> bigger(slots_.empty() ? 16 : 2 * slots_.size());
    for (size_t i = 0; i < size_; ++i) bigger[i] = std::move((*this)[i]);
    slots_.swap(bigger);
    head_ = 0;
  }
  std::vector<T> slots_;  // a power of two long
  size_t head_ = 0, size_ = 0;
};

}  // namespace clpc
