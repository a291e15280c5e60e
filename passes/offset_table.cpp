// offset-table: every work offset the CL defines, gathered before the program is written, and
// each operation's motion put into its offset's frame.
//
// The pre-scan gives every frame record in file order (lower/prescan.cpp): SET registers with the
// CAMERA (or CSYS, MSYS) frame next to them, and — when the machine asks for one offset per
// frame (offsets.per_frame) — the frames of NX MSYS, Creo $$-> CSYS and APT CSYS, and the base
// frame of operations with none. Equal frames share a register; a SET keeps its register;
// other frames get registers in order of first use, from the machine's default one, skipping
// those SETs take; running out is an error. Each frame's rotary position comes from the
// kinematic solver (the tool along the frame's Z), and its machine offset is where its origin
// is then (offsets.reference_height: the seed's #503, the reference base's height above the
// table centre, which lies at the machine origin).
//
// In an operation whose tool axis is its frame's Z (3+2 work), the motion is put into the
// frame: p' = T (p - o), with T the table's rotation there (a machine without rotaries: the
// frame's own axes), the register selected and the rotaries positioned. Operations in the
// base frame just select its register. Other five-axis operations are left to the kinematics
// pass.
//
// Its contract (what it expects, guarantees, reads, and the IR facts it requires and provides)
// is offset_table_pass() at the end of this file.
#include <cmath>
#include <map>
#include <set>

#include "machine/kinematics.h"
#include "support/text.h"
#include "passes/passes.h"

