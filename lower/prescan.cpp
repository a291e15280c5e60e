#include "lower/prescan.h"

#include <algorithm>
#include <cstring>
#include <set>

#include "grammar/parse.h"
#include "lower/frame_records.h"
#include "lower/params.h"
#include "lower/tool_records.h"

namespace clpc {

namespace {

// PARTNO/'name' (Fusion) names the part without its quotes.
std::string unquote(std::string_view t) {
  if (t.size() >= 2 && (t.front() == '\'' || t.front() == '"') && t.back() == t.front()) t = t.substr(1, t.size() - 2);
  return std::string(t);
}

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
        if (u.source == ir::FrameSource::Msys) {  // relative to the first MSYS, as lowering has it
          if (!msys0_) msys0_ = u.frame;
          u.frame = ir::compose(msys0_->inverse(), u.frame);
        }
        u.loc = r.loc;
        u.set_register = pending_set_;
        pending_set_ = 0;
        frame_ = u;
        frame_seen_ = true;
        info_.frames.push_back(u);
        last_frame_unpaired_ = u.set_register == 0;
        frame_motion_ = r.motion_skipped;
        break;
      }
      case MajorId::Set: {
        // SET pairs with the frame record next to it in its operation, before or after; one
        // with none there selects its register for the frame in force (passes/offset_table.cpp).
        int reg = read_set_register(r, nullptr);
        if (reg <= 0) break;
        // A frame record cut in (motion between) is no longer next to a SET that follows: that
        // SET is the next frame's (APT files with no operation records: CAMERA, the cuts, SET/55,
        // CAMERA). It named the first frame, whose part was cut in G55 while G55 held the second.
        if (r.motion_skipped != frame_motion_) last_frame_unpaired_ = false;
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
      case MajorId::Select:
        if (!r.params.empty() && r.params[0].is("TOOL")) info_.preselects_given = true;
        break;
      case MajorId::Loadtl: case MajorId::Load: case MajorId::Turret: {
        ToolRecord t = read_tool_record(r, nullptr);
        if (t.number < 0) break;
        bool first_in_op = explicit_ < 0;
        explicit_ = t.number;
        ir::ToolInfo& tool = slot(t.number, r.loc);
        loads_.push_back(size_t(&tool - info_.tools.data()));
        if (!pending_name_.empty() && (tool.name.empty() || tool.name == op_name_)) tool.name = pending_name_;
        pending_name_.clear();
        if (tool.name.empty() && first_in_op) tool.name = op_name_;
        if (pending_.any) { attach(tool, pending_); pending_ = {}; }
        if (t.length > 0) load_lengths_.emplace_back(size_t(&tool - info_.tools.data()), t.length);
        load_motion_ = r.motion_skipped;
        break;
      }
      case MajorId::Tldata: case MajorId::Cutter: {
        if (r.id == MajorId::Tldata && !r.params.empty()) family(r, r.params[0]);
        ToolGeometry g = read_tool_geometry(r, nullptr);
        if (!g.any) break;
        // A tool's data stands after its load (Creo: LOADTL, then $$-> CUTTER) or before the
        // next one (NX, CATIA: the data, then LOAD/LOADTL/TURRET). Creo's "$$-> CUTTER" always
        // follows its load, and a file whose first plain CUTTER/TLDATA follows a load writes them
        // all after it: then the record is the loaded tool's, also when the number was loaded
        // before (a second operation with the same tool). Otherwise the loaded tool takes it only
        // while it has none, and the rest waits for the next load.
        if (!r.data_comment && !order_known_) {
          after_load_ = explicit_ >= 0;
          order_known_ = true;
        }
        const bool after = r.data_comment || after_load_;
        if (explicit_ >= 0 && (after || !has_geometry(slot(explicit_, r.loc)))) attach(slot(explicit_, r.loc), g);
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
      case MajorId::Cycle:  // a cycle's own feed (NX's CYCLE/DRILL,...,MMPM,f) names the unit too
      case MajorId::Thread:  // and a thread's lead (THREAD/TURN,LEAD,1.5,IPR)
        for (const Param& p : r.params) {
          std::optional<ir::Units> u;
          if (p.is("MMPM") || p.is("MMPR")) u = ir::Units::Mm;
          if (p.is("IPM") || p.is("IPR")) u = ir::Units::Inch;
          if (!u) continue;
          if (!feed_units_) feed_units_ = u;
          if (!feed_word_loc_[int(*u)].valid()) feed_word_loc_[int(*u)] = r.loc;
          break;
        }
        break;
      case MajorId::Partno:
        if (info_.part_name.empty()) info_.part_name = unquote(r.text);
        break;
      // CATIA: the name of the tool the next LOADTL loads (it stands before it in every
      // corpus file), or of the one just loaded while it has none and nothing has moved since.
      // (Given to the tool in the spindle, T2's name went to T1's... T3's to T2; helper-56.)
      case MajorId::Tprint:
        if (!r.text.empty()) {
          std::string name(r.text.substr(0, r.text.find(',')));
          ir::ToolInfo* t = explicit_ >= 0 ? &slot(explicit_, r.loc) : nullptr;
          if (t && (t->name.empty() || t->name == op_name_) && r.motion_skipped == load_motion_) t->name = name;
          else pending_name_ = name;
        }
        break;
      case MajorId::Machin: case MajorId::Mode:
        if (!r.params.empty()) family(r, r.params[0]);
        break;
      case MajorId::Toolno:  // CATIA: TOOLNO/n,TURN|MILL|DRILL,...
        if (r.params.size() > 1) family(r, r.params[1]);
        break;
      default: break;
    }
  }

