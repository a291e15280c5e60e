// Real CL files as each CAM system writes them, for the systems whose files could not be shared
// (SolidWorks CAM, Fusion, NCL, CAMWorks) and for the forms of the corpus's systems that its
// files show once: small inputs written from ../shared/design/CL_FORMATS.md, each compiled
// whole and checked by the blocks it must give and the diagnostics, word for word.
#include "driver/readback_commands.h"
#include "helpers.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;
using ::testing::Not;

namespace {

// The diagnostics without their source lines and carets, and the files without their folders.
std::string messages(const std::string& diags) {
  std::istringstream in(diags);
  std::string line, out;
  while (std::getline(in, line)) {
    if (line.find(": warning: ") == std::string::npos && line.find(": error: ") == std::string::npos &&
        line.find(": note: ") == std::string::npos)
      continue;
    size_t colon = line.find(':'), slash = line.rfind('/', colon);
    out += (slash == std::string::npos ? line : line.substr(slash + 1)) + "\n";
  }
  return out;
}

bool verifies(const std::string& cl, const Machine& m) {
  TempDir t;
  write_file(t.path("part.cl"), cl);
  std::ostringstream err;
  VerifyReport r = verify_file(t.path("part.cl"), m, VerifyOptions{}, err);
  EXPECT_TRUE(r.ok) << err.str();
  return r.ok;
}

}  // namespace

// SolidWorks CAM APT: CSYS with 12 values, RAPID/, the 6-value CIRCLE (right-hand rule, the
// radius from where the tool is), CYCLE/INIT ... CYCLE/OFF or CYCLE/CLEAR with FEDTO, RAPTO,
// RTRCTO, DWELL, 1STPECK, SUBPECK, INCR, and INSERT notes for the operator.
TEST(CamSystems, SolidWorksCamApt) {
  const std::string cl =
      "PARTNO/SWCAM BRACKET\nUNITS/MM\nCSYS/1.0,0.0,0.0,0.0,0.0,1.0,0.0,0.0,0.0,0.0,1.0,0.0\n"
      "INSERT/Stock Size X222. Y100. Z25.\nINSERT/[HOLDER=BT40-ER32]\nLOADTL/1\nSPINDL/3000,RPM,CLW\nRAPID/\n"
      "GOTO/0,0,10\nFEDRAT/500,MMPM\nGOTO/0,0,-2\nGOTO/10,0,-2\nCIRCLE/10,10,-2,0,0,1\nGOTO/20,10,-2\nGOTO/20,30,-2\n"
      "RAPID/\nGOTO/20,30,10\nCYCLE/INIT\nCYCLE/DRILL,FEDTO,10,MMPM,100,RAPTO,2,RTRCTO,5,DWELL,0.5\nGOTO/30,30,0\n"
      "GOTO/40,30,0\nCYCLE/OFF\nCYCLE/INIT\nCYCLE/DEEP2,FEDTO,20,1STPECK,5,SUBPECK,3,MMPM,80,RAPTO,2,RTRCTO,5\n"
      "GOTO/50,30,0\nCYCLE/CLEAR\nCYCLE/DEEP,FEDTO,12,INCR,4,MMPM,80,RAPTO,2\nGOTO/60,30,0\nCYCLE/OFF\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"));
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_EQ(messages(c.diags),
            "part.cls:4:1: warning: INSERT 'Stock Size X222. Y100. Z25.' is no block the control reads ('S' at column 1 has "
            "no number after it): written as a comment (program.inserts = \"raw\" writes it as it is) [-Winsert]\n"
            "part.cls:5:1: warning: INSERT '[HOLDER=BT40-ER32]' is no block the control reads ('[' at column 1 starts no "
            "address word): written as a comment (program.inserts = \"raw\" writes it as it is) [-Winsert]\n");
  EXPECT_THAT(c.output, HasSubstr("(STOCK SIZE X222. Y100. Z25.)\n([HOLDER=BT40-ER32])\n"));
  EXPECT_THAT(c.output, HasSubstr("N90 G17 G03 X20. Y10. I0. J10.\n"));
  // RTRCTO: the tool goes to the return level before the cycle, so G98 returns there.
  EXPECT_THAT(c.output, HasSubstr("N110 G00 Z10.\nN120 X30.\nN130 Z5.\nN140 G98 G82 X30. Y30. Z-10. R2. P500 F100.\n"
                                  "N150 X40.\nN160 G80\n"));
  // Two peck sizes: no canned cycle has them, so the pecks are written out.
  EXPECT_THAT(c.output, HasSubstr("N170 G00 X50.\nN180 Z2.\nN190 G01 Z-5. F80.\nN200 G00 Z2.\nN210 Z-4.5\nN220 G01 Z-8.\n"));
  EXPECT_THAT(c.output, HasSubstr("G98 G83 X60. Y30. Z-12. R2. Q4. F80.\n"));
  verifies(cl, machine("fanuc-mill"));
}

// Fusion's "APT ISO 4343" post: MODE/MILL, PARTNO/'quoted', COMMENT/'text', LOADTL with
// words, and MOVARC (the end point from the angle, right-hand rule; a negative angle the other way).
TEST(CamSystems, FusionAptWithMovarc) {
  const std::string cl =
      "MODE/MILL\nPARTNO/'fusion part'\nUNITS/MM\nCOMMENT/'adaptive1'\nLOADTL/1,IN,1,ADJUST,1\nSPINDL/5000,RPM,CLW\n"
      "FEDRAT/1000,MMPM\nMULTAX/OFF\nRAPID\nGOTO/20,0,5\nGOTO/20,0,-1\nMOVARC/0,0,-1,0,0,1,20,ANGLE,90\nGOTO/-10,20,-1\n"
      "MOVARC/-10,10,-1,0,0,1,10,ANGLE,-180\nGOTO/-10,-10,-1\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"));
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("O1000 (FUSION PART)\n"));
  EXPECT_THAT(c.output, HasSubstr("(ADAPTIVE1)\n"));
  EXPECT_THAT(c.output, HasSubstr("N80 G17 G03 X0. Y20. I-20. J0.\nN90 G01 X-10.\nN100 G02 Y0. I0. J-10.\nN110 G01 Y-10.\n"));
  // The move into the second arc meets it at a cusp: the CL's sense is cut, and said so.
  EXPECT_EQ(messages(c.diags),
            "part.cls:14:1: warning: arc: MOVARC's angle (right-hand rule about its axis) says clockwise, and it is cut "
            "clockwise; but the arc is tangent to the move entering it only if it turns counter-clockwise (a cusp or a "
            "plunge onto the arc?) [-Warc-geometry]\n");
  verifies(cl, machine("fanuc-mill"));
  EXPECT_EQ(first_error(lower_text("GOTO/20,0,0\nMOVARC/0,0,0,0,0,1,20,90\n").diags),
            "2:8: MOVARC needs xc,yc,zc,i,j,k,r,ANGLE,a (the centre, the axis, the radius and the angle turned)");
  EXPECT_EQ(first_error(lower_text("GOTO/20,0,0\nMOVARC/0,0,0,0,0,1,15,ANGLE,90\n").diags),
            "2:1: CIRCLE: the arc's start point (the previous position) is 5 mm off its circle of radius 15 mm (at most "
            "0.01 mm is taken: the control alarms, or cuts another arc)");
}

// NCCS NCL: REMARK headers, MACHIN/PWORKS, blanks padding every field, FEDRAT without a unit.
TEST(CamSystems, NclPaddedFields) {
  const std::string cl =
      "REMARK  NCL generated\nPARTNO TEST PLATE\nMACHIN/PWORKS,1\nUNITS/MM\nLOADTL/3\nSPINDL/RPM,2500,CLW\n"
      "FROM  /   50.0000,   10.0000,    5.0000\nRAPID\nGOTO  /    0.0000,    0.0000,    5.0000\nFEDRAT/ 100\n"
      "GOTO  /    0.0000,    0.0000,   -1.0000\nGOTO  /   30.0000,    0.0000,   -1.0000\nGOHOME\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"));
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_EQ(messages(c.diags), "");
  // GOHOME goes up and across: up first on the Fanuc's non-linear rapids (rapid-split).
  EXPECT_THAT(c.output, HasSubstr("N70 G94 G01 Z-1. F100.\nN80 X30.\nN90 G00 Z5.\nN100 X50. Y10.\n"));
}

// CAMWorks .clt: OPFEATSTART/OPFEATEND operations, BOX (the stock), trailing commas, blanks
// between numbers, CIRCLE with its sense as a word, CYCLE/ON after the cycle's record, a Windows
// code page in a comment, ROTABL in radians.
TEST(CamSystems, CamWorksClt) {
  const std::string cl =
      "PARTNO/CAMWORKS PART\nUNITS/INCH\nBOX/0,0,0,4,3,1\nOPFEATSTART/Pocket1\nLOADTL/2,\nSPINDL/1800,RPM,CLW,\n"
      "FEDRAT/20,IPM,\nRAPID/\nGOTO/1.0 0.0 0.5,\nGOTO/1.0,0.0,-0.1,\nCIRCLE/0,0,-0.1,0,0,1,1.0,COUNTERCLOCKWISE\n"
      "GOTO/0.0,1.0,-0.1,\nCIRCLE/0,0,-0.1,0,0,1,1.0,CLW\nGOTO/-1.0,0.0,-0.1\nRAPID/\nGOTO/-1.0,0.0,0.5\n"
      "OPFEATEND/Pocket1\n$$ Kommentar \xe4\n"
      "CYCLE/DRILL,FEDTO,0.5,IPM,5,RAPTO,0.1\nCYCLE/OFF\nCYCLE/ON\nGOTO/2,2,0\nGOTO/3,2,0\nCYCLE/OFF\nFINI\n";
  Machine m = machine("haas-umc750");
  Compiled c = compile_text(cl, m);
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(messages(c.diags), HasSubstr("part.cls:13:1: warning: arc: the CIRCLE's sense word says clockwise, and it is cut "
                                           "clockwise; but the arc is tangent to the move entering it only if it turns "
                                           "counter-clockwise (a cusp or a plunge onto the arc?) [-Warc-geometry]\n"));
  EXPECT_THAT(messages(c.diags), HasSubstr("part.cls:18:14: warning: invalid UTF-8 in a comment: byte 0xE4, read as a one-byte "
                                           "code page (--input-encoding latin1 says so for the file) [-Winvalid-utf8]\n"));
  EXPECT_THAT(messages(c.diags), HasSubstr("part.cls:19:1: warning: CYCLE/DRILL drills no hole: no GOTO before its CYCLE/OFF [-Wcycle]\n"));
  EXPECT_THAT(c.output, HasSubstr("(POCKET1)\n"));
  EXPECT_THAT(c.output, HasSubstr("G17 G03 X0. Y1. I-1. J0.\n"));
  EXPECT_THAT(c.output, HasSubstr("G02 X-1. Y0. I0. J-1.\n"));
  EXPECT_THAT(c.output, HasSubstr("G98 G81 X2. Y2. Z-0.5 R0.1 F5.\n"));
  EXPECT_THAT(c.output, Not(HasSubstr("BOX")));
  // ROTABL positions the table in radians: a quarter turn of A, which the UMC-750 lacks.
  Compiled rot = compile_text("UNITS/INCH\nOPFEATSTART/x\nLOADTL/1\nROTABL/1.5707963,AAXIS,TABLE,CCLW\nFINI\n", m);
  EXPECT_FALSE(rot.ok);
  EXPECT_THAT(messages(rot.diags), HasSubstr("part.cls:4:1: error: rotary indexing (ROTATE, ROTABL) on machine 'haas-umc750': the machine "
                                   "has no A axis on its table to index; post for a machine that has, or have the CAM system "
                                   "write the turned tool path (its tool axes, MULTAX)"));
}

// CATIA: TOOLNO and TPRINT (the tool's name), a start point before the first tool change, and a
// lathe profile arc as TLON,GOFWD/(CIRCLE/...),ON,(LINE/...) set off along INDIRV.
TEST(CamSystems, CatiaContourOnTheLathe) {
  const std::string cl =
      "$$*CATIA0\nPARTNO PART TO BE MACHINED\nRAPID\nGOTO  /   60.00000,    0.00000,   20.00000\nCUTTER/    0.800000\n"
      "TOOLNO/1,TURN,1,0,3,    0.400000,$\n    0.000000,    0.000000,    0.100000,MMPR,  500.000000,SFM,$\n"
      "CCLW,ON,    0.000000,NOTE\nTPRINT/SDJCL 1210 D07,SDJCL 1210 D07\nLOADTL/1,1,1\nFEDRAT/    0.3000,MMPR\n"
      "SPINDL/  300.0000,RPM,CCLW\nGOTO  /   20.40000,    0.00000,  -41.00000\nFEDRAT/    0.1000,MMPR\n"
      "GOTO  /   20.40000,    0.00000,  -30.00000\nAUTOPS\nINDIRV/    0.00000,    0.00000,    1.00000\n"
      "TLON,GOFWD/      (CIRCLE/     25.00000,      0.00000,    -30.00000,$\n"
      "       4.60000),ON,(LINE/     25.00000,      0.00000,    -30.00000,$\n"
      "                              25.00000,      0.00000,    -25.40000)\nGOTO  /   30.40000,    0.00000,   -25.40000\nFINI\n";
  Machine lathe = machine("fanuc-lathe");
  Compiled c = compile_text(cl, lathe);
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(messages(c.diags),
              HasSubstr("part.cls:4:1: warning: rapid motion before the first tool change (T1 at line 10) is taken as the start "
                        "point (as FROM): no motion is written for it [-Wmotion-before-tool]\n"));
  EXPECT_THAT(c.output, HasSubstr("(T1 D=0.8 CR=0. - SDJCL 1210 D07)\n"));
  EXPECT_THAT(c.output, HasSubstr("N50 G99 G01 X40.8 Z-41. F0.3\nN60 Z-30. F0.1\nN70 G03 X50. Z-25.4 I4.6 K0.\nN80 G01 X60.8\n"));
  verifies(cl, lathe);
}

// CATIA contouring on a mill: ON, 2, INTOF goes round to the second time the tool meets the line
// (here the whole circle); what needs the tool's shape to stop is refused, saying what to do.
TEST(CamSystems, CatiaContourForms) {
  const std::string head = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,200\nRAPID\nGOTO/-3.74601,-0.63826,5\n"
                           "GOTO/-3.74601,-0.63826,-10\nINDIRV/   -0.16796,    0.98579,    0.00000\n";
  Compiled c = compile_text(head + "TLON,GOFWD/(CIRCLE/0,0,-10,3.8),ON,2,INTOF,(LINE/0,0,-10,-3.74601,-0.63826,-10)\n",
                            machine("fanuc-mill"));
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N80 G17 G02 I3.746 J0.638\n"));
  auto err = [&](const std::string& rec) { return first_error(lower_text(head + rec).diags); };
  EXPECT_EQ(err("TLLFT,GOFWD/(CIRCLE/0,0,-10,3.8),ON,(LINE/0,0,-10,1,0,-10)\n"),
            "9:1: TLON,GOFWD contouring: only TLON (the tool centre on the drive surface) is read; TLLFT and TLRGT set the "
            "tool beside it by its radius; have the CAM system write the motion as GOTO and CIRCLE records (in CATIA: "
            "circular interpolation output as CIRCLE, or the PP table's GOTO form)");
  EXPECT_THAT(err("GOFWD/(CIRCLE/0,0,-10,3.8),ON,(LINE/0,0,-10,1,0,-10)\n"),
              HasSubstr("9:1: TLON,GOFWD contouring: GOFWD without TLON, TLLFT or TLRGT before it: where the tool stands "
                        "against the curve (on it, or beside it by its radius) is not said;"));
  EXPECT_EQ(err("TLON,GOFWD/(CIRCLE/0,0,-10,3.8),TANTO,(LINE/0,0,-10,1,0,-10)\n"),
            "9:33: TLON,GOFWD contouring: only ON (the tool centre on the check surface) is read; TANTO stops the tool by "
            "its radius; have the CAM system write the motion as GOTO and CIRCLE records (in CATIA: circular interpolation "
            "output as CIRCLE, or the PP table's GOTO form)");
  EXPECT_EQ(err("TLON,GOFWD/(CIRCLE/0,0,-10,5),ON,(LINE/0,0,-10,1,0,-10)\n"),
            "9:1: TLON,GOFWD contouring: the tool (at 3.7999956246948496 from the centre) is not on the circle of radius 5; have the "
            "CAM system write the motion as GOTO and CIRCLE records (in CATIA: circular interpolation output as CIRCLE, or "
            "the PP table's GOTO form)");
}

// CATIA's cycles: by position (depth, clearance), and the ICAM PP table's keywords with RETURN.
TEST(CamSystems, CatiaCycles) {
  Lowered pos = lower_text("CYCLE/DRILL, 12.000000, 3.000000, 100.000000,MMPM\nGOTO/0,0,0\nCYCLE/OFF\n");
  EXPECT_EQ(first_error(pos.diags), "");
  EXPECT_THAT(pos.ir, HasSubstr("cycle-on drill depth 12 clear 3 feed 100"));
  Lowered icam = lower_text("CYCLE/DRILL,DEPTH,    4.600000,MMPR,    0.080000,CLEAR,    2.000000,$\nRETURN,    8.000000\n"
                            "GOTO/0,0,0\nCYCLE/OFF\n");
  EXPECT_EQ(first_error(icam.diags), "");
  EXPECT_THAT(icam.ir, HasSubstr("cycle-on drill depth 4.6 clear 2 retract 8 feed 0.08 /rev"));
  EXPECT_EQ(first_error(lower_text("CYCLE/DEEP, 12.0, 3.0, 4.0\n").diags),
            "1:13: CYCLE/DEEP: the values have no keywords, and which is the peck is not known; have the CAM system write "
            "keywords (DEPTH, STEP, CLEAR, ...)");
}

