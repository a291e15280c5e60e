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

// INDIRV before a CIRCLE is the way the tool sets off round it (APT: the next motion's
// direction). It was dropped: an arc INDIRV sends clockwise the long way round (270 degrees) was
// cut counter-clockwise by the right-hand rule, certified (helper-48). It decides where nothing
// else does; a known CAM system's convention or a sense word saying the other way, or an INDIRV
// along the radius, is an error at the CIRCLE; a GOTO between uses it up.
TEST(ArcConventions, IndirvBeforeACircleGivesItsSense) {
  auto cl = [](const std::string& head, const std::string& indirv, const std::string& circle) {
    return head + "UNITS/MM\nLOADTL/1\nCUTTER/10\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/10,0,5\nFEDRAT/MMPM,200\nGOTO/10,0,-1\n" +
           indirv + circle + "\nGOTO/0,10,-1\nGOTO/0,10,5\nRAPID\nGOTO/0,10,50\nFINI\n";
  };
  const std::string circle = "CIRCLE/0,0,-1,0,0,1,10";
  Compiled cw = compile_text(cl("", "INDIRV/0,-1,0\n", circle), machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(cw.ok) << cw.diags;
  EXPECT_THAT(cw.output, ::testing::HasSubstr("G17 G02 X0. Y10. I-10. J0.\n"));
  Compiled ccw = compile_text(cl("", "INDIRV/0,1,0\n", circle), machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(ccw.ok) << ccw.diags;
  EXPECT_THAT(ccw.output, ::testing::HasSubstr("G17 G03 X0. Y10. I-10. J0.\n"));
  // Used up by the GOTO after it: the circle keeps the right-hand rule.
  Compiled stale = compile_text(cl("", "INDIRV/0,-1,0\nGOTO/10,0,-1\n", circle), machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(stale.ok) << stale.diags;
  EXPECT_THAT(stale.output, ::testing::HasSubstr("G17 G03 X0. Y10. I-10. J0.\n"));
  // A GODLTA (or FROM, GOHOME, MOVARC) uses it up as well: an INDIRV down the axis for a plunge
  // was taken for the circle's and refused it.
  Compiled plunge = compile_text(cl("", "GOTO/10,0,0\nINDIRV/0,0,-1\nGODLTA/0,0,-1\n", circle), machine("fanuc-mill"),
                                 {.certify = true});
  ASSERT_TRUE(plunge.ok) << plunge.diags;
  EXPECT_THAT(plunge.output, ::testing::HasSubstr("G17 G03 X0. Y10. I-10. J0.\n"));
  Compiled worded = compile_text(cl("", "INDIRV/0,-1,0\n", circle + ",CCLW"), machine("fanuc-mill"));
  EXPECT_FALSE(worded.ok);
  EXPECT_THAT(worded.diags, ::testing::HasSubstr("part.cls:10:1: error: CIRCLE: INDIRV at line 9 sets off clockwise about the "
                                                 "circle's axis, the circle's own sense is the other way: which way the tool "
                                                 "goes is ambiguous"));
  Compiled nx = compile_text(cl("TOOL PATH/OP1,TOOL,EM10\n", "INDIRV/0,1,0\n", circle), machine("fanuc-mill"));
  EXPECT_FALSE(nx.ok);
  EXPECT_THAT(nx.diags, ::testing::HasSubstr("part.cls:11:1: error: CIRCLE: INDIRV at line 10 sets off counter-clockwise"));
  Compiled radial = compile_text(cl("", "INDIRV/1,0,0\n", circle), machine("fanuc-mill"));
  EXPECT_FALSE(radial.ok);
  EXPECT_THAT(radial.diags, ::testing::HasSubstr("part.cls:10:1: error: CIRCLE: INDIRV at line 9 points along the circle's "
                                                 "radius or axis: which way round the tool goes is not said"));
}