namespace clpc {

namespace {

using ir::Vec3;

constexpr double kPi = 3.14159265358979323846;

class OffsetTablePass : public Pass {
 public:
  void begin(PassContext& ctx) override {
    const OffsetSettings& s = ctx.machine.offsets;
    k_ = ctx.kinematics();
    const double f = ctx.from_output();
    auto& table = ctx.info.offsets;
    table.clear();
    // A frame whose Z the machine cannot turn the tool to (any Z but the program's on a machine
    // without rotaries; beyond the rotary limits, a part turned over, on one with) is a setup of
    // its own: the part set up again with that Z up, in a register of its own, after a stop.
    auto reachable = [&](const Vec3& z) {
      return k_.has_rotaries() ? kin::choose(k_, z, nullptr, true).found : (z - Vec3::UnitZ()).norm() <= 1e-9;
    };
    bool any_set = false;
    setups_ = false;
    for (const ir::FrameUse& u : ctx.info.frames) {
      any_set = any_set || u.set_register != 0;
      setups_ = setups_ || !reachable(u.frame.z_axis());
    }
    if (!s.per_frame && !any_set && !setups_) return;
    for (const RotaryAxis& r : k_.rotaries)
      if (!r.table) {
        // Located at the first frame that asks for a register (a SET, or a Z the head cannot turn to).
        SourceLoc at;
        for (const ir::FrameUse& u : ctx.info.frames)
          if (u.set_register != 0 || !reachable(u.frame.z_axis()) || s.per_frame) {
            at = u.loc;
            break;
          }
        ctx.diags.error(at, "work offsets per frame need rotary axes on the table side; machine '" + ctx.machine.name +
                                "' turns its head");
        return;
      }
    std::set<int> used;
    for (const ir::FrameUse& u : ctx.info.frames)
      if (u.set_register) used.insert(ir::register_index(u.set_register));
    const int standard = s.standard_last - s.standard_first + 1;
    const int max_index = standard + s.extended_count;
    const double h = s.reference_height * f;  // program units
    const double to_out = 1 / f;
    std::vector<Vec3> setup_axes{Vec3::UnitZ()};
    for (const ir::FrameUse& u : ctx.info.frames) {
      if (!s.per_frame && !setups_ && u.set_register == 0) continue;
      if (find(table, u.frame, u.set_register)) continue;
      if (u.set_register) {
        bool clash = false;
        for (const ir::WorkOffset& w : table)
          if (w.set_register == u.set_register) {
            ctx.diags.error(u.loc, "SET/" + std::to_string(u.set_register) + " is given a second frame; its register holds the frame of line " +
                                       std::to_string(w.loc.line) + " already (one register, one offset)");
            clash = true;
            break;
          }
        if (clash) continue;
      }
      int index = u.set_register ? ir::register_index(u.set_register) : 0;
      if (!index) {
        index = s.default_index;
        while (used.count(index)) ++index;
        used.insert(index);
      }
      if (index > max_index) {
        ctx.diags.error(u.loc, "work-offset table: this frame needs a register beyond machine '" + ctx.machine.name + "''s " +
                                   std::to_string(max_index) + " (" + std::to_string(table.size()) + " frames before it)");
        continue;
      }
      ir::WorkOffset w;
      w.index = index;
      w.set_register = u.set_register;
      w.base = u.no_record;
      w.frame = u.frame;
      w.source = u.source;
      w.loc = u.loc;
      const ir::Mat3& R = u.frame.rotation;
      w.seed_a = std::abs(std::atan2(R(2, 1), R(2, 2))) * 180 / kPi;
      w.seed_c = std::atan2(R(1, 0), R(0, 0)) * 180 / kPi;
      Vec3 z = R.col(2);
      if (k_.has_rotaries() && reachable(z)) {
        kin::Choice c = kin::choose(k_, z, nullptr, true);
        w.has_rotary = true;
        w.rotary = c.a;
        w.machine = kin::table_point(k_, c.a, u.frame.origin + Vec3(0, 0, h)) * to_out;
        w.setup = setups_ ? 1 : 0;
        if (s.table == OffsetTable::G65Macro) check_seed(ctx, w);
      } else {
        const bool turned = (R - ir::Mat3::Identity()).cwiseAbs().maxCoeff() > 1e-9;
        if (turned && s.table != OffsetTable::None) {
          ctx.diags.error(u.loc, "work-offset table: machine '" + ctx.machine.name + "' " +
                                     (k_.has_rotaries() ? "cannot turn the tool to this frame's Z within its rotary limits"
                                                        : "has no rotary axes to turn this frame up") +
                                     "; with offsets.table = \"none\" such a frame is a setup of its own, its offset "
                                     "set on the machine");
          continue;
        }
        w.machine = (u.frame.origin + Vec3(0, 0, h)) * to_out;
        size_t k = 0;
        while (k < setup_axes.size() && (setup_axes[k] - z).norm() > 1e-9) ++k;
        if (k == setup_axes.size()) setup_axes.push_back(z);
        w.setup = int(k + 1);
      }
      if (s.table == OffsetTable::G65Macro && index > standard) {
        ctx.diags.error(u.loc, "work-offset table: the seed's macro sets G54-G59 only (G10 L2 P1-P6); this frame needs register " +
                                   std::to_string(index));
        continue;
      }
      table.push_back(w);
    }
  }