// Records that move the tool and are not read stop the post, naming what to do; records that
// do not are a warning and a comment.
TEST(CamSystems, RecordsThatMoveAreReadOrRefused) {
  auto err = [](const std::string& rec) { return first_error(lower_text(rec).diags); };
  EXPECT_EQ(err("LOOP/START,15\n"),
            "1:1: 'LOOP' moves the tool and clpc does not read it: a repeat of the records that follow; have the CAM system "
            "write them out in full");
  EXPECT_EQ(err("DNTCUT\n"),
            "1:1: 'DNTCUT' moves the tool and clpc does not read it: the motion after it is not to be cut; have the CAM "
            "system leave that motion out");
  EXPECT_EQ(err("GOTO/0,0,5\nTRANS/10,0,0\nGOTO/1,1,5\n"),
            "2:1: 'TRANS' moves the tool and clpc does not read it: it shifts the coordinates that follow; set the part's "
            "origin in the CAM system or with the work offset (SET, CAMERA)");
  EXPECT_EQ(err("GOTO/0,0,5\nTRANS/0,0,0\nGOTO/1,1,5\n"), "");  // shifts nothing, as ORIGIN/0,0,0
  EXPECT_THAT(err("TRANS/0,0,0.001\n"), ::testing::StartsWith("1:1: 'TRANS' moves the tool"));
  for (const char* word : {"POSTN/IN,5", "SAFPOS", "GOCLER", "PIVOTZ/100"})
    EXPECT_THAT(err(std::string(word) + "\n"), ::testing::StartsWith("1:1: '" + std::string(word).substr(0, std::string(word).find('/')) + "' moves the tool"));
  EXPECT_EQ(err("THREAD/TURN,1.5\n"), "");
  EXPECT_EQ(err("THREAD/SPIRAL,1.5\n"), "1:8: THREAD: a thread is TURN, FACE or TAPER (or THREAD/OFF), found 'SPIRAL'");
  EXPECT_EQ(err("THREAD/TURN,LEAD,1.5,STARTS,2\n"),
            "1:22: THREAD: unknown word 'STARTS' (read: TURN, FACE, TAPER, LEAD, PITCH, MMPR, IPR, the lead, OFF)");
  EXPECT_EQ(err("TLAXIS/NORMPS\n"),
            "1:1: 'TLAXIS' moves the tool and clpc does not read it: only TLAXIS/i,j,k (a fixed tool axis) is read; an axis "
            "tied to surfaces needs the part model: have the CAM system write the tool axis on every GOTO (MULTAX)");
  EXPECT_EQ(err("CYCLE/AUTO\n"),
            "1:1: 'CYCLE' moves the tool and clpc does not read it: CYCLE/AUTO leaves the choice of cycle to the post; have "
            "the CAM system write the cycle (DRILL, DEEP, TAP, ...) with its depth");
  // ORIGIN shifts every coordinate after it, in a sense posts disagree on: none is nothing.
  EXPECT_EQ(err("ORIGIN/0,0,0\nGOTO/0,0,0\n"), "");
  EXPECT_EQ(lower_text("ORIGIN/0,0,0\nGOTO/0,0,0\n").diags.size(), 0u);
  EXPECT_EQ(err("ORIGIN/0,0,-25.4\n"),
            "1:1: ORIGIN moves every coordinate after it, and posts apply it in opposite senses: clpc does not guess "
            "which; set the part's origin in the CAM system's machine coordinate system (MCS, CSYS) or with the work "
            "offset (SET, CAMERA) instead");
  Lowered l = lower_text("AICC/ON,10\nGOTO/0,0,0\n");
  EXPECT_EQ(first_error(l.diags), "");
  ASSERT_EQ(l.diags.size(), 1u);
  EXPECT_EQ(l.diags[0].message, "unknown record 'AICC' (passed through as a comment)");
  EXPECT_THAT(l.ir, HasSubstr("passthrough \"AICC/ON,10\""));
  Compiled strict = compile_text("UNITS/MM\nAICC/ON,10\n", machine("fanuc-mill"), [] {
    CompileOptions o;
    o.werror = true;
    return o;
  }());
  EXPECT_FALSE(strict.ok);
  EXPECT_THAT(messages(strict.diags), HasSubstr("part.cls:2:1: error: unknown record 'AICC' (passed through as a comment) [-Werror,-Wunknown-record]"));
}

// A tilted frame on a machine without rotaries is a setup of its own: a register, a stop for
// the operator with what to do, and the points in that frame. On the UMC-750 the table turns.
TEST(CamSystems, TiltedFrameOnThreeAndFiveAxes) {
  const std::string cl =
      "TOOL PATH/OP1,TOOL,EM10\nLOAD/TOOL,1\nMSYS/0,0,0,1,0,0,0,1,0\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,100\nRAPID\n"
      "GOTO/0,0,10\nGOTO/0,0,0\nGOTO/20,0,0\nEND-OF-PATH\nTOOL PATH/OP2,TOOL,EM10\n"
      "MSYS/50,0,0,0.7071067812,0,-0.7071067812,0,1,0\nRAPID\nGOTO/0,0,10\nGOTO/0,0,0\nGOTO/20,0,0\nEND-OF-PATH\n";
  Compiled three = compile_text(cl, machine("fanuc-mill"));
  ASSERT_TRUE(three.ok) << three.diags;
  EXPECT_THAT(messages(three.diags),
              HasSubstr("part.cls:14:1: warning: machine 'fanuc-mill' has no rotary axes: this operation is cut in setup 2 "
                        "(register 2), the part set up again after an operator stop [-Wsetup]\n"));
  EXPECT_THAT(three.output, HasSubstr("(G54 = MSYS LINE 3 ORIGIN X0 Y0 Z0)\n(G55 = MSYS LINE 12 ORIGIN X50 Y0 Z0)\n"));
  EXPECT_THAT(three.output,
              HasSubstr("(OP2)\n(SETUP 2: TURN THE PART SO THE FRAME OF LINE 12 HAS Z UP, REGISTER 2)\nN90 G91 G28 Z0.\nN100 M05\nN110 M00\nN120 S1000 M03\nN130 G90 G55 G00 X0. Y0.\n"
                        "N140 G43 H01 Z10.\nN150 G94 G01 Z0. F100.\nN160 X20.\n"));
  // (G43 H again after the stop: the operator may have pressed RESET, or restart here; the tool
  // came down a tool length low; helper-67, helper-70.)
  verifies(cl, machine("fanuc-mill"));
  // Without a retract the part was turned under the tool (helper-67: certified).
  Compiled no_retract = compile_text(cl, machine("nr", "[nr]\ninherits = \"fanuc-mill\"\n[nr.codes]\nsafe_retract = \"\"\n"));
  EXPECT_FALSE(no_retract.ok);
  EXPECT_THAT(messages(no_retract.diags),
              HasSubstr("part.cls:14:1: error: machine 'nr' has no code to retract the tool before the operator sets the "
                        "part up again (codes.safe_retract is empty): the part would be turned under the tool, and the "
                        "next setup's first move made at the last one's height\n"));
  Compiled five = compile_text(cl, machine("haas-umc750"));
  ASSERT_TRUE(five.ok) << five.diags;
  EXPECT_THAT(five.output, HasSubstr("(OP2)\nN60 G53 G00 Z0.\nN65 M11 M13\nN70 G00 B45.\nN75 M10 M12\nN80 G254\n"
                                     "N85 G00 X1.3919 Y0.\nN90 Z1.7856\nN95 G94 G01 Z1.3919 F3.94\nN100 X2.1793\n"));
  verifies(cl, machine("haas-umc750"));
}

// check -t runs what compile runs: the backend's checks too.
TEST(CamSystems, CheckWithAMachineReportsWhatCompileReports) {
  TempDir t;
  write_file(t.path("tilt.cls"), "UNITS/MM\nLOADTL/1\nSPINDL/RPM,100,CLW\nFEDRAT/MMPM,100\nGOTO/0,0,0,0.6,0,0.8\n");
  RunResult check = run_clpc("check " + t.path("tilt.cls") + " -t fanuc-mill");
  RunResult compile = run_clpc("compile " + t.path("tilt.cls") + " -t fanuc-mill -o -");
  EXPECT_EQ(check.status, 1);
  EXPECT_EQ(compile.status, 1);
  EXPECT_EQ(messages(check.err), messages(compile.err));
  EXPECT_THAT(check.err, HasSubstr("tilt.cls:5:1: error: tool axis (0.6, 0, 0.8) is not the spindle axis, and machine "
                                   "'fanuc-mill' has no rotary axes to tilt it"));
}

// Feeds in the other unit's words than UNITS says: named, with the option.
TEST(CamSystems, FeedWordsThatContradictUnits) {
  Compiled c = compile_text("UNITS/INCHES\nLOADTL/1\nSPINDL/RPM,100,CLW\nFEDRAT/250,MMPM\nGOTO/0,0,0\n", machine("fanuc-mill"));
  EXPECT_THAT(messages(c.diags), HasSubstr("part.cls: warning: the file says its units are inches, but the feed at line 4 is in "
                                 "millimetres: if its numbers are millimetres, --input-units mm reads them so"));
  // A thread's lead in the other unit's words is such a feed too (it was converted silently).
  Compiled t = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/RPM,500,CLW\nFEDRAT/0.2,MMPR\nRAPID\nGOTO/20,0,5\n"
                            "THREAD/TURN,LEAD,0.0625,IPR\nGOTO/19,0,5\nGOTO/19,0,-20\nRAPID\nGOTO/20,0,-20\nTHREAD/OFF\n",
                            machine("fanuc-lathe"));
  EXPECT_THAT(messages(t.diags), HasSubstr("part.cls: warning: the file says its units are millimetres, but the feed at line "
                                           "7 is in inches"));
}

// A file of many read windows with thousands of records kept as text (a 2 MB Fusion file once
// crashed here: a comment's text and its instruction fell in two chunks of the operation).
TEST(CamSystems, ManyPassthroughRecordsAcrossReadWindows) {
  std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,500\n";
  int n = 0;
  while (cl.size() < 3u * 1024 * 1024) {
    if (n % 5 == 0) cl += "PPFUN/" + std::to_string(n) + ",SOMETHING\n";
    if (n % 7 == 0) cl += "PPRINT note " + std::to_string(n) + "\n";
    cl += "GOTO/" + std::to_string(n % 100) + ",1.5,-1\n";
    ++n;
  }
  CompileOptions o;
  o.lower.chunk_size = 1000;
  Compiled c = compile_text(cl, machine("fanuc-mill"), o);
  ASSERT_TRUE(c.ok) << c.diags.substr(0, 2000);
  auto occurrences = [&](const std::string& what) {
    size_t k = 0;
    for (size_t at = c.output.find(what); at != std::string::npos; at = c.output.find(what, at + 1)) ++k;
    return k;
  };
  EXPECT_EQ(occurrences("(CL: PPFUN/"), size_t((n + 4) / 5));
  EXPECT_EQ(occurrences("(NOTE "), size_t((n + 6) / 7));
}

// A frame whose Z points down (the part turned over for its back side) is beyond the UMC-750's
// rotaries (B -35..120): a setup of its own, as on a three-axis machine.
TEST(CamSystems, FlippedFrameBeyondTheRotariesIsASetup) {
  const std::string cl =
      "TOOL PATH/TOP,TOOL,EM10\nLOAD/TOOL,1\nMSYS/0,0,0,1,0,0,0,1,0\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,100\nRAPID\n"
      "GOTO/0,0,10\nGOTO/0,0,0\nGOTO/20,0,0\nEND-OF-PATH\nTOOL PATH/BOTTOM,TOOL,EM10\nMSYS/0,0,-30,1,0,0,0,-1,0\nRAPID\n"
      "GOTO/0,0,10\nGOTO/0,0,0\nGOTO/20,5,0\nEND-OF-PATH\n";
  Machine haas = machine("haas-umc750");
  Compiled c = compile_text(cl, haas);
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(messages(c.diags),
              HasSubstr("part.cls:14:1: warning: machine 'haas-umc750' cannot turn the tool to this frame's Z: this operation "
                        "is cut in setup 2 (register 2), the part set up again after an operator stop [-Wsetup]\n"));
  EXPECT_THAT(c.output, HasSubstr("(SETUP 2: TURN THE PART SO THE FRAME OF LINE 12 HAS Z UP, REGISTER 2)\n"));
  EXPECT_THAT(c.output, HasSubstr("M00\n"));
  EXPECT_THAT(c.output, HasSubstr("G55"));
  verifies(cl, haas);
}

// What shops put in INSERT and PREFUN records around a finish: codes that change how fast the
// tool goes along the path, never where (high-speed and AI contour modes, look-ahead, exact
// stop and cutting mode). They are written as given and read back as such, so the program is
// certified; a dwell in revolutions lasts as long as the spindle takes to make them.
// (INSERT/G05.1 Q1 once hung the compile: the block check's number scan stopped advancing
// after a decimal point.)
TEST(CamSystems, SpeedCodesInInsertsAndDwellsInRevolutions) {
  const std::string cl =
      "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1200,CLW\nFEDRAT/MMPM,300\nRAPID\nGOTO/0,0,10\nINSERT/G05.1 Q1\n"
      "INSERT/G05 P10000\nPREFUN/61\nINSERT/G08 P1\nGOTO/0,0,-1\nGOTO/10,0,-1\nDELAY/REV,5\nINSERT/G64\n"
      "GOTO/10,10,-1\nINSERT/G05.1 Q0\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"));
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_EQ(messages(c.diags), "");
  EXPECT_THAT(c.output, HasSubstr("\nN60 G43 H01 Z10.\nG05.1 Q1\nG05 P10000\nG61\nG08 P1\nN70 G94 G01 X0. Y0. Z-1. F300.\n"));
  // 5 turns at 1200 rpm: 0.25 s, in the Fanuc's milliseconds.
  EXPECT_THAT(c.output, HasSubstr("\nN80 X10.\nN90 G04 P250\nG64\nN100 G01 X10. Y10. Z-1. F300.\nG05.1 Q0\n"));
  verifies(cl, machine("fanuc-mill"));
  // An INSERT that moves an axis is written, and said not to be checked (a dwell's X is no axis).
  // Packed blocks too; a macro's words (GT, GOTO, SIN) are no addresses. A '%' (the tape mark)
  // never reaches the program, not even in an INSERT's comment.
  Compiled moved = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/RPM,1200,CLW\nRAPID\nGOTO/0,0,10\nINSERT/G00 Z-30. (DOWN)\n"
                                "INSERT/G04 X1.5\nINSERT/G0X10.Y5.\nINSERT/G04X1.5\nINSERT/IF[#1GT0]GOTO10\n"
                                "INSERT/#1=SIN[#2]\nINSERT/G04 P500 (50% FEED)\nINSERT/#3006=1\nRAPID\nGOTO/0,0,20\nFINI\n",
                                machine("fanuc-mill"));
  ASSERT_TRUE(moved.ok) << moved.diags;
  EXPECT_EQ(messages(moved.diags),
            "part.cls:6:1: warning: INSERT 'G00 Z-30. (DOWN)' holds axis words (Z): it is written as given, and what it "
            "moves is not checked against the CL (the certificate follows the CL's own moves) [-Winsert]\n"
            "part.cls:8:1: warning: INSERT 'G0X10.Y5.' holds axis words (XY): it is written as given, and what it "
            "moves is not checked against the CL (the certificate follows the CL's own moves) [-Winsert]\n"
            "part.cls:12:1: warning: INSERT 'G04 P500 (50% FEED)' is no block the control reads ('%' is the tape mark, "
            "which ends the program where the control loads it): written as a comment (program.inserts = \"raw\" writes "
            "it as it is) [-Winsert]\n");
  EXPECT_THAT(moved.output, HasSubstr("\nG04X1.5\nIF[#1GT0]GOTO10\n#1=SIN[#2]\n(G04 P500 50 FEED)\n#3006=1\n"));
  // With the spindle stopped no time is known: refused where it stands.
  Compiled stopped = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/OFF\nDELAY/REV,5\nFINI\n", machine("fanuc-mill"));
  EXPECT_FALSE(stopped.ok);
  EXPECT_THAT(stopped.diags, HasSubstr(":4:1: error: DELAY/REV: a dwell of 5 revolutions needs the spindle turning at a set "
                                       "speed, and it is stopped here; give the dwell in seconds"));
}

// APT's feed mode is modal: a FEDRAT without a unit word keeps the mode and unit of the last
// one that named them (ISO 4343 posts, G-Post, IMSpost), per minute in the program's units
// before any. Per revolution kept is said, since a feed per minute read per revolution would be
// a crash; inverse time is never kept.
TEST(CamSystems, AFeedWithoutAUnitKeepsTheLastOnesMode) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nFEDRAT/200\nGOTO/0,0,1\nFEDRAT/0.2,MMPR\nGOTO/10,0,1\n"
                         "FEDRAT/0.3\nGOTO/20,0,1\nFEDRAT/IPM,10\nGOTO/30,0,1\nFEDRAT/20\nGOTO/40,0,1\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"));
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_EQ(messages(c.diags),
            "part.cls: warning: the file says its units are millimetres, but the feed at line 10 is in inches: if its "
            "numbers are inches, --input-units inch reads them so [-Wunits]\n"
            "part.cls:5:1: warning: the first move of T1 is a cut, with no FROM or rapid before it to say where it starts: "
            "on a mill it is positioned over its end at rapid and fed down along Z from where the tool change (or the "
            "program's start) leaves the tool; a lathe feeds it straight from there [-Wapproach]\n"
            "part.cls:8:1: warning: FEDRAT/0.3 has no unit word: per revolution, as the FEDRAT at line 6 set it (the feed "
            "mode stays until a FEDRAT names another) [-Wfeed-unit]\n");
  EXPECT_THAT(c.output, HasSubstr("N50 G54 G00 X0. Y0.\nN60 G43 H01 G94 G01 Z1. F200.\nN70 G95 X10. F0.2\nN80 X20. F0.3\n"
                                  "N90 G94 X30. F254.\nN100 X40. F508.\n"));
  verifies(cl, machine("fanuc-mill"));
  // After inverse time: per minute in the file's units (mm), said; the UMC-750 writes inches.
  Compiled inverse = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,5\nFEDRAT/INVERS,10\n"
                                  "GOTO/0,0,1\nFEDRAT/200\nGOTO/10,0,1\nFINI\n",
                                  machine("haas-umc750"));
  ASSERT_TRUE(inverse.ok) << inverse.diags;
  EXPECT_EQ(messages(inverse.diags),
            "part.cls:8:1: warning: FEDRAT/200 has no unit word after the inverse-time FEDRAT at line 6: per minute in the "
            "file's units (inverse time belongs to the moves it was written for) [-Wfeed-unit]\n");
  EXPECT_THAT(inverse.output, HasSubstr(" G93 G01 Z0.0394 F10.\nN55 G94 X0.3937 F7.87\n"));
}

