#include "ir/tables.h"

#include <algorithm>
#include <set>

#include "grammar/parse.h"
#include "ir/frame_records.h"
#include "ir/tool_records.h"

namespace clpc {

namespace {

// Follows operations and tool records to build the tool list in order of first use. A tool
// named (NX TOOL PATH) but never numbered gets the lowest number no record uses.
class TableBuilder : public RecordSink {
 public:
  explicit TableBuilder(const PrescanOptions& opt) : opt_(opt) {}

  void record(const Record& r) override {
    if (r.kind != Record::Kind::Statement) return;
    switch (r.id) {
      case MajorId::Msys: case MajorId::Csys: case MajorId::Camera: {
        ir::FrameUse u;
        if (!read_frame(r, nullptr, u.frame, u.source)) break;
        u.loc = r.loc;
        u.set_register = pending_set_;
        pending_set_ = 0;
        frame_ = u;
        frame_seen_ = true;
        info_.frames.push_back(u);
        last_frame_unpaired_ = u.set_register == 0;
        break;
      }
      case MajorId::Set: {
        // SET pairs with the frame record next to it in its operation, before or after; one
        // with none there selects its register for the frame in force (passes/offset_table.cpp).
        int reg = read_set_register(r, nullptr);
        if (reg <= 0) break;
        if (last_frame_unpaired_ && !info_.frames.empty()) {
          info_.frames.back().set_register = reg;
          last_frame_unpaired_ = false;
        } else {
          flush_pending_set();  // two SETs without a frame record between: the first is the frame in force's
          pending_set_ = reg;
          pending_set_loc_ = r.loc;
        }
        break;
      }
      case MajorId::ToolPath: {
        end_op();
        in_op_ = true;
        op_name_ = tool_name_of_tool_path(r);
        op_loc_ = r.loc;
        break;
      }
      case MajorId::Featno:
        if (r.data_comment) { end_op(); in_op_ = true; op_name_.clear(); op_loc_ = r.loc; }
        break;
      case MajorId::EndOfPath: end_op(); break;
      case MajorId::End: if (r.data_comment) end_op(); break;
      case MajorId::Loadtl: case MajorId::Load: case MajorId::Turret: {
        ToolRecord t = read_tool_record(r, nullptr);
        if (t.number < 0 || t.preselect) break;
        bool first_in_op = explicit_ < 0;
        explicit_ = t.number;
        ir::ToolInfo& tool = slot(t.number, r.loc);
        if (tool.name.empty() && first_in_op) tool.name = op_name_;
        if (pending_.any) { attach(tool, pending_); pending_ = {}; }
        break;
      }
      case MajorId::Tldata: case MajorId::Cutter: {
        ToolGeometry g = read_tool_geometry(r, nullptr);
        if (!g.any) break;
        if (explicit_ >= 0) attach(slot(explicit_, r.loc), g);
        else pending_ = g;
        break;
      }
      case MajorId::Units: case MajorId::Unit:
        if (!units_ && !r.params.empty() && r.params[0].is_word()) {
          auto u = units_word(r.params[0].text);
          if (u) units_ = *u;
        }
        break;
      case MajorId::Fedrat:
        if (!feed_units_) {
          for (const Param& p : r.params) {
            if (p.is("MMPM") || p.is("MMPR")) { feed_units_ = ir::Units::Mm; break; }
            if (p.is("IPM") || p.is("IPR")) { feed_units_ = ir::Units::Inch; break; }
          }
        }
        break;
      case MajorId::Partno:
        if (info_.part_name.empty()) info_.part_name = std::string(r.text);
        break;
      case MajorId::Machin:
        if (!r.params.empty() && (r.params[0].is("TURN") || r.params[0].is("LATHE"))) info_.lathe = true;
        break;
      default: break;
    }
  }

