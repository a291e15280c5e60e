// floor: what "as fast as reading the file" means on this machine. It reads a CL file in
// large blocks, parses every number of every GOTO with std::from_chars (`GOTO/` or Creo's
// `GOTO / `, continued over lines ending in `$`) and writes one formatted line per GOTO
// (integer formatting, large output buffer) — no semantics at all.
// clpc's whole compile is measured against it (bench/run.sh).
//
//   floor INPUT OUTPUT
#include <fcntl.h>
#include <unistd.h>

#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace {

constexpr size_t kBlock = 1 << 20;

class Out {
 public:
  explicit Out(int fd) : fd_(fd) { buf_.reserve(kBlock + 256); }
  ~Out() { flush(); }
  // value with 4 decimals, as a control word: integer arithmetic only
  void word(char letter, double v) {
    buf_.push_back(letter);
    long long q = (long long)(v * 10000.0 + (v < 0 ? -0.5 : 0.5));
    if (q < 0) {
      buf_.push_back('-');
      q = -q;
    }
    char d[24];
    auto [p, ec] = std::to_chars(d, d + sizeof d, q / 10000);
    buf_.append(d, p);
    buf_.push_back('.');
    long long f = q % 10000;
    char frac[4] = {char('0' + f / 1000), char('0' + f / 100 % 10), char('0' + f / 10 % 10), char('0' + f % 10)};
    buf_.append(frac, 4);
    buf_.push_back(' ');
  }
  void end_line() {
    buf_.back() = '\n';
    if (buf_.size() >= kBlock) flush();
  }
  void flush() {
    size_t at = 0;
    while (at < buf_.size()) {
      ssize_t n = write(fd_, buf_.data() + at, buf_.size() - at);
      if (n <= 0) break;
      at += size_t(n);
    }
    buf_.clear();
  }

 private:
  int fd_;
  std::string buf_;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: floor INPUT OUTPUT\n");
    return 2;
  }
  int in = open(argv[1], O_RDONLY);
  int outfd = open(argv[2], O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (in < 0 || outfd < 0) {
    std::perror("floor");
    return 1;
  }
  Out out(outfd);
  std::vector<char> buf(kBlock + 4096);
  size_t keep = 0;
  long gotos = 0;
  static const char letters[] = "XYZIJK";
  int k = 0;             // numbers of the GOTO being read
  bool in_goto = false;  // a GOTO continued on the next line
  // Every number from p to e (separated by blanks and commas) as the GOTO's next word; stops
  // at the first thing that is not a number (a '$').
  auto numbers = [&](const char* p, const char* e) {
    while (p < e && k < 6) {
      while (p < e && (*p == ' ' || *p == ',')) ++p;
      double v;
      auto [q, ec] = std::from_chars(p, e, v);
      if (ec != std::errc()) break;
      out.word(letters[k++], v);
      p = q;
    }
    return p;
  };
  for (;;) {
    ssize_t n = read(in, buf.data() + keep, kBlock);
    if (n < 0) return 1;
    size_t len = keep + size_t(n);
    size_t line = 0;
    for (;;) {
      const char* nl = static_cast<const char*>(std::memchr(buf.data() + line, '\n', len - line));
      if (!nl) break;
      const char* p = buf.data() + line;
      const char* e = nl;
      if (in_goto) {
        // A continuation line of a GOTO (the last ended in '$'): its numbers follow on.
        p = numbers(p, e);
      } else if (e - p > 5 && std::memcmp(p, "GOTO", 4) == 0 && (p[4] == '/' || p[4] == ' ')) {
        p += 4;
        while (p < e && *p == ' ') ++p;
        if (p < e && *p == '/') {
          k = 0;
          in_goto = true;
          p = numbers(p + 1, e);
        }
      }
      if (in_goto) {
        // Continued when the line's last character but blanks is '$' (Creo, APT).
        const char* t = e;
        while (t > p && (t[-1] == ' ' || t[-1] == '\r')) --t;
        if (!(t > p && t[-1] == '$')) {
          out.end_line();
          ++gotos;
          in_goto = false;
        }
      }
      line = size_t(nl - buf.data()) + 1;
    }
    keep = len - line;
    std::memmove(buf.data(), buf.data() + line, keep);
    if (n == 0) break;
  }
  std::fprintf(stderr, "floor: %ld GOTOs\n", gotos);
  return 0;
}