// A dwell passed through INSERT (a hole's bottom in Mastercam, PowerMill or hyperMILL APT) was
// written, then refused by the certificate as a dwell the CL has no DELAY for (helper-66).
TEST(CamSystems, ADwellInAnInsertIsTheClsOwn) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,200\nRAPID\nGOTO/0,0,10\n"
                         "INSERT/G04 P1000\nGOTO/0,0,-1\nGOTO/10,0,-1\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("\nN60 G43 H01 Z10.\nG04 P1000\nN70 G94 G01 X0. Y0. Z-1. F200.\n"));
  EXPECT_TRUE(verifies(cl, machine("fanuc-mill")));
  // A DELAY beside it is still held: never shorter (helper-69: G04 P2000 made P20 passed).
  const std::string both = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,200\nRAPID\nGOTO/0,0,10\nGOTO/0,0,-1\n"
                           "DELAY/2\nINSERT/G04 P500\nGOTO/10,0,-1\nFINI\n";
  Compiled b = compile_text(both, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(b.ok) << b.diags;
  ASSERT_THAT(b.output, HasSubstr("G04 P2000\n"));
  TempDir t;
  write_file(t.path("part.cl"), both);
  std::string cut_short = b.output;
  cut_short.replace(cut_short.find("G04 P2000\n"), 10, "G04 P20\n");
  write_file(t.path("part.nc"), cut_short);
  RunResult r = run_clpc("verify '" + t.path("part.cl") + "' -t fanuc-mill --program '" + t.path("part.nc") + "'");
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.err, HasSubstr("the program dwells 0.520 s before this move, the CL's DELAY (line 8) is 2.000 s"));
}

// G93's F is one over the block's minutes, given by the CL for one move. A move the program
// writes as several blocks (an arc cut in quarters, an arc made lines under TCPC) gave each
// block the whole move's F: four quarters took four times the CL's time, certified. Refused;
// a move written as one block keeps its F.
TEST(CamSystems, AnInverseTimeFeedIsNotCopiedOntoTheBlocksOfASplitMove) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,3000,CLW\nRAPID\nGOTO/0,10,50\nFEDRAT/MMPM,100\nGOTO/0,10,0\n"
                         "FEDRAT/INVERS,4\nCIRCLE/0,0,0,0,0,1,10\nGOTO/0,10,0\nFINI\n";
  Compiled whole = compile_text(cl, machine("fanuc-mill"));
  ASSERT_TRUE(whole.ok) << whole.diags;
  EXPECT_THAT(whole.output, HasSubstr("\nN80 G17 G93 G03 I0. J-10. F4.\n"));
  Compiled quarters = compile_text(cl, machine("m", "[m]\ninherits = \"fanuc-mill\"\n[m.arcs]\nmax_sweep = 90\n"));
  EXPECT_FALSE(quarters.ok);
  EXPECT_EQ(messages(quarters.diags),
            "part.cls:9:1: error: an inverse-time feed (FEDRAT/INVERS) for a move the program writes as more than one "
            "block: each block would take the whole move's time; have the CAM system write a feed per minute here (or "
            "the move as the blocks it writes)\n");
}

// Cutter compensation left on at the end (CUTCOM/OFF with no move after it, or never turned
// off) is cancelled before the finish's retract: G40 alone, then the finish.
TEST(CamSystems, CompensationStillOnAtTheEndIsCancelledBeforeTheFinish) {
  for (const char* off : {"CUTCOM/OFF\n", ""}) {
    const std::string cl = std::string("UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,200\nGOTO/0,-10,-1\n"
                                       "CUTCOM/LEFT\nGOTO/0,0,-1\nGOTO/20,0,-1\nGOTO/20,0,10\n") + off + "FINI\n";
    Compiled c = compile_text(cl, machine("fanuc-mill"));
    ASSERT_TRUE(c.ok) << c.diags;
    EXPECT_THAT(c.output, HasSubstr("N70 G41 D1 Y0.\nN80 X20.\nN90 Z10.\nN100 G40\nN110 M05\nN120 G91 G28 Z0.\n")) << off;
    verifies(cl, machine("fanuc-mill"));
  }
}

// ... but not where the tool last cut: the G40 alone is taken on the finish's Z home, which goes
// from the offset point to the contour's, into the wall by the radius, at the cut's depth
// (helper-67: certified). Nor before a tool change, nor after an arc or a ramp out.
TEST(CamSystems, CompensationEndedWithNoMoveWhereTheToolCutIsRefused) {
  const std::string head = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,-10,20\nFEDRAT/MMPM,200\nGOTO/0,-10,-1\n"
                           "CUTCOM/LEFT\nGOTO/0,0,-1\nGOTO/20,0,-1\n";
  const std::string still_on = "part.cls:8:1: error: cutter compensation left on to the end, where the tool last cut: the control "
                               "ends G41/G42 on the post's next move (the retract), which pulls the tool by its radius onto "
                               "the contour, into the wall; give a move after CUTCOM/OFF, across and away from the wall, "
                               "or end it after a retract straight up the tool axis\n";
  const std::string off_at_11 = "part.cls:11:1: error: CUTCOM/OFF with no move after it, where the tool last cut: the control "
                               "ends G41/G42 on the post's next move (the retract), which pulls the tool by its radius onto "
                               "the contour, into the wall; give a move after CUTCOM/OFF, across and away from the wall, "
                               "or end it after a retract straight up the tool axis\n";
  const std::pair<std::string, std::string> cases[] = {
      {head + "FINI\n", still_on},
      {head + "GOTO/30,0,5\nFINI\n", still_on},  // ramped out, not straight up
      {head + "CIRCLE/20,10,-1,0,0,1,10\nGOTO/30,10,-1\nFINI\n", still_on},
      {head + "CUTCOM/OFF\nFINI\n", off_at_11},
      {head + "CUTCOM/OFF\nLOADTL/2\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/50,50,20\nFINI\n", off_at_11},
  };
  for (const auto& [cl, error] : cases)
    for (const char* name : {"fanuc-mill", "haas-umc750"}) {
      Compiled c = compile_text(cl, machine(name));
      EXPECT_FALSE(c.ok) << name << "\n" << cl;
      EXPECT_EQ(messages(c.diags), error) << name << "\n" << cl;
    }
  // A lead-out across carries the G40; a rapid out leaves the tool in the air.
  for (const char* out : {"CUTCOM/OFF\nGOTO/30,0,-1\nFINI\n", "RAPID\nGOTO/20,0,20\nFINI\n"}) {
    Compiled c = compile_text(head + out, machine("fanuc-mill"));
    EXPECT_TRUE(c.ok) << out << c.diags;
  }
}

// '%' is the tape mark: Fanuc and Haas controls loading a file stop at the first one, so a
// part name or note that holds one ("50% SCALE") must not carry it into a comment.
TEST(CamSystems, APercentSignNeverReachesTheProgram) {
  const std::string cl = "PARTNO 50% SCALE\nUNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,200\n"
                         "PPRINT RPM 100% ; CHECK\nGOTO/0,0,1\nFINI\n";
  for (const char* name : {"fanuc-mill", "haas-umc750"}) {
    Compiled c = compile_text(cl, machine(name));
    ASSERT_TRUE(c.ok) << c.diags;
    EXPECT_EQ(std::count(c.output.begin(), c.output.end(), '%'), 2) << c.output;  // the two tape marks
    EXPECT_THAT(c.output, HasSubstr("(RPM 100 ; CHECK)\n")) << name;
  }
}

// A number too long for its fixed width in a machine's code (the lathe's T{tool:2}{offset:2})
// is an error at the record: T112112 or T05105 would be read as another tool and offset.
TEST(CamSystems, AToolNumberTooLongForTheLathesTWordIsRefusedAtItsRecord) {
  const std::string rest = "SPINDL/RPM,500,CLW\nFEDRAT/MMPR,0.1\nRAPID\nGOTO/20,0,2\nGOTO/20,0,-10\nFINI\n";
  Compiled big = compile_text("UNITS/MM\nLOADTL/112\n" + rest, machine("fanuc-lathe"));
  EXPECT_FALSE(big.ok);
  EXPECT_THAT(messages(big.diags), HasSubstr("part.cls:2:1: error: tool 112 does not fit the 2 digits the machine's code gives "
                                             "it ({tool:2}): the control would read another number\n"));
  Compiled offset = compile_text("UNITS/MM\nLOADTL/5,OSETNO,105\n" + rest, machine("fanuc-lathe"));
  EXPECT_FALSE(offset.ok);
  EXPECT_EQ(messages(offset.diags), "part.cls:2:1: error: offset 105 does not fit the 2 digits the machine's code gives it "
                                    "({offset:2}): the control would read another number\n");
  Compiled fits = compile_text("UNITS/MM\nLOADTL/5,OSETNO,15\n" + rest, machine("fanuc-lathe"));
  ASSERT_TRUE(fits.ok) << fits.diags;
  EXPECT_THAT(fits.output, HasSubstr("T0515"));
}

// SPINDL/MAXRPM,n as a record of its own (a record that moves nothing never stops a post): the
// clamp for each later surface speed that names none, and at once for one running (a new G50 S);
// while the spindle is stopped it waits for the next SPINDL. ISO 4343's gear range words are left
// to the control. A surface speed with no clamp at all takes the machine's limit, said.
TEST(CamSystems, ASpindleClampOfItsOwnHoldsForTheSurfaceSpeedsAfterIt) {
  const std::string cl =
      "UNITS/MM\nLOADTL/1\nSPINDL/MAXRPM,2500\nSPINDL/SMM,200,CLW,HIGH\nFEDRAT/0.2,MMPR\nRAPID\nGOTO/40,0,2\n"
      "GOTO/30,0,2\nGOTO/30,0,-20\nSPINDL/MAXRPM,1800\nGOTO/40,0,-20\nSPINDL/OFF\nSPINDL/MAXRPM,1500\nSPINDL/SMM,150,CLW\n"
      "GOTO/40,0,-25\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_EQ(messages(c.diags), "");
  EXPECT_THAT(c.output, HasSubstr("\nN40 G50 S2500\nN50 G96 S200 M03\nN60 G00 X80. Z2.\nN70 G99 G01 X60. F0.2\nN80 Z-20.\n"
                                  "N90 G50 S1800\nN100 G96 S200 M03\nN110 G99 G01 X80. Z-20. F0.2\nN120 M05\n"
                                  "N130 G50 S1500\nN140 G96 S150 M03\nN150 G99 G01 X80. Z-25. F0.2\n"));
  Compiled unclamped = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/SMM,200,CLW\nFEDRAT/0.2,MMPR\nRAPID\nGOTO/40,0,2\nFINI\n",
                                    machine("fanuc-lathe"));
  ASSERT_TRUE(unclamped.ok) << unclamped.diags;
  EXPECT_EQ(messages(unclamped.diags),
            "part.cls:3:1: warning: constant surface speed without MAXRPM: clamped at the machine's limit of 3000 rpm (give "
            "SPINDL/...,MAXRPM,n for the part's or the chuck's limit) [-Wspindle-clamp]\n");
  EXPECT_THAT(unclamped.output, HasSubstr("\nN40 G50 S3000\nN50 G96 S200 M03\n"));
  Compiled above = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/SMM,200,CLW,MAXRPM,4000\nFEDRAT/0.2,MMPR\nRAPID\nGOTO/40,0,2\nFINI\n",
                                machine("fanuc-lathe"));
  ASSERT_TRUE(above.ok) << above.diags;
  EXPECT_EQ(messages(above.diags), "part.cls:3:1: warning: MAXRPM 4000 is above machine 'fanuc-lathe''s spindle limit: "
                                   "clamped at 3000 rpm [-Wspindle-clamp]\n");
  EXPECT_THAT(above.output, HasSubstr("\nN40 G50 S3000\n"));
  // After a tool change a clamp alone clamps the last tool's surface speed, which the post
  // starts again for the new tool (a lathe's index leaves it running; helper-73), until the new
  // tool's SPINDL; SPINDL/ON,MAXRPM,n restarts with the new clamp.
  Compiled changed = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/SMM,200,CLW,MAXRPM,2000\nFEDRAT/0.2,MMPR\nRAPID\n"
                                  "GOTO/40,0,2\nLOADTL/2\nSPINDL/MAXRPM,1500\nSPINDL/RPM,800,CLW\nRAPID\nGOTO/40,0,5\n"
                                  "SPINDL/OFF\nSPINDL/SMM,180,CLW\nSPINDL/OFF\nSPINDL/ON,MAXRPM,1200\nGOTO/40,0,6\nFINI\n",
                                  machine("fanuc-lathe"));
  ASSERT_TRUE(changed.ok) << changed.diags;
  EXPECT_THAT(changed.output, HasSubstr("\nN80 T0202 (T2)\nN90 G50 S1500\nN100 G96 S200 M03\nN110 G97 S800 M03\nN120 G00 X80. Z5.\n"
                                        "N130 M05\nN140 G50 S1500\nN150 G96 S180 M03\nN160 M05\nN170 G50 S1200\n"
                                        "N180 G96 S180 M03\n"));
  Compiled negative = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/MAXRPM,-3\nFINI\n", machine("fanuc-lathe"));
  EXPECT_FALSE(negative.ok);
  EXPECT_THAT(negative.diags, HasSubstr("part.cls:3:15: error: SPINDL: MAXRPM must not be negative, found -3"));
}