  void run(ir::Operation& op, PassContext& ctx) override {
    const auto& table = ctx.info.offsets;
    if (table.empty()) return;
    // Frames and registers are modal, across operations; SET pairs with the frame record next
    // to it in its operation, as in the pre-scan (lower/prescan.cpp).
    std::vector<ir::Instr>& out = scratch_;  // kept: no allocation per operation
    out.clear();
    out.reserve(op.body.size() + 4);
    setup_end_ = 0;
    for (size_t i = 0; i < op.body.size(); ++i) {
      ir::Instr& in = op.body[i];
      if (auto* f = std::get_if<ir::SetFrame>(&in.op)) {
        frame_ = f->frame;
        frame_loc_ = in.loc;
        source_ = f->source;
        reg_ = pending_;
        pending_ = 0;
        unpaired_ = reg_ == 0;
        active_ = false;
        out.push_back(std::move(in));
        continue;
      }
      if (auto* s = std::get_if<ir::SelectOffset>(&in.op)) {
        if (unpaired_) {
          reg_ = s->reg;
          unpaired_ = false;
        } else if (frame_record_ahead(op, i)) {
          pending_ = s->reg;
        } else {
          reg_ = s->reg;
        }
        active_ = false;
        continue;  // written again with its entry, at the first motion
      }
      const bool motion = (std::holds_alternative<ir::Move>(in.op) && std::get<ir::Move>(in.op).kind != ir::MoveKind::From) ||
                          std::holds_alternative<ir::Arc>(in.op) || std::holds_alternative<ir::Hole>(in.op);
      if (std::holds_alternative<ir::ToolChange>(in.op)) {
        in_cut_ = false;
        unpaired_ = false;
        setup_end_ = out.size() + 1;
      }
      if (motion) unpaired_ = false;  // a SET after the frame's cuts is the next frame's (the pre-scan's rule)
      const bool cut = (std::holds_alternative<ir::Move>(in.op) && std::get<ir::Move>(in.op).kind == ir::MoveKind::Feed) ||
                       std::holds_alternative<ir::Arc>(in.op);
      if (motion && !active_) {
        const Vec3 z_before = z_;
        activate(op, i, in.loc, out, ctx);
        // A cut that runs on from the last frame's cut into a 3+2 frame (or out of one): the
        // program retracts and turns the rotaries between the two, so the CL's cut from the
        // one to the other is not made (a feed down from the retract height took its place,
        // certified). Another register alone moves nothing: the feed goes on in it.
        if (cut && in_cut_ && entry_ && (z_ - z_before).norm() > 1e-9)
          ctx.diags.error(in.loc, "this cut runs on from the last point of the frame before into the frame of line " +
                                      std::to_string(frame_loc_.line) + ", a 3+2 position of its own (work offset " +
                                      std::to_string(selected_) + "): the program retracts and turns the rotaries between "
                                      "the two points, so the cut between is not made; have the CAM system leave the "
                                      "material (a RAPID) before the frame changes");
      }
      if (motion) in_cut_ = cut || std::holds_alternative<ir::Hole>(in.op);
      if (transform_ && motion) {
        apply(in);
        if (!along_z(in)) {
          // Only a later chunk of a very long operation can get here: the first decided 3+2.
          ctx.diags.error(in.loc, "this operation's tool axis leaves its frame's Z after the first " +
                                      std::to_string(op.body.size()) + " records; split the operation in the CAM system");
          transform_ = false;
        }
      }
      // (A CUTCOM belongs where it stands: the next fixture's register came before the last
      // one's CUTCOM/OFF, and the post met it with compensation still on; helper-72.)
      const bool comp = std::holds_alternative<ir::CutterComp>(in.op);
      out.push_back(std::move(in));
      if (motion || comp) setup_end_ = out.size();
    }
    if (op.last_chunk) {
      // The next operation decides 3+2 afresh, in the frame in force.
      active_ = false;
      transform_ = false;
      unpaired_ = false;
      pending_ = 0;
    }
    op.body.swap(out);
  }

 private:
  const ir::WorkOffset* find(const std::vector<ir::WorkOffset>& table, const ir::Frame& f, int reg) const {
    for (const ir::WorkOffset& w : table)
      if (w.frame.same_as(f, 1e-6, 1e-9) && (reg == 0 || w.set_register == reg)) return &w;
    return nullptr;
  }

