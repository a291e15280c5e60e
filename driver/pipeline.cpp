#include "driver/pipeline.h"

#include "driver/stages.h"
#include "grammar/parse.h"
#include "support/threads.h"

namespace clpc {

namespace {

bool moves(const ir::Operation& op) {
  for (const ir::Instr& in : op.body)
    if (std::holds_alternative<ir::Move>(in.op) || std::holds_alternative<ir::Arc>(in.op)) return true;
  return false;
}

// The single schedule's lowering output: each chunk through the passes and to the sink at once.
class Direct : public OperationSink {
 public:
  Direct(PassManager& pm, Diagnostics& pass_diags, Diagnostics& front_diags, Diagnostics& d, ProgramSink& sink, bool& motion,
         bool sink_after_errors)
      : pm_(pm), pass_diags_(pass_diags), front_diags_(front_diags), d_(d), sink_(sink), motion_(motion),
        sink_after_errors_(sink_after_errors) {}
  void operation(ir::Operation& op) override {
    for (const auto& x : front_diags_.take_deferred()) d_.replay(x);
    pm_.run(op);
    for (const auto& x : pass_diags_.take_deferred()) d_.replay(x);
    motion_ = motion_ || moves(op);
    if (sink_after_errors_ || !d_.has_errors()) sink_.operation(op);
  }

 private:
  PassManager& pm_;
  Diagnostics &pass_diags_, &front_diags_, &d_;
  ProgramSink& sink_;
  bool& motion_;
  bool sink_after_errors_;
};

}  // namespace

Pipeline::Pipeline(const Machine& m, std::vector<std::string> passes, ir::ProgramInfo& info, Diagnostics& d,
                   PipelineOptions opt)
    : m_(m), passes_(std::move(passes)), info_(info), d_(d), opt_(std::move(opt)) {}

bool Pipeline::run(SourceFile& src, ProgramSink& sink) {
  // The passes report into deferred Diagnostics, replayed here in order: the same whether
  // they run on this thread or their own.
  auto deferred = [&] {
    Diagnostics x(nullptr);
    x.set_source(&src);
    x.set_deferred(true);
    return x;
  };
  Diagnostics pass_diags = deferred();
  PassContext ctx{info_, m_, pass_diags};
  PassManager pm(ctx, passes_, opt_.instruments);
  pm.begin();
  for (const Diagnostics::Deferred& x : pass_diags.take_deferred()) d_.replay(x);
  sink.begin(info_);
  bool motion = false;

  if (opt_.schedule == Schedule::Single || !threads_available()) {
    Diagnostics front_diags = deferred();
    Direct direct(pm, pass_diags, front_diags, d_, sink, motion, opt_.sink_after_errors);
    try {
      Lowerer low(info_, front_diags, direct, opt_.lower);
      ParseOptions po;
      po.latin1 = opt_.latin1;
      parse_cl(src, front_diags, low, po);
      low.finish();
    } catch (const FatalError&) {
      for (const auto& x : front_diags.take_deferred()) d_.replay(x);
      for (const auto& x : pass_diags.take_deferred()) d_.replay(x);
      throw;
    }
    for (const auto& x : front_diags.take_deferred()) d_.replay(x);
  } else {
    // The passes up to the costliest on their own thread, the rest here before the sink.
    const size_t split = pm.split_point();
    Diagnostics late_diags = deferred();
    PassContext late{info_, m_, late_diags};
    PieceQueue lowered, passed;
    FrontEnd front(src, info_, lowered, opt_.latin1, opt_.lower);
    PassStage stage(pm, split, ctx, lowered, passed);
    struct StopOnExit {  // on an exception here: the threads give up, then join
      PieceQueue &a, &b;
      ~StopOnExit() {
        a.stop();
        b.stop();
      }
    } stop{lowered, passed};
    for (;;) {
      Piece p = passed.pop();
      if (!p.end && split < pm.size()) {
        pm.run(p.op, split, pm.size(), late);
        for (auto& x : late_diags.take_deferred()) p.diags.push_back(std::move(x));
      }
      for (const Diagnostics::Deferred& x : p.diags) d_.replay(x);
      if (p.end) break;
      motion = motion || moves(p.op);
      // After an error no output is written: skip the sink's work.
      if (opt_.sink_after_errors || !d_.has_errors()) sink.operation(p.op);
      lowered.give_spare(std::move(p.op));
    }
  }
  if (opt_.sink_after_errors || !d_.has_errors()) sink.end();
  return motion;
}

}  // namespace clpc