// NX's centreline drilling on a lathe under constant surface speed: at X0 G96 turns at the
// clamp (3000 rpm), where the CL's 80 m/min on a 10 mm drill is 2546. The drill cuts at G97
// S2546; the surface speed comes back at the next cut off the axis. A turning tool fed along
// the axis after facing to centre keeps G96 (the clamp is what the CL asks); a drill without
// a diameter is refused.
TEST(CamSystems, ADrillOnTheSpindlesAxisTurnsAtItsOwnSurfaceSpeed) {
  const std::string cl =
      "UNITS/MM\nLOAD/TOOL,1\nSPINDL/SMM,200,CLW,MAXRPM,2500\nFEDRAT/MMPR,0.25\nRAPID\nGOTO/30,0,5\nGOTO/30,0,0\n"
      "GOTO/0,0,0\nGOTO/0,0,1\nRAPID\nGOTO/30,0,5\nTOOL PATH/DRILLING,TOOL,DRILL_10\nTLDATA/DRILL,10,118,50,0\n"
      "LOAD/TOOL,5\nSPINDL/SMM,80,CLW,MAXRPM,3000\nRAPID\nGOTO/0,0,10\nGOTO/0,0,-20\nRAPID\nGOTO/0,0,10\nRAPID\n"
      "GOTO/20,0,2\nGOTO/20,0,-5\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("\nN70 G99 G01 Z0. F0.25\nN80 X0.\nN90 Z1.\n"));
  EXPECT_THAT(c.output, HasSubstr("\nN130 G50 S3000\nN140 G96 S80 M03\nN150 G00 X0. Z10.\nN160 G97 S2546 M03\n"
                                  "N170 G99 G01 Z-20. F0.25\nN180 G00 Z10.\nN190 X40. Z2.\nN200 G96 S80 M03\n"
                                  "N210 G01 Z-5.\n"));
  Compiled no_diameter = compile_text(
      "UNITS/MM\nTLDATA/DRILL,0,118,50,0\nLOAD/TOOL,5\nSPINDL/SMM,80,CLW,MAXRPM,3000\nFEDRAT/MMPR,0.1\nRAPID\n"
      "GOTO/0,0,10\nGOTO/0,0,-20\nFINI\n",
      machine("fanuc-lathe"));
  EXPECT_FALSE(no_diameter.ok);
  EXPECT_THAT(no_diameter.diags, HasSubstr("part.cls:8:1: error: drilling on the spindle's axis under constant surface "
                                           "speed (G96): the spindle would turn at its clamp; tool 5 has no diameter"));
  // The drill's speed ends with its cuts: the next tool's G71 (no SPINDL of its own) roughed at
  // the drill's 2546 rpm, with G96 written inside P..Q where the control reads no S.
  Compiled next_op = compile_text(
      "UNITS/MM\nTLDATA/DRILL,10,118,50,0\nLOAD/TOOL,5\nSPINDL/SMM,80,CLW,MAXRPM,3000\nFEDRAT/MMPR,0.1\nRAPID\n"
      "GOTO/0,0,10\nGOTO/0,0,-20\nRAPID\nGOTO/0,0,10\nTLDATA/TURN,0.4,80,55,15,0\nLOAD/TOOL,1\nFEDRAT/MMPR,0.25\n"
      "RAPID\nGOTO/26,0,2\nCYCLE/ROUGH,TURN,DEPTH,4,RETRACT,1,ALLOW,0.2,0.1,FINISH\nRAPID\nGOTO/10,0,2\n"
      "GOTO/10,0,-15\nGOTO/15,0,-25\nGOTO/26,0,-25\nCYCLE/OFF\nRAPID\nGOTO/60,0,50\nFINI\n",
      machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(next_op.ok) << next_op.diags;
  EXPECT_THAT(next_op.output, HasSubstr("\nN70 G97 S2546 M03\nN80 G99 G01 Z-20. F0.1\nN90 G00 Z10.\nN100 G96 S80 M03\n"
                                        "N110 G28 U0. W0.\nN120 T0101 (T1 - TURN)\n"));
  EXPECT_EQ(next_op.output.find("G96", next_op.output.find("G71")), std::string::npos);
  // TLDATA/DRILL no longer says a file is for a mill: an NX mill hole program posted to a lathe
  // is refused at its holes off the axis (they were drilled as rings, certified).
  Compiled off_axis = compile_text(
      "UNITS/MM\nTLDATA/DRILL,8,118,50,35,0\nLOAD/TOOL,3\nSPINDL/RPM,1200,CLW\nRAPID\nGOTO/-30,0,10,0,0,1\n"
      "CYCLE/DRILL,20,MMPM,120,3\nGOTO/-30,0,0\nCYCLE/OFF\n",
      machine("fanuc-lathe"));
  EXPECT_FALSE(off_axis.ok);
  EXPECT_THAT(off_axis.diags, HasSubstr("part.cls:8:1: error: a hole off the spindle's axis on a lathe (at x -30, y 0): the "
                                        "part turns, so the drill would cut a ring"));
}

// The first MSYS is the part's setup. An NX file whose first operation is a tilted face (a
// local MCS) and whose later one is square to the absolute frame had every face cut turned by
// the first's tilt, silently; it is said now.
TEST(CamSystems, AFirstMsysTurnedFromALaterSquareOneIsSaid) {
  const std::string op2 = "TOOL PATH/TOP,TOOL,EM\nMSYS/0,0,0,1,0,0,0,1,0\nRAPID\nGOTO/0,0,1\nEND-OF-PATH\n";
  Compiled c = compile_text("UNITS/MM\nTOOL PATH/SIDE30,TOOL,EM\nTLDATA/MILL,10,0,50,0,0\n"
                            "MSYS/2,0,1,0.8660254,0,-0.5,0,1,0\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,1\n"
                            "END-OF-PATH\n" + op2,
                            machine("haas-umc750"));
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(messages(c.diags), HasSubstr("part.cls:11:1: warning: this MSYS is square to the absolute frame, but the first "
                                           "one (line 4), which clpc takes as the part's setup on the machine"));
}

// Creo under MULTAX/ON writes every GOTO with its tool axis. The GOTOs after a CIRCLE that go
// on round it with the arc's own axis are the arc: only the first was joined, the others cut
// as 30-degree chords 0.034 in inside the circle (certified: verify read them so too).
TEST(CamSystems, CreoGotosWithTheArcsOwnToolAxisGoOnRoundTheArc) {
  const std::string cl =
      "$$*          Pro/CLfile  Version 19.0 - 9728\nMACHIN / MILL, 01\nUNITS / INCHES\nLOADTL / 1\nMULTAX / ON\n"
      "SPINDL / RPM, 3000.000000,  CLW\nRAPID\nGOTO / 1.0, 0.0, 0.1, 0.0, 0.0, 1.0\nFEDRAT / 10.000000,  IPM\n"
      "GOTO / 1.0, 0.0, -0.1, 0.0, 0.0, 1.0\nCIRCLE / 0.0, 0.0, -0.1, 0.0, 0.0, 1.0, 1.0\n"
      "GOTO / 0.866025, 0.5, -0.1, 0.0, 0.0, 1.0\nGOTO / 0.5, 0.866025, -0.1, 0.0, 0.0, 1.0\n"
      "GOTO / 0.0, 1.0, -0.1, 0.0, 0.0, 1.0\nGOTO / -0.5, 1.0, -0.1, 0.0, 0.1, 0.99498744\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"), {.certify = true});
  ASSERT_FALSE(c.ok);  // the last GOTO tilts the tool: a three-axis mill refuses it, after the arc
  Compiled flat = compile_text(cl.substr(0, cl.find("GOTO / -0.5")) + "FINI\n", machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(flat.ok) << flat.diags;
  EXPECT_THAT(flat.output, HasSubstr("N70 G94 G01 Z-2.54 F254.\nN80 G17 G03 X0. Y25.4 I-25.4 J0.\nN90 M05\n"));
  Compiled umc = compile_text(cl.substr(0, cl.find("GOTO / -0.5")) + "FINI\n", machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(umc.ok) << umc.diags;
  EXPECT_THAT(umc.output, HasSubstr("N50 G94 G01 Z-0.1 F10.\nN55 G17 G03 X0. Y1. I-1. J0.\nN60 M05\n"));
  // Five-axis after the arc: under TCPC the arc is cut as lines within the tolerance, all of
  // it (the chords were 30 degrees long).
  Compiled five = compile_text(cl, machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(five.ok) << five.diags;
  EXPECT_THAT(five.output, HasSubstr("\nN50 X0.9992 Y0.0393\n"));
}

// NX's second setup on a lathe: an MSYS with Z reversed (the part turned round). Its points
// were put through the first frame and cut from the chuck's side (Z-102 to Z-80), certified.
// A shift along Z alone is the same setup.
TEST(CamSystems, ALatheFrameTurnedFromTheFirstIsASetupOfItsOwn) {
  const std::string head =
      "TOOL PATH/OP1,TOOL,OD_35_L\nTLDATA/TURN,0.4,35,55,15,0\nMSYS/0,0,0,1,0,0,0,1,0\nUNITS/MM\nLOAD/TOOL,1\n"
      "SPINDL/RPM,1000,CLW\nFEDRAT/MMPR,0.1\nRAPID\nGOTO/30,0,2\nGOTO/15,0,2\nGOTO/15,0,-20\nEND-OF-PATH\n";
  Compiled turned = compile_text(head + "MSYS/0,0,-100,1,0,0,0,-1,0\nRAPID\nGOTO/30,0,2\nGOTO/15,0,-20\n",
                                 machine("fanuc-lathe"));
  EXPECT_FALSE(turned.ok);
  EXPECT_THAT(turned.diags, HasSubstr("part.cls:13:1: error: this MSYS is turned from the first one (the program's frame, "
                                      "along the spindle's axis): on a lathe only a shift along Z is one setup"));
  Compiled shifted = compile_text(head + "MSYS/0,0,-10,1,0,0,0,1,0\nRAPID\nGOTO/30,0,2\nGOTO/15,0,-20\nGOTO/30,0,-20\n",
                                  machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(shifted.ok) << shifted.diags;
  EXPECT_THAT(shifted.output, HasSubstr("G00 X60. Z-8.\n"));
  // NX's 4-decimal origin: a frame shifted along its own turned Z is 0.00002 off the axis.
  Compiled rounded = compile_text(
      "TOOL PATH/OP1,TOOL,OD\nMSYS/0,0,0,0.8660254,0,-0.5,0,1,0\nUNITS/MM\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\n"
      "FEDRAT/MMPR,0.1\nRAPID\nGOTO/30,0,2\nGOTO/15,0,-20\nEND-OF-PATH\nTOOL PATH/OP2,TOOL,OD\n"
      "MSYS/-5.0000,0.0000,-8.6603,0.8660254,0,-0.5,0,1,0\nRAPID\nGOTO/30,0,2\nGOTO/14,0,-20\nGOTO/30,0,-20\nEND-OF-PATH\n",
      machine("fanuc-lathe"), {.certify = true});
  EXPECT_TRUE(rounded.ok) << rounded.diags;
  // Creo's CSYS: its points are in the program's frame, but a frame turned from the first is
  // a second setup all the same (it was posted as one).
  Compiled creo = compile_text(
      "$$-> CSYS / 1,0,0,0, 0,1,0,0, 0,0,1,0\nUNITS / MM\nLOADTL / 1\nSPINDL / RPM, 1000, CLW\nFEDRAT / 0.1, MMPR\n"
      "RAPID\nGOTO / 30, 0, 2\nGOTO / 15, 0, -20\n$$-> CSYS / 1,0,0,0, 0,-1,0,0, 0,0,-1,-100\nRAPID\nGOTO / 30, 0, 2\n",
      machine("fanuc-lathe"));
  EXPECT_FALSE(creo.ok);
  EXPECT_THAT(creo.diags, HasSubstr("part.cls:9:6: error: this frame is turned from the first one"));
}

// Points before the file's first MSYS are in the absolute frame, or in that MSYS if NX left it
// out of the first operation: where the MSYS is elsewhere the two put the part in different
// places. Both operations were cut at the same place, certified.
TEST(CamSystems, MotionBeforeAFirstMsysElsewhereIsRefused) {
  const std::string op1 = "UNITS/MM\nTOOL PATH/OP1,TOOL,MILL\nTLDATA/MILL,10,0,75,0,0\nLOAD/TOOL,1\nSPINDL/RPM,3000,CLW\n"
                          "RAPID\nGOTO/0,0,50,0,0,1\nFEDRAT/MMPM,250\nGOTO/0,0,10\nGOTO/20,0,10\nRAPID\nGOTO/20,0,50\n"
                          "END-OF-PATH\nTOOL PATH/OP2,TOOL,MILL\n";
  const std::string op2 = "RAPID\nGOTO/0,0,50,0,0,1\nFEDRAT/MMPM,250\nGOTO/0,0,10\nGOTO/20,0,10\nEND-OF-PATH\n";
  Compiled shifted = compile_text(op1 + "MSYS/100,0,0,1,0,0,0,1,0\n" + op2, machine("fanuc-mill"));
  EXPECT_FALSE(shifted.ok);
  EXPECT_EQ(messages(shifted.diags),
            "part.cls:15:1: error: the file's first MSYS comes after motion and is not the absolute frame: the points "
            "before it may be in the absolute frame or in this one, and the two put the part in different places; "
            "give the first operation its MSYS\n");
  // The absolute frame itself: both readings agree.
  Compiled absolute = compile_text(op1 + "MSYS/0,0,0,1,0,0,0,1,0\n" + op2, machine("fanuc-mill"), {.certify = true});
  EXPECT_TRUE(absolute.ok) << absolute.diags;
}

// Numbers and words after a code or a tool that clpc does not read are said, never dropped
// silently: a number after the tool's that could be an offset register (TURRET/5,12) keeps the
// tool's own offset with a warning; ISO 4343's AUXFUN/n,NEXT is read, AUXFUN/8,2 is warned.
TEST(CamSystems, WordsAfterACodeOrAToolThatAreNotReadAreSaid) {
  Compiled lathe = compile_text("UNITS/MM\nTURRET/5,12\nSPINDL/RPM,500,CLW\nFEDRAT/0.2,MMPR\nRAPID\nGOTO/40,0,2\nFINI\n",
                                machine("fanuc-lathe"));
  ASSERT_TRUE(lathe.ok) << lathe.diags;
  EXPECT_EQ(messages(lathe.diags),
            "part.cls:2:10: warning: TURRET: 12 after the tool number is read as the tool's corrector, not an offset "
            "register: the offset is the tool's number, 5 (write OSETNO,12 for register 12) [-Wtool-offset]\n");
  EXPECT_THAT(lathe.output, HasSubstr("\nN30 T0505 (T5)\n"));
  // CATIA's correctors (LOADTL/2,2,2 then LOADTL/2,1) say nothing.
  Compiled catia = compile_text("UNITS/MM\nLOADTL/2,2,2\nLOADTL/2,1\nSPINDL/RPM,500,CLW\nRAPID\nGOTO/0,0,20\nFINI\n",
                                machine("fanuc-mill"));
  ASSERT_TRUE(catia.ok) << catia.diags;
  EXPECT_EQ(messages(catia.diags), "");
  Compiled codes = compile_text("UNITS/MM\nLOADTL/1\nAUXFUN/8,NEXT\nAUXFUN/9,2\nPREFUN/61,ON\nSPINDL/RPM,500,CLW\nRAPID\n"
                                "GOTO/0,0,20\nFINI\n",
                                machine("fanuc-mill"));
  ASSERT_TRUE(codes.ok) << codes.diags;
  EXPECT_EQ(messages(codes.diags),
            "part.cls:4:10: warning: AUXFUN: '2' after the code is not read (the code M9 is written alone) [-Wignored-word]\n"
            "part.cls:5:11: warning: PREFUN: 'ON' after the code is not read (the code G61 is written alone) [-Wignored-word]\n");
  EXPECT_THAT(codes.output, HasSubstr("\nM8\nM9\nG61\n"));
  // A word of a tool change clpc does not read (a turret side, a manual change) was dropped
  // silently; CATIA's SETOOL,x,y,z and Fusion's IN,n say nothing the program needs.
  Compiled words = compile_text("UNITS/MM\nTURRET/3,REAR\nSPINDL/RPM,500,CLW\nRAPID\nGOTO/40,0,2\n"
                                "TURRET/1,OSETNO,1,SETOOL,0,0,0\nLOADTL/2,IN,2,ADJUST,2\nRAPID\nGOTO/40,0,5\nFINI\n",
                                machine("fanuc-lathe"));
  ASSERT_TRUE(words.ok) << words.diags;
  EXPECT_EQ(messages(words.diags), "part.cls:2:10: warning: TURRET: the word 'REAR' is not read (the tool is loaded with its "
                                   "number and offset register only) [-Wignored-word]\n");
}

// CUTCOM/ON resumes the side and register of the last CUTCOM/LEFT|RIGHT (as SPINDL/ON restarts
// the last speed); with none before it the side is not known, and it is refused where it stands.
TEST(CamSystems, CompensationOnResumesTheLastSide) {
  const std::string cl =
      "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,200\nRAPID\nGOTO/0,0,5\nGOTO/0,0,-1\nCUTCOM/LEFT,21\n"
      "GOTO/10,0,-1\nCUTCOM/OFF\nGOTO/10,10,-1\nCUTCOM/ON\nGOTO/0,10,-1\nCUTCOM/OFF\nGOTO/0,20,-1\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"));
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("\nN70 G94 G01 Z-1. F200.\nN80 G41 D21 X10.\nN90 G40 Y10.\nN100 G41 D21 X0.\nN110 G40 Y20.\n"));
  verifies(cl, machine("fanuc-mill"));
  // Another tool has no side of its own to resume (the last one's D would be another diameter).
  Compiled other = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,200\nRAPID\nGOTO/0,0,5\n"
                                "CUTCOM/LEFT,21\nGOTO/10,0,5\nCUTCOM/OFF\nGOTO/10,10,5\nLOADTL/2\nSPINDL/RPM,1000,CLW\n"
                                "CUTCOM/ON\nGOTO/0,10,5\nFINI\n",
                                machine("fanuc-mill"));
  EXPECT_FALSE(other.ok);
  EXPECT_THAT(other.diags, HasSubstr("part.cls:13:1: error: CUTCOM/ON with no earlier CUTCOM/LEFT or RIGHT"));
  Compiled unknown = compile_text("UNITS/MM\nLOADTL/1\nCUTCOM/ON\nFINI\n", machine("fanuc-mill"));
  EXPECT_FALSE(unknown.ok);
  EXPECT_THAT(unknown.diags, HasSubstr("part.cls:3:1: error: CUTCOM/ON with no earlier CUTCOM/LEFT or RIGHT: which side is not known"));
}

// Words before the major word are read before a contour motion (TLON,GOFWD/...) only. Before
// a record that moves or sets how the tool cuts, dropping the record (it was passed through as a
// comment: RAPID,GOTO lost its move, exit 0) or ignoring the words would post a guess: refused.
// Before an unknown record or a text one they travel with it, as before.
TEST(CamSystems, WordsBeforeARecordThatCutsAreRefusedNotDropped) {
  const std::string head = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,200\nFROM/0,0,10\n";
  Compiled rapid = compile_text(head + "RAPID,GOTO/5,5,10\nFINI\n", machine("fanuc-mill"));
  EXPECT_FALSE(rapid.ok);
  EXPECT_EQ(messages(rapid.diags),
            "part.cls:6:1: error: 'RAPID,GOTO': words before GOTO are read only before a contour motion "
            "(TLON,GOFWD/...); what they change in it is not known: write them as records of their own\n");
  Compiled feed = compile_text(head + "XX,FEDRAT/50\nGOTO/5,5,10\nFINI\n", machine("fanuc-mill"));
  EXPECT_FALSE(feed.ok);
  EXPECT_THAT(feed.diags, HasSubstr("part.cls:6:1: error: 'XX,FEDRAT': words before FEDRAT are read only"));
  Compiled shift = compile_text(head + "XX,TRANS/1,0,0\nGOTO/5,5,10\nFINI\n", machine("fanuc-mill"));
  EXPECT_FALSE(shift.ok);
  EXPECT_THAT(shift.diags, HasSubstr("part.cls:6:1: error: 'XX,TRANS' moves the tool and clpc does not read it"));
  Compiled text = compile_text(head + "XX,PPRINT/HELLO\nXX,FOO/1\nGOTO/5,5,10\nFINI\n", machine("fanuc-mill"));
  ASSERT_TRUE(text.ok) << text.diags;
  EXPECT_EQ(messages(text.diags),
            "part.cls:6:1: warning: 'XX,PPRINT': the words before PPRINT are not read (the record is passed through as a "
            "comment) [-Wignored-word]\n"
            "part.cls:7:1: warning: unknown record 'FOO' (passed through as a comment) [-Wunknown-record]\n");
  EXPECT_THAT(text.output, HasSubstr("\n(CL: XX,PPRINT/HELLO)\n(CL: XX,FOO/1)\nN50 G54 G00 X0. Y0.\nN60 G43 H01 Z10.\nN70 G94 G01 X5. Y5. F200.\n"));
}