  // A word saying which kind of machine the file is for: the first one is kept; a file that
  // says both (a mill-turn part) says nothing.
  void family(const Record& r, const Param& word) {
    if (!word.is_word() || mixed_) return;
    std::string said;
    for (const char* w : {"TURN", "LATHE", "GROOVE", "THREAD"})
      if (word.is(w)) said = "lathe";
    // A drill says nothing: NX writes TLDATA/DRILL for centreline drilling on a lathe too.
    if (word.is("MILL")) said = "mill";
    if (said.empty()) return;
    if (!info_.family_said.empty() && info_.family_said != said) {
      mixed_ = true;
      info_.family_said.clear();
      info_.lathe = false;
      return;
    }
    if (!info_.family_said.empty()) return;
    info_.family_said = said;
    info_.family_record = std::string(r.major) + "/";
    for (size_t i = 0; i < r.params.size() && &r.params[i] <= &word; ++i)
      info_.family_record += (i ? "," : "") + std::string(r.params[i].name());
    info_.family_loc = r.loc;
    info_.lathe = said == "lathe";
  }

  ir::ProgramInfo finish() {
    end_op();
    // Number the named-only tools with numbers no record uses.
    std::set<int> used;
    for (auto& t : info_.tools) if (!t.auto_numbered) used.insert(t.number);
    // A name that is a pocket number (NX's TOOL,12) is that number where no record uses it.
    std::set<const ir::ToolInfo*> by_name;
    for (auto& t : info_.tools) {
      if (!t.auto_numbered || t.name.empty() || t.name.size() > 3 ||
          t.name.find_first_not_of("0123456789") != std::string::npos)
        continue;
      const int n = std::stoi(t.name);
      if (n < 1 || used.count(n)) continue;
      t.number = n;
      by_name.insert(&t);
      used.insert(n);
    }
    int next = 1;
    for (auto& t : info_.tools) {
      if (!t.auto_numbered || by_name.count(&t)) continue;
      while (used.count(next)) ++next;
      t.number = next;
      used.insert(next);
    }
    for (const auto& [line, name] : named_ops_) info_.named_tool_ops.emplace_back(line, info_.tool_number_for_name(name));
    // A length on the load (LOADTL/n,LENGTH,l) for a tool its data (TLDATA, CUTTER) gave none.
    for (const auto& [i, length] : load_lengths_)
      if (info_.tools[i].length == 0) info_.tools[i].length = length;
    for (size_t i : loads_)
      if (info_.tool_changes.empty() || info_.tool_changes.back() != info_.tools[i].number)
        info_.tool_changes.push_back(info_.tools[i].number);
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
    info_.units_doubt = units_doubt(info_);
    return std::move(info_);
  }

