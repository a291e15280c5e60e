// Where a program is written: a temporary file beside the target, renamed into place only
// when the compile succeeded. A failed or interrupted run never leaves a half-written program
// and never clobbers an older one. Output to "-" goes through an anonymous temporary file
// too, and is copied to standard output only on success; so is output to a device or a pipe
// (/dev/null), which a rename would replace.
#pragma once

#include <condition_variable>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>

#include <sys/stat.h>

#include "support/text_channel.h"

namespace clpc {

class OutputFile {
 public:
  OutputFile() = default;
  ~OutputFile();  // discards unless committed
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  // Creates the temporary file for `path` ("-" = standard output). Also removes temporary
  // files that earlier clpc runs, now dead, left beside `path`.
  bool open(const std::string& path, std::string& error);
  // Writes nowhere (fuzzing, benchmarks of the backend alone): what is written is dropped.
  void open_null() { null_ = true; }
  void write(std::string_view s) {
    if (buf_.size() + s.size() > kBuffer) flush();
    buf_.append(s);
  }
  // Renames the temporary file into place (or copies it to standard output, a device or a
  // pipe).
  bool commit(std::string& error);
  void discard();
  // Writes out everything written so far, so the program can be read back (verified) before
  // it is committed; false, with the reason, when the file cannot be written. Then
  // read_path() names the file: the temporary, or /proc/self/fd/N for an anonymous one.
  bool finish_writing(std::string& error);
  std::string read_path() const;
  // Also hands what is written to `c` as it is written (the certificate reading the program
  // beside the compile); end_tee() hands over the rest and closes `c`.
  void tee(TextChannel* c) { tee_ = c; }
  void end_tee();
  const std::string& temp_path() const { return temp_; }

  static constexpr size_t kBuffer = 1 << 20;

 private:
  // A full buffer is written by a writer thread while the next one fills (the copy into the
  // page cache is off the compile's critical path); programs under a buffer never start it.
  void flush();
  void finish_writes();  // waits for the writer; the file then holds all that was written
  void writer();
  std::string path_, temp_;
  int keep_mode_ = -1;  // the permissions of the file replaced (-1: none there)
  int fd_ = -1;
  bool to_stdout_ = false;
  bool to_special_ = false;  // a device or pipe: copied to, like standard output
  bool null_ = false;
  bool failed_ = false;
  int errno_ = 0;
  TextChannel* tee_ = nullptr;
  std::string buf_;
  std::string writing_;       // the buffer the writer has
  bool write_pending_ = false;
  bool writer_stop_ = false;
  std::mutex lock_;
  std::condition_variable changed_;
  std::thread thread_;
};

// Removes, on SIGINT/SIGTERM/SIGHUP/SIGPIPE, every temporary output still open, then dies of
// the signal. Installed once by the command line.
void install_output_cleanup_handlers();

// Files this run reads (a CL file, a program verify checks or plot draws): OutputFile::open
// refuses to replace one, whatever command writes (`plot part.cls -o part.cls`, `verify
// --report` onto the CL, `verify --program hand.nc -o hand.nc` each destroyed its input).
// protect_input returns a token for release_input (0: nothing protected, not a regular file).
uint64_t protect_input(const std::string& path);
uint64_t protect_input_fd(int fd);  // standard input redirected from a file (`- < part.cls`)
uint64_t protect_input(const struct stat& st);
void release_input(uint64_t token);
bool is_protected_input(const std::string& path);
// Protects a file for a scope.
struct ProtectedInput {
  explicit ProtectedInput(const std::string& path) : token(protect_input(path)) {}
  ~ProtectedInput() { release_input(token); }
  ProtectedInput(const ProtectedInput&) = delete;
  ProtectedInput& operator=(const ProtectedInput&) = delete;
  uint64_t token;
};

}  // namespace clpc