// Creo writes "$$-> CUTTER" after its load, also when a tool number is loaded again: it was
// read as the next tool's (T3 listed with T1's 10 mm). A number given another diameter than
// before (one pocket, two cutters) is warned, and a cutting speed on it has no one rpm: refused.
TEST(CamSystems, EachCreoCutterIsItsOwnLoadsAndASecondDiameterIsSaid) {
  auto op = [](int tool, const char* d) {
    return "LOADTL / " + std::to_string(tool) + "\n$$-> CUTTER / " + d + "\nSPINDL / RPM, 1000, CLW\nRAPID\nGOTO / 0,0,10\n";
  };
  const std::string creo = "$$-> MFGNO / PART\nUNITS / MM\n" + op(1, "10.000000") + op(2, "6.000000") +
                           op(1, "10.000000") + op(3, "3.000000") + "FINI\n";
  Compiled c = compile_text(creo, machine("fanuc-mill"));
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("\n(T1 D=10. CR=0.)\n(T2 D=6. CR=0.)\n(T3 D=3. CR=0.)\n"));
  EXPECT_EQ(messages(c.diags), "");
  const std::string twice = "$$-> MFGNO / PART\nUNITS / MM\n" + op(1, "10.000000") + op(1, "12.000000") + "FINI\n";
  Compiled w = compile_text(twice, machine("fanuc-mill"));
  ASSERT_TRUE(w.ok) << w.diags;
  EXPECT_EQ(messages(w.diags),
            "part.cls:9:6: warning: tool 1 is given the diameter 12 here, but 10 where it was first loaded (line 3): "
            "the program's tool list keeps 10; give each cutter a number of its own [-Wtool-geometry]\n");
  // CATIA's order (CUTTER, then its LOADTL): the same.
  const std::string catia = "UNITS/MM\nCUTTER/10\nLOADTL/1\nSPINDL/200,SMM,CLW\nRAPID\nGOTO/0,0,10\nCUTTER/20\n"
                            "LOADTL/1\nSPINDL/200,SMM,CLW\nRAPID\nGOTO/0,0,20\nFINI\n";
  Compiled speed = compile_text(catia, machine("fanuc-mill"));
  EXPECT_FALSE(speed.ok);
  EXPECT_EQ(messages(speed.diags),
            "part.cls:7:1: warning: tool 1 is given the diameter 20 here, but 10 where it was first loaded (line 3): "
            "the program's tool list keeps 10; give each cutter a number of its own [-Wtool-geometry]\n"
            "part.cls:4:1: error: a cutting speed (SPINDL/SFM, SMM) on a mill turns into rpm at the cutter's diameter, "
            "and tool 1 is given two (10, and 20 at line 7): give the speed in RPM, or each cutter a number of its own\n");
  // (Each load begins an operation in a file with none: the post stops at the first's error.)
  // A file whose CUTTER follows its LOADTL writes them all so: T1 reloaded, then T2's own 6 mm.
  const std::string after = "UNITS/MM\nLOADTL/1\nCUTTER/10\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,10\nLOADTL/1\n"
                            "CUTTER/10\nRAPID\nGOTO/0,0,20\nLOADTL/2\nCUTTER/6\nSPINDL/200,SMM,CLW\nRAPID\nGOTO/0,0,20\nFINI\n";
  Compiled a = compile_text(after, machine("fanuc-mill"));
  ASSERT_TRUE(a.ok) << a.diags;
  EXPECT_THAT(a.output, HasSubstr("\n(T1 D=10. CR=0.)\n(T2 D=6. CR=0.)\n"));
  EXPECT_THAT(a.output, HasSubstr(" S10610 M03\n"));
  EXPECT_EQ(messages(a.diags), "");
  // NX's TLDATA with a kind alone gives no diameter: the next one's is the tool's first.
  const std::string nx = "TOOL PATH/OP1,TOOL,T10\nTLDATA/MILL\nLOAD/TOOL,1,ADJUST,1\nUNITS/MM\nSPINDL/RPM,1000,CLW\n"
                         "RAPID\nGOTO/0,0,10\nEND-OF-PATH\nTOOL PATH/OP2,TOOL,T10\nTLDATA/MILL,10.0000,0.0000,50.0000\n"
                         "LOAD/TOOL,1,ADJUST,1\nSPINDL/200,SMM,CLW\nRAPID\nGOTO/0,0,20\nEND-OF-PATH\nFINI\n";
  Compiled n = compile_text(nx, machine("fanuc-mill"));
  ASSERT_TRUE(n.ok) << n.diags;
  EXPECT_THAT(n.output, HasSubstr(" S6366 M03\n"));
  EXPECT_EQ(messages(n.diags), "");
}

// A CUTCOM register goes where the machine's G41/G42 has a place for it (a mill's D word). A
// Fanuc lathe's G41 takes none (the T word's offset holds the nose radius and tip): the number
// is said not to be written. A word CUTCOM does not read is said too; a plane word is silent.
TEST(CamSystems, ACompensationRegisterTheMachineHasNoPlaceForIsSaid) {
  const std::string turn =
      "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nFEDRAT/0.2,MMPR\nRAPID\nGOTO/50,0,10\nCUTCOM/LEFT,3\n"
      "GOTO/40,0,5\nGOTO/40,0,-20\nCUTCOM/OFF\nGOTO/50,0,-20\nFINI\n";
  Compiled lathe = compile_text(turn, machine("fanuc-lathe"));
  ASSERT_TRUE(lathe.ok) << lathe.diags;
  EXPECT_THAT(lathe.output, HasSubstr("\nN60 G41 G99 G01 X80. Z5. F0.2\n"));
  EXPECT_EQ(messages(lathe.diags),
            "part.cls:7:1: warning: CUTCOM register 3 is not written: the comp_left code of machine 'fanuc-lathe' "
            "('G41') takes no register, so the compensation uses offset 1, the one the T word selects [-Wtool-offset]\n");
  // The register the T word selects (OSETNO) is silent, and so is CUTCOM/ON resuming one already said.
  Compiled osetno = compile_text("UNITS/MM\nLOADTL/1,OSETNO,5\nSPINDL/RPM,1000,CLW\nFEDRAT/0.2,MMPR\nRAPID\n"
                                 "GOTO/50,0,10\nCUTCOM/LEFT,5\nGOTO/40,0,5\nCUTCOM/OFF\nGOTO/50,0,5\nCUTCOM/ON\n"
                                 "GOTO/40,0,0\nCUTCOM/OFF\nGOTO/50,0,0\nFINI\n",
                                 machine("fanuc-lathe"));
  ASSERT_TRUE(osetno.ok) << osetno.diags;
  EXPECT_THAT(osetno.output, HasSubstr("T0105"));
  EXPECT_EQ(messages(osetno.diags), "");
  Compiled said_once = compile_text("UNITS/MM\nLOADTL/1,OSETNO,5\nSPINDL/RPM,1000,CLW\nFEDRAT/0.2,MMPR\nRAPID\n"
                                    "GOTO/50,0,10\nCUTCOM/LEFT,1\nGOTO/40,0,5\nCUTCOM/OFF\nGOTO/50,0,5\nCUTCOM/ON\n"
                                    "GOTO/40,0,0\nCUTCOM/OFF\nGOTO/50,0,0\nFINI\n",
                                    machine("fanuc-lathe"));
  ASSERT_TRUE(said_once.ok) << said_once.diags;
  EXPECT_EQ(messages(said_once.diags),
            "part.cls:7:1: warning: CUTCOM register 1 is not written: the comp_left code of machine 'fanuc-lathe' "
            "('G41') takes no register, so the compensation uses offset 5, the one the T word selects [-Wtool-offset]\n");
  // The tool's own number is what the T word selects anyway: nothing to say.
  Compiled own = compile_text("UNITS/MM\nLOADTL/3\nSPINDL/RPM,1000,CLW\nFEDRAT/0.2,MMPR\nRAPID\nGOTO/50,0,10\n"
                              "CUTCOM/RIGHT,3\nGOTO/40,0,5\nCUTCOM/OFF\nGOTO/50,0,5\nFINI\n",
                              machine("fanuc-lathe"));
  ASSERT_TRUE(own.ok) << own.diags;
  EXPECT_EQ(messages(own.diags), "");
  const std::string mill =
      "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,200\nRAPID\nGOTO/0,0,5\nGOTO/0,0,-1\n"
      "CUTCOM/LEFT,XYPLAN,ADJUST,21\nGOTO/10,0,-1\nCUTCOM/OFF,SIDE\nGOTO/10,10,-1\nFINI\n";
  Compiled m = compile_text(mill, machine("fanuc-mill"));
  ASSERT_TRUE(m.ok) << m.diags;
  EXPECT_THAT(m.output, HasSubstr("\nN80 G41 D21 X10.\nN90 G40 Y10.\n"));
  EXPECT_EQ(messages(m.diags), "part.cls:10:12: warning: CUTCOM: 'SIDE' is not read [-Wignored-word]\n");
}

// One tool loaded again with another offset register (NX and APT write LOADTL/1,ADJUST,21 or
// OSETNO for a second operation with the same cutter): the tool stays in the spindle or at the
// cut, and the new register is written. It was dropped (the tool was "already there"), so the
// program ran the second operation on the first register and verify refused it.
TEST(CamSystems, TheSameToolLoadedWithAnotherOffsetWritesTheNewOffset) {
  const std::string cl = "UNITS/MM\nLOADTL/1,ADJUST,1\nSPINDL/1000,CLW\nRAPID\nGOTO/0,0,50\nFEDRAT/100\n"
                         "GOTO/10,0,0\nLOADTL/1,ADJUST,21\nRAPID\nGOTO/0,0,50\nFEDRAT/100\nGOTO/10,0,0\n"
                         "LOADTL/1,ADJUST,21\nGOTO/10,0,-10\nFINI\n";
  Compiled mill = compile_text(cl, machine("fanuc-mill"));
  ASSERT_TRUE(mill.ok) << mill.diags;
  // No second M06, the spindle keeps turning; Z comes down again with H21. The third LOADTL
  // names the register in force: nothing is written.
  EXPECT_THAT(mill.output, HasSubstr("\nN70 G94 G01 X10. Z0. F100.\nN80 G91 G28 Z0.\nN90 G90 G00 X10. Y0.\n"
                                     "N100 G43 H21 Z50.\nN110 X0.\nN120 G94 G01 X10. Z0. F100.\nN130 Z-10.\n"));
  EXPECT_EQ(mill.output.find("M06", mill.output.find("M06") + 1), std::string::npos);
  verifies(cl, machine("fanuc-mill"));
  std::string turn = cl;
  for (size_t at; (at = turn.find("ADJUST")) != std::string::npos;) turn.replace(at, 6, "OSETNO");
  Compiled lathe = compile_text(turn, machine("fanuc-lathe"));
  ASSERT_TRUE(lathe.ok) << lathe.diags;
  EXPECT_THAT(lathe.output, HasSubstr("\nN60 G98 G01 X20. Z0. F100.\nN70 G28 U0. W0.\nN80 T0121 (T1)\n"));
  EXPECT_EQ(lathe.output.find("T0121", lathe.output.find("T0121") + 1), std::string::npos);
  verifies(turn, machine("fanuc-lathe"));
}

// COOLNT with more than one word: every word is read. Only the first was: COOLNT/MIST,OFF
// turned the mist on (M07), COOLNT/ON,MIST gave flood. A word left over is said; of two
// coolants the first is turned on (never none), and ON with OFF is passed through with a warning.
TEST(CamSystems, EveryWordOfACoolantRecordIsRead) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/1000,CLW\nFEDRAT/100\nCOOLNT/ON,MIST\nRAPID\nGOTO/0,0,5\n"
                         "COOLNT/MIST,OFF\nGOTO/0,0,-1\nCOOLNT/FLOOD,HIGH\nGOTO/10,0,-1\nCOOLNT/FLOOD,MIST\n"
                         "COOLNT/ON,OFF\nCOOLNT/OFF,FLOOD\nGOTO/20,0,-1\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"));
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("\nN50 M07\nN60 G54 G00 X0. Y0.\nN70 G43 H01 Z5.\nN80 M09\n"
                                  "N90 G94 G01 Z-1. F100.\nN100 M08\nN110 X10.\nN120 M08\n"
                                  "(CL: COOLNT/ON,OFF)\nN130 M09\nN140 X20.\n"));
  EXPECT_EQ(messages(c.diags),
            "part.cls:10:14: warning: COOLNT: 'HIGH' is not read [-Wignored-word]\n"
            "part.cls:12:14: warning: COOLNT: two coolants, 'FLOOD' and 'MIST': only 'FLOOD' is turned on [-Wcoolant]\n"
            "part.cls:13:1: warning: COOLNT: both ON and OFF (passed through as a comment) [-Wcoolant]\n");
}

// RAPID, FEDRAT, then the move: posts read RAPID as the next move's only, or as in force until
// a FEDRAT. The move was rapid (a plunge into the part at G00); it is now fed, with a warning.
TEST(CamSystems, AFedratBetweenRapidAndItsMoveFeedsTheMove) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/1000,CLW\nFEDRAT/100\nRAPID\nGOTO/0,0,5\nRAPID\nFEDRAT/MMPM,50\n"
                         "GOTO/0,0,-1\nRAPID\nGOTO/0,0,5\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"));
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("\nN60 G43 H01 Z5.\nN70 G94 G01 Z-1. F50.\nN80 G00 Z5.\n"));
  EXPECT_EQ(messages(c.diags),
            "part.cls:8:1: warning: FEDRAT after RAPID and before the move: the move is fed, not rapid (some posts keep "
            "RAPID for the next move; write the FEDRAT after it if that is meant) [-Wrapid-cancelled]\n");
  verifies(cl, machine("fanuc-mill"));
}

// A cutting speed on a mill (CATIA writes SPINDL/v,SMM when the speed is given as one) is the
// rpm at the cutter's diameter, n = 1000 v / (pi D): 200 m/min on a 10 mm cutter is 6366 rpm;
// 500 ft/min on a 1/2 inch cutter is 3820 rpm (the shop's 3.82 x SFM / D). Without a diameter,
// or a tool, no rpm is known: refused where the speed stands.
TEST(CamSystems, ACuttingSpeedOnAMillIsTheRpmAtTheCuttersDiameter) {
  const std::string cl = "UNITS/MM\nCUTTER/10,0\nLOADTL/1\nSPINDL/200,SMM,CLW\nFEDRAT/200,MMPM\nRAPID\nGOTO/0,0,5\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"));
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("\nN30 T1 M06 (T1 D=10. CR=0.)\nN40 S6366 M03\n"));
  verifies(cl, machine("fanuc-mill"));
  Compiled inch = compile_text("UNITS/INCHES\nCUTTER/0.5\nLOADTL/2\nSPINDL/SFM,500,CCLW\nRAPID\nGOTO/0,0,1\nFINI\n",
                               machine("haas-umc750"));
  ASSERT_TRUE(inch.ok) << inch.diags;
  EXPECT_THAT(inch.output, HasSubstr(" S3820 M04\n"));
  // The programmer's MAXRPM holds: 200 m/min on 10 mm under MAXRPM 5000 is 5000 rpm.
  Compiled clamped = compile_text("UNITS/MM\nCUTTER/10,0\nLOADTL/1\nSPINDL/200,SMM,CLW,MAXRPM,5000\nRAPID\nGOTO/0,0,5\nFINI\n",
                                  machine("fanuc-mill"));
  ASSERT_TRUE(clamped.ok) << clamped.diags;
  EXPECT_THAT(clamped.output, HasSubstr("\nN40 S5000 M03\n"));
  Compiled none = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/200,SMM,CLW\nRAPID\nGOTO/0,0,5\nFINI\n", machine("fanuc-mill"));
  EXPECT_FALSE(none.ok);
  EXPECT_THAT(none.diags, HasSubstr("part.cls:3:1: error: a cutting speed (SPINDL/SFM, SMM) on a mill turns into rpm at the "
                                    "cutter's diameter, and tool 1 has no diameter (CUTTER, TLDATA): give the speed in RPM, "
                                    "or the tool's diameter"));
}

// A mill drills along the axis square to the plane and compensates in the plane. After an arc
// in ZX or YZ the control stayed in G18/G19, and the next drilling cycle (and G41) ran in it:
// G81 Z-12 in G18 rapids 17 mm down in Z and drills along Y. G17 comes first now, and the
// reader refuses a cycle or compensation in another plane.
TEST(CamSystems, CyclesAndCompensationAfterAnArcInAnotherPlaneAreInG17) {
  const std::string head = "UNITS/MM\nLOADTL/1\nCUTTER/10\nSPINDL/1000,RPM,CLW\nFEDRAT/500,MMPM\nRAPID\nGOTO/0,0,50\n"
                           "RAPID\nGOTO/0,0,20\nGOTO/10,0,5\nCIRCLE/0,0,5,0,1,0,10\nGOTO/0,0,15\nRAPID\nGOTO/0,0,20\n";
  const std::string drill = head + "CYCLE/DRILL,FEDTO,12,RAPTO,3,MMPM,100\nGOTO/0,0,0\nCYCLE/OFF\nFINI\n";
  Compiled c = compile_text(drill, machine("fanuc-mill"));
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("G18 G03 X0. Z15. K0. I-10.\nN100 G00 Z20.\nN110 G17 G98 G81 X0. Y0. Z-12. R3. F100.\n"));
  verifies(drill, machine("fanuc-mill"));
  const std::string comp = head + "CUTCOM/LEFT,1\nGOTO/10,0,15\nGOTO/10,10,15\nCUTCOM/OFF\nGOTO/10,10,25\nFINI\n";
  Compiled k = compile_text(comp, machine("fanuc-mill"));
  ASSERT_TRUE(k.ok) << k.diags;
  EXPECT_THAT(k.output, HasSubstr("N110 G17 G41 D1 G01 X10. Z15.\n"));
  // The program as it was written before: refused by the reader, at the cycle's block.
  std::string before = c.output;
  before.replace(before.find("G17 G98 G81"), 4, "");
  Compiled v = verify_text(drill, machine("fanuc-mill"), before);
  EXPECT_FALSE(v.ok);
  EXPECT_THAT(v.diags, HasSubstr("part.cl:14:1: error: the program: a drilling cycle in G18: the control drills along the "
"axis square to that plane, not Z; G17 first [G-code line 17]"));
}

