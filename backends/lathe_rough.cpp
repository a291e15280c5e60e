// Stock removal on a Fanuc lathe (docs/lathe.md, "Stock removal"): a CYCLE/ROUGH section
// becomes the two-block G71 (G72 for facing), its profile numbered N(P) .. N(Q) right after it,
// and G70 when the CL finishes too:
//   G71 U(d) R(e)
//   G71 P(P) Q(Q) U(2u) W(w) F(f)
//   N(P) G00 X(A')          the first block: along the level axis alone (type I)
//   ...                     the profile, written as any motion
//   N(Q) G01 X(B) Z(B)      its end, named
//   G70 P(P) Q(Q)
// The section is proved first with the control's own expansion (ir/stock_model.h): a profile
// the control would refuse (a pocket, a first block along both axes) is a located error.
#include <cmath>

#include "backends/lathe.h"
#include "ir/stock_model.h"
#include "support/text.h"

namespace clpc {

namespace {

// P and Q are sequence numbers: whole numbers, never a point.
AddressFormat sequence_format() {
  AddressFormat f;
  f.decimals = 0;
  f.point = AddressFormat::Point::Never;
  return f;
}

}  // namespace

void LatheBackend::write_rough(const ir::Operation& op, size_t at, SourceLoc loc) {
  const ir::RoughMark& m = std::get<ir::RoughMark>(op.body[at].op);
  size_t end = at + 1;
  while (end < op.body.size() && !std::holds_alternative<ir::RoughMark>(op.body[end].op)) ++end;
  resume_at_ = end + 1;
  if (end >= op.body.size()) {
    d_.error(loc, "internal: CYCLE/ROUGH's profile does not end in its chunk");
    return;
  }
  if (!tool_loaded_for_cut(loc)) return;
  const char* name = m.facing ? "G72" : "G71";
  const CodeTemplate& code = m.facing ? m_.codes.rough_face : m_.codes.rough_turn;
  if (code.empty() || (m.finish && m_.codes.rough_finish.empty())) {
    d_.error(loc, "machine '" + m_.name + "' has no " + (code.empty() ? std::string(name) : std::string("G70")) +
                      " (codes." + (code.empty() ? (m.facing ? "rough_face" : "rough_turn") : "rough_finish") +
                      "): CYCLE/ROUGH cannot be written");
    return;
  }
  if (!position_known_ || !in_plane(m.start, loc)) {
    if (!position_known_) d_.error(loc, "CYCLE/ROUGH with no programmed position before it: the cycle starts where the tool stands");
    return;
  }
  // The profile as the control will read it, in output units; only motion may stand in it.
  std::vector<stock::Element> profile;
  ir::Vec3 p = m.start;
  size_t first_move = 0;
  for (size_t i = at + 1; i < end; ++i) {
    const ir::Instr& in = op.body[i];
    if (const auto* mv = std::get_if<ir::Move>(&in.op)) {
      if (mv->kind == ir::MoveKind::From) continue;
      if (!in_plane(mv->point, in.loc)) return;
      if (!first_move) first_move = i;
      profile.push_back({p * k_, mv->point * k_, false, ir::Vec3::Zero(), false, 0});
      p = mv->point;
    } else if (const auto* a = std::get_if<ir::Arc>(&in.op)) {
      if (!in_plane(a->end, in.loc) || !in_plane(a->center, in.loc)) return;
      if (!first_move) first_move = i;
      const bool ccw = (a->dir == ir::ArcDir::Ccw) == (a->axis.y() > 0);  // about +Y
      profile.push_back({p * k_, a->end * k_, true, a->center * k_, ccw, 0});
      p = a->end;
    } else if (!std::holds_alternative<ir::Feed>(in.op) && !std::holds_alternative<ir::Comment>(in.op)) {
      d_.error(in.loc, "inside CYCLE/ROUGH only the profile's motion (and its feeds) may stand: the control reads these "
                       "blocks as the profile");
      return;
    }
  }
  // Proved with the numbers as written, as verify and the rough-cycles pass take them: the
  // control computes where each level meets the profile from those.
  std::string why;
  stock::Params params = stock::params_of(m, k_, true);
  ir::Vec3 start = m.start * k_;
  if (!stock::round_as_written(params, start, profile, [&](char letter, double v) { return as_written(v, m_.format(letter)); })) {
    d_.error(loc, std::string("CYCLE/ROUGH: a word of the ") + name + " cycle or its profile cannot be written");
    return;
  }
  if (stock::expand(start, profile, params, why).empty()) {
    d_.error(loc, std::string("CYCLE/ROUGH: the control's ") + name + " cannot cut this profile: " + why);
    return;
  }
  const auto* first = first_move ? std::get_if<ir::Move>(&op.body[first_move].op) : nullptr;
  if (!first) {
    d_.error(loc, "CYCLE/ROUGH: the profile must begin with a straight move along " + std::string(m.facing ? "Z" : "X"));
    return;
  }
  long np = 0, nq = 0;
  if (!e_.reserve_number(np) || !e_.reserve_number(nq)) {
    d_.error(loc, "the program's block numbers have wrapped past N" + std::to_string(m_.sequence.max) + ": " + name +
                      "'s P and Q could name two blocks; raise sequence.max");
    return;
  }
  // A G41/G42 waiting for its first move would start on a profile block: the control would
  // ramp the nose radius on along the profile's first cut (a taper where the CL has none), and
  // the roughing before G70 would run uncompensated.
  if (comp_pending_set_ && comp_pending_.side != ir::CompSide::Off) {
    d_.error(loc, std::string("cutter compensation (CUTCOM) starts inside the ") + name +
                      " cycle's profile: the control would start it on a profile block, not where the CL does; start it "
                      "on the move to the cycle's start point (CUTCOM before that move)");
    return;
  }
  const double feed = m.feed > 0 ? m.feed : feed_;
  const ir::FeedMode mode = m.feed > 0 ? m.feed_mode : feed_mode_;
  if (!(feed > 0)) {
    d_.error(loc, "CYCLE/ROUGH with no feed rate: give FEED in the record or a FEDRAT before it");
    return;
  }
  end_drill_speed(loc);  // never inside P..Q, where the control reads no S
  restore_after_stop(loc, true);
  cut_since_stop_ = true;
  const AddressFormat seq = sequence_format();
  const AddressFormat& len = m_.format('Z');  // radius values, as lengths
  e_.begin(loc);
  absolute_code();
  e_.code(code);
  e_.argument(m.facing ? 'W' : 'U', m.depth * k_, len);
  e_.argument('R', m.retract * k_, len);
  e_.end();
  e_.begin(loc);
  feed_mode_code(mode);
  e_.code(code);
  e_.argument('P', double(np), seq);
  e_.argument('Q', double(nq), seq);
  e_.argument('U', m.allow_x * k_, m_.format('X'));  // the diameter, as X is written
  e_.argument('W', m.allow_z * k_, len);
  if (!write_feed(feed * k_, mode, m.feed > 0 ? loc : feed_loc_)) return;
  e_.end();
  feed_written_ = false;

  // N(P): along the level axis alone, as the control requires of type I.
  const ir::Vec3 a1 = first->point * k_;
  e_.number_next(np);
  e_.begin(op.body[first_move].loc);
  motion_ = Motion::None;  // the control wants G00 or G01 in this block, modal or not
  motion_code(first->kind == ir::MoveKind::Rapid ? Motion::Rapid : Motion::Linear);
  if (m.facing) e_.word('Z', a1.z());
  else e_.word('X', a1.x());
  e_.end();
  pos_ = first->point;
  for (size_t i = first_move + 1; i < end; ++i) visit(op, op.body[i]);
  // N(Q): where the profile ends, named (a block of no length: the profile's last block may
  // have written nothing, its end being where the tool was).
  e_.number_next(nq);
  e_.begin(op.body[end].loc);
  motion_code(Motion::Linear);
  e_.word('X', pos_.x() * k_);
  e_.word('Z', pos_.z() * k_);
  e_.end();
  if (m.finish) {
    e_.begin(op.body[end].loc);
    e_.code(m_.codes.rough_finish);
    e_.argument('P', double(np), seq);
    e_.argument('Q', double(nq), seq);
    e_.end();
  }
  // The control is back at A; the profile's modal words were read, not run.
  motion_ = Motion::None;
  feed_written_ = false;
  e_.set_last('X', m.start.x() * k_);
  e_.set_last('Z', m.start.z() * k_);
  reach_.went_in = false;  // the cycle returns to its start
  pos_ = m.start;
  position_known_ = true;
}

}  // namespace clpc