  // The seed's macro turns the part by its own A and C: warn where they are not the angles the
  // rotaries go to (frames not of the form Rz(C) Rx(A) with A >= 0, or a machine without an A/C
  // table).
  void check_seed(PassContext& ctx, const ir::WorkOffset& w) {
    const auto& r = k_.rotaries;
    bool ac = r.size() == 2 && r[0].name == "A" && r[1].name == "C";
    bool same = ac && std::abs(w.rotary[0] - w.seed_a) < 1e-6 && std::abs(std::remainder(w.rotary[1] - w.seed_c, 360.0)) < 1e-6;
    if (!same)
      ctx.diags.warning(w.loc, "the seed's G65 macro computes this offset for A" + num_text(std::round(w.seed_a * 1e4) / 1e4) + " C" +
                                   num_text(std::round(w.seed_c * 1e4) / 1e4) + " (an A/C table), not for where the rotaries go; "
                                   "offsets.table = \"g10\" computes it for the machine",
                        "seed-macro");
  }

  // Whether the SET at i pairs with a frame record after it in its operation (before another
  // SET), as the pre-scan pairs them.
  static bool frame_record_ahead(const ir::Operation& op, size_t i) {
    for (size_t j = i + 1; j < op.body.size(); ++j) {
      const ir::Op& o = op.body[j].op;
      if (std::holds_alternative<ir::SetFrame>(o)) return true;
      if (std::holds_alternative<ir::SelectOffset>(o)) return false;
    }
    return false;
  }

