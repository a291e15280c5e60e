// Text handed from one thread to another in chunks, through a bounded queue: the program a
// compile writes, read back by its certificate as it is written (driver/certify.h). The
// writer blocks while `kChunks` chunks wait unread, so memory stays bounded whatever the
// program's size; chunk buffers go back and forth, none allocated per chunk once running.
#pragma once

#include <deque>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "support/handoff.h"

namespace clpc {

class TextChannel {
 public:
  static constexpr size_t kChunks = 4;

  // Writer: a copy of `text` goes to the reader (dropped once the reader has given up).
  void push(std::string_view text);
  // Writer: no more text; the reader sees the end after what was pushed.
  void close();
  // Reader: the next chunk into `out` (its old buffer kept for reuse); false at the end.
  bool pop(std::string& out);
  // Reader: gives up; pushes are dropped from now on, so the writer never waits for it.
  void abandon();

 private:
  std::mutex lock_;
  Handoff handoff_{kChunks};
  std::deque<std::string> full_;
  std::vector<std::string> spare_;
  bool closed_ = false, abandoned_ = false;
};

}  // namespace clpc
