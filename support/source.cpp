#include "support/source.h"
#include "support/output.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>

namespace clpc {

namespace {

// Copies all of `in` into an anonymous temporary file and returns its descriptor.
int spool_to_temp(int in, std::string& error) {
  const char* dir = std::getenv("TMPDIR");
  std::string tmpl = std::string(dir && *dir ? dir : "/tmp") + "/clpc-stdin-XXXXXX";
  int fd = mkstemp(tmpl.data());
  if (fd < 0) {
    error = "cannot create a temporary file to hold standard input: " + std::string(strerror(errno));
    return -1;
  }
  unlink(tmpl.c_str());  // gone when closed, whatever happens
  std::string buf(1 << 20, '\0');
  for (;;) {
    ssize_t n = read(in, buf.data(), buf.size());
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      error = "cannot read standard input: " + std::string(strerror(errno));
      close(fd);
      return -1;
    }
    for (ssize_t done = 0; done < n;) {
      ssize_t w = write(fd, buf.data() + done, size_t(n - done));
      if (w < 0) {
        if (errno == EINTR) continue;
        error = "cannot spool standard input: " + std::string(strerror(errno));
        close(fd);
        return -1;
      }
      done += w;
    }
  }
  return fd;
}

}  // namespace

bool SourceFile::open(const std::string& path, std::string& error) {
  name_ = path == "-" ? "<stdin>" : path;
  int fd = path == "-" ? dup(0) : ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    error = "cannot open '" + path + "': " + strerror(errno);
    return false;
  }
  struct stat st {};
  if (fstat(fd, &st) != 0) {
    error = "cannot read '" + path + "': " + strerror(errno);
    close(fd);
    return false;
  }
  if (S_ISDIR(st.st_mode)) {
    error = "'" + path + "' is a directory";
    close(fd);
    return false;
  }
  release_input(protected_);
  protected_ = protect_input_fd(fd);  // (standard input redirected from a file is that file)
  if (!S_ISREG(st.st_mode)) {
    int spooled = spool_to_temp(fd, error);
    close(fd);
    if (spooled < 0) return false;
    fd = spooled;
    if (fstat(fd, &st) != 0) {
      error = "cannot read spooled input: " + std::string(strerror(errno));
      close(fd);
      return false;
    }
  }
  fd_ = fd;
  size_ = uint64_t(st.st_size);
  opened_size_ = int64_t(st.st_size);
  opened_mtime_ns_ = int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
  drop_end_of_file_marks();
  detect_cr_line_ends();
  return true;
}

// DOS ended text files with Ctrl-Z (0x1A), and files that passed through DOS-era editors and
// DNC software still carry it: at the very end it is no text, and the file ends before it.
void SourceFile::drop_end_of_file_marks() {
  char c;
  while (size_ > 0 && read_raw(size_ - 1, &c, 1) == 1 && c == '\x1A') --size_;
}

// Classic Mac OS ended lines with CR alone, and text from old Mac CAM stations and some DNC
// links still does. Such a file has no LF in its head and a CR that is no CR LF's: every CR is
// then a line end, read as LF. One byte for one, so offsets, columns and the lines a diagnostic
// shows stay those of the file. A file with LF line ends (or CR LF) keeps a lone CR as a blank.
void SourceFile::detect_cr_line_ends() {
  std::string head(65536, '\0');  // (not on the stack: the browser build's is small)
  const long n = read_raw(0, head.data(), head.size());
  if (n <= 0) return;
  const std::string_view text(head.data(), size_t(n));
  const size_t cr = text.find('\r');
  if (cr == std::string_view::npos || text.find('\n') != std::string_view::npos) return;
  // A CR at the very end of the head may be the first half of a CR LF cut by the head's end.
  cr_line_ends_ = cr + 1 < text.size() || uint64_t(n) == size_;
}

void SourceFile::open_memory(std::string name, std::string_view text) {
  name_ = std::move(name);
  memory_ = text;
  in_memory_ = true;
  size_ = text.size();
  drop_end_of_file_marks();
  detect_cr_line_ends();
}

bool SourceFile::changed_since_open() const {
  struct stat st {};
  if (fd_ < 0 || opened_size_ < 0 || fstat(fd_, &st) != 0) return false;
  return int64_t(st.st_size) != opened_size_ ||
         int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec != opened_mtime_ns_;
}

SourceFile::~SourceFile() {
  if (fd_ >= 0) close(fd_);
  release_input(protected_);
}

long SourceFile::read_at(uint64_t offset, char* dst, size_t n) const {
  const long got = read_raw(offset, dst, n);
  if (cr_line_ends_ && got > 0) std::replace(dst, dst + got, '\r', '\n');
  return got;
}

long SourceFile::read_raw(uint64_t offset, char* dst, size_t n) const {
  if (offset >= size_) return 0;
  n = size_t(std::min<uint64_t>(n, size_ - offset));  // the file ends at size_ (end-of-file marks)
  if (in_memory_) {
    size_t k = n;
    std::memcpy(dst, memory_.data() + offset, k);
    return long(k);
  }
  for (;;) {
    ssize_t r = pread(fd_, dst, n, off_t(offset));
    if (r < 0 && errno == EINTR) continue;
    return long(r);
  }
}

void SourceFile::note_line_start(uint32_t line, uint64_t offset) {
  if (line == 0 || (line - 1) % kCheckpointEvery != 0) return;
  size_t k = (line - 1) / kCheckpointEvery;
  std::lock_guard<std::mutex> lock(checkpoints_lock_);
  if (k == checkpoints_.size()) checkpoints_.push_back(offset);
  else if (k == 0) checkpoints_[0] = offset;  // line 1 after a byte-order mark
}

std::string SourceFile::line_text(uint32_t line) const {
  if (line == 0) return {};
  size_t k;
  uint64_t off;
  {
    std::lock_guard<std::mutex> lock(checkpoints_lock_);
    k = std::min<size_t>((line - 1) / kCheckpointEvery, checkpoints_.size() - 1);
    off = checkpoints_[k];
  }
  uint32_t at = uint32_t(k * kCheckpointEvery + 1);
  char buf[8192];
  std::string out;
  while (true) {
    long n = read_at(off, buf, sizeof buf);
    if (n <= 0) return at == line ? out : std::string();
    for (long i = 0; i < n; ++i) {
      char c = buf[i];
      if (c == '\n') {
        if (at == line) {
          if (!out.empty() && out.back() == '\r') out.pop_back();
          return out;
        }
        ++at;
        continue;
      }
      if (at == line && out.size() < 512) out.push_back(c);
    }
    off += uint64_t(n);
  }
}

}  // namespace clpc