// A block written as given (INSERT, PREFUN, AUXFUN) that sets a state the post neither keeps
// nor writes again is refused at its record: G41 with no CUTCOM (every point off by the radius), M99 (the program again, endlessly), M05 (the cuts
// after it with the spindle stopped). What the post keeps it writes again after the block
// (G49 was certified with every Z after it off by the tool's length: G43 H comes again).
TEST(CamSystems, InsertedBlocksThatChangeWhatThePostKeepsAreRefusedOrUndone) {
  const std::string head = "UNITS/MM\nLOADTL/1\nSPINDL/1000,RPM,CLW\nFEDRAT/500,MMPM\nRAPID\nGOTO/0,0,5\n";
  const std::string tail = "GOTO/10,0,5\nGOTO/10,10,5\nFINI\n";
  const std::pair<const char*, const char*> refused[] = {
      {"INSERT/G41 D1", "the block 'G41 D1' (INSERT, PREFUN or AUXFUN) turns cutter compensation on (G41), which moves "
                        "every point after it off the CL's: CUTCOM gives it"},
      {"AUXFUN/99", "the block 'M99' (INSERT, PREFUN or AUXFUN) calls or returns from a subprogram (M99): in a main "
                    "program M99 starts it again from the top, endlessly; the post writes no subprograms"},
      {"AUXFUN/5", "the block 'M5' (INSERT, PREFUN or AUXFUN) turns, stops or orients the spindle (M5) where the post's "
                   "spindle state does not follow: SPINDL gives it"},
      {"INSERT/G68 X0 Y0 R30", "the block 'G68 X0 Y0 R30' (INSERT, PREFUN or AUXFUN) changes the coordinate system or "
                               "its offsets (G68), so the program's positions would mean other places: the frames "
                               "(SET, CAMERA, MSYS) give them"},
      {"INSERT/H05", "the block 'H05' (INSERT, PREFUN or AUXFUN) changes the tool length register (H), which the post "
                     "selects from LOADTL: every Z after it would be off"},
      // A work offset written through its system variable (helper-57): G54's X moved 100 mm.
      {"INSERT/#5221 = 100.", "the block '#5221 = 100.' (INSERT, PREFUN or AUXFUN) sets the control's system variable "
                              "#5221 (work and tool offsets and modal state live there), so the program's positions or "
                              "offsets after it could mean other places: the frames (SET, CAMERA, MSYS) and the tool "
                              "records give them; the program's own variables (#1 to #999), alarms, counters and timers (#3000 to "
                              "#3999) are written"},
      {"INSERT/M97 P65", "the block 'M97 P65' (INSERT, PREFUN or AUXFUN) calls a local subprogram (M97, Haas): the "
                         "control jumps to the N number it names, and the post writes no subprograms"},
      {"AUXFUN/30", "the block 'M30' (INSERT, PREFUN or AUXFUN) ends the program (M30): the blocks after it would never "
                    "run; the post ends it"},
      // Another register than the one in force: the post's own came back at the next move, and
      // the cuts ran in G54 (helper-45).
      {"INSERT/G55", "the block 'G55' (INSERT, PREFUN or AUXFUN) selects a work offset (G55) other than the one the "
                     "post has in force: it writes its own with the next move, so the cuts after it would not run in "
                     "the block's; SET/n (55 for G55, 101 for the first extended register) selects it"},
      {"INSERT/G54.1 P7", "the block 'G54.1 P7' (INSERT, PREFUN or AUXFUN) selects a work offset (G54.1) other than "
                          "the one the post has in force"},
      {"INSERT/G54 P2", "the block 'G54 P2' (INSERT, PREFUN or AUXFUN) selects a work offset (G54) other than the one "
                        "the post has in force"},
  };
  for (const auto& [record, message] : refused) {
    Compiled c = compile_text(head + record + "\n" + tail, machine("fanuc-mill"));
    EXPECT_FALSE(c.ok) << record;
    EXPECT_THAT(c.diags, HasSubstr(std::string("part.cls:7:1: error: ") + message)) << record;
  }
  // In a macro call H and D are arguments (a probing macro's tolerance): written.
  Compiled probe = compile_text(head + "INSERT/G65 P9814 D50. Z-10. H.05\n" + tail, machine("fanuc-mill"));
  ASSERT_TRUE(probe.ok) << probe.diags;
  EXPECT_THAT(probe.output, HasSubstr("\nG65 P9814 D50. Z-10. H.05\n"));
  // Undone: G91 (G90 with the next block), the register in force said again (G54 again), G95
  // (G94 again).
  Compiled u = compile_text(head + "PREFUN/91\nINSERT/G54\nPREFUN/95\n" + tail, machine("fanuc-mill"));
  ASSERT_TRUE(u.ok) << u.diags;
  EXPECT_THAT(u.output, HasSubstr("\nG91\nG54\nG95\nN70 G90 G54 G94 G01 X10. Y0. Z5. F500.\n"));
  verifies(head + "PREFUN/91\nINSERT/G54\nPREFUN/95\n" + tail, machine("fanuc-mill"));
  // G49 (a safety line): the length offset again with the next move; a comment names no code.
  const std::string g49 = head + "PREFUN/49\nINSERT/G18\nINSERT/M01 (G17 NEXT)\nCYCLE/DRILL,FEDTO,2,RAPTO,1,MMPM,100\n"
                          "GOTO/10,10,0\nCYCLE/OFF\n" + tail;
  Compiled s = compile_text(g49, machine("fanuc-mill"));
  ASSERT_TRUE(s.ok) << s.diags;
  // (The M01 stops the spindle, as OPSTOP's does: it is started again before the hole.)
  EXPECT_THAT(s.output, HasSubstr("\nG49\nG18\nM01 (G17 NEXT)\nN70 S1000 M03\nN80 G43 H01 G17 G94 G98 G81 X10. Y10. Z-2. R1. F100.\n"));
  verifies(g49, machine("fanuc-mill"));
  // A lathe's G50 with axis words sets the coordinate system; G50 S alone is the spindle clamp.
  const std::string lathe_head = "UNITS/MM\nLOADTL/1\nSPINDL/1000,RPM,CLW\nFEDRAT/0.2,MMPR\nRAPID\nGOTO/50,0,5\n";
  const std::string lathe_tail = "GOTO/50,0,-20\nGOTO/60,0,-20\nFINI\n";
  Compiled g50 = compile_text(lathe_head + "INSERT/G50 X100. Z5.\n" + lathe_tail, machine("fanuc-lathe"));
  EXPECT_FALSE(g50.ok);
  EXPECT_THAT(g50.diags, HasSubstr("part.cls:7:1: error: the block 'G50 X100. Z5.' (INSERT, PREFUN or AUXFUN) sets "
                                   "the coordinate system where the tool stands (G50 with axis words)"));
  Compiled clamp = compile_text(lathe_head + "INSERT/G50 S2500\n" + lathe_tail, machine("fanuc-lathe"));
  ASSERT_TRUE(clamp.ok) << clamp.diags;
  EXPECT_THAT(clamp.output, HasSubstr("\nG50 S2500\n"));
  // On a five-axis machine the rotaries stay where they were: written again after the block they
  // were unclamped (M11 M13) in the middle of the cut. The post's own brake codes are refused.
  const std::string haas = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,3000,CLW\nRAPID\nGOTO/10,10,5\nFEDRAT/MMPM,200\n"
                           "GOTO/10,10,-2\nGOTO/60,10,-2\n";
  Compiled brake = compile_text(haas + "AUXFUN/8\nGOTO/60,40,-2\nFINI\n", machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(brake.ok) << brake.diags;
  EXPECT_THAT(brake.output, HasSubstr("\nM8\nN60 G01 X2.3622 Y1.5748 Z-0.0787 F7.87\n"));
  // M50 is the Haas's pallet change: it may move them (helper-33).
  Compiled pallet = compile_text(haas + "AUXFUN/50\nGOTO/60,40,-2\nFINI\n", machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(pallet.ok) << pallet.diags;
  EXPECT_THAT(pallet.output, HasSubstr("\nM50\nN60 M11 M13\nN65 G00 B0. C0.\nN70 M10 M12\nN75 G01 X2.3622"));
  // A block that may move them (an axis word, even B-10.; G53): they are positioned again as the
  // post positions them, unclamped, alone, and clamped (restated with the cut, they were left
  // unclamped). A G28 with no axis named, which homes every axis on the Haas, is refused.
  Compiled again = compile_text(haas + "INSERT/G00 B-10.\nGOTO/60,40,-2\nFINI\n", machine("haas-umc750"));
  ASSERT_TRUE(again.ok) << again.diags;
  EXPECT_THAT(again.output, HasSubstr(" M11 M13\nN65 G00 B0. C0.\nN70 M10 M12\nN75 G01 X2.3622 Y1.5748 Z-0.0787 F7.87\n"));
  // After G53 Z0. the tool is up there over the last point: over the cut's end at rapid, then
  // fed down (fed straight from machine home it went diagonally down into the part).
  Compiled up = compile_text(haas + "INSERT/G53 G00 Z0.\nGOTO/60,40,-2\nFINI\n", machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(up.ok) << up.diags;
  EXPECT_THAT(up.output, HasSubstr(" M11 M13\nN65 G00 B0. C0.\nN70 M10 M12\nN75 X2.3622 Y1.5748\nN80 G01 Z-0.0787 F7.87\n"));
  // Z alone to somewhere else (G00 Z-2.) is not up: the cut is fed from there as the CL says
  // (positioned across at that depth, it was a rapid through the material).
  Compiled down = compile_text(haas + "INSERT/G00 Z-2.\nGOTO/60,40,-2\nFINI\n", machine("haas-umc750"));
  ASSERT_TRUE(down.ok) << down.diags;
  EXPECT_THAT(down.output, HasSubstr("N75 G01 X2.3622 Y1.5748 Z-0.0787 F7.87\n"));
  Compiled home = compile_text(haas + "INSERT/G28\nGOTO/60,40,-2\nFINI\n", machine("haas-umc750"));
  EXPECT_FALSE(home.ok);
  EXPECT_THAT(home.diags, HasSubstr("part.cls:9:1: error: the block 'G28' (INSERT, PREFUN or AUXFUN) returns to a "
                                    "reference point (G28) with no axis named, which homes every axis on some "
                                    "controls: the CL's next move would start there; name the axes it returns (G91 "
                                    "G28 Z0.)"));
  Compiled clamp_raw = compile_text(haas + "INSERT/M10\nGOTO/60,40,-2\nFINI\n", machine("haas-umc750"));
  EXPECT_FALSE(clamp_raw.ok);
  EXPECT_THAT(clamp_raw.diags, HasSubstr("part.cls:9:1: error: the block 'M10' (INSERT, PREFUN or AUXFUN) clamps or "
                                         "unclamps the rotary axis B (M10), which the post does around each rotary "
                                         "move: the next would turn it against its brake, or cut with it free"));
  // G96 makes every S after it a surface speed, with no clamp: the face ran at 800 m/min where
  // the CL said 800 rpm (certified).
  Compiled css = compile_text(lathe_head + "PREFUN/96\n" + lathe_tail, machine("fanuc-lathe"));
  EXPECT_FALSE(css.ok);
  EXPECT_THAT(css.diags, HasSubstr("part.cls:7:1: error: the block 'G96' (INSERT, PREFUN or AUXFUN) turns constant "
                                   "surface speed on (G96), so every S after it would be read as the other kind of "
                                   "speed: SPINDL/SMM|SFM (with MAXRPM) or SPINDL/RPM gives it"));
}

// Cuts with the spindle stopped: an arc said nothing (only straight feeds were warned), and a
// drilling cycle with no SPINDL since the tool change was certified. A hole is an error: a
// drill fed into the part without turning breaks. An arc warns, as a straight feed does, where
// the tool never turned (peening, incremental forming); where the CL turned the spindle and
// stopped it with SPINDL/OFF, a feed on is an error, said once (helper-67: certified).
TEST(CamSystems, CutsWithTheSpindleStoppedAreWarnedAndHolesRefused) {
  const std::string head = "UNITS/MM\nLOADTL/1\nRAPID\nGOTO/10,0,5\nFEDRAT/200,MMPM\n";
  Compiled hole = compile_text(head + "CYCLE/DRILL,FEDTO,10,RAPTO,3,MMPM,100\nGOTO/10,0,0\nCYCLE/OFF\nFINI\n",
                               machine("fanuc-mill"));
  EXPECT_FALSE(hole.ok);
  EXPECT_THAT(hole.diags, HasSubstr("part.cls:7:1: error: a hole drilled with the spindle stopped (no SPINDL since the "
                                    "tool change, or SPINDL/OFF): the tool would be fed into the part without turning"));
  Compiled arc = compile_text(head + "GOTO/10,0,-1\nCIRCLE/0,0,-1,0,0,1,10\nGOTO/-10,0,-1\nFINI\n", machine("fanuc-mill"));
  ASSERT_TRUE(arc.ok) << arc.diags;
  EXPECT_THAT(arc.diags, HasSubstr("part.cls:7:1: warning: arc with the spindle stopped [-Wspindle-stopped]"));
  Compiled stopped = compile_text(head + "SPINDL/1000,CLW\nGOTO/10,0,-1\nSPINDL/OFF\nCIRCLE/0,0,-1,0,0,1,10\nGOTO/-10,0,-1\n"
                                         "GOTO/-10,-5,-1\nFINI\n",
                                  machine("fanuc-mill"));
  EXPECT_FALSE(stopped.ok);
  EXPECT_EQ(messages(stopped.diags), "part.cls:9:1: error: arc with the spindle stopped: SPINDL/OFF at line 8 stopped it "
                                     "and no SPINDL starts it again, so the cutter would be fed in without turning\n");
  // Started again, or another tool loaded (it may be one that does not turn): as before.
  EXPECT_TRUE(compile_text(head + "SPINDL/1000,CLW\nGOTO/10,0,-1\nSPINDL/OFF\nSPINDL/800,CLW\nGOTO/20,0,-1\nFINI\n",
                           machine("fanuc-mill")).ok);
  // helper-68: a tool that does not turn, loaded after one that did, says so with SPINDL/OFF
  // (a warning); a feed straight up after SPINDL/OFF is the retract; the same tool loaded again
  // (CATIA, NX: at every operation) is still the tool that turned.
  const std::string turned = head + "SPINDL/1000,CLW\nGOTO/10,0,-1\nRAPID\nGOTO/10,0,50\n";
  Compiled forming = compile_text(turned + "LOADTL/2\nSPINDL/OFF\nRAPID\nGOTO/10,0,5\nGOTO/10,0,-1\nFINI\n",
                                  machine("fanuc-mill"));
  ASSERT_TRUE(forming.ok) << forming.diags;
  EXPECT_THAT(forming.diags, HasSubstr("part.cls:14:1: warning: cutting move with the spindle stopped [-Wspindle-stopped]"));
  EXPECT_TRUE(compile_text(head + "SPINDL/1000,CLW\nGOTO/10,0,-1\nSPINDL/OFF\nGOTO/10,0,50\nFINI\n", machine("fanuc-mill")).ok);
  Compiled reload = compile_text(turned + "SPINDL/OFF\nLOADTL/1\nRAPID\nGOTO/10,0,5\nGOTO/10,0,-1\nFINI\n",
                                 machine("fanuc-mill"));
  EXPECT_THAT(reload.diags, HasSubstr("part.cls:14:1: error: cutting move with the spindle stopped: SPINDL/OFF at line 10"));
}

// APT's spindle runs until SPINDL/OFF; the machine's M06 (a mill's), M00 and M01 stop it. A CL
// that writes SPINDL only when the speed changes (or before the LOADTL) had its next tools cut
// with the spindle stopped, certified. The post starts it again, and the coolant after a stop.
TEST(CamSystems, TheSpindleTheControlStopsIsStartedAgainAsTheClLeftIt) {
  Compiled c = compile_text("UNITS/MM\nSPINDL/1000,RPM,CLW\nCOOLNT/FLOOD\nLOADTL/1\nRAPID\nGOTO/20,0,5\n"
                            "FEDRAT/100,MMPM\nGOTO/20,0,-2\nRAPID\nGOTO/20,0,50\nLOADTL/2\nRAPID\nGOTO/30,0,5\n"
                            "GOTO/30,0,-5\nRAPID\nGOTO/30,0,50\nSTOP\nRAPID\nGOTO/40,0,5\nGOTO/40,0,-5\nFINI\n",
                            machine("fanuc-mill"));
  ASSERT_TRUE(c.ok) << c.diags;
  // Before the first cut (the CL may give the SPINDL after the approach); the coolant at once.
  EXPECT_THAT(c.output, HasSubstr("N50 T1 M06 (T1)\nN60 G54 G00 X20. Y0.\nN70 G43 H01 Z5.\nN80 S1000 M03\n"
                                  "N90 G94 G01 Z-2. F100.\n"));
  // (The coolant again after another tool's M06, for a restart at its T word; helper-70.)
  EXPECT_THAT(c.output, HasSubstr("N120 T2 M06 (T2)\nN130 M08\nN140 G90 G54 G00 X30. Y0.\nN150 G43 H02 Z5.\nN160 S1000 M03\n"));
  EXPECT_THAT(c.output, HasSubstr("N190 M00\nN200 M08\nN210 X40.\nN220 Z5.\nN230 S1000 M03\nN240 G01 Z-5.\n"));
  EXPECT_THAT(c.diags, HasSubstr("part.cls:8:1: warning: the spindle is started again for T1 as the CL left it running "
                                 "(1000 rpm): the CL gives no SPINDL after the tool change, which stops it "
                                 "[-Wspindle-restart]"));
  EXPECT_THAT(c.diags, HasSubstr("part.cls:14:1: warning: the spindle is started again for T2"));
  EXPECT_THAT(c.diags, Not(HasSubstr("spindle-stopped")));
  // The CL's SPINDL after the approach (FFCAM writes it so): the new tool's speed, not the last
  // one's before it (the restart waits for the first cut).
  Compiled later = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/12000,RPM,CLW\nRAPID\nGOTO/20,0,5\nFEDRAT/100,MMPM\n"
                                "GOTO/20,0,-2\nRAPID\nGOTO/20,0,50\nLOADTL/2\nRAPID\nGOTO/30,0,50\nSPINDL/200,RPM,CCLW\n"
                                "RAPID\nGOTO/30,0,5\nGOTO/30,0,-5\nFINI\n",
                                machine("fanuc-mill"));
  ASSERT_TRUE(later.ok) << later.diags;
  EXPECT_THAT(later.output, HasSubstr("N100 T2 M06 (T2)\nN110 G90 G54 G00 X30. Y0.\nN120 G43 H02 Z50.\nN130 S200 M04\n"));
  EXPECT_THAT(later.diags, Not(HasSubstr("spindle-restart")));
  // An M01 before the M06 (optional_stop = "tool-change") stops it first: still said.
  Compiled stop = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/1000,RPM,CLW\nRAPID\nGOTO/20,0,5\nFEDRAT/100,MMPM\n"
                               "GOTO/20,0,-2\nLOADTL/2\nRAPID\nGOTO/30,0,5\nGOTO/30,0,-5\nFINI\n",
                               machine("m", "[m]\ninherits = \"fanuc-mill\"\n[m.program]\noptional_stop = \"tool-change\"\n"));
  ASSERT_TRUE(stop.ok) << stop.diags;
  EXPECT_THAT(stop.output, HasSubstr("N90 M01\nN100 T2 M06 (T2)\n"));
  EXPECT_THAT(stop.diags, HasSubstr("part.cls:11:1: warning: the spindle is started again for T2"));
  // A stop written raw (AUXFUN/0, INSERT/M01) stops them as STOP does: the next hole was drilled
  // with the spindle stopped, and without coolant.
  Compiled raw = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/1000,RPM,CLW\nCOOLNT/ON\nRAPID\nGOTO/20,0,50\n"
                              "CYCLE/DRILL,DEPTH,10,MMPM,100,CLEAR,2\nGOTO/20,0,0\nAUXFUN/0\nGOTO/40,0,0\nCYCLE/OFF\nFINI\n",
                              machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(raw.ok) << raw.diags;
  EXPECT_THAT(raw.output, HasSubstr("\nM0\nN100 S1000 M03\nN110 M08\nN120 G98 G81 X40."));
  // SPINDL/OFF before the change: nothing to start again.
  Compiled off = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/1000,CLW\nRAPID\nGOTO/20,0,5\nSPINDL/OFF\nLOADTL/2\n"
                              "RAPID\nGOTO/30,0,5\nFINI\n",
                              machine("fanuc-mill"));
  ASSERT_TRUE(off.ok) << off.diags;
  EXPECT_THAT(off.output, HasSubstr("N90 T2 M06 (T2)\nN100 G90 G54 G00 X30. Y0.\n"));
  EXPECT_THAT(off.diags, Not(HasSubstr("spindle-restart")));
}

