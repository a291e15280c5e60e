#include "support/progress.h"

#include <unistd.h>

#include <cstdio>

namespace clpc {

Progress::Progress(std::string name, uint64_t total, bool enabled)
    : name_(std::move(name)), total_(total), active_(enabled && total >= kMinBytes && isatty(STDERR_FILENO)) {
  if (size_t s = name_.rfind('/'); s != std::string::npos) name_ = name_.substr(s + 1);
  start_ = last_ = std::chrono::steady_clock::now();
}

Progress::~Progress() {
  if (active_) std::fputs("\r\033[K", stderr);  // leave the line clean for what follows
}

void Progress::phase(const char* what) {
  std::lock_guard<std::mutex> g(lock_);
  phase_ = what;
  done_ = 0;
  start_ = std::chrono::steady_clock::now();
  draw(0, true);
}

void Progress::update(uint64_t done) {
  std::lock_guard<std::mutex> g(lock_);
  // Two readers may report in one phase (the compile and the certificate beside it, each at
  // its own place in the input): the bar shows the one ahead, and never steps back.
  if (done <= done_) return;
  done_ = done;
  draw(done, false);
}

void Progress::clear() {
  std::lock_guard<std::mutex> g(lock_);
  if (active_) std::fputs("\r\033[K", stderr);
}

void Progress::draw(uint64_t done, bool force) {
  if (!active_) return;
  auto now = std::chrono::steady_clock::now();
  if (!force && now - last_ < std::chrono::milliseconds(100) && done < total_) return;
  last_ = now;
  const int width = 30;
  double f = total_ ? double(done) / double(total_) : 1;
  if (f > 1) f = 1;
  int fill = int(f * width);
  char bar[width + 1];
  for (int i = 0; i < width; ++i) bar[i] = i < fill ? '=' : i == fill ? '>' : ' ';
  bar[width] = 0;
  double secs = std::chrono::duration<double>(now - start_).count();
  double mbs = secs > 0 ? double(done) / secs / 1e6 : 0;
  std::fprintf(stderr, "\r\033[K%s: %-8s [%s] %3d%%  %.0f MB/s", name_.c_str(), phase_, bar, int(f * 100), mbs);
  std::fflush(stderr);
}

}  // namespace clpc
