// The evidence behind each CAM dialect's arc convention (docs/arcs.md): over every arc of the
// corpus, where the tangent of the neighbouring cutting moves decides a direction, it must
// agree with the sense lowering reads for it (the CAM system's CIRCLE convention; INDIRV for
// CATIA's contours).
#include "helpers.h"
#include "passes/arc_direction.h"

using namespace clpc;
using namespace clpc::test;

TEST(ArcConventions, CorpusGeometryAgreesWithEachDialectsConvention) {
  if (corpus_dir().empty()) GTEST_SKIP() << "no corpus at " << CLPC_CORPUS_DIR;
  struct Tally {
    int arcs = 0, agree = 0, disagree = 0, undecided = 0, conflicting = 0;
  };
  std::map<std::string, Tally> by_layout;
  for (const std::string& f : corpus_files()) {
    Lowered l = lower_text(read_file(f));
    const double min_len = 20 * 0.001 / ir::mm_per_unit(l.info.units);
    ir::Vec3 last(0, 0, 0), incoming(0, 0, 0);
    bool have_last = false;
    for (const auto& op : l.ops) {
      for (size_t i = 0; i < op.body.size(); ++i) {
        const auto& in = op.body[i];
        if (auto* m = std::get_if<ir::Move>(&in.op)) {
          incoming = m->kind == ir::MoveKind::Feed && have_last ? ir::Vec3(m->point - last) : ir::Vec3::Zero();
          last = m->point;
          have_last = true;
          continue;
        }
        auto* a = std::get_if<ir::Arc>(&in.op);
        if (!a) continue;
        ir::Vec3 out = ir::Vec3::Zero();
        for (size_t j = i + 1; j < op.body.size(); ++j) {
          if (auto* m = std::get_if<ir::Move>(&op.body[j].op)) {
            if (m->kind == ir::MoveKind::Feed) out = m->point - a->end;
            break;
          }
          if (std::holds_alternative<ir::Arc>(op.body[j].op)) break;
        }
        ArcEvidence e = arc_evidence(op, *a, incoming, out, min_len);
        const char* form = a->layout == ir::ArcLayout::Nx11      ? "CIRCLE, 11 values"
                           : a->layout == ir::ArcLayout::Creo7   ? "CIRCLE, 7 values"
                           : a->layout == ir::ArcLayout::Contour ? "TLON,GOFWD circle"
                                                                 : "other";
        std::string key = std::string(ir::cam_system_name(l.info.cam)) + ", " + form;
        Tally& t = by_layout[key];
        ++t.arcs;
        if (e.conflicting()) ++t.conflicting;
        else if (e.geometry() == ir::ArcDir::Unknown) ++t.undecided;
        else if (e.geometry() == a->hint) ++t.agree;
        else {
          ++t.disagree;
          ADD_FAILURE() << f << ":" << in.loc.line << ": geometry says the other way round";
        }
        incoming.setZero();  // the next move's tangent comes from this arc; not tallied here
        last = a->end;
      }
    }
  }
  for (auto& [layout, t] : by_layout) {
    std::printf("%-26s %4d arcs: geometry agrees with the convention %4d, disagrees %d, undecided %d, conflicting %d\n",
                layout.c_str(), t.arcs, t.agree, t.disagree, t.undecided, t.conflicting);
    EXPECT_EQ(t.disagree, 0);
    EXPECT_GT(t.agree, t.arcs / 4) << layout << ": too little evidence";
  }
  EXPECT_EQ(by_layout.count("NX, CIRCLE, 11 values"), 1u);
  EXPECT_EQ(by_layout.count("Creo, CIRCLE, 7 values"), 1u);
  EXPECT_EQ(by_layout.count("CATIA, TLON,GOFWD circle"), 1u);
}