// Through-spindle coolant and air with their own off codes (the UMC-750's M89 and M84) are
// stopped by them: the M09 written for COOLNT/OFF, another coolant, or the finish left the
// through-spindle coolant running.
TEST(CamSystems, ACoolantWithItsOwnOffCodeIsStoppedByIt) {
  Compiled c = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/RPM,3000,CLW\nCOOLNT/THRU\nRAPID\nGOTO/10,10,5\n"
                            "FEDRAT/MMPM,200\nGOTO/10,10,-2\nCOOLNT/OFF\nGOTO/60,10,-2\nCOOLNT/ON\nGOTO/60,40,-2\n"
                            "COOLNT/AIR\nGOTO/10,40,-2\nCOOLNT/FLOOD\nGOTO/10,10,-2\nCOOLNT/AIR\nRAPID\nGOTO/10,10,50\nFINI\n",
                            machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  std::string codes;
  for (size_t at = c.output.find(" M"); at != std::string::npos; at = c.output.find(" M", at + 1))
    if (c.output.compare(at, 3, " M8") == 0 || c.output.compare(at, 3, " M0") == 0) codes += c.output.substr(at + 1, 3) + " ";
  EXPECT_EQ(codes, "M06 M03 M88 M89 M88 M89 M83 M84 M08 M09 M83 M84 M05 ");
  // After an M01 (the operator's switch may be off, and the coolant still on) the next coolant
  // is written as from the one the CL left on: M89 before flood, not nothing.
  Compiled stop = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/RPM,3000,CLW\nCOOLNT/THRU\nRAPID\nGOTO/10,10,5\n"
                               "FEDRAT/MMPM,200\nGOTO/10,10,-2\nOPSTOP\nCOOLNT/FLOOD\nGOTO/60,10,-2\nFINI\n",
                               machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(stop.ok) << stop.diags;
  EXPECT_THAT(stop.output, HasSubstr("\nN60 M01\nN65 M89\nN70 M08\n"));
}

// A record of no motion with nothing after its slash says nothing: FEDRAT/ stopped the post where
// COOLNT/ and PPRINT/ were read past. It is ignored with a warning; the program is the same.
TEST(CamSystems, RecordsWithNothingAfterTheSlashAreIgnoredWithAWarning) {
  const std::string head = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,3000,CLW\nRAPID\nGOTO/10,10,5\nFEDRAT/MMPM,200\nGOTO/10,10,-2\n";
  const std::string tail = "GOTO/60,10,-2\nFINI\n";
  const Compiled plain = compile_text(head + tail, machine("fanuc-mill"));
  ASSERT_TRUE(plain.ok) << plain.diags;
  for (const char* record : {"FEDRAT", "SPINDL", "DELAY", "AUXFUN", "PREFUN", "TLDATA", "CUTTER", "UNITS"}) {
    Compiled c = compile_text(head + record + "/\n" + tail, machine("fanuc-mill"), {.certify = true});
    ASSERT_TRUE(c.ok) << record << c.diags;
    EXPECT_EQ(messages(c.diags), std::string("part.cls:8:1: warning: ") + record +
                                     " with nothing after it says nothing; ignored [-Wempty-record]\n");
    EXPECT_EQ(c.output, plain.output) << record;
  }
  // A record that moves or chooses the tool still needs its words.
  Compiled tool = compile_text(head + "LOADTL/\n" + tail, machine("fanuc-mill"));
  EXPECT_FALSE(tool.ok);
}

// A feed above the machine's max_feed was written as max_feed without a word.
TEST(CamSystems, AFeedAboveTheMachinesLimitIsClampedWithAWarning) {
  Compiled c = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/1000,CLW\nRAPID\nGOTO/0,0,5\nFEDRAT/MMPM,99999\nGOTO/0,0,-1\n"
                            "GOTO/10,0,-1\nFINI\n",
                            machine("fanuc-mill"));
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("G01 Z-1. F10000.\n"));
  EXPECT_THAT(c.diags, HasSubstr("part.cls:6:1: warning: feed 99999 is above machine 'fanuc-mill''s max_feed 10000: "
                                 "written as 10000, slower than the CL asks [-Wfeed-clamped]"));
}

