#include "support/output.h"
#include "support/threads.h"


#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <utility>
#include <vector>

namespace clpc {

namespace {

// Temporary outputs still open, for the signal handler. Fixed slots: the handler may only
// touch async-signal-safe things.
constexpr int kSlots = 64;
char g_temp_paths[kSlots][4096];
// A slot is claimed (used), then its path written, then published (ready): with -j N another
// thread may look at the slots meanwhile, and reads a path only once it is whole.
std::atomic<bool> g_temp_used[kSlots];
std::atomic<bool> g_temp_ready[kSlots];

int register_temp(const std::string& p) {
  if (p.size() >= sizeof g_temp_paths[0]) return -1;
  for (int i = 0; i < kSlots; ++i) {
    bool expected = false;
    if (g_temp_used[i].compare_exchange_strong(expected, true)) {
      std::memcpy(g_temp_paths[i], p.c_str(), p.size() + 1);
      g_temp_ready[i].store(true, std::memory_order_release);
      return i;
    }
  }
  return -1;
}

void unregister_temp(const std::string& p) {
  for (int i = 0; i < kSlots; ++i)
    if (g_temp_ready[i].load(std::memory_order_acquire) && p == g_temp_paths[i]) {
      g_temp_ready[i] = false;
      g_temp_used[i] = false;
    }
}

void on_signal(int sig) {
  for (int i = 0; i < kSlots; ++i)
    if (g_temp_ready[i]) unlink(g_temp_paths[i]);
  signal(sig, SIG_DFL);
  raise(sig);
}

std::string link_target(const std::string& path) {
  char buf[4096];
  const ssize_t n = readlink(path.c_str(), buf, sizeof buf - 1);
  return n > 0 ? std::string(buf, size_t(n)) : std::string("?");
}

std::string dir_of(const std::string& path) {
  size_t slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

std::string base_of(const std::string& path) {
  size_t slash = path.rfind('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// ".<name>.clpc-<pid>-XXXXXX": removes those whose pid no longer runs.
void remove_stale_temps(const std::string& dir, const std::string& base) {
  std::string prefix = "." + base + ".clpc-";
  DIR* d = opendir(dir.c_str());
  if (!d) return;
  while (dirent* e = readdir(d)) {
    std::string n = e->d_name;
    if (n.compare(0, prefix.size(), prefix) != 0) continue;
    long pid = std::strtol(n.c_str() + prefix.size(), nullptr, 10);
    if (pid <= 0) continue;
    if (kill(pid_t(pid), 0) == 0 || errno != ESRCH) continue;
    unlink((dir + "/" + n).c_str());
  }
  closedir(d);
}

bool write_all(int fd, const char* p, size_t n) {
  while (n) {
    ssize_t w = ::write(fd, p, n);
    if (w < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    p += w;
    n -= size_t(w);
  }
  return true;
}

}  // namespace

void install_output_cleanup_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    // SIGPIPE too: diagnostics piped into `head` that has gone (clpc compile ... 2>&1 | head)
    // end the run as they would any program's, but not with a temporary file left behind; and
    // every other signal that ends a process (Ctrl-\'s SIGQUIT, a timer's SIGALRM, a file size
    // limit's SIGXFSZ: each left a temporary). One the run was started ignoring (nohup's HUP, a
    // background job's QUIT) stays ignored.
    for (int s : {SIGINT, SIGTERM, SIGHUP, SIGPIPE, SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM, SIGVTALRM, SIGPROF, SIGXCPU,
                  SIGXFSZ}) {
      struct sigaction old {};
      if (sigaction(s, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
      struct sigaction sa {};
      sa.sa_handler = on_signal;
      sigemptyset(&sa.sa_mask);
      sigaction(s, &sa, nullptr);
    }
  });
}

namespace {
struct Input {
  uint64_t id;
  dev_t dev;
  ino_t ino;
};
std::mutex g_inputs_lock;
std::vector<Input> g_inputs;  // files being read (an inode is only one while its file is open)
uint64_t g_next_input = 1;
}  // namespace

uint64_t protect_input(const std::string& path) {
  struct stat st {};
  if (path.empty() || path == "-" || stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return 0;
  return protect_input(st);
}

uint64_t protect_input_fd(int fd) {
  struct stat st {};
  if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) return 0;
  return protect_input(st);
}

uint64_t protect_input(const struct stat& st) {
  std::lock_guard<std::mutex> hold(g_inputs_lock);
  g_inputs.push_back({g_next_input, st.st_dev, st.st_ino});
  return g_next_input++;
}

void release_input(uint64_t id) {
  if (id == 0) return;
  std::lock_guard<std::mutex> hold(g_inputs_lock);
  for (size_t i = 0; i < g_inputs.size(); ++i)
    if (g_inputs[i].id == id) {
      g_inputs.erase(g_inputs.begin() + std::ptrdiff_t(i));
      return;
    }
}

bool is_protected_input(const std::string& path) {
  struct stat st {};
  if (path.empty() || path == "-" || stat(path.c_str(), &st) != 0) return false;
  std::lock_guard<std::mutex> hold(g_inputs_lock);
  for (const Input& in : g_inputs)
    if (in.dev == st.st_dev && in.ino == st.st_ino) return true;
  return false;
}

OutputFile::~OutputFile() { discard(); }

bool OutputFile::open(const std::string& path, std::string& error) {
  if (is_protected_input(path)) {
    error = "the output '" + path + "' is a file this run reads (the CL, or the program checked or drawn); refusing to "
            "overwrite it";
    return false;
  }
  path_ = path;
  to_stdout_ = path == "-";
  keep_mode_ = -1;
  struct stat st;
  if (!to_stdout_ && lstat(path.c_str(), &st) == 0 && S_ISLNK(st.st_mode)) {
    // A symbolic link is written through (the program replaces the file it names): renamed over,
    // the link itself became a file and its target kept the old program.
    char* real = realpath(path.c_str(), nullptr);
    if (!real) {
      error = "cannot write '" + path + "': it is a symbolic link to '" + link_target(path) + "', which does not exist";
      return false;
    }
    path_ = real;
    std::free(real);
  }
  // A device or pipe (/dev/null, a FIFO) cannot be renamed over: the program goes through an
  // anonymous temporary file and is copied to it on success, as to standard output.
  to_special_ = !to_stdout_ && stat(path_.c_str(), &st) == 0 && !S_ISREG(st.st_mode);
  if (!to_stdout_ && !to_special_ && stat(path_.c_str(), &st) == 0) {
    // A program a shop made read-only (a proven program) is not replaced; one that is replaced
    // keeps its permissions (it came back 644 from a 640).
    if ((st.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0) {
      error = "cannot write '" + path + "': it is read-only (write-protected); refusing to replace it";
      return false;
    }
    keep_mode_ = int(st.st_mode & 07777);
  }
  if (to_special_ && S_ISDIR(st.st_mode)) {
    error = "cannot write '" + path + "': it is a directory";
    return false;
  }
  buf_.reserve(kBuffer);
  std::string dir, tmpl;
  if (to_stdout_ || to_special_) {
    const char* t = std::getenv("TMPDIR");
    dir = t && *t ? t : "/tmp";
    tmpl = dir + "/.clpc-stdout.clpc-" + std::to_string(getpid()) + "-XXXXXX";
  } else {
    dir = dir_of(path_);
    std::string base = base_of(path_);
    remove_stale_temps(dir, base);
    tmpl = dir + "/." + base + ".clpc-" + std::to_string(getpid()) + "-XXXXXX";
  }
  fd_ = mkstemp(tmpl.data());
  if (fd_ < 0) {
    error = "cannot create the output in '" + dir + "': " + strerror(errno);
    return false;
  }
  temp_ = tmpl;
  register_temp(temp_);
  if (to_stdout_ || to_special_) {
    unlink(temp_.c_str());  // anonymous: nothing to clean up, whatever happens
    unregister_temp(temp_);
  } else {
    // mkstemp makes 0600; a program file should get the usual permissions, and its owner
    // always reads it (the certificate does; Emscripten's file system starts with umask 0777).
    mode_t um = umask(0);
    umask(um);
    fchmod(fd_, (0666 & ~um) | S_IRUSR | S_IWUSR);
  }
  return true;
}

void OutputFile::flush() {
  if (tee_) tee_->push(buf_);
  if (null_) buf_.clear();
  if (fd_ < 0 || buf_.empty()) return;
  if (!threads_available()) {  // (the browser build) written here and now
    if (!failed_ && !write_all(fd_, buf_.data(), buf_.size())) {
      failed_ = true;
      errno_ = errno;
    }
    buf_.clear();
    return;
  }
  if (!thread_.joinable()) {
    writing_.reserve(kBuffer);
    thread_ = std::thread([this] { writer(); });
  }
  std::unique_lock<std::mutex> g(lock_);
  changed_.wait(g, [&] { return !write_pending_; });
  writing_.swap(buf_);
  write_pending_ = true;
  g.unlock();
  changed_.notify_all();
  buf_.clear();
}

void OutputFile::end_tee() {
  if (!tee_) return;
  tee_->push(buf_);
  tee_->close();
  tee_ = nullptr;
}

void OutputFile::writer() {
  name_this_thread("clpc-writer");
  std::unique_lock<std::mutex> g(lock_);
  for (;;) {
    changed_.wait(g, [&] { return write_pending_ || writer_stop_; });
    if (!write_pending_) return;
    g.unlock();
    bool ok = failed_ || write_all(fd_, writing_.data(), writing_.size());
    int err = errno;
    g.lock();
    if (!ok && !failed_) {
      failed_ = true;
      errno_ = err;
    }
    writing_.clear();
    write_pending_ = false;
    changed_.notify_all();
  }
}

void OutputFile::finish_writes() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> g(lock_);
    writer_stop_ = true;
  }
  changed_.notify_all();
  thread_.join();
  writer_stop_ = false;
}

bool OutputFile::finish_writing(std::string& error) {
  if (fd_ < 0) {
    error = "no output open";
    return false;
  }
  // The last buffer, written here once the writer has done its part.
  finish_writes();
  if (!buf_.empty() && !failed_ && !write_all(fd_, buf_.data(), buf_.size())) {
    failed_ = true;
    errno_ = errno;
  }
  buf_.clear();
  if (failed_) {
    error = "cannot write the output: " + std::string(strerror(errno_));
    return false;
  }
  return true;
}

std::string OutputFile::read_path() const {
  if (fd_ < 0) return {};
  if (to_stdout_ || to_special_) return "/proc/self/fd/" + std::to_string(fd_);
  return temp_;
}

bool OutputFile::commit(std::string& error) {
  if (fd_ < 0) {
    error = "no output open";
    return false;
  }
  if (!finish_writing(error)) {
    discard();
    return false;
  }
  if (to_stdout_ || to_special_) {
    int out = 1;
    if (to_special_ && (out = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC)) < 0) {
      error = "cannot write '" + path_ + "': " + strerror(errno);
      discard();
      return false;
    }
    char buf[1 << 16];
    off_t off = 0;
    for (;;) {
      ssize_t n = pread(fd_, buf, sizeof buf, off);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        error = "cannot read back the output: " + std::string(strerror(errno));
        discard();
        return false;
      }
      if (n == 0) break;
      if (!write_all(out, buf, size_t(n))) {
        error = (to_special_ ? "cannot write '" + path_ + "': " : std::string("cannot write to standard output: ")) +
                strerror(errno);
        if (out != 1) close(out);
        discard();
        return false;
      }
      off += n;
    }
    if (out != 1) close(out);
    close(fd_);
    fd_ = -1;
    return true;
  }
  if (close(fd_) != 0) {
    fd_ = -1;
    error = "cannot write the output: " + std::string(strerror(errno));
    discard();
    return false;
  }
  fd_ = -1;
  if (keep_mode_ >= 0) chmod(temp_.c_str(), mode_t(keep_mode_));
  if (rename(temp_.c_str(), path_.c_str()) != 0) {
    error = "cannot write '" + path_ + "': " + strerror(errno);
    unlink(temp_.c_str());
    unregister_temp(temp_);
    temp_.clear();
    return false;
  }
  unregister_temp(temp_);
  temp_.clear();
  return true;
}

void OutputFile::discard() {
  finish_writes();
  if (fd_ >= 0) {
    close(fd_);
    fd_ = -1;
  }
  if (!temp_.empty() && !to_stdout_ && !to_special_) {
    unlink(temp_.c_str());
    unregister_temp(temp_);
  }
  temp_.clear();
  buf_.clear();
}

}  // namespace clpc
