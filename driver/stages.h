// The compile as a pipeline of threads: the front end (lexer, parser, lowering) and the
// passes each run on a thread of their own, the backend on the caller's, so a two-core
// machine works on two stages at once. Operations cross over bounded queues — memory stays a
// few chunks whatever the file's size — and their storage comes back for reuse. Each stage's
// diagnostics travel with the operation they concern and are replayed, in order, on the
// caller's thread before its backend sees it: the output and the diagnostics are those of a
// one-thread compile, byte for byte.
#pragma once

#include <deque>
#include <mutex>
#include <thread>
#include <vector>

#include "support/diagnostics.h"
#include "support/handoff.h"
#include "ir/ir.h"
#include "lower/lower.h"
#include "support/source.h"
#include "passes/pass_manager.h"

namespace clpc {

// An operation chunk on its way, or the end, with the diagnostics found before it.
struct Piece {
  ir::Operation op;
  std::vector<Diagnostics::Deferred> diags;
  bool end = false;
};

class PieceQueue {
 public:
  bool push(Piece&& p);  // false once the queue is stopped (the consumer has gone)
  Piece pop();           // blocks; a stopped, empty queue gives an end piece
  void stop();
  // Storage for the producer to fill again.
  void give_spare(ir::Operation&& op);
  ir::Operation take_spare();

 private:
  static constexpr size_t kDepth = 4;
  static constexpr size_t kSpares = 12;  // every operation in flight comes back: no fresh memory per chunk
  std::mutex lock_;
  Handoff handoff_{kDepth};
  std::deque<Piece> queue_;
  std::vector<ir::Operation> spare_;
  bool stopped_ = false;
  bool ended_ = false;  // the end piece is in the queue
};

// Lowers `src` on its own thread into `out`.
class FrontEnd {
 public:
  FrontEnd(SourceFile& src, const ir::ProgramInfo& info, PieceQueue& out, bool latin1 = false, LowerOptions lower = {});
  ~FrontEnd();  // waits for the thread (stop the queue first to make it give up)

 private:
  class Sink;
  void run();
  SourceFile& src_;
  const ir::ProgramInfo& info_;
  PieceQueue& out_;
  bool latin1_;
  LowerOptions lower_;
  Diagnostics diags_;
  std::thread thread_;
};

// Runs passes [0, upto) over each piece from `in` on its own thread, into `out`, in `ctx`
// (whose Diagnostics is in deferred mode).
class PassStage {
 public:
  PassStage(PassManager& pm, size_t upto, PassContext& ctx, PieceQueue& in, PieceQueue& out);
  ~PassStage();

 private:
  void run();
  PassManager& pm_;
  size_t upto_;
  PassContext& ctx_;
  PieceQueue& in_;
  PieceQueue& out_;
  std::thread thread_;
};

}  // namespace clpc