  // At an operation's first motion (or the first after a frame or register change): select
  // the register, and if all the motion from here to the operation's end is along the frame's
  // Z, position the rotaries and put the points in the frame.
  void activate(ir::Operation& op, size_t from, SourceLoc loc, std::vector<ir::Instr>& out, PassContext& ctx) {
    active_ = true;
    transform_ = false;
    const ir::WorkOffset* w = find(ctx.info.offsets, frame_, reg_);
    entry_ = w != nullptr;
    if (!w && reg_ == 0 && !ctx.machine.offsets.per_frame && !default_taken_reported_) {
      // Motion in the part frame, which the default register holds: a SET that gives that
      // register to a frame elsewhere leaves it one origin for two (verify refused every point
      // of one of them, with no word on why).
      for (const ir::WorkOffset& t : ctx.info.offsets)
        if (t.set_register && t.index == ctx.machine.offsets.default_index && !t.frame.is_identity(1e-9)) {
          ctx.diags.error(loc, "this motion is in the part frame, whose register is the default one, but SET/" +
                                   std::to_string(t.set_register) + " (line " + std::to_string(t.loc.line) +
                                   ") gives that register to another frame: one register cannot hold both origins; "
                                   "give that frame another register (SET/55), or every frame its own "
                                   "(offsets.per_frame = true)");
          default_taken_reported_ = true;
          break;
        }
    }
    z_ = frame_.rotation.col(2);
    if (!w) {
      if (!ctx.machine.offsets.per_frame && reg_ == 0 && selected_ && selected_ != ctx.machine.offsets.default_index) {
        // A frame record with no SET after a SET's frame: its points are in the part frame (as
        // lowering puts every point), which the default register holds; the register selected
        // before holds the other frame's origin and would stay in force on the control.
        out.push_back({loc, ir::SelectOffset{0, ctx.machine.offsets.default_index}});
        selected_ = ctx.machine.offsets.default_index;
        return;
      }
      if (ctx.machine.offsets.per_frame) {
        ctx.diags.error(loc, "work-offset table: no register for the frame this motion is in (motion before the first "
                             "frame record of a file without TOOL PATH or FEATNO records?)");
      } else if (reg_) {
        out.push_back({loc, ir::SelectOffset{reg_, ir::register_index(reg_)}});
        selected_ = ir::register_index(reg_);
      }
      return;
    }
    // Selected and positioned before the spindle and coolant of the operation start: the
    // table turns with the tool stopped and dry, as posts do after a tool change.
    auto at = out.begin() + std::ptrdiff_t(std::min(setup_end_, out.size()));
    if (w->setup != 0 && w->setup != setup_) {
      // Another setup: a stop for the operator, and what to do in a comment beside it.
      // Short enough for a control's comment length (Haas: 80).
      const std::string what = "SETUP " + std::to_string(w->setup) + ": " +
                               (w->setup == 1 ? std::string("THE PART AS FIRST SET UP")
                                              : "TURN THE PART SO THE FRAME OF LINE " + std::to_string(w->loc.line) +
                                                    " HAS Z UP") +
                               ", REGISTER " + std::to_string(w->index);
      if (setup_ != 0 || w->setup != 1) {
        ctx.diags.warning(loc, "machine '" + ctx.machine.name + "' " +
                                   (k_.has_rotaries() ? "cannot turn the tool to this frame's Z"
                                                      : std::string("has no rotary axes")) +
                                   ": this operation is cut in setup " +
                                   std::to_string(w->setup) + " (register " + std::to_string(w->index) +
                                   "), the part set up again after an operator stop",
                          "setup");
        ir::TextRef t = op.add_text(what);  // in this chunk's pool
        at = out.insert(at, {loc, ir::Comment{t}}) + 1;
        if (setup_ != 0) {
          ir::Stop stop;
          stop.setup = true;
          at = out.insert(at, {loc, stop}) + 1;
        }
      }
      setup_ = w->setup;
    }
    at = out.insert(at, {loc, ir::SelectOffset{w->set_register, w->index}}) + 1;
    selected_ = w->index;
    // The frame's Z in the program frame, where lowering puts every point and tool axis.
    const Vec3 z_model = frame_.rotation.col(2);
    indexed_ = true;
    for (size_t j = from; j < op.body.size(); ++j) {
      const ir::Instr& in = op.body[j];
      if (std::holds_alternative<ir::SetFrame>(in.op)) break;  // the next frame decides for itself
      const Vec3* a = nullptr;
      if (auto* m = std::get_if<ir::Move>(&in.op); m && m->kind != ir::MoveKind::From) a = &m->axis;
      else if (auto* arc = std::get_if<ir::Arc>(&in.op)) a = &arc->tool_axis;
      else if (auto* h = std::get_if<ir::Hole>(&in.op)) a = &h->axis;
      if (!a) continue;
      if ((*a - z_model).norm() > 1e-9) indexed_ = false;
    }
    if (!indexed_) {
      // Five-axis motion (the tool axis leaves the frame's Z) is left to the kinematics pass, in
      // the program frame. The register selected holds this frame's origin (and the read-back,
      // under TCPC, does not add it): written in the program frame under it, every point would
      // be off by the origin. Refused until the frame is carried into the five-axis motion.
      if (!frame_.is_identity(1e-9))
        ctx.diags.error(loc, "this operation's tool axis leaves its frame's Z (five-axis motion), and its work offset "
                             "(register " + std::to_string(w->index) + ", the frame of line " + std::to_string(w->loc.line) +
                             ") is not the program's frame: clpc writes five-axis motion only in the program's frame; "
                             "have the CAM system write this operation there");
      return;
    }
    transform_ = true;
    if (w->has_rotary) {
      out.insert(at, {loc, ir::RotaryPosition{w->rotary, true}});
      T_ = kin::table_rotation(k_, w->rotary);
    } else {
      // The part is set up with the frame's axes along the machine's. In one setup it stands one
      // way: the first frame of the setup says which. Another frame of that setup turned about
      // Z from it would need the turn in its register, which holds an origin only.
      auto [first, fresh] = setup_turn_.try_emplace(w->setup, frame_.rotation, w->loc);
      if (!fresh && !frame_.rotation.isApprox(first->second.first, 1e-9))
        ctx.diags.error(loc, "this operation's frame (line " + std::to_string(w->loc.line) + ") is turned about Z from the frame of line " +
                                 std::to_string(first->second.second.line) + ", in the same setup: work offset register " +
                                 std::to_string(w->index) + " holds its origin, not its turn, on a machine without rotary "
                                 "axes; have the CAM system write both operations in frames turned alike");
      T_ = frame_.rotation.transpose();  // the frame's own coordinates: the part turned to it
    }
  }

