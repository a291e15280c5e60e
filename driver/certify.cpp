#include "driver/certify.h"

#include <cmath>
#include <cstdio>


#include "driver/pipeline.h"
#include "readback/program_reader.h"
#include "support/text.h"
#include "support/threads.h"

namespace clpc {

namespace {

VerifyReport new_report(SourceFile& src, const Machine& m, const CertifyOptions& opt) {
  VerifyReport rep;
  rep.input = src.name();
  rep.machine = m.name;
  rep.units = m.units;
  rep.five_axis = m.kinematics.has_rotaries();
  rep.tolerance = opt.tolerance > 0 ? opt.tolerance : default_tolerance(m);
  rep.axis_tolerance = opt.axis_tolerance;
  rep.compiled = true;
  rep.collect_samples = opt.collect_samples;
  return rep;
}

// The program from `rd` against the reference: the CL lowered again and given its meaning
// by verify's own rules, none of the compile's passes. The compile has reported the CL's own
// problems: quiet here.
void compare(SourceFile& src, ProgramReader& rd, const Machine& m, const ir::ProgramInfo& info, const CertifyOptions& opt,
             Diagnostics& d, VerifyReport& rep, const LowerOptions& lower) {
  rd.read_ahead();  // the reader on a thread of its own: the comparison is the longest stage
  std::unique_ptr<ProgramSink> comparison = make_comparison(m, info, rd, d, rep);
  Diagnostics quiet(nullptr);
  quiet.set_source(&src);
  ir::ProgramInfo tables = info;
  PipelineOptions po;
  po.latin1 = opt.latin1;
  po.sink_after_errors = true;
  po.lower = lower;
  Pipeline reference(m, {}, tables, quiet, po);
  try {
    reference.run(src, *comparison);
  } catch (const FatalError&) {
    // More problems than are worth listing: the report says how many were found.
  }
  rep.program = rd.totals();
  rep.ok = rep.problem_count == 0 && rep.max_deviation <= rep.tolerance;
}

}  // namespace

VerifyReport certify(SourceFile& src, const std::string& program, const Machine& m, const ir::ProgramInfo& info,
                     const CertifyOptions& opt, Diagnostics& d) {
  VerifyReport rep = new_report(src, m, opt);
  std::string why;
  ProgramReader rd(m, info);
  if (!opt.dynamic_time) rd.skip_dynamic_time();
  if (!rd.open(program, why)) {
    d.error({}, "cannot read the program back to verify it: " + why);
    return rep;
  }
  compare(src, rd, m, info, opt, d, rep, LowerOptions{});
  return rep;
}

// The compile's sink with the certificate beside it.
class CertifyBeside::Sink : public ProgramSink {
 public:
  Sink(CertifyBeside& c, std::unique_ptr<ProgramSink> inner) : c_(c), inner_(std::move(inner)) {}
  void begin(const ir::ProgramInfo& info) override {
    inner_->begin(info);
    c_.start(info);  // the passes' begin() have filled the tables (the offset table) by now
  }
  void operation(const ir::Operation& op) override { inner_->operation(op); }
  void end() override {
    inner_->end();
    c_.out_.end_tee();
  }

