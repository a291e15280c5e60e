#include "readback/program_reader.h"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "machine/block_check.h"
#include "support/text.h"
#include "support/threads.h"

namespace clpc {

using ir::Vec3;

namespace {
constexpr size_t kChunk = 1 << 20;
bool finite(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }
}  // namespace

ir::Arc arc_of(const TipSegment& s) {
  ir::Arc a;
  a.start = s.start;
  a.end = s.end;
  a.center = s.center;
  a.axis = s.normal;
  a.radius = s.raw.start_radius;
  a.dir = s.raw.ccw ? ir::ArcDir::Ccw : ir::ArcDir::Cw;
  a.sweep = s.raw.sweep;
  return a;
}

ProgramReader::ProgramReader(const Machine& m, const ir::ProgramInfo& info) : m_(m), info_(info), reader_(m), timer_(m.motion, m.kinematics) {
  known_registers_.insert(m.offsets.default_index);
  pole_free_ = kin::pole_free_axis(m.kinematics);
  for (const ir::WorkOffset& w : info.offsets) known_registers_.insert(w.index);
  use_offsets_ = !info.offsets.empty();
  if (use_offsets_) {
    reference_height_ = m.offsets.reference_height;
    // Set by hand on the machine: the values clpc computed (and listed in the head).
    if (m.offsets.table == OffsetTable::None)
      for (const ir::WorkOffset& w : info.offsets) offsets_[w.index] = w.machine;
    // The default register, when no frame of the CL is put in it, holds the part frame as the
    // operator set it: untilted, its zero on the reference base (the offset the macro gives a
    // frame at the part zero, A0 C0), not on the table centre.
    bool default_listed = false;
    for (const ir::WorkOffset& w : info.offsets) default_listed |= w.index == m.offsets.default_index;
    if (!default_listed) offsets_[m.offsets.default_index] = Vec3(0, 0, reference_height_);
    // The frames the operator turns the part to: all of them without rotaries, the setups
    // beyond the rotaries' reach with.
    for (const ir::WorkOffset& w : info.offsets)
      if (!m.kinematics.has_rotaries() || w.setup > 1) setup_turns_[w.index] = w.frame.rotation;
  }
}

const ir::Mat3& ProgramReader::setup_turn(int reg) const {
  static const ir::Mat3 identity = ir::Mat3::Identity();
  auto it = setup_turns_.find(reg);
  return it == setup_turns_.end() ? identity : it->second;
}

ProgramReader::~ProgramReader() {
  stop_ahead();
  if (file_) std::fclose(file_);
}

bool ProgramReader::open(const std::string& path, std::string& error) {
  file_ = std::fopen(path.c_str(), "rb");
  if (!file_) {
    error = "cannot read '" + path + "': " + std::strerror(errno);
    return false;
  }
  return true;
}

bool ProgramReader::read_line(std::string& line) {
  line.clear();
  for (;;) {
    size_t nl = buf_.find('\n', buf_pos_);
    if (nl != std::string::npos) {
      line.append(buf_, buf_pos_, nl - buf_pos_);
      buf_pos_ = nl + 1;
      return true;
    }
    line.append(buf_, buf_pos_, std::string::npos);
    buf_.clear();
    buf_pos_ = 0;
    if (eof_) return !line.empty();
    if (channel_) {
      if (!channel_->pop(buf_)) eof_ = true;
      continue;
    }
    buf_.resize(kChunk);
    size_t n = std::fread(buf_.data(), 1, kChunk, file_);
    buf_.resize(n);
    if (n < kChunk) eof_ = true;
  }
}

kin::Angles ProgramReader::angles(const std::array<double, 3>& abc) const {
  kin::Angles a{0, 0};
  const auto& r = m_.kinematics.rotaries;
  for (size_t i = 0; i < r.size() && i < a.size(); ++i) a[i] = abc[size_t(r[i].name[0] - 'A')];
  return a;
}

// Control coordinates -> tool tip in the part frame. With tool-centre-point control X Y Z
// are the tip in the part frame already; with a dynamic work offset they are turned with the
// table about the part zero; otherwise they are machine axes, in the work offset's frame.
Vec3 ProgramReader::part_point(const gcode::Segment& s, const Vec3& p, const kin::Angles& a, const Vec3& shift) const {
  const KinematicsSettings& k = m_.kinematics;
  // In a tilted plane the control puts the tip at the plane's point, as with TCPC.
  if (s.plane) return s.plane->origin + s.plane->rotation * p;
  if (!k.has_rotaries() && !use_offsets_) return p;
  if (s.tcp) return p;
  if (s.dwo) return kin::table_rotation(k, a).transpose() * p;
  // A setup of its own (no rotaries): the register's frame turned the part, its Z up.
  Vec3 machine = setup_turn(s.work_offset) * p;
  double height = 0;
  if (use_offsets_) {
    machine += shift;
    height = reference_height_;
  }
  // The rotaries at zero (3-axis work, drilling on a five-axis machine): the chain is the
  // identity, and the reader reads millions of such segments (a peck cycle's every move).
  if (a == kin::Angles{0, 0}) return machine - Vec3(0, 0, height);
  double pivot = k.pivot;
  if (const ir::ToolInfo* t = info_.tool(s.tool)) pivot += t->length * ir::mm_per_unit(info_.units) / ir::mm_per_unit(m_.units);
  return kin::part_tip(k, a, machine, pivot) - Vec3(0, 0, height);
}

Vec3 ProgramReader::tip_at(const TipSegment& s, double t) const {
  const gcode::Segment& r = s.raw;
  kin::Angles a0 = angles(r.rotary_start), a1 = angles(r.rotary), a{0, 0};
  a = kin::between(m_.kinematics, a0, a1, t);  // a modulo axis the short way, as the control turns it
  return part_point(r, r.start + t * (r.end - r.start), a, s.shift);
}

Vec3 ProgramReader::axis_at(const TipSegment& s, double t) const {
  const gcode::Segment& r = s.raw;
  const kin::Angles a = kin::between(m_.kinematics, angles(r.rotary_start), angles(r.rotary), t);
  return setup_turn(r.work_offset) * kin::tool_axis_in_part(m_.kinematics, a);
}

bool ProgramReader::through_pole(const TipSegment& s) const {
  if (!pole_free_) return false;
  const size_t tilt = 1 - *pole_free_;
  return angles(s.raw.rotary_start)[tilt] * angles(s.raw.rotary)[tilt] < 0;
}

void ProgramReader::account(const gcode::Segment& s) {
  ProgramTotals& t = totals_;
  if (dynamic_time_) timer_.add(s);
  const bool known = finite(s.start) && finite(s.end);
  double len = 0;
  if (known) {
    if (s.kind == gcode::Segment::Kind::Arc) {
      double rise = (s.end - s.start).dot(s.normal);
      len = std::hypot(s.start_radius * s.sweep * 3.14159265358979323846 / 180, rise);
    } else {
      len = (s.end - s.start).norm();
    }
  }
  switch (s.kind) {
    case gcode::Segment::Kind::Rapid: {
      ++t.rapids;
      t.rapid_length += len;
      if (!known) break;
      double longest = (s.end - s.start).cwiseAbs().maxCoeff();
      if (m_.rapid_rate > 0) t.rapid_minutes += longest / m_.rapid_rate;
      else if (longest > 0) t.rapid_time_known = false;
      break;
    }
    case gcode::Segment::Kind::Feed:
    case gcode::Segment::Kind::Arc: {
      ++(s.kind == gcode::Segment::Kind::Arc ? t.arcs : t.feeds);
      t.feed_length += len;
      if (s.inverse_time) {
        if (s.feed > 0) t.feed_minutes += 1 / s.feed;
      } else if (m_.kinematics.degrees_per_minute && gcode::feeds_combined(s)) {
        if (s.feed > 0) t.feed_minutes += gcode::combined_length(s, m_.kinematics) / s.feed;
        else t.feed_time_known = false;
      } else if (len > 0) {
        double rate = s.per_rev ? s.feed * s.rpm : s.feed;
        if (rate > 0) t.feed_minutes += len / rate;
        else t.feed_time_known = false;
      }
      break;
    }
  }
}

void ProgramReader::take_events() {
  gcode::Result& r = reader_.result();
  for (const gcode::Event& e : r.events) {
    switch (e.kind) {
      case gcode::Event::Kind::OffsetSet:
        // Where the CL sets no work offset the registers are the operator's: a G10 L2 P1 X100.
        // moved G54 and the whole part was cut elsewhere, passed (helper-60).
        if (!use_offsets_) {
          r.problems.push_back({e.line, "G10 sets work offset register " + std::to_string(e.reg) +
                                            ", which the operator sets up: the CL gives it no value, so the part's "
                                            "zero would move"});
          break;
        }
        known_registers_.insert(e.reg);
        offsets_[e.reg] = e.v;
        break;
      case gcode::Event::Kind::ToolChange:
        timer_.stop();
        ++totals_.tool_changes;
        if (m_.tool_change_time > 0) totals_.tool_change_minutes += m_.tool_change_time / 60;
        else totals_.tool_change_time_known = false;
        break;
      case gcode::Event::Kind::Dwell:
        timer_.stop();
        totals_.dwell_minutes += e.value / 60;
        break;
      case gcode::Event::Kind::Stop:
      case gcode::Event::Kind::Spindle: timer_.stop(); break;
      case gcode::Event::Kind::CycleStart: ++totals_.cycle_holes; break;
      default: break;
    }
  }
  r.events.clear();
}

bool ProgramReader::read_next(TipSegment& out) {
  gcode::Result& r = reader_.result();
  while (next_segment_ >= r.segments.size()) {
    r.segments.clear();
    next_segment_ = 0;
    if (!read_line(line_)) {
      // A program with no M30 or M02 was passed: the control stops at the last block with the
      // spindle turning and the program not rewound (a hand edit that cut the end off).
      if (!r.ended && !end_said_ && totals_.lines > 0) {
        end_said_ = true;
        r.problems.push_back({int(totals_.lines), "the program has no end (M30 or M02): the control stops after its last "
                                                  "block with the spindle and coolant as they were"});
      }
      if (dynamic_time_ && timer_.known()) {
        totals_.dynamic_known = true;
        totals_.dynamic_minutes = timer_.minutes() + totals_.dwell_minutes + totals_.tool_change_minutes;
      }
      return false;
    }
    ++totals_.lines;
    totals_.bytes += long(line_.size()) + 1;
    reader_.line(line_);
    totals_.blocks = r.blocks;
    take_events();  // an offset set on a line applies to that line's own motion (G10 comes first)
  }
  const gcode::Segment& s = r.segments[next_segment_++];
  account(s);
  if (!known_registers_.count(s.work_offset) && reported_registers_.insert(s.work_offset).second) {
    const std::string name = s.work_offset <= 6 ? "G" + std::to_string(53 + s.work_offset)
                                                : "extended work offset " + std::to_string(s.work_offset - 6);
    r.problems.push_back({s.line, "the program works in " + name +
                                      ", which it never sets and the setup does not list: the tool goes wherever that "
                                      "register's zero happens to be"});
  }
  out.raw = s;
  out.shift = Vec3::Zero();
  if (use_offsets_)
    if (auto it = offsets_.find(s.work_offset); it != offsets_.end()) out.shift = it->second;
  const kin::Angles a0 = angles(s.rotary_start), a1 = angles(s.rotary);
  if (!table_turned_said_ && turned_without_part_frame(s, a0, a1)) {
    table_turned_said_ = true;
    r.problems.push_back({s.line, table_turned_problem()});
  }
  out.start = part_point(s, s.start, a0, out.shift);
  out.end = part_point(s, s.end, a1, out.shift);
  out.rotates = a0 != a1;
  if (m_.kinematics.has_rotaries() && a1 != axis_angles_) {
    // 3+2 work reads thousands of segments at the same angles: the chain is turned once for them.
    axis_angles_ = a1;
    axis_in_part_ = kin::tool_axis_in_part(m_.kinematics, a1);
  }
  out.axis = setup_turn(s.work_offset) * axis_in_part_;
  if (s.kind == gcode::Segment::Kind::Arc) {
    out.center = part_point(s, s.center, a1, out.shift);
    out.normal = s.plane ? Vec3(s.plane->rotation * s.normal)
                 : s.tcp ? s.normal
                 : !m_.kinematics.has_rotaries()
                     ? Vec3(setup_turn(s.work_offset) * s.normal)
                     : Vec3(setup_turn(s.work_offset) * kin::table_rotation(m_.kinematics, a1).transpose() * s.normal);
  }
  out.index = index_++;
  return true;
}

// On a machine whose 3+2 and five-axis work are both written in the part's frame (a dynamic
// work offset or a tilted plane, and TCPC), the shop sets the work offset at the part's zero,
// wherever that lies from the table's centre of rotation. A move with the table turned and none
// of them in force is then in machine axes about a point clpc does not know: G254 deleted after
// a B90 C90 index passed, read as if the part's zero were on the centre (helper-49). A machine
// whose posts transform (kinematics.simultaneous or .indexed = "transform") has its work offset
// on that centre by its own rule, and is read so. Rotary-only moves (the index itself) are not
// judged; a move to a place from an unknown one is (the approach before G254).
bool ProgramReader::turned_without_part_frame(const gcode::Segment& s, const kin::Angles& a0, const kin::Angles& a1) const {
  const KinematicsSettings& k = m_.kinematics;
  if (!k.has_rotaries() || k.simultaneous == Simultaneous::Transform || k.indexed == Indexed::Transform) return false;
  auto turned = [&](const kin::Angles& a) {  // a table's rotary (a head's turns the tool, not the part's zero)
    for (size_t i = 0; i < k.rotaries.size() && i < a.size(); ++i)
      if (k.rotaries[i].table && std::isfinite(a[i]) && a[i] != 0) return true;  // (an angle not yet known is no turn)
    return false;
  };
  if (s.tcp || s.dwo || s.plane || !(turned(a0) || turned(a1))) return false;
  for (int i = 0; i < 3; ++i)
    if (std::isfinite(s.end[i]) && !(s.start[i] == s.end[i])) return true;  // X, Y or Z moved (from unknown, too)
  return false;
}

std::string ProgramReader::table_turned_problem() const {
  // The code a template turns the mode on with: its last G word (G234 of "G00 G234 H{offset}").
  auto g_code = [](const std::string& text) -> std::string {
    const std::vector<double> g = code_numbers(text, 'G');
    if (g.empty()) return "";
    char word[32];
    std::snprintf(word, sizeof word, "G%g", g.back());
    return word;
  };
  std::string modes;  // the machine's ways of working in the part's frame
  auto add = [&](const std::string& what, const std::string& code) {
    if (!code.empty()) modes += (modes.empty() ? "" : ", ") + what + " (" + code + ")";
  };
  add("TCPC", g_code(m_.codes.tcp_on.text));
  add("a dynamic work offset", g_code(m_.codes.dwo_on.text));
  add("a tilted plane", g_code(m_.codes.plane_on.text));
  return "the table is turned and none of " + modes + " is in force: the control moves X Y Z as machine axes, and where "
         "the part's zero lies from the table's centre of rotation is the setup's, unknown here (this machine writes its "
         "3+2 and five-axis work in the part's frame)";
}

std::vector<gcode::Problem> ProgramReader::take_reader_problems() {
  std::vector<gcode::Problem> p;
  p.swap(reader_.result().problems);
  return p;
}

std::vector<gcode::Problem> ProgramReader::take_problems() {
  if (!ahead_) return take_reader_problems();
  std::vector<gcode::Problem> p;
  p.swap(problems_);
  return p;
}

bool ProgramReader::next(TipSegment& out) {
  if (!ahead_) return read_next(out);
  if (ended_) return false;
  if (current_at_ == current_.size()) {
    std::unique_lock<std::mutex> g(lock_);
    handoff_.wait_for_items(g, [&] { return batches_.size(); }, [&] { return last_batch_in_; });
    current_ = std::move(batches_.front());  // (the last batch holds the end: never empty before)
    batches_.pop_front();
    current_at_ = 0;
    handoff_.taken(g, batches_.size());
  }
  Item& it = current_[current_at_++];
  for (gcode::Problem& p : it.problems) problems_.push_back(std::move(p));
  if (it.end) {
    ended_ = true;
    return false;
  }
  out = std::move(it.segment);
  return true;
}

void ProgramReader::read_ahead() {
  if (ahead_ || !threads_available()) return;  // (without threads next() reads as asked)
  ahead_ = true;
  thread_ = std::thread([this] { ahead(); });
}

void ProgramReader::ahead() {
  name_this_thread("clpc-readback");
  for (bool end = false; !end;) {
    std::vector<Item> batch;
    batch.reserve(kBatch);
    while (batch.size() < kBatch && !end) {
      Item& it = batch.emplace_back();  // read in place: a segment is some hundreds of bytes
      end = !read_next(it.segment);
      it.end = end;
      it.problems = take_reader_problems();
    }
    std::unique_lock<std::mutex> g(lock_);
    handoff_.wait_for_room(g, [&] { return batches_.size(); }, [&] { return stop_; });
    if (stop_) return;
    batches_.push_back(std::move(batch));
    if (end) {
      last_batch_in_ = true;
      g.unlock();
      handoff_.wake_both();
    } else {
      handoff_.added(g, batches_.size());
    }
  }
}

void ProgramReader::stop_ahead() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> g(lock_);
    stop_ = true;
  }
  handoff_.wake_both();
  thread_.join();
}

const ProgramTotals& ProgramReader::totals() {
  stop_ahead();
  return totals_;
}

}  // namespace clpc
