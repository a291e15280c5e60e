// A progress bar on standard error, for long compiles: shown only when standard error is a
// terminal and the input is large (a few MB); otherwise it does nothing.
#pragma once

#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace clpc {

class Progress {
 public:
  static constexpr uint64_t kMinBytes = 4u << 20;

  // `enabled`: the caller wants it (the terminal and size checks are made here).
  Progress(std::string name, uint64_t total, bool enabled);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void phase(const char* what);  // "pre-scan", "compile", "verify": each runs over the input
  void update(uint64_t done);    // bytes of the input read in this phase (the most reported counts)
  void clear();                  // before other text goes to standard error
  bool active() const { return active_; }

 private:
  void draw(uint64_t done, bool force);
  std::string name_;
  uint64_t total_;
  bool active_;
  const char* phase_ = "";
  uint64_t done_ = 0;  // the furthest point reported in this phase
  std::chrono::steady_clock::time_point start_, last_;
  std::mutex lock_;  // the front end's thread updates, the other clears for diagnostics
};

}  // namespace clpc