 private:
  CertifyBeside& c_;
  std::unique_ptr<ProgramSink> inner_;
};

CertifyBeside::CertifyBeside(SourceFile& src, const Machine& m, OutputFile& out, CertifyOptions opt)
    : src_(src), m_(m), out_(out), opt_(opt), diags_(nullptr), report_(new_report(src, m, opt)) {
  diags_.set_source(&src);
  diags_.set_deferred(true);
}

CertifyBeside::~CertifyBeside() {
  // A compile that stopped: the certificate reads to the end of what there is, then stops.
  out_.tee(nullptr);
  channel_.close();
  if (thread_.joinable()) thread_.join();
}

std::unique_ptr<ProgramSink> CertifyBeside::wrap(std::unique_ptr<ProgramSink> sink) {
  if (threads_available()) out_.tee(&channel_);
  return std::make_unique<Sink>(*this, std::move(sink));
}

void CertifyBeside::start(const ir::ProgramInfo& info) {
  info_ = info;
  if (!threads_available()) return;  // finish() reads the program back when it is written
  thread_ = std::thread([this] {
    name_this_thread("clpc-certify");
    ProgramReader rd(m_, info_);
    if (!opt_.dynamic_time) rd.skip_dynamic_time();
    rd.open(channel_);
    try {
      // The reference's lowering on a thread of its own, as in the compile, for the
      // comparison is the longest stage of all; in chunks of a quarter of the compile's, so
      // the two pipelines' queues together hold little more than the compile's alone.
      LowerOptions lower;
      lower.chunk_size = LowerOptions{}.chunk_size / 4;
      compare(src_, rd, m_, info_, opt_, diags_, report_, lower);
    } catch (const FatalError&) {
    }
    // Whatever is still to come is not read: the compile must not wait for it.
    channel_.abandon();
  });
}

VerifyReport CertifyBeside::finish(Diagnostics& d) {
  if (!threads_available()) {
    // No thread to read it beside the compile (the browser build): read the program back
    // from where it was written, now that it is whole.
    report_ = certify(src_, out_.read_path(), m_, info_, opt_, diags_);
    for (const Diagnostics::Deferred& x : diags_.take_deferred()) d.replay(x);
    return std::move(report_);
  }
  out_.end_tee();  // (done already when the pipeline ended normally)
  channel_.close();
  if (thread_.joinable()) thread_.join();
  for (const Diagnostics::Deferred& x : diags_.take_deferred()) d.replay(x);
  return std::move(report_);
}

namespace {

std::string where(const VerifyReport& r, SourceLoc loc, int gcode_line) {
  std::string s;
  if (loc.valid()) s += " at " + r.input + ":" + std::to_string(loc.line);
  if (gcode_line > 0) s += " (G-code line " + std::to_string(gcode_line) + ")";
  return s;
}

}  // namespace

std::string certificate_line(const VerifyReport& r, const std::string& program_name) {
  const char* u = r.units == ir::Units::Inch ? "in" : "mm";
  const int dec = r.units == ir::Units::Inch ? 5 : 4;
  std::string s = std::string("clpc: ") + (r.ok ? "certified " : "NOT certified ") + program_name + ": " +
                  std::to_string(r.cl_points) + " points, " + std::to_string(r.cl_arcs) + " arcs, " +
                  std::to_string(r.cl_holes) + " holes";
  if (r.cl_groove_points) s += ", " + std::to_string(r.cl_groove_points) + " groove cuts";
  if (r.cl_thread_cuts) s += ", " + std::to_string(r.cl_thread_cuts) + " thread cuts";
  s += " checked; max deviation ";
  s += std::isinf(r.max_deviation) ? std::string("unbounded") : fixed_text(r.max_deviation, dec) + " " + u;
  s += where(r, r.max_loc, r.max_gcode_line);
  if (r.five_axis) s += ", tool axis " + fixed_text(r.max_axis_deviation, 4) + " deg" + where(r, r.max_axis_loc, r.max_axis_gcode_line);
  s += "; tolerance " + fixed_text(r.tolerance, dec) + " " + u;
  if (r.five_axis) s += ", " + fixed_text(r.axis_tolerance, 4) + " deg";
  if (r.ambiguous_arcs)
    s += "; " + std::to_string(r.ambiguous_arcs) + " arc" + (r.ambiguous_arcs == 1 ? "" : "s") +
         " where the CL's convention and its geometry disagree (first at " + r.input + ":" +
         std::to_string(r.ambiguous_loc.line) + ")";
  if (!r.ok) s += "; " + std::to_string(r.problem_count) + " problem" + (r.problem_count == 1 ? "" : "s");
  return s;
}

}  // namespace clpc