  std::map<int, std::pair<ir::Mat3, SourceLoc>> setup_turn_;  // each setup's first frame, without rotaries

  Vec3 point(const Vec3& p) const { return T_ * (p - frame_.origin); }
  Vec3 dir(const Vec3& v) const { return T_ * v; }

  void apply(ir::Instr& in) const {
    if (auto* m = std::get_if<ir::Move>(&in.op)) {
      m->point = point(m->point);
      m->axis = dir(m->axis);
    } else if (auto* a = std::get_if<ir::Arc>(&in.op)) {
      a->start = point(a->start);
      a->end = point(a->end);
      a->center = point(a->center);
      a->axis = dir(a->axis);
      a->tool_axis = dir(a->tool_axis);
    } else if (auto* h = std::get_if<ir::Hole>(&in.op)) {
      h->point = point(h->point);
      h->axis = dir(h->axis);
    }
  }

  static bool along_z(const ir::Instr& in) {
    const Vec3* a = nullptr;
    if (auto* m = std::get_if<ir::Move>(&in.op)) a = &m->axis;
    else if (auto* arc = std::get_if<ir::Arc>(&in.op)) a = &arc->tool_axis;
    else if (auto* h = std::get_if<ir::Hole>(&in.op)) a = &h->axis;
    return !a || (*a - Vec3::UnitZ()).norm() <= 1e-6;
  }

  KinematicsSettings k_;
  std::vector<ir::Instr> scratch_;
  ir::Frame frame_;
  int selected_ = 0;     // the register last selected (0: none yet)
  bool in_cut_ = false;  // the last motion cut (a feed, an arc, a hole): the tool may be in the material
  bool entry_ = false;   // the frame in force has an entry of the table (a register, a rotary position)
  bool default_taken_reported_ = false;  // motion in the part frame met a SET frame in the default register
  Vec3 z_ = Vec3::UnitZ();  // the Z of the frame in force
  SourceLoc frame_loc_;  // the frame record in force
  ir::FrameSource source_ = ir::FrameSource::Csys;
  int reg_ = 0;       // the SET register in force (0: none)
  bool setups_ = false;  // frames become setups (a machine without rotaries)
  int setup_ = 0;        // the setup the part is in (0: none yet)
  int pending_ = 0;   // a SET waiting for the frame record after it
  size_t setup_end_ = 0;  // in this chunk's output: after its tool change or last motion
  bool unpaired_ = false;  // the last frame record has no SET yet
  bool active_ = false, indexed_ = false, transform_ = false;
  ir::Mat3 T_ = ir::Mat3::Identity();
};

}  // namespace

const PassInfo& offset_table_pass() {
  static const PassInfo info{
      .name = "offset-table",
      .summary = "gather SET/CAMERA (and per-frame MSYS/CSYS) frames into a work-offset table; select each "
                 "operation's register and position its 3+2 work",
      .expects = "frame and SET records as lowered; the pre-scan's frame list",
      .guarantees = "the program's offset table holds one entry per distinct frame with a SET (every distinct "
                    "frame with offsets.per_frame): equal frames share a register, SET registers are kept, the "
                    "others given in order of first use from offsets.default (an error when the registers run "
                    "out, or when one SET register is given two frames); each entry has its rotary position and "
                    "its offset in machine coordinates; each operation selects its frame's register; an operation "
                    "whose tool axis is its frame's Z (3+2) has its rotaries positioned and clamped before its "
                    "spindle starts and its points in the frame's coordinates; other operations are left to "
                    "kinematics; with no SET and no per_frame, nothing changes",
      .settings = "offsets.*, codes.offset_set, codes.offset_set_extended, codes.macro_call, kinematics.*",
      .needs = 0,
      .provides = ir::OffsetsAssigned,
      .breaks = 0,
      .costly = false,
      .make = [] { return std::unique_ptr<Pass>(std::make_unique<OffsetTablePass>()); },
  };
  return info;
}

}  // namespace clpc
