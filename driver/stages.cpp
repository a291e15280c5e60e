#include "driver/stages.h"


#include "grammar/parse.h"
#include "lower/lower.h"
#include "support/threads.h"

namespace clpc {

// --- the queue -------------------------------------------------------------------------------

bool PieceQueue::push(Piece&& p) {
  std::unique_lock<std::mutex> g(lock_);
  handoff_.wait_for_room(g, [&] { return queue_.size(); }, [&] { return stopped_; });
  if (stopped_) return false;
  const bool end = p.end;
  queue_.push_back(std::move(p));
  if (end) {
    ended_ = true;
    g.unlock();
    handoff_.wake_both();
    return true;
  }
  handoff_.added(g, queue_.size());
  return true;
}

Piece PieceQueue::pop() {
  std::unique_lock<std::mutex> g(lock_);
  handoff_.wait_for_items(g, [&] { return queue_.size(); }, [&] { return stopped_ || ended_; });
  Piece p;
  if (queue_.empty()) {
    p.end = true;
    return p;
  }
  p = std::move(queue_.front());
  queue_.pop_front();
  handoff_.taken(g, queue_.size());
  return p;
}

void PieceQueue::stop() {
  {
    std::lock_guard<std::mutex> g(lock_);
    stopped_ = true;
  }
  handoff_.wake_both();
}

void PieceQueue::give_spare(ir::Operation&& op) {
  op.clear();
  std::lock_guard<std::mutex> g(lock_);
  if (spare_.size() < kSpares) spare_.push_back(std::move(op));
}

ir::Operation PieceQueue::take_spare() {
  std::lock_guard<std::mutex> g(lock_);
  if (spare_.empty()) return {};
  ir::Operation op = std::move(spare_.back());
  spare_.pop_back();
  return op;
}

// --- the front end ---------------------------------------------------------------------------

class FrontEnd::Sink : public OperationSink {
 public:
  explicit Sink(FrontEnd& f) : f_(f) {}
  void operation(ir::Operation& op) override {
    // The lowerer goes on filling `op`: it gets spare storage, this chunk goes over.
    Piece p;
    p.op = f_.out_.take_spare();
    std::swap(p.op, op);
    op.clear();
    p.diags = f_.diags_.take_deferred();
    if (!f_.out_.push(std::move(p))) throw FatalError{};
  }

 private:
  FrontEnd& f_;
};

FrontEnd::FrontEnd(SourceFile& src, const ir::ProgramInfo& info, PieceQueue& out, bool latin1, LowerOptions lower)
    : src_(src), info_(info), out_(out), latin1_(latin1), lower_(lower), diags_(nullptr) {
  diags_.set_source(&src);
  diags_.set_deferred(true);
  thread_ = std::thread([this] { run(); });
}

FrontEnd::~FrontEnd() {
  if (thread_.joinable()) thread_.join();
}

void FrontEnd::run() {
  name_this_thread("clpc-front");
  Sink sink(*this);
  try {
    Lowerer low(info_, diags_, sink, lower_);
    ParseOptions po;
    po.latin1 = latin1_;
    parse_cl(src_, diags_, low, po);
    low.finish();
  } catch (const FatalError&) {
    // Too many errors, or the consumer stopped: what was found still goes over.
  }
  Piece last;
  last.end = true;
  last.diags = diags_.take_deferred();
  out_.push(std::move(last));
}

// --- the passes ------------------------------------------------------------------------------

PassStage::PassStage(PassManager& pm, size_t upto, PassContext& ctx, PieceQueue& in, PieceQueue& out)
    : pm_(pm), upto_(upto), ctx_(ctx), in_(in), out_(out) {
  thread_ = std::thread([this] { run(); });
}

PassStage::~PassStage() {
  if (thread_.joinable()) thread_.join();
}

void PassStage::run() {
  name_this_thread("clpc-passes");
  for (;;) {
    Piece p = in_.pop();
    if (p.end) {
      out_.push(std::move(p));
      return;
    }
    try {
      pm_.run(p.op, 0, upto_, ctx_);
    } catch (const FatalError&) {
      // Too many errors: the front end stops, the backend hears of them and stops too.
      in_.stop();
      Piece last;
      last.end = true;
      last.diags = std::move(p.diags);
      for (auto& d : ctx_.diags.take_deferred()) last.diags.push_back(std::move(d));
      out_.push(std::move(last));
      return;
    }
    for (auto& d : ctx_.diags.take_deferred()) p.diags.push_back(std::move(d));
    if (!out_.push(std::move(p))) {
      in_.stop();
      return;
    }
  }
}

}  // namespace clpc
