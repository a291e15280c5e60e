// Source files and locations: where every record, instruction and diagnostic comes from.
#pragma once

#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace clpc {

// A position in the input, 1-based. line == 0 means "no location" (e.g. a whole-program
// diagnostic). Kept at 8 bytes because every IR instruction carries one.
struct SourceLoc {
  uint32_t line = 0;
  uint32_t col = 0;
  bool valid() const { return line != 0; }
  friend bool operator==(SourceLoc a, SourceLoc b) { return a.line == b.line && a.col == b.col; }
};

// An input file opened for reading. Non-seekable inputs (standard input, pipes) are spooled
// to an unlinked temporary file first, so every input can be read twice (pre-scan, then
// compile) and any line can be fetched again for a diagnostic, without holding the file in
// memory.
class SourceFile {
 public:
  // Opens `path` ("-" = standard input). Returns false and sets `error` on failure.
  bool open(const std::string& path, std::string& error);
  // Wraps an in-memory text (tests, fuzzers). The text must outlive the SourceFile.
  void open_memory(std::string name, std::string_view text);
  ~SourceFile();
  // True where the regular file read has another size or modification time than when opened
  // (truncated, appended to or rewritten meanwhile).
  bool changed_since_open() const;
  SourceFile() = default;
  SourceFile(const SourceFile&) = delete;
  SourceFile& operator=(const SourceFile&) = delete;

  const std::string& name() const { return name_; }
  // Reads up to `n` bytes at absolute `offset`; returns the count (0 at end, -1 on error).
  // The end is size(): trailing Ctrl-Z bytes (DOS's end-of-file mark) are not part of the file.
  // In a file whose lines end in CR alone, every CR is read as LF.
  long read_at(uint64_t offset, char* dst, size_t n) const;
  uint64_t size() const { return size_; }
  // True when the file's lines end in CR alone (classic Mac OS): read_at gives LF for each CR.
  bool cr_line_ends() const { return cr_line_ends_; }

  // The lexer reports how far it has read (for a progress display).
  void on_progress(std::function<void(uint64_t)> f) { progress_ = std::move(f); }
  void reached(uint64_t offset) const {
    if (progress_) progress_(offset);
  }

  // The lexer reports where lines start as it goes; a sparse index of them lets
  // `line_text` find any earlier line quickly.
  void note_line_start(uint32_t line, uint64_t offset);
  // The text of line `line` (without its end), or "" when unknown. At most 512 bytes.
  std::string line_text(uint32_t line) const;

 private:
  void drop_end_of_file_marks();
  void detect_cr_line_ends();
  long read_raw(uint64_t offset, char* dst, size_t n) const;
  std::string name_;
  int fd_ = -1;
  uint64_t protected_ = 0;  // protect_input's token: no output of this run may replace the file
  std::string_view memory_;
  bool in_memory_ = false;
  uint64_t size_ = 0;
  int64_t opened_size_ = -1, opened_mtime_ns_ = 0;  // a regular file's, when opened
  bool cr_line_ends_ = false;
  std::function<void(uint64_t)> progress_;
  static constexpr uint32_t kCheckpointEvery = 1024;
  std::vector<uint64_t> checkpoints_{0};  // offset of line 1 + k * kCheckpointEvery
  mutable std::mutex checkpoints_lock_;    // the lexer adds while diagnostics read (two threads)
};

}  // namespace clpc
