#include "support/threads.h"

#include <atomic>

#if !defined(__EMSCRIPTEN__)
#include <pthread.h>
#endif

namespace clpc {

namespace {
#if defined(__EMSCRIPTEN__) && !defined(__EMSCRIPTEN_PTHREADS__)
constexpr bool kCanThread = false;
#else
constexpr bool kCanThread = true;
#endif
std::atomic<bool> allowed{kCanThread};
}  // namespace

bool threads_available() { return allowed.load(std::memory_order_relaxed); }

void set_threads_available(bool on) { allowed = on && kCanThread; }

void name_this_thread(const char* name) {
#if !defined(__EMSCRIPTEN__)
  pthread_setname_np(pthread_self(), name);
#else
  (void)name;
#endif
}

}  // namespace clpc