  // Whether the numbers look like the other unit than the file says (docs/cl-input.md, "Units"):
  // feeds written in the other unit's words, or a tool no shop holds in this unit.
  std::string units_doubt(const ir::ProgramInfo& info) const {
    if (!info.units_given || info.units_reason == "--input-units") return {};
    const ir::Units other = info.units == ir::Units::Mm ? ir::Units::Inch : ir::Units::Mm;
    if (feed_word_loc_[int(other)].valid())
      return "the feed at line " + std::to_string(feed_word_loc_[int(other)].line) + " is in " +
             (other == ir::Units::Inch ? "inches" : "millimetres");
    for (const ir::ToolInfo& t : info.tools) {
      const double mm = t.diameter * ir::mm_per_unit(info.units);
      if (info.units == ir::Units::Inch && mm > 6 * 25.4)
        return "tool T" + std::to_string(t.number) + " would be " + num_text(t.diameter) + " in across (" +
               num_text(std::round(mm)) + " mm)";
    }
    return {};
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
  static bool has_geometry(const ir::ToolInfo& t) {
    return t.diameter != 0 || t.corner_radius != 0 || t.length != 0 || !t.kind.empty();
  }
  // The first geometry a tool number is given is its own; another diameter later is noted (a
  // pocket holds one cutter) for the lowerer to warn of and a cutting speed to refuse.
  static void attach(ir::ToolInfo& t, const ToolGeometry& g) {
    if (t.kind.empty()) t.kind = g.kind;
    if (t.length == 0) t.length = g.length;
    if (t.diameter == 0 && t.corner_radius == 0) {  // a kind alone (TLDATA/MILL) gives no diameter
      t.diameter = g.diameter;
      t.corner_radius = g.corner_radius;
    } else if (g.diameter > 0 && std::abs(g.diameter - t.diameter) > 1e-9 && !t.other_diameter_at.valid()) {
      t.other_diameter_at = g.loc;
      t.other_diameter = g.diameter;
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
      loads_.push_back(size_t(found - info_.tools.data()));
    }
    in_op_ = false;
    explicit_ = -1;
    op_name_.clear();
    pending_ = {};
  }

  const PrescanOptions& opt_;
  ir::ProgramInfo info_;
  bool order_known_ = false;  // the first plain CUTTER/TLDATA seen: does the file write them
  bool after_load_ = false;   // after their load (true) or before it (CATIA, NX)?
  bool in_op_ = false;
  std::string op_name_;
  SourceLoc op_loc_;
  int explicit_ = -1;
  ToolGeometry pending_;
  std::optional<ir::Frame> msys0_;
  std::string pending_name_;  // TPRINT before its LOADTL
  uint32_t load_motion_ = 0;  // motion records before the last load (Record::motion_skipped)
  bool mixed_ = false;        // the file says mill and lathe
  std::optional<ir::Units> units_, feed_units_;
  SourceLoc feed_word_loc_[2];  // the first feed in mm, in inches
  std::vector<std::pair<uint32_t, std::string>> named_ops_;
  std::vector<size_t> loads_;  // each tool load, as an index into info_.tools
  std::vector<std::pair<size_t, double>> load_lengths_;  // LOADTL/n,LENGTH,l: the tool, l
  int pending_set_ = 0;
  SourceLoc pending_set_loc_;
  ir::FrameUse frame_ = base_frame();  // the frame in force
  bool frame_seen_ = false;
  bool last_frame_unpaired_ = false;
  uint32_t frame_motion_ = 0;  // motion records skipped before the last frame record

  static ir::FrameUse base_frame() {
    ir::FrameUse u;
    u.no_record = true;
    return u;
  }
};

// The CAM system, from signatures its files carry near their start (docs/cl-input.md, "CAM
// systems"). The first 64 KiB are enough: every signature is a header or an early record. A
// signature is a record only that system writes: a shop's "$$-> ROUGH" comment made a file
// Creo's (whose arcs join later points on the circle: a chord became a half circle, certified),
// and a CYCLE/INIT, which any ISO 4343 post writes, made one SolidWorks CAM's (ROTABL radians).
void recognise_cam_system(const SourceFile& src, ir::ProgramInfo& info) {
  std::string head(64 * 1024, '\0');
  long n = src.read_at(0, head.data(), head.size());
  head.resize(n > 0 ? size_t(n) : 0);
  struct Sig {
    const char* text;
    const char* line;  // what the line starts with (after blanks): nullptr, the text itself
    ir::CamSystem cam;
  };
  static constexpr Sig kSigs[] = {
      {"$$*CATIA0", nullptr, ir::CamSystem::Catia},       {"CATIA APT VERSION", "$$", ir::CamSystem::Catia},
      {"Pro/CLfile", "$$", ir::CamSystem::Creo},          {"$$-> MFGNO", nullptr, ir::CamSystem::Creo},
      {"$$-> FEATNO", nullptr, ir::CamSystem::Creo},      {"$$-> CSYS", nullptr, ir::CamSystem::Creo},
      {"TOOL PATH/", nullptr, ir::CamSystem::Nx},         {"APTCL-SPEC,MAKINO-FF", "PPRINT", ir::CamSystem::Nx},
      {"MOVARC/", nullptr, ir::CamSystem::Fusion},        {"MODE/MILL", nullptr, ir::CamSystem::Fusion},
      {"MODE/TURN", nullptr, ir::CamSystem::Fusion},      {"OPFEATSTART", nullptr, ir::CamSystem::SolidWorks},
      {"MACHIN/PWORKS", nullptr, ir::CamSystem::Ncl},
  };
  // The signature met first in the file wins: a header comes first, and a later comment naming
  // another system ("PPRINT SEE CATIA APT VERSION NOTES" in an NX file) turned every arc.
  size_t best = std::string::npos;
  for (const Sig& sig : kSigs) {
    std::string_view t = sig.text;
    for (size_t at = head.find(t); at != std::string::npos && at < best; at = head.find(t, at + 1)) {
      size_t ls = head.rfind('\n', at);
      ls = ls == std::string::npos ? 0 : ls + 1;
      const size_t first = head.find_first_not_of(" \t", ls);
      if (!sig.line ? first != at : head.compare(first, std::strlen(sig.line), sig.line) != 0) continue;
      best = at;
      info.cam = sig.cam;
      info.cam_evidence = "line " + std::to_string(1 + std::count(head.begin(), head.begin() + std::ptrdiff_t(at), '\n')) +
                          ": " + std::string(t);
      break;
    }
  }
}

}  // namespace

ir::ProgramInfo prescan_program(SourceFile& src, const PrescanOptions& opt) {
  MajorSet want;
  for (MajorId id : {MajorId::ToolPath, MajorId::Featno, MajorId::EndOfPath, MajorId::End,
                     MajorId::Loadtl, MajorId::Load, MajorId::Turret, MajorId::Tldata,
                     MajorId::Cutter, MajorId::Units, MajorId::Unit, MajorId::Fedrat, MajorId::Cycle, MajorId::Thread,
                     MajorId::Partno, MajorId::Tprint, MajorId::Machin, MajorId::Mode, MajorId::Toolno, MajorId::Msys, MajorId::Csys, MajorId::Camera,
                     MajorId::Set, MajorId::Select})
    want.add(id);
  TableBuilder b(opt);
  prescan_cl(src, b, want);
  ir::ProgramInfo info = b.finish();
  info.source_name = src.name();
  recognise_cam_system(src, info);
  return info;
}

}  // namespace clpc
