// Subroutines: DEFSUB/n ... ENDSUB keeps copies of the body's records; CALSUB/n replays them
// through lowering, so a subroutine behaves exactly as if its records were written in place.
#include "lower/lower.h"
#include "lower/params.h"

namespace clpc {

namespace {
constexpr int kMaxCallDepth = 16;
constexpr size_t kMaxStoredRecords = 1u << 20;
// Calls inside calls multiply: eleven levels of twenty calls replayed 2e14 moves, writing
// 23 MB/s until the disk filled. No real file replays this many records.
constexpr size_t kMaxReplayedRecords = 1u << 22;
}  // namespace

// Called for DEFSUB, and for every record while a DEFSUB is open. Returns true when the
// record was taken into the definition.
bool Lowerer::record_subroutine(const Record& r) {
  if (defining_sub_ < 0) {  // DEFSUB itself
    ParamReader ps(r, d_);
    auto n = ps.integer(0, "the subroutine number", 0, 99999);
    if (!n) return true;
    if (subs_.count(*n)) d_.warning(r.loc, "DEFSUB/" + std::to_string(*n) + " redefines an earlier subroutine", "subroutine");
    subs_[*n].clear();
    defining_sub_ = *n;
    defining_loc_ = r.loc;
    return true;
  }
  if (r.kind == Record::Kind::Statement && !r.data_comment) {
    if (r.id == MajorId::Endsub) {
      defining_sub_ = -1;
      return true;
    }
    if (r.id == MajorId::Defsub) {
      d_.error(r.loc, "DEFSUB inside DEFSUB/" + std::to_string(defining_sub_) + ": subroutine definitions cannot nest");
      return true;
    }
  }
  if (r.kind == Record::Kind::Comment) return true;
  if (keep_stored(r)) subs_[defining_sub_].push_back(OwnedRecord::of(r));
  return true;
}

bool Lowerer::keep_stored(const Record& r) {
  if (++stored_records_ > kMaxStoredRecords) {
    if (stored_records_ == kMaxStoredRecords + 1)
      d_.error(r.loc, "subroutines and INDEX blocks hold more than 1048576 records; clpc stops keeping them");
    return false;
  }
  return true;
}

Lowerer::OwnedRecord Lowerer::OwnedRecord::of(const Record& r) {
  OwnedRecord o;
  o.rec = r;
  o.head.assign(r.head.begin(), r.head.end());
  o.params.assign(r.params.begin(), r.params.end());
  auto own = [&](std::string_view t) {
    o.storage.append(t);
    o.sizes.push_back(uint32_t(t.size()));
  };
  own(r.major);
  own(r.text);
  for (const Param& p : r.head) own(p.text);
  for (const Param& p : r.params) own(p.text);
  return o;
}

// The record again, its text in this copy's storage; `scratch` holds head and parameters.
Record Lowerer::OwnedRecord::view(std::vector<Param>& scratch) const {
  Record v = rec;
  std::string_view all = storage;
  size_t at = 0, k = 0;
  auto next = [&] {
    std::string_view t = all.substr(at, sizes[k]);
    at += sizes[k++];
    return t;
  };
  v.major = next();
  v.text = next();
  scratch.assign(head.begin(), head.end());
  scratch.insert(scratch.end(), params.begin(), params.end());
  for (Param& p : scratch) p.text = next();
  v.head = std::span<const Param>(scratch.data(), head.size());
  v.params = std::span<const Param>(scratch.data() + head.size(), params.size());
  return v;
}

void Lowerer::lower_calsub(const Record& r) {
  ParamReader ps(r, d_);
  auto n = ps.integer(0, "the subroutine number", 0, 99999);
  if (!n) return;
  if (r.params.size() > 1) {
    // CALSUB/1,3 or CALSUB/1,TIMES,3: a repeat count, or an argument; played once it was lost.
    d_.error(r.params[1].loc, "CALSUB/" + std::to_string(*n) + ": the words after the subroutine number (a repeat "
                              "count?) are not read; write one CALSUB/" + std::to_string(*n) + " for each call");
    return;
  }
  auto it = subs_.find(*n);
  if (it == subs_.end()) {
    d_.error(r.params[0].loc, "CALSUB/" + std::to_string(*n) + ": no such subroutine (DEFSUB must come first)");
    return;
  }
  if (call_depth_ >= kMaxCallDepth) {
    d_.error(r.loc, "CALSUB/" + std::to_string(*n) + ": subroutine calls nest deeper than 16 (recursion?)");
    return;
  }
  ++call_depth_;
  // A copy: the body could redefine subroutines while it plays.
  std::vector<OwnedRecord> body = it->second;
  std::vector<Param> scratch;
  d_.push_context(r.loc, "called from");
  for (const OwnedRecord& o : body) {
    if (!replay_one_more(r.loc)) break;
    record(o.view(scratch));
  }
  d_.pop_context();
  --call_depth_;
}

// One more record replayed by a CALSUB or a COPY, false past the limit (said once): calls and
// copies inside others multiply (COPY of 10000 inside COPY of 10000 wrote 2.77 GB from 16
// lines, and one more level would never end; helper-51).
bool Lowerer::replay_one_more(SourceLoc at) {
  if (++replayed_records_ <= kMaxReplayedRecords) return true;
  if (replayed_records_ == kMaxReplayedRecords + 1)
    d_.error(at, "CALSUB and COPY replay more than " + std::to_string(kMaxReplayedRecords) +
                     " records (calls and copies inside others multiply); clpc stops replaying them");
  return false;
}

}  // namespace clpc