// A FROM before a tool's first move says where the CL's first line starts. Where that move is
// a cut, the tool was fed diagonally from where the tool change left it (certified: verify too
// started at the FROM); it is brought to the FROM point at rapid first (X Y, then Z with the
// length offset), and an arc right after FROM has its start (it was refused). With no FROM,
// the first cut is said (-Wapproach).
TEST(CamSystems, AFirstCutAfterFromStartsAtTheFrom) {
  Compiled line = compile_text("UNITS/MM\nCUTTER/10\nLOADTL/1\nSPINDL/1000,RPM,CLW\nFROM/20,0,10\nFEDRAT/100,MMPM\n"
                               "GOTO/30,0,0\nGOTO/40,0,0\nLOADTL/2\nSPINDL/1000,RPM,CLW\nGOTO/50,0,0\nFINI\n",
                               machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(line.ok) << line.diags;
  EXPECT_THAT(line.output, HasSubstr("N40 S1000 M03\nN50 G54 G00 X20. Y0.\nN60 G43 H01 Z10.\nN70 G94 G01 X30. Z0. F100.\n"));
  EXPECT_EQ(messages(line.diags),
            "part.cls:11:1: warning: the first move of T2 is a cut, with no FROM or rapid before it to say where it "
            "starts: on a mill it is positioned over its end at rapid and fed down along Z from where the tool change (or "
            "the program's start) leaves the tool; a lathe feeds it straight from there [-Wapproach]\n");
  // That cut: over its end first, then down along Z with the length offset (it was fed
  // diagonally from the tool change down through whatever stood between).
  EXPECT_THAT(line.output, HasSubstr("N120 G90 G54 G00 X50. Y0.\nN130 G43 H02 G94 G01 Z0. F100.\n"));
  Compiled arc = compile_text("UNITS/MM\nCUTTER/10\nLOADTL/1\nSPINDL/1000,RPM,CLW\nFROM/20,0,0\nFEDRAT/100,MMPM\n"
                              "CIRCLE/0,0,0,0,0,1,20\nGOTO/-20,0,0\nFINI\n",
                              machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(arc.ok) << arc.diags;
  EXPECT_THAT(arc.output, HasSubstr("N50 G54 G00 X20. Y0.\nN60 G43 H01 Z0.\nN70 G17 G94 G03 X-20. I-20. J0. F100.\n"));
  // NX loads the tool at every operation: a load of the tool in the spindle moves nothing, and
  // its first cut is no approach.
  Compiled again = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/1000,RPM,CLW\nRAPID\nGOTO/0,0,5\nFEDRAT/100,MMPM\nGOTO/0,0,0\n"
                                "LOADTL/1\nGOTO/10,0,0\nFINI\n",
                                machine("fanuc-mill"));
  ASSERT_TRUE(again.ok) << again.diags;
  EXPECT_EQ(messages(again.diags), "");
  // A rapid after the FROM positions the tool itself: nothing is added.
  Compiled rapid = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/1000,RPM,CLW\nFROM/0,0,100\nRAPID\nGOTO/30,0,5\n"
                                "FEDRAT/100,MMPM\nGOTO/30,0,0\nFINI\n",
                                machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(rapid.ok) << rapid.diags;
  EXPECT_THAT(rapid.output, HasSubstr("N40 S1000 M03\nN50 G54 G00 X30. Y0.\nN60 G43 H01 Z100.\nN70 Z5.\nN80 G94 G01 Z0. F100.\n"));
}

// A CAM system is known by a record only it writes. A shop's "$$-> ROUGH CONTOUR" comment made
// a file Creo's, whose arcs take later points on the circle: a chord after a quarter arc became
// a half circle (certified). A CYCLE/INIT, which any ISO 4343 post writes, made a file SolidWorks
// CAM's, whose ROTABL is in radians: ROTABL/90 turned the part 90 radians (certified). (helper-32)
TEST(CamSystems, OnlyARecordOfItsOwnNamesTheCamSystem) {
  const std::string arc = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/60,50,5\nFEDRAT/500,MMPM\n"
                          "GOTO/60,50,-2\nCIRCLE/50,50,-2,0,0,1,10\nGOTO/50,60,-2\nGOTO/40,50,-2\nFINI\n";
  Compiled shop = compile_text("$$-> ROUGH CONTOUR\n" + arc, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(shop.ok) << shop.diags;
  EXPECT_THAT(shop.output, HasSubstr("G03 X50. Y60. I-10. J0.\nN90 G01 X40. Y50.\n"));
  // Creo's own data comment: the point on the circle goes on round the arc (docs/arcs.md).
  Compiled creo = compile_text("$$-> MFGNO / PART\n" + arc, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(creo.ok) << creo.diags;
  EXPECT_THAT(creo.output, HasSubstr("G03 X40. I-10. J0.\n"));

  const std::string rot = "UNITS/MM\nLOADTL/2\nCUTTER/6.8\nSPINDL/RPM,2000,CLW\nROTABL/90,CAXIS\nRAPID\nGOTO/20,0,25\n"
                          "CYCLE/INIT\nCYCLE/DRILL,FEDTO,12,MMPM,200,RAPTO,2\nGOTO/20,0,0\nCYCLE/OFF\nFINI\n";
  Compiled iso = compile_text(rot, machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(iso.ok) << iso.diags;
  EXPECT_THAT(iso.output, HasSubstr(" G81 X0. Y0.7874 "));  // (20,0) turned 90 degrees
  // In a SolidWorks CAM file the angle is radians; more than a turn of them is refused.
  // A whole turn written to four decimals is a turn.
  std::string turn = rot;
  turn.replace(turn.find("ROTABL/90"), 9, "ROTABL/6.2832");
  Compiled whole = compile_text("OPFEATSTART/Drill1\n" + turn, machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(whole.ok) << whole.diags;
  EXPECT_THAT(whole.output, HasSubstr(" G81 X0.7874 Y0. "));
  // A comment naming another system after NX's header does not make the file that system's
  // (read as CATIA's, an NX arc turned the other way round its centre).
  Compiled nx = compile_text("TOOL PATH/CONTOUR,TOOL,EM10\nLOAD/TOOL,1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,100\n"
                             "PPRINT SEE CATIA APT VERSION NOTES\n$$ Pro/CLfile\nGOTO/90,70,-1\n"
                             "CIRCLE/80,70,-1,0,0,1,10.0,0.06,0.5,10.0,0.0\nGOTO/80,80,-1\nEND-OF-PATH\n",
                             machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(nx.ok) << nx.diags;
  EXPECT_THAT(nx.output, HasSubstr("G02 X80. Y80. I-10. J0.\n"));
  Compiled sw = compile_text("OPFEATSTART/Drill1\n" + rot, machine("haas-umc750"));
  EXPECT_FALSE(sw.ok);
  EXPECT_THAT(sw.diags, HasSubstr("part.cls:6:8: error: ROTABL: SolidWorks CAM / CAMWorks files give the angle in "
                                  "radians (the file was taken for one from line 1: OPFEATSTART), and 90 radians is "
                                  "more than a whole turn: is the angle in degrees?"));
  // The other way round: radians in a file that does not say it is SolidWorks CAM's (its .apt
  // flavour has no OPFEATSTART). ROTABL/1.570796 was a turn of 1.57 degrees, certified.
  for (const char* radians : {"1.570796", "0.785398", "3.141593", "-0.5236", "0.392699", "0.218166", "1.571", "1.2566", "0.3927"}) {
    std::string quarter = rot;
    quarter.replace(quarter.find("ROTABL/90"), 9, std::string("ROTABL/") + radians);
    Compiled r = compile_text(quarter, machine("haas-umc750"));
    EXPECT_FALSE(r.ok) << radians;
    EXPECT_THAT(r.diags, HasSubstr("part.cls:5:8: error: ROTABL: " + std::string(radians) + " is ")) << radians;
    EXPECT_THAT(r.diags, HasSubstr(" degrees in radians, to the digits given: SolidWorks CAM / CAMWorks write ROTABL in "
                                   "radians, other systems in degrees, and nothing in this file says which wrote it"));
  }
  // Degrees that are no such fraction stay degrees.
  for (const char* degrees : {"1.5", "12.5", "33.3333", "7.25", "2.125", "0.375", "1.0", "0.480000", "4.800", "2.330000"}) {
    std::string d = rot;
    d.replace(d.find("ROTABL/90"), 9, std::string("ROTABL/") + degrees);
    Compiled r = compile_text(d, machine("haas-umc750"), {.certify = true});
    EXPECT_TRUE(r.ok) << degrees << r.diags;
  }
}

// A cut with no feed is refused once, at its move: the made-up feed of 0 drew a second error at
// every later move, whose advice (more decimals) had nothing to do with it. (helper-31)
TEST(CamSystems, ACutWithNoFeedIsRefusedOnce) {
  Compiled c = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nRAPID\nGOTO/0,0,50\nGOTO/10,0,0\nGOTO/20,0,0\n"
                            "GOTO/30,0,0\nFINI\n",
                            machine("fanuc-mill"));
  EXPECT_FALSE(c.ok);
  EXPECT_EQ(messages(c.diags), "part.cls:6:1: error: cutting move with no feed rate: no FEDRAT before it\n");
}

// A line of text between the points of a Creo arc is written before the arc, which goes on:
// it ended the arc, and the points after it were cut as chords up to 0.76 mm inside the 10 mm
// circle (certified). (helper-34)
TEST(CamSystems, TextBetweenTheCreoArcsPointsDoesNotEndTheArc) {
  const std::string pts = "GOTO / 80, 80, -1\nGOTO / 72.9289321881, 77.0710678119, -1\nGOTO / 70, 70, -1\n";
  for (const char* text : {"PPRINT hello\n", "FOOBAR/1\n", "$$ note\n"}) {
    Compiled c = compile_text("$$*          Pro/CLfile  Version 19.0 - 9738\nUNITS / MM\nLOADTL / 4\n"
                              "SPINDL / RPM, 3000, CLW\nRAPID\nGOTO / 90, 70, 2\nFEDRAT / 300, MMPM\nGOTO / 90, 70, -1\n"
                              "CIRCLE / 80, 70, -1, 0, 0, 1, 10\nGOTO / 87.0710678119, 77.0710678119, -1\n" +
                                  std::string(text) + pts + "GOTO / 60, 70, -1\n",
                              machine("fanuc-mill"), {.certify = true});
    ASSERT_TRUE(c.ok) << text << c.diags;
    EXPECT_THAT(c.output, HasSubstr("G03 X70. I-10. J0.\nN90 G01 X60.\n")) << text;
  }
  // Also where the text fills the chunk (the compile's 1024 instructions, the certificate's 256):
  // flushed away, the arc closed there, refused in one reading and cut as chords in both in the
  // other (certified). (helper-37)
  for (int moves : {248, 249, 250, 1016, 1017, 1018}) {
    std::string cl = "$$*          Pro/CLfile  Version 19.0 - 9738\nUNITS / MM\nLOADTL / 4\nSPINDL / RPM, 3000, CLW\n"
                     "RAPID\nGOTO / 90, 70, 2\nFEDRAT / 300, MMPM\n";
    for (int i = 0; i < moves; ++i) cl += i % 2 ? "GOTO / 90, 70, 2\n" : "GOTO / 90, 71, 2\n";
    cl += "GOTO / 90, 70, -1\nCIRCLE / 80, 70, -1, 0, 0, 1, 10\nGOTO / 87.0710678119, 77.0710678119, -1\nPPRINT hello\n" +
          pts + "GOTO / 60, 70, -1\n";
    Compiled c = compile_text(cl, machine("fanuc-mill"), {.certify = true});
    ASSERT_TRUE(c.ok) << moves << c.diags;
    EXPECT_THAT(c.output, HasSubstr(" G03 X70. I-10. J0.\n")) << moves;
  }
}

// An O word at the start of an inserted block begins another program when the file is loaded:
// the program ended there (exit 0, certified). Refused at the INSERT. (helper-36)
TEST(CamSystems, AnInsertedProgramNumberIsRefused) {
  Compiled c = compile_text("UNITS/MM\nLOADTL/1\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,100\nRAPID\nGOTO/0,0,5\n"
                            "INSERT/O1234\nGOTO/10,0,0\n",
                            machine("fanuc-mill"));
  EXPECT_FALSE(c.ok);
  EXPECT_THAT(c.diags, HasSubstr("part.cls:7:1: error: the block 'O1234' (INSERT, PREFUN or AUXFUN) starts another "
                                 "program (O1234): loaded into the control, the program would end before it; the post "
                                 "writes the program number"));
}

// TOOLNO describes a tool (CATIA lists the job's tools with it, vtx550 three before its first
// LOADTL); some older posts change tools on it alone. Where it names another tool than the one
// loaded and no LOADTL follows before a move, a warning says which tool cuts (helper-43).
TEST(CamSystems, AToolnoWithNoLoadAfterItSaysWhichToolCuts) {
  const std::string head = "UNITS/MM\nCUTTER/10\nLOADTL/3\nSPINDL/1000,RPM,CLW\nFEDRAT/200,MMPM\nRAPID\nGOTO/0,0,10\n"
                           "GOTO/0,0,-1\nRAPID\nGOTO/0,0,50\n";
  Compiled alone = compile_text(head + "TOOLNO/4,8\nRAPID\nGOTO/50,0,10\nGOTO/50,0,-1\n", machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(alone.ok) << alone.diags;
  EXPECT_THAT(alone.diags, HasSubstr("part.cls:11:1: warning: TOOLNO names tool 4, and no LOADTL or TURRET follows it before "
                                     "the move at line 13: the moves after it are cut with T3, the tool loaded"));
  Compiled loaded = compile_text(head + "TOOLNO/4,8\nLOADTL/4\nRAPID\nGOTO/50,0,10\nGOTO/50,0,-1\n", machine("fanuc-mill"),
                                 {.certify = true});
  ASSERT_TRUE(loaded.ok) << loaded.diags;
  EXPECT_THAT(loaded.diags, Not(HasSubstr("TOOLNO")));
  Compiled same = compile_text(head + "TOOLNO/3\nRAPID\nGOTO/50,0,10\n", machine("fanuc-mill"), {.certify = true});
  EXPECT_THAT(same.diags, Not(HasSubstr("TOOLNO")));
  // A file that loads no tool at all: its first cut is refused, and the TOOLNO that meant one is
  // named (helper-51). One that loads it later after a start point is CATIA's way: no word.
  Compiled none = compile_text("UNITS/MM\nTOOLNO/5,10\nCUTTER/10\nSPINDL/RPM,1000,CLW\nFEDRAT/MMPM,100\nRAPID\n"
                               "GOTO/0,0,5\nGOTO/0,0,-1\n", machine("fanuc-mill"));
  EXPECT_FALSE(none.ok);
  EXPECT_THAT(none.diags, HasSubstr("part.cls:2:1: warning: TOOLNO names tool 5, and no LOADTL or TURRET follows it before "
                                    "the move at line 7: no tool is loaded (TOOLNO describes a tool; LOADTL/5 or TURRET/5 loads it): a mill "
                                    "refuses the cut, a lathe's program writes no T word and cuts with the tool and offset "
                                    "the turret holds"));
  Compiled later = compile_text("UNITS/MM\nTOOLNO/5,10\nRAPID\nGOTO/0,0,50\nLOADTL/5\nSPINDL/RPM,1000,CLW\n"
                                "FEDRAT/MMPM,100\nRAPID\nGOTO/0,0,5\nGOTO/0,0,-1\n", machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(later.ok) << later.diags;
  EXPECT_THAT(later.diags, Not(HasSubstr("TOOLNO")));
}

// CATIA writes a Machining Axis Change as another "$$*CATIA0" block: its points are in the new
// axis system. Read as a comment, the cut ran in the first frame, certified (helper-56). A
// later block with the first's matrix (karlo_DEMO3) changes nothing.
TEST(CamSystems, ACatiaAxisSystemOtherThanTheFirstIsRefused) {
  const std::string head = "$$     CATIA APT VERSION 1.0\n$$*CATIA0\n$$ Manufacturing Program.1\n"
                           "$$     1.00000     0.00000     0.00000     0.00000\n$$     0.00000     1.00000     0.00000     0.00000\n"
                           "$$     0.00000     0.00000     1.00000     0.00000\nUNITS/MM\nLOADTL/1\nSPINDL/ 3000.0000,RPM,CLW\n"
                           "RAPID\nGOTO  /    0.00000,    0.00000,   50.00000\n";
  const std::string cut = "RAPID\nGOTO  /    0.00000,    0.00000,    5.00000\nFEDRAT/  300.0000,MMPM\n"
                          "GOTO  /    0.00000,    0.00000,   -2.00000\nGOTO  /   20.00000,    0.00000,   -2.00000\n";
  Compiled turned = compile_text(head + "$$*CATIA0\n$$ Axis System.2\n$$     0.00000     0.00000    -1.00000    50.00000\n"
                                        "$$     0.00000     1.00000     0.00000     0.00000\n"
                                        "$$     1.00000     0.00000     0.00000   -20.00000\n" + cut,
                                 machine("haas-umc750"));
  EXPECT_FALSE(turned.ok);
  EXPECT_THAT(turned.diags, HasSubstr("part.cls:12:1: error: CATIA changes the machining axis system here (its matrix is not "
                                      "that of the cuts before it): the points after it are in the new axis system, which clpc does "
                                      "not put into the first; post each axis system's operations from a file of its own, "
                                      "or give them one machining axis system in CATIA"));
  Compiled same = compile_text(head + "$$*CATIA0\n$$ MSYS/\n$$     1.00000     0.00000     0.00000     0.00000\n"
                                      "$$     0.00000     1.00000     0.00000     0.00000\n"
                                      "$$     0.00000     0.00000     1.00000     0.00000\n" + cut,
                               machine("haas-umc750"), {.certify = true});
  EXPECT_TRUE(same.ok) << same.diags;
  // Another block before any motion replaces the first: nothing was cut in it (helper-58).
  Compiled before = compile_text("$$*CATIA0\n$$ A\n$$ B\n$$ C\n$$     0.00000     0.00000    -1.00000    50.00000\n"
                                 "$$     0.00000     1.00000     0.00000     0.00000\n$$     1.00000     0.00000     0.00000   -20.00000\n" +
                                     head + cut,
                                 machine("haas-umc750"));
  EXPECT_TRUE(before.ok) << before.diags;
}

// CATIA's TPRINT names the tool the LOADTL after it loads: given to the tool in the spindle
// while it had none, T2's name went to T1's... T3's to T2 (helper-56). After a load, with
// nothing moved since, it names the tool just loaded.
TEST(CamSystems, ATprintNamesTheToolItsLoadtlLoads) {
  auto job = [](int t, const std::string& name) {
    return "TPRINT/" + name + "\nLOADTL/" + std::to_string(t) + "\nSPINDL/1000,RPM,CLW\nRAPID\nGOTO/0,0,50\n";
  };
  Compiled c = compile_text("UNITS/MM\n" + job(1, "T1 End Mill D 10") + job(2, "T2 Drill D 8") + job(3, "T3 Ball Mill D 6") + "FINI\n",
                            machine("fanuc-mill"));
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("(T1 - T1 END MILL D 10)\n(T2 - T2 DRILL D 8)\n(T3 - T3 BALL MILL D 6)\n"));
  Compiled after = compile_text("UNITS/MM\nLOADTL/1\nRAPID\nGOTO/0,0,50\nLOADTL/3\nTPRINT/T3 Ball\nRAPID\nGOTO/0,0,50\nFINI\n",
                                machine("fanuc-mill"));
  ASSERT_TRUE(after.ok) << after.diags;
  EXPECT_THAT(after.output, HasSubstr("(T1)\n(T3 - T3 BALL)\n"));
}

// A file with no operation records (CATIA, Fusion, a generic APT post) was one operation: one
// five-axis move put it all under TCPC, the 3-axis arcs cut as lines and a vertical tap
// refused (helper-56). Each tool load begins an operation. (Verify judged the tap's feed out
// with the next tool's spindle speed.)
TEST(CamSystems, EachLoadBeginsAnOperationInAFileWithNone) {
  const std::string cl = "UNITS/MM\nLOADTL/3\nSPINDL/RPM,200,CLW\nRAPID\nGOTO/-30,-30,15\n"
                         "CYCLE/TAP,FEDTO,10,MMPM,300,RAPTO,5\nGOTO/-30,-30,0\nCYCLE/OFF\n"
                         "LOADTL/4\nSPINDL/RPM,6000,CLW\nRAPID\nGOTO/0,-50,30,0,0,1\nFEDRAT/MMPM,800\n"
                         "GOTO/0,-45,-5,0,-0.5,0.866025\n";
  Compiled c = compile_text(cl, machine("haas-umc750"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N50 G94 G98 G84 X-1.1811 Y-1.1811 Z-0.3937 R0.1969 F11.811\nN55 G80\n"));
  EXPECT_THAT(c.output, HasSubstr("N65 T4 M06 (T4)\nN70 S6000 M03\nN75 G54 G00 G234 H04\nN80 M11 M13\nN85 G00 X0. Y-1.9685 B0. C0.\n"));
}

// Names are names: NX's TOOL PATH naming a tool 12 gave it no name, and its cuts were refused
// as made with no tool loaded (helper-61). A name that is a pocket number is that number.
TEST(CamSystems, AToolNamedByANumberIsNamedAndNumberedSo) {
  const std::string cl = "TOOL PATH/FACE_1,TOOL,12\nTLDATA/MILL,10,0,50,0,0\nUNITS/MM\nSPINDL/RPM,2000,CLW\nRAPID\n"
                         "GOTO/0,0,20\nFEDRAT/MMPM,200\nGOTO/10,0,-1\nRAPID\nGOTO/10,0,20\nEND-OF-PATH\n";
  Compiled c = compile_text(cl, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.diags, HasSubstr("part.cls:1:1: warning: operation 'FACE_1' names tool '12' but loads no tool number; "
                                 "using T12 [-Wtool-by-name]"));
  EXPECT_THAT(c.output, HasSubstr(" T12 M06 (T12 D=10. CR=0. - 12)\n"));
}

// A lathe's turret index leaves the spindle and coolant running, but each tool's blocks say
// them again before its first move: a restart at T0505 (the operator searches to the T word)
// found the spindle stopped and fed the insert into a still bar (helper-70: certified). A
// SPINDL of the CL's right after the index is the one written, once.
TEST(CamSystems, ALathesToolSaysItsSpindleAndCoolantAgain) {
  const std::string head = "UNITS/MM\nTURRET/1\nSPINDL/RPM,1000,CLW\nCOOLNT/FLOOD\nRAPID\nGOTO/26,0,2\nFEDRAT/MMPR,0.2\n"
                           "GOTO/26,0,-30\nGOTO/30,0,-30\nRAPID\nGOTO/60,0,5\nTURRET/5\n";
  const std::string tail = "RAPID\nGOTO/20,0,-1\nFEDRAT/MMPR,0.1\nGOTO/0,0,-1\nRAPID\nGOTO/60,0,5\nFINI\n";
  Compiled c = compile_text(head + tail, machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("N110 T0505 (T5)\nN120 G97 S1000 M03\nN130 M08\nN140 G00 X40. Z-1.\n"));
  Compiled own = compile_text(head + "SPINDL/RPM,1500,CLW\n" + tail, machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(own.ok) << own.diags;
  EXPECT_THAT(own.output, HasSubstr("N110 T0505 (T5)\nN120 G97 S1500 M03\nN130 M08\nN140 G00 X40. Z-1.\n"));
}

// The post's own retract in mid-program (the next fixture, a setup stop) with compensation on:
// the fixture's register came before the CL's CUTCOM/OFF, and G91 G28 Z0. ran under G41 from
// the wall, certified (helper-72). Compensation ended after a retract gets its G40 up there;
// ended where the tool cut, or left on, it is an error. NX's load of the same tool at every
// operation changes nothing (the G40 goes on the CL's next move), and a retract's point a few
// 1e-5 off the arc's end it leaves (a CATIA GOFWD) is still straight up.
TEST(CamSystems, ThePostsRetractInMidProgramNeverRunsUnderCompensation) {
  const std::string cut = "UNITS/MM\nSET/54\nLOADTL/1\nSPINDL/RPM,2000,CLW\nRAPID\nGOTO/-20,0,10\nRAPID\nGOTO/-20,0,-5\n"
                          "FEDRAT/MMPM,300\nCUTCOM/LEFT,1\nGOTO/0,0,-5\nGOTO/50,0,-5\nGOTO/60,10,-5\nCUTCOM/OFF\n";
  const std::string next = "SET/55\nRAPID\nGOTO/-20,0,10\nRAPID\nGOTO/-20,0,-5\nGOTO/0,0,-5\nFINI\n";
  Compiled at_wall = compile_text(cut + next, machine("fanuc-mill"));
  EXPECT_FALSE(at_wall.ok);
  EXPECT_THAT(messages(at_wall.diags),
              HasSubstr("part.cls:17:1: error: another work offset (the next fixture) with cutter compensation ended by a "
                        "CUTCOM/OFF (line 14) with no move after it, where the tool last cut: the post retracts first"));
  Compiled up = compile_text(cut + "GOTO/60,10,10\n" + next, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(up.ok) << up.diags;
  EXPECT_THAT(up.output, HasSubstr("N100 X60. Y10.\nN110 Z10.\nN120 G40\nN130 G91 G28 Z0.\nN140 G90 G55 G00 X-20. Y0.\n"));
  const std::string nx = "UNITS/MM\nTOOL PATH/OP1,TOOL,EM\nLOAD/TOOL,1,ADJUST,1\nSPINDL/RPM,2000,CLW\nRAPID\n"
                         "GOTO/-20,0,10\nRAPID\nGOTO/-20,0,-5\nFEDRAT/MMPM,300\nCUTCOM/LEFT,1\nGOTO/0,0,-5\nGOTO/50,0,-5\n"
                         "GOTO/60,10,-5\nCUTCOM/OFF\nEND-OF-PATH\nTOOL PATH/OP2,TOOL,EM\nLOAD/TOOL,1,ADJUST,1\nRAPID\n"
                         "GOTO/60,10,10\nRAPID\nGOTO/-20,0,10\nEND-OF-PATH\nFINI\n";
  Compiled reload = compile_text(nx, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(reload.ok) << reload.diags;
  EXPECT_THAT(reload.output, HasSubstr("(OP2)\nN110 G00 Z10.\nN120 G40 X-20. Y0.\n"));
  const std::string gofwd = "UNITS/MM\nLOADTL/1\nSPINDL/RPM,2000,CLW\nRAPID\nGOTO/-20,0,10\nRAPID\nGOTO/-20,0,-5\n"
                            "FEDRAT/MMPM,300\nCUTCOM/LEFT,1\nGOTO/0,0,-5\nGOTO/50,0,-5\nINDIRV/1,0,0\n"
                            "TLON,GOFWD/(CIRCLE/50,10,-5,10),ON,(LINE/57,0,-5,57,10,-5)\nGOTO/57,2.8586,10\nFINI\n";
  Compiled arc = compile_text(gofwd, machine("fanuc-mill"), {.certify = true});
  EXPECT_TRUE(arc.ok) << arc.diags;
  // The next operation's CUTCOM/LEFT before its approach waits for its move across; the last
  // one's G40 goes before the retract (helper-73: refused as compensation left on).
  const std::string op = "TOOL PATH/OP,TOOL,EM10\nTLDATA/MILL,10,0,50,0,0\nLOAD/TOOL,1\n";
  const std::string next_op = "UNITS/MM\n" + op + "SET/54\nMSYS/0,0,0,1,0,0,0,1,0\nSPINDL/RPM,3000,CLW\nFEDRAT/MMPM,300\n"
                              "RAPID\nGOTO/-20,-20,10\nGOTO/-20,-20,-5\nCUTCOM/LEFT,1\nGOTO/0,-10,-5\nGOTO/50,-10,-5\n"
                              "CUTCOM/OFF\nGOTO/50,-10,10\nEND-OF-PATH\n" + op + "SET/55\nMSYS/200,0,0,1,0,0,0,1,0\n"
                              "CUTCOM/LEFT,1\nSPINDL/RPM,3000,CLW\nFEDRAT/MMPM,300\nRAPID\nGOTO/-20,-20,10\n"
                              "GOTO/-20,-20,-8\nGOTO/0,-10,-8\nGOTO/50,-10,-8\nCUTCOM/OFF\nGOTO/60,-20,-8\nGOTO/60,-20,10\n"
                              "END-OF-PATH\nFINI\n";
  Compiled k = compile_text(next_op, machine("fanuc-mill"), {.certify = true});
  ASSERT_TRUE(k.ok) << k.diags;
  EXPECT_THAT(k.output, HasSubstr("N100 Z10.\n(OP)\nN110 G40\nN120 G91 G28 Z0.\nN130 S3000 M03\nN140 G90 G55 G00 X-20. Y-20.\n"));
}

// SPINDL/MAXRPM alone after a tool change clamps the surface speed the post starts again for
// the new tool: it was dropped, and the lathe's T2 ran to the last tool's G50 S2500 where the
// CL asked 1500 (helper-73).
TEST(CamSystems, AClampAloneAfterAToolChangeClampsTheSpeedStartedAgain) {
  const std::string cl = "UNITS/MM\nLOADTL/1\nSPINDL/SMM,200,MAXRPM,2500,CLW\nFEDRAT/0.2,MMPR\nRAPID\nGOTO/30,0,2\n"
                         "GOTO/30,0,-20\nGOTO/35,0,-20\nRAPID\nGOTO/50,0,20\nLOADTL/2\nSPINDL/MAXRPM,1500\nRAPID\n"
                         "GOTO/20,0,2\nGOTO/20,0,-20\nGOTO/25,0,-20\nRAPID\nGOTO/50,0,20\nFINI\n";
  Compiled c = compile_text(cl, machine("fanuc-lathe"), {.certify = true});
  ASSERT_TRUE(c.ok) << c.diags;
  EXPECT_THAT(c.output, HasSubstr("(T2)\nN120 G50 S1500\nN130 G96 S200 M03\n"));
  EXPECT_EQ(c.output.find("G50 S2500", c.output.find("T0202")), std::string::npos) << "T1's clamp only";
}