  ir::ProgramInfo finish() {
    end_op();
    // Number the named-only tools with numbers no record uses.
    std::set<int> used;
    for (auto& t : info_.tools) if (!t.auto_numbered) used.insert(t.number);
    int next = 1;
    for (auto& t : info_.tools) {
      if (!t.auto_numbered) continue;
      while (used.count(next)) ++next;
      t.number = next;
      used.insert(next);
    }
    for (const auto& [line, name] : named_ops_) info_.named_tool_ops.emplace_back(line, info_.tool_number_for_name(name));
    if (opt_.units) {
      info_.units = *opt_.units;
      info_.units_given = true;
      info_.units_reason = "--input-units";
    } else if (units_) {
      info_.units = *units_;
      info_.units_given = true;
    } else if (feed_units_) {
      info_.units = *feed_units_;
      info_.units_reason = std::string("no UNITS record; the feed units say ") +
                           (*feed_units_ == ir::Units::Inch ? "inches" : "millimetres");
    } else {
      info_.units = ir::Units::Mm;
      info_.units_reason = "no UNITS record and no feed unit; assuming millimetres";
    }
    return std::move(info_);
  }

 private:
  ir::ToolInfo& slot(int number, SourceLoc loc) {
    for (auto& t : info_.tools)
      if (!t.auto_numbered && t.number == number) return t;
    ir::ToolInfo t;
    t.number = number;
    t.first_use = loc;
    info_.tools.push_back(t);
    return info_.tools.back();
  }
  static void attach(ir::ToolInfo& t, const ToolGeometry& g) {
    if (t.diameter == 0 && t.corner_radius == 0 && t.length == 0 && t.kind.empty()) {
      t.kind = g.kind;
      t.diameter = g.diameter;
      t.corner_radius = g.corner_radius;
      t.length = g.length;
    }
  }
  // A SET no frame record pairs with names the register of the frame in force.
  void flush_pending_set() {
    if (!pending_set_) return;
    ir::FrameUse u = frame_;
    u.loc = pending_set_loc_;
    u.set_register = pending_set_;
    info_.frames.push_back(u);
    pending_set_ = 0;
  }

  void end_op() {
    // Frames and registers are modal: an operation without a frame record works in the frame
    // in force, the base frame before any.
    if (pending_set_) {
      flush_pending_set();
    } else if (in_op_ && !frame_seen_) {
      ir::FrameUse u = frame_;
      u.loc = op_loc_;
      info_.frames.push_back(u);
    }
    last_frame_unpaired_ = false;
    pending_set_ = 0;
    if (in_op_ && explicit_ < 0 && !op_name_.empty()) {
      ir::ToolInfo* found = nullptr;
      for (auto& t : info_.tools)
        if (t.name == op_name_) { found = &t; break; }
      if (!found) {
        ir::ToolInfo t;
        t.name = op_name_;
        t.auto_numbered = true;
        t.first_use = op_loc_;
        info_.tools.push_back(t);
        found = &info_.tools.back();
      }
      if (pending_.any) attach(*found, pending_);
      named_ops_.emplace_back(op_loc_.line, op_name_);
    }
    in_op_ = false;
    explicit_ = -1;
    op_name_.clear();
    pending_ = {};
  }

  const PrescanOptions& opt_;
  ir::ProgramInfo info_;
  bool in_op_ = false;
  std::string op_name_;
  SourceLoc op_loc_;
  int explicit_ = -1;
  ToolGeometry pending_;
  std::optional<ir::Units> units_, feed_units_;
  std::vector<std::pair<uint32_t, std::string>> named_ops_;
  int pending_set_ = 0;
  SourceLoc pending_set_loc_;
  ir::FrameUse frame_ = base_frame();  // the frame in force
  bool frame_seen_ = false;
  bool last_frame_unpaired_ = false;

  static ir::FrameUse base_frame() {
    ir::FrameUse u;
    u.no_record = true;
    return u;
  }
};

}  // namespace

ir::ProgramInfo prescan_program(SourceFile& src, const PrescanOptions& opt) {
  MajorSet want;
  for (MajorId id : {MajorId::ToolPath, MajorId::Featno, MajorId::EndOfPath, MajorId::End,
                     MajorId::Loadtl, MajorId::Load, MajorId::Turret, MajorId::Tldata,
                     MajorId::Cutter, MajorId::Units, MajorId::Unit, MajorId::Fedrat,
                     MajorId::Partno, MajorId::Machin, MajorId::Msys, MajorId::Csys, MajorId::Camera,
                     MajorId::Set})
    want.add(id);
  TableBuilder b(opt);
  prescan_cl(src, b, want);
  ir::ProgramInfo info = b.finish();
  info.source_name = src.name();
  return info;
}

}  // namespace clpc
