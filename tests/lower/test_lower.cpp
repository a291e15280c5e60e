// Lowering: every record form of docs/cl-input.md becomes the right IR, and each lowering
// error names the record, line and column.
#include "helpers.h"
#include "ir/printer.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

namespace {

// The instruction lines of the lowered IR ("line:col<TAB>text" -> "text").
std::vector<std::string> instrs(const std::string& cl, const std::vector<std::string>& passes = {}) {
  Lowered l = lower_text(cl, passes);
  EXPECT_EQ(first_error(l.diags), "") << cl;
  std::vector<std::string> out;
  for (const auto& op : l.ops)
    for (const auto& in : op.body) {
      std::ostringstream o;
      ir::print_instr(o, op, in);
      std::string s = o.str();
      out.push_back(s.substr(s.find('\t') + 1, s.size() - s.find('\t') - 2));
    }
  return out;
}

std::string err(const std::string& cl) { return first_error(lower_text(cl).diags); }

// Every warning, "line:col: message" each on a line of its own.
std::string warn(const std::string& cl) {
  std::string out;
  for (const Diagnostic& x : lower_text(cl).diags)
    if (x.severity == Severity::Warning)
      out += std::to_string(x.loc.line) + ":" + std::to_string(x.loc.col) + ": " + x.message + "\n";
  return out;
}

}  // namespace

TEST(Lower, GotoThreeAndSixValuesToolAxisPersists) {
  EXPECT_THAT(instrs("GOTO/1,2,3\nGOTO/4,5,6,0,0.6,0.8\nGOTO/7,8,9\n"),
              ElementsAre("feed (1, 2, 3)", "feed (4, 5, 6) axis (0, 0.6, 0.8)", "feed (7, 8, 9) axis (0, 0.6, 0.8)"));
}

// An axis written to few digits is made a unit vector; one far from length 1 is no axis (six
// values that are two points, as under MULTAX/OFF) and is refused, not made one at a guess.
TEST(Lower, ToolAxisIsNormalised) {
  EXPECT_THAT(instrs("GOTO/1,2,3,0,0,1.004\n"), ElementsAre("feed (1, 2, 3) axis (0, 0, 1)"));
  EXPECT_EQ(err("GOTO/10,0,5,20,0,5\n"),
            "1:13: GOTO: the tool axis (i,j,k) is not a unit vector (its length is 20.6155): these are not a tool axis's values");
}

// Under MULTAX/OFF six values are two points to APT, a point and its axis to a CAM system that
// left MULTAX/OFF in force: the second point (0,0,1) was dropped, certified. Refused; MULTAX/ON
// or a bare MULTAX (CATIA) gives the axis again. (helper-32)
TEST(Lower, SixValuesUnderMultaxOffAreRefused) {
  EXPECT_EQ(err("MULTAX/OFF\nGOTO/10,0,-2,0,0,1\n"),
            "2:14: GOTO: six values under MULTAX/OFF: APT reads two points, a tool axis needs MULTAX/ON; have the "
            "CAM system write MULTAX/ON before points with a tool axis");
  EXPECT_THAT(instrs("MULTAX/OFF\nGOTO/1,2,3\nMULTAX/ON\nGOTO/10,0,-2,0,0,1\nMULTAX/OFF\nMULTAX\nGOTO/4,5,6,0,0,1\n"),
              ElementsAre("feed (1, 2, 3)", "feed (10, 0, -2) axis (0, 0, 1)", "feed (4, 5, 6) axis (0, 0, 1)"));
}

// A MULTAX that says neither ON nor OFF, or both, is no guess: MULTAX/OFF,XYZ and MULTAX/OF
// were read as ON and a GOTO's second point taken for a tool axis (helper-64).
TEST(Lower, AMultaxOfAnyOtherWordIsRefused) {
  for (const char* rec : {"MULTAX/OFF,XYZ", "MULTAX/OF", "MULTAX/0", "MULTAX/OFF,ON"})
    EXPECT_EQ(err(std::string(rec) + "\nGOTO/30,10,-1,0,0,1\n"),
              "1:1: MULTAX: expected ON or OFF (or nothing, for ON): whether the GOTOs carry tool axes cannot be told")
        << rec;
}

// A record glued to what follows (a '/' missing) lost its motion or setting with a warning:
// GOTO10.0 skipped the plunge, LOADTL2 the tool change, UNITSINCHES the units (helper-64).
TEST(Lower, ARecordGluedToWhatFollowsIsRefused) {
  EXPECT_EQ(err("GOTO10.0000,10.0000,-1.0000\n"),
            "1:1: 'GOTO10' reads as GOTO glued to what follows (a '/' missing?): skipped, its motion or setting would be "
            "lost; write GOTO/...");
  EXPECT_EQ(err("LOADTL2\n"), "1:1: 'LOADTL2' reads as LOADTL glued to what follows (a '/' missing?): as an unknown "
                               "record its motion or setting would be lost; write LOADTL/...");
  for (const char* rec : {"UNITSINCHES", "RAPIDGOTO/30,20,-1", "FEDRAT1000,MMPM", "CIRCLE90.03,1,2"})
    EXPECT_THAT(err(std::string(rec) + "\n"), HasSubstr("glued to what follows")) << rec;
  // Words that only begin like a record are unknown records, as before.
  EXPECT_EQ(err("RAPIDS\nCOOLNT2\nFROMAGE/1\n"), "");
}

// Lines with no motion never stop a post: a tape mark alone on its line (a CL file sent through
// DNC) and END OF FILE were errors (helper-64, helper-61). A '%' with more on its line is not.
TEST(Lower, TapeMarksAndEndOfFileLinesAreNoStop) {
  EXPECT_EQ(err("%\nGOTO/1,2,3\nEND OF FILE\nFINI\n%\n"), "");
  EXPECT_THAT(warn("%\nGOTO/1,2,3\n"), HasSubstr("1:1: a tape mark ('%' alone on its line, from a punched tape or a DNC "
                                                  "transfer) is ignored"));
  EXPECT_EQ(err("% 12\nGOTO/1,2,3\n"), "1:1: expected a major word at the start of a record, found '%'");
}

// A record that only names or describes, written wrong, and a line that opens as a comment does
// in other languages, moved nothing yet stopped the post (helper-64). Skipped with a warning,
// unless the line holds a motion record further on.
TEST(Lower, MalformedRecordsWithoutMotionAreNoStop) {
  EXPECT_EQ(err("PAINT/1e400\nPAINT/COLOR,(31\nINTOL/0.01,'x\n(SETUP 2)\n; roughing\n* note\n# x\nGOTO/1,2,3\n"), "");
  EXPECT_EQ(warn("PAINT/1e400\n(SETUP 2)\nGOTO/1,2,3\n"),
            "1:7: malformed PAINT record ignored (it carries nothing to cut): number out of range: '1e400'\n"
            "2:1: not a CL record (a line starting with '('): the line is ignored\n");
  // A record that changes how the tool cuts still stops the post; so does a motion record
  // hidden further on the line.
  EXPECT_EQ(err("FEDRAT/1e400\n"), "1:8: number out of range: '1e400'");
  EXPECT_EQ(err("(SETUP) GOTO/1,2,3\n"),
            "1:1: not a CL record (a line starting with '('), yet the line holds GOTO/ further on: skipped, it would be lost");
  EXPECT_THAT(err("; note SPINDL/OFF\n"), HasSubstr("the line holds SPINDL/ further on"));
  // Words of a note are no records (helper-68): a record's name alone, one in the note's
  // parentheses, or after a "$$".
  EXPECT_EQ(err("* RETRACT AT RAPID\n; PROGRAM STOP\n(CHECK FEDRAT/ BEFORE RUN)\nPAINT/1e400 $$ then GOTO/1,2,3\n"), "");
}

// Two records on a line: the second read as a parameter of the first, its motion lost
// silently (helper-64: PAINT/COLOR,31 GOTO/10,0,10 and INTOL/0.01 GOTO/20,0,10 posted nothing).
TEST(Lower, ARecordInsideAnothersParametersIsRefused) {
  for (const char* line : {"PAINT/COLOR,31 GOTO/10,0,10", "INTOL/0.01 GOTO/20,0,10", "GOTO/1,2,3 GOTO/4,5,6"}) {
    const size_t col = std::string_view(line).find("GOTO/", 1) + 1;
    EXPECT_EQ(err(std::string(line) + "\n"), "1:" + std::to_string(col) +
                                                 ": 'GOTO/' inside a parameter: a record of its own on this line (a "
                                                 "line end missing?); read as a parameter, it would be lost")
        << line;
  }
  EXPECT_THAT(err("PAINT/COLOR,3 FEDRAT/100\n"), HasSubstr("'FEDRAT/' inside a parameter"));
  // Every record that moves the tool or changes how it cuts, whichever record it is in; after
  // APT's ';' or a label's ')'; and the records that stand alone (helper-68: these were warnings).
  for (const char* line : {"PAINT/COLOR,31 LOADTL/2", "INTOL/0.01 UNITS/INCHES", "PAINT/COLOR,31 SPINDL/OFF",
                           "PAINT/COLOR,31 LOAD/TOOL,2", "PAINT/COLOR,31 COOLNT/ON", "PAINT/COLOR,31;GOTO/10,0,10",
                           "PAINT/COLOR,31 L1)GOTO/10,0,10", "TOOLNO/1 MULTAX/ON"})
    EXPECT_THAT(err(std::string(line) + "\n"), HasSubstr("/' inside a parameter")) << line;
  EXPECT_EQ(err("INTOL/0.01 RAPID\n"), "1:12: 'RAPID' inside a parameter: a record of its own on this line (a line end "
                                        "missing?); read as a parameter, it would be lost");
  EXPECT_THAT(err("INTOL/0.01 GOHOME\n"), HasSubstr("1:12: 'GOHOME' inside a parameter"));
  // A slash inside a name is no record: LOADTL/1,EM 1/2 FLAT, TOOL PATH/D10/R2. Nor are common
  // words and records' names in small letters, in names and notes (helper-69).
  EXPECT_EQ(err("LOADTL/1,EM 1/2 FLAT\nPAINT/COLOR,D10/R2\nPAINT/TOOL,MY_GOTO/2\n"), "");
  EXPECT_EQ(err("; copy/paste of op 3, check before run\n* Part must be rotated/flipped; load/unload by hand\n"
                "# THREAD/MILL OPERATION FOLLOWS\n(OP 2 (SEE SHEET 2) COOLNT/FLOOD)\nOPFEATSTART/Face then rapid\n"
                "TOOL PATH/THREAD_MILL,TOOL,M8 THREAD/MILL\nPAINT/COLOR,186 LOAD/UNLOAD\nEND-OF-PATH\n"),
            "");
}

// SPINDL/RPM,1200,CW: the direction words' plain spellings, from generic posts (helper-66).
TEST(Lower, SpindleDirectionsInPlainWords) {
  EXPECT_EQ(err("SPINDL/RPM,1200,CW\nSPINDL/RPM,1200,CCW\nSPINDL/1200,CLOCKWISE\n"), "");
  EXPECT_EQ(err("SPINDL/RPM,1200,CW,CCLW\n"),
            "1:20: SPINDL: CLW and CCLW say opposite things in one record; which is meant is not known");
}

// ARCSLP/OFF, ROTHED/OFF, PLUNGE/OFF, POSTN/OFF switch off what clpc never switches on: nothing
// to do. They stopped the post as motion clpc does not read (helper-66).
TEST(Lower, ARecordThatOnlySwitchesOffIsNothing) {
  EXPECT_EQ(err("ARCSLP/OFF\nROTHED/OFF\nPLUNGE/OFF\nPOSTN/OFF\nREFSYS/NOMORE\nGOTO/1,2,3\n"), "");
  EXPECT_THAT(err("ARCSLP/ON\n"), HasSubstr("1:1: 'ARCSLP' moves the tool and clpc does not read it"));
  EXPECT_THAT(err("ROTHED/OFF,30\n"), HasSubstr("1:1: 'ROTHED' moves the tool"));
}

// A sequence number beside a record, not in columns 73-80, was read as one more number:
// GOTO/10,20 ... 0080 cut at Z80 (helper-66). Blank-separated numbers in a record whose others
// are comma-separated are no CAMWorks list (whose trailing comma ends it).
TEST(Lower, NumbersApartByBlanksAmongCommasAreRefused) {
  EXPECT_EQ(err("GOTO/10,20                  0080\n"),
            "1:29: numbers apart by blanks ('20                  0080') in a record whose others are apart by commas: a "
            "sequence number beside the record, or a comma missing? which is meant is not known");
  EXPECT_THAT(err("GOTO/1 2,3\n"), HasSubstr("1:8: numbers apart by blanks ('1 2')"));
  EXPECT_EQ(err("GOTO/1.0 2.0 3.0\nGOTO/1.0 0.0 0.5,\nGOTO/1 2 3 $$ x, y\n"), "");
  EXPECT_EQ(err("GOTO/1,0,0.5\nCIRCLE/0.0 0.0 0.5 0.0 0.0 1.0 1.0,COUNTERCLOCKWISE\nGOTO/0,1,0.5\n"), "");  // CAMWorks' sense word
}

// A printed CL listing's numbered lines gave fifty errors, each "found '8'" (helper-66): one
// error at the first says what the file is.
TEST(Lower, NumberedLinesAreSaidOnce) {
  EXPECT_EQ(err("    1  PARTNO NUMBERED\n    2  UNITS/MM\n    7  GOTO/0,0,10\n"),
            "1:5: a number before the record: the lines are numbered, as in a printed CL listing (APT's CLPRNT), not a "
            "CL file; strip the numbers (the later numbered lines are not said again)");
  EXPECT_EQ(lower_text("    1  PARTNO NUMBERED\n    2  UNITS/MM\n    7  GOTO/0,0,10\n").diags.size(), 1u);
}

// COMMENT is free text, as PPRINT: an apostrophe inside its quotes stopped the post
// (helper-61). One pair of enclosing quotes is the record's, not the text's.
TEST(Lower, ACommentIsFreeText) {
  EXPECT_EQ(err("COMMENT/'Operator's note: check vise'\nCOMMENT/\"5\" vise\nCOMMENT/'a'b\n"), "");
}

// A negative clearance puts the R plane inside the part: written R-2. without a word (helper-62).
TEST(Lower, ANegativeClearanceIsSaid) {
  EXPECT_THAT(warn("GOTO/0,0,10\nCYCLE/DRILL,DEPTH,10,MMPM,100,CLEAR,-2\nGOTO/0,0,0\nCYCLE/OFF\n"),
              HasSubstr("2:1: CYCLE/DRILL: the clearance -2 puts the R plane 2 below the hole's top: the tool goes there "
                        "at rapid, into the hole (right only where a pilot or a counterbore is already there)\n"));
  EXPECT_THAT(warn("GOTO/0,0,10\nCYCLE/DRILL,DEPTH,10,MMPM,100,CLEAR,2\nGOTO/0,0,0\nCYCLE/OFF\n"),
              Not(HasSubstr("below the hole's top")));
}

// One time in one unit: DELAY/2,3 dwelled 3 s, DELAY/SEC,2,REV two revolutions (helper-61).
TEST(Lower, ADelayOfTwoTimesOrTwoUnitsIsRefused) {
  EXPECT_EQ(err("DELAY/2,3\n"), "1:9: DELAY: more than one time (2, then 3): which one is meant cannot be told");
  EXPECT_EQ(err("DELAY/SEC,2,REV\n"), "1:13: DELAY: both SEC and REV: seconds or revolutions of the spindle cannot be told");
  EXPECT_EQ(err("DELAY/2,SEC\nDELAY/3,REV\n"), "");
}

// A whole number too large for a double was taken for an underflow and read as 0: GOTO/<400
// digits> posted X0. (helper-64). Overflow is an error; an underflow is still 0.
TEST(Lower, ANumberTooLargeIsAnErrorNotZero) {
  EXPECT_THAT(err("GOTO/" + std::string(400, '9') + ",10,-1\n"), HasSubstr("1:6: number out of range: '999"));
  EXPECT_THAT(err("GOTO/1" + std::string(320, '0') + ".5,10,-1\n"), HasSubstr("number out of range"));
  EXPECT_EQ(err("GOTO/0." + std::string(400, '0') + "1,10,-1\nGOTO/1e-400,0,0\n"), "");
}

// APT's GOTO carries a list of points (ISO 3592): three values each under MULTAX/OFF, six
// under MULTAX/ON; nine values were refused (helper-51). A count that reads two ways is
// refused: a multiple of six with no MULTAX said. RAPID is its first point's.
TEST(Lower, AGotoOfSeveralPointsIsEachPoint) {
  EXPECT_THAT(instrs("MULTAX/OFF\nRAPID\nGOTO/0,0,0,10,0,0,10,10,0\n"),
              ElementsAre("rapid (0, 0, 0)", "feed (10, 0, 0)", "feed (10, 10, 0)"));
  EXPECT_THAT(instrs("GOTO/0,0,0,10,0,0,10,10,0\n"), ElementsAre("feed (0, 0, 0)", "feed (10, 0, 0)", "feed (10, 10, 0)"));
  EXPECT_THAT(instrs("MULTAX/OFF\nGOTO/0,0,0,10,0,0\n"), ElementsAre("feed (0, 0, 0)", "feed (10, 0, 0)"));
  EXPECT_THAT(instrs("MULTAX/ON\nGOTO/0,0,0,0,0,1,10,0,0,0,0,1\n"),
              ElementsAre("feed (0, 0, 0) axis (0, 0, 1)", "feed (10, 0, 0) axis (0, 0, 1)"));
  EXPECT_EQ(err("GOTO/0,0,0,10,0,0,10,10,0,0,10,0\n"),
            "1:12: GOTO: 12 values and no MULTAX said: 4 points, or 2 with their tool axes? Have the CAM system write "
            "MULTAX/ON or MULTAX/OFF before it");
  EXPECT_EQ(err("MULTAX/ON\nGOTO/0,0,0,0,0,1,10,0,0\n"),
            "2:18: GOTO: 9 values under MULTAX/ON, which are not whole points of six (x,y,z,i,j,k)");
  EXPECT_EQ(err("MULTAX/OFF\nGOTO/0,0,0,10,0,0,1\n"),
            "2:19: GOTO: 7 values under MULTAX/OFF, which are not whole points of three");
  EXPECT_EQ(err("GOTO/0,0,0,10,0,0,1,2\n"), "1:19: GOTO: 8 values, which are not whole points of three");
  EXPECT_THAT(warn("MULTAX/OFF\nRAPID\nGOTO/0,0,0,10,0,0\n"),
              HasSubstr("3:12: RAPID before a GOTO of several points is taken for its first point: the rest are fed"));
}

TEST(Lower, RapidIsOneShot) {
  EXPECT_THAT(instrs("RAPID\nGOTO/1,2,3\nGOTO/4,5,6\nRAPID/\nGOTO/0,0,0\n"),
              ElementsAre("rapid (1, 2, 3)", "feed (4, 5, 6)", "rapid (0, 0, 0)"));
}

// FEDRAT/RAPID, FEDRAT/LOCK and MAXIPM stopped the post (helper-48): none moves anything but
// RAPID's next move, which is RAPID's reading.
TEST(Lower, FedratRapidLockAndMaxipm) {
  EXPECT_THAT(instrs("FEDRAT/MMPM,100\nFEDRAT/RAPID\nGOTO/1,2,3\nGOTO/4,5,6\nFEDRAT/LOCK\nFEDRAT/LOCK,OFF\n"
                     "FEDRAT/MAXIPM,200\nFEDRAT/MMPM,300,MAXMMPM,3000\nGOTO/0,0,0\n"),
              ElementsAre("feed-rate 100 /min", "rapid (1, 2, 3)", "feed (4, 5, 6)", "feed-rate 300 /min", "feed (0, 0, 0)"));
  EXPECT_THAT(warn("FEDRAT/LOCK\nFEDRAT/MAXIPM,200\n"),
              ::testing::StrEq("1:1: FEDRAT/LOCK: clpc's machines have no code to lock the feed override; the feed is "
                               "unchanged\n2:8: FEDRAT: MAXIPM,200 is a limit for feeds a post computes; clpc writes the "
                               "CL's feeds and does not apply it\n"));
  EXPECT_EQ(err("FEDRAT/LOCK,200\n"), "1:8: FEDRAT: unknown word 'LOCK'");
}

TEST(Lower, FromGohomeGodlta) {
  // A cut first after FROM starts at the FROM point: the tool is brought there at rapid.
  EXPECT_THAT(instrs("FROM/0,0,100\nGOTO/1,1,1\nGODLTA/1,2,3\nGODLTA/-2\nGOHOME\nGOHOME/5,5,50\n"),
              ElementsAre("from (0, 0, 100)", "rapid (0, 0, 100)", "feed (1, 1, 1)", "feed (2, 3, 4)", "feed (2, 3, 2)", "rapid (0, 0, 100)",
                          "rapid (5, 5, 50)"));
  // GOHOME/ZAXIS homes Z alone, to the FROM point's (it stopped the post; helper-45).
  EXPECT_THAT(instrs("FROM/0,0,100\nGOTO/10,20,1\nGOHOME/ZAXIS\nGOHOME/XAXIS,YAXIS\n"),
              ElementsAre("from (0, 0, 100)", "rapid (0, 0, 100)", "feed (10, 20, 1)", "rapid (10, 20, 100)",
                          "rapid (0, 0, 100)"));
  EXPECT_EQ(err("GOTO/10,20,1\nGOHOME/ZAXIS\n"), "2:1: GOHOME/ZAXIS needs an earlier FROM (home) and a position");
  EXPECT_EQ(err("FROM/0,0,100\nGOTO/10,20,1,0,0.6,0.8\nGOHOME/ZAXIS\n"),
            "3:1: GOHOME by axis with the tool tilted: a move along the machine's axes to home would not take the tool "
            "up its axis; have the CAM system write the retract as a GOTO");
}

// RETRCT asks the post for a retract clpc does not make: the CL's next move must be that
// retract (up the tool axis), or a tool change; any other motion would cross at the depth cut.
TEST(Lower, RetractIsTheNextMoveUpTheToolAxisOrRefused) {
  EXPECT_THAT(instrs("GOTO/1,1,-2\nRETRCT\nSPINDL/OFF\nRAPID\nGOTO/1,1,50\nGOTO/9,9,50\n"),
              ElementsAre("feed (1, 1, -2)", "spindle off", "rapid (1, 1, 50)", "feed (9, 9, 50)"));
  EXPECT_THAT(instrs("GOTO/1,1,-2,0,0.6,0.8\nRETRCT\nGOTO/1,4,2\n"),
              ElementsAre("feed (1, 1, -2) axis (0, 0.6, 0.8)", "feed (1, 4, 2) axis (0, 0.6, 0.8)"));
  EXPECT_EQ(err("LOADTL/1\nGOTO/1,1,-2\nRETRCT\nLOADTL/2\nGOTO/9,9,-2\n"), "");
  EXPECT_EQ(err("RETRCT\nGOTO/9,9,-2\n"), "");  // no position yet: nothing to retract from
  EXPECT_EQ(err("FROM/0,0,100\nGOTO/1,1,-2\nRETRCT\nGOHOME\n"),
            "3:1: RETRCT asks for a retract to the clearance surface, which clpc does not make: the next move (line 4) does not "
            "go straight up the tool axis, so the tool would cross at the depth it cut; write the retract as motion in the CAM system");
  EXPECT_THAT(err("GOTO/10,0,0\nRETRCT\nCIRCLE/0,0,0,0,0,1,10,0.06,0.5,20,0\nGOTO/0,10,0\n"), HasSubstr("2:1: RETRCT asks"));
  EXPECT_THAT(err("GOTO/10,0,0\nRETRCT\nCIRCLE/0,0,0,0,0,1,10,0.06,0.5,20,0\nGOTO/0,10,0\n"), HasSubstr("(line 3) is an arc"));
}

TEST(Lower, CircleNxElevenValues) {
  EXPECT_THAT(instrs("GOTO/10,0,0\nCIRCLE/0,0,0,0,0,1,10,0.06,0.5,20,0\nGOTO/0,10,0\n"),
              ElementsAre("feed (10, 0, 0)", "arc ? to (0, 10, 0) center (0, 0, 0) axis (0, 0, 1) r 10 hint cw nx11"));
}

TEST(Lower, CircleCreoSevenValuesWithContinuation) {
  EXPECT_THAT(instrs("GOTO/10,0,0\nCIRCLE / 0., 0., 0.,  $\n0., 0., -1.,  10.\nGOTO/0,10,0\n"),
              ElementsAre("feed (10, 0, 0)", "arc ? to (0, 10, 0) center (0, 0, 0) axis (0, 0, -1) r 10 hint ccw creo7"));
}

TEST(Lower, CircleSolidWorksSixValuesDerivesRadius) {
  EXPECT_THAT(instrs("GOTO/3,4,0\nCIRCLE/0,0,0,0,0,1\nGOTO/-3,4,0\n"),
              ElementsAre("feed (3, 4, 0)", "arc ? to (-3, 4, 0) center (0, 0, 0) axis (0, 0, 1) r 5 hint ccw noradius6"));
}

TEST(Lower, CircleNxTimesIsExtraTurns) {
  EXPECT_THAT(instrs("GOTO/10,0,0\nCIRCLE/0,0,0,0,0,1,10,0.06,0.5,20,0,TIMES,3\nGOTO/10,0,-3\n"),
              ElementsAre("feed (10, 0, 0)", "arc ? to (10, 0, -3) center (0, 0, 0) axis (0, 0, 1) r 10 hint cw nx11 turns+2"));
}

TEST(Lower, CreoIntermediatePointsJoinTheArc) {
  // In a file Creo wrote ($$-> data comments), two points further along the same circle, the
  // same way round: one arc.
  const std::string path = "GOTO/10,0,0\nCIRCLE/0,0,0,0,0,1,10\nGOTO/0,10,0\nGOTO/-10,0,0\nGOTO/0,-10,0\nGOTO/0,-20,0\n";
  EXPECT_THAT(instrs("$$-> MFGNO / 1\n" + path),
              ElementsAre("feed (10, 0, 0)",
                          "arc ? to (0, -10, 0) center (0, 0, 0) axis (0, 0, 1) r 10 hint ccw creo7 via (0, 10, 0) via (-10, 0, 0)",
                          "feed (0, -20, 0)"));
  // Elsewhere (APT's points after a CIRCLE keep each chord within the CAM tolerance of the
  // arc) a step whose chord leaves the arc by more than 0.01 mm is a straight move: these are
  // a quarter circle and three chords of 2.9 mm sagitta (a square's edges after a corner arc).
  EXPECT_THAT(instrs(path), ElementsAre("feed (10, 0, 0)", "arc ? to (0, 10, 0) center (0, 0, 0) axis (0, 0, 1) r 10 hint ccw creo7",
                                        "feed (-10, 0, 0)", "feed (0, -10, 0)", "feed (0, -20, 0)"));
  // Points as close as an APT processor's (2 degrees apart: 0.0015 mm) join the arc anywhere.
  EXPECT_THAT(instrs("GOTO/10,0,0\nCIRCLE/0,0,0,0,0,1,10\nGOTO/9.993908,0.348995,0\nGOTO/9.975641,0.697565,0\nGOTO/20,0,0\n"),
              ElementsAre("feed (10, 0, 0)",
                          "arc ? to (9.975641, 0.697565, 0) center (0, 0, 0) axis (0, 0, 1) r 10 hint ccw creo7 via (9.993908, 0.348995, 0)",
                          "feed (20, 0, 0)"));
}

// A step to the opposite point (a half turn: a quadrant point to the next but one) has no sense
// of its own; the sign of its cross product is zero, or whatever the CL's rounding makes it. It
// follows the arc's other steps, or the convention where the arc has none yet. It was refused
// as "not the same sense", and the rest of the arc was cut as a chord (through the centre).
TEST(Lower, AHalfTurnStepFollowsTheArc) {
  const std::string creo = "$$-> MFGNO / 1\nGOTO/10,0,0\nCIRCLE/0,0,0,0,0,1,10\n";
  // First step a half turn: the next point, further round counter-clockwise, joins.
  EXPECT_THAT(instrs(creo + "GOTO/-10,0,0\nGOTO/0,-10,0\nGOTO/0,-10,5\n"),
              ElementsAre("feed (10, 0, 0)",
                          "arc ? to (0, -10, 0) center (0, 0, 0) axis (0, 0, 1) r 10 hint ccw creo7 via (-10, 0, 0)",
                          "feed (0, -10, 5)"));
  // The same with the half turn's end rounded to either side of the diameter.
  for (const char* y : {"0.0001", "-0.0001"})
    EXPECT_THAT(instrs(creo + "GOTO/-10," + y + ",0\nGOTO/0,-10,0\nGOTO/0,-10,5\n"),
                ElementsAre("feed (10, 0, 0)", HasSubstr("arc ? to (0, -10, 0)"), "feed (0, -10, 5)"))
        << y;
  // A half turn after the arc's end: half a turn further round, or a straight pass across the
  // centre (over a round face)? The CL does not say: refused where the point stands.
  EXPECT_EQ(err(creo + "GOTO/0,10,0\nGOTO/0,-10,0\nGOTO/0,-10,5\n"),
            "5:1: this point lies opposite the end of the arc before it, on its circle: half a turn further round or a "
            "straight move through the centre, which the CL does not tell apart; have the CAM system write the arc's "
            "points closer, or another point between");
  // Under an inverse-time feed each CL move keeps its own block and time: points close to the
  // arc stay lines; Creo's wide steps, the arc itself, are refused (one F cannot time them).
  EXPECT_THAT(instrs("FEDRAT/INVERS,100\nGOTO/10,0,0\nCIRCLE/0,0,0,0,0,1,10\nGOTO/9.993908,0.348995,0\n"
                     "GOTO/9.975641,0.697565,0\n"),
              ElementsAre("feed-rate 100 inverse-time", "feed (10, 0, 0)",
                          "arc ? to (9.993908, 0.348995, 0) center (0, 0, 0) axis (0, 0, 1) r 10 hint ccw creo7",
                          "feed (9.975641, 0.697565, 0)"));
  EXPECT_EQ(err("FEDRAT/INVERS,4\n" + creo + "GOTO/0,10,0\nGOTO/-10,0,0\n"),
            "6:1: an inverse-time feed (FEDRAT/INVERS) on an arc given by more than one point: the arc is one block, and "
            "one F cannot give each point's move its time; have the CAM system write a feed per minute here");
  // A point that lies behind the half turn in the convention's sense does not join: counter-
  // clockwise, (0, 10) comes before (-10, 0). It is a straight move.
  EXPECT_THAT(instrs(creo + "GOTO/-10,0,0\nGOTO/0,10,0\n"),
              ElementsAre("feed (10, 0, 0)", "arc ? to (-10, 0, 0) center (0, 0, 0) axis (0, 0, 1) r 10 hint ccw creo7",
                          "feed (0, 10, 0)"));
  // Two half turns are back at the start: the circle closed, or a straight move across the
  // centre (a D-shaped outline)? The CL does not say, and either cut where the other was meant
  // leaves the path by the radius. It was cut straight and certified; refused where it stands.
  EXPECT_EQ(err(creo + "GOTO/-10,0,0\nGOTO/10,0,0\n"),
            "5:1: this point lies on the circle of the arc before it, 180.0 degrees round from its end, but joined, "
            "the arc would close a full turn or pass it: the CL does not tell the arc carried on from a straight move "
            "across, and cut straight it would leave the circle by 10.0000; have the CAM system write the arc with its "
            "own CIRCLE records");
  // The same closed by quarter points (cut straight, the last quarter was a chord 2.93 mm inside
  // the circle), and
  // Creo points on the circle at another height (a helix written as points): refused.
  EXPECT_THAT(err(creo + "GOTO/0,10,0\nGOTO/-10,0,0\nGOTO/0,-10,0\nGOTO/10,0,0\nGOTO/0,10,0\n"),
              HasSubstr("7:1: this point lies on the circle of the arc before it, 90.0 degrees round from its end, but "
                        "joined, the arc would close a full turn or pass it"));
  EXPECT_THAT(err(creo + "GOTO/0,10,1\nGOTO/-10,0,2\n"),
              HasSubstr("5:1: this point lies on the circle of the arc before it, 90.0 degrees round from its end, but at "
                        "another height along its axis"));
  // Closed by twelve points written to 10 decimals: the sum of the steps lands on either side of
  // a full turn by rounding; refused alike (it was joined into a "full circle" whose points read
  // as clockwise, refused as a contradiction, for some radii and counts).
  EXPECT_THAT(err("$$-> MFGNO / 1\nGOTO/15,0,0\nCIRCLE/0,0,0,0,0,1,15\nGOTO/12.9903810568,7.5000000000,0\nGOTO/7.5000000000,12.9903810568,0\nGOTO/0.0000000000,15.0000000000,0\nGOTO/-7.5000000000,12.9903810568,0\nGOTO/-12.9903810568,7.5000000000,0\nGOTO/-15.0000000000,0.0000000000,0\nGOTO/-12.9903810568,-7.5000000000,0\nGOTO/-7.5000000000,-12.9903810568,0\nGOTO/-0.0000000000,-15.0000000000,0\nGOTO/7.5000000000,-12.9903810568,0\nGOTO/12.9903810568,-7.5000000000,0\nGOTO/15.0000000000,-0.0000000000,0\n"),
              HasSubstr("15:1: this point lies on the circle of the arc before it, 30.0 degrees round from its end, but "
                        "joined, the arc would close a full turn or pass it"));
  // Outside Creo a point on the circle joins only within the chord tolerance: a wide step is a
  // straight move (APT's points keep their chords within the CAM tolerance).
  EXPECT_THAT(instrs("GOTO/10,0,0\nCIRCLE/0,0,0,0,0,1,10\nGOTO/-10,0,0\nGOTO/10,0,0\n"),
              ElementsAre("feed (10, 0, 0)", HasSubstr("arc ? to (-10, 0, 0)"), "feed (10, 0, 0)"));
}

TEST(Lower, RetractAfterArcIsNotAnIntermediatePoint) {
  EXPECT_THAT(instrs("GOTO/10,0,0\nCIRCLE/0,0,0,0,0,1,10\nGOTO/0,10,0\nGOTO/0,10,5\n"),
              ElementsAre("feed (10, 0, 0)", "arc ? to (0, 10, 0) center (0, 0, 0) axis (0, 0, 1) r 10 hint ccw creo7",
                          "feed (0, 10, 5)"));
}

TEST(Lower, NxArcTakesOnlyOnePoint) {
  EXPECT_THAT(instrs("GOTO/10,0,0\nCIRCLE/0,0,0,0,0,1,10,0.06,0.5,20,0\nGOTO/0,10,0\nGOTO/-10,0,0\n"),
              ::testing::Contains("feed (-10, 0, 0)"));
}

TEST(Lower, ToolRecords) {
  EXPECT_THAT(instrs("LOAD/TOOL,3,ADJUST,13\nLOADTL/4\nLOADTL / 5,  OSETNO,  15\nTURRET/6\nSELECT/TOOL,7\n"),
              ElementsAre("tool-change T3 H13", "tool-change T4", "tool-change T5 H15", "tool-change T6", "tool-preselect T7"));
}

// APT's LOADTL/n,LENGTH,l gives the tool's gauge length, never an offset register: the length
// offset stays the tool's own (H = n); the length counts where TLDATA/CUTTER gives none.
TEST(Lower, LoadtlLengthIsTheToolsLengthNotAnOffsetRegister) {
  Lowered l = lower_text("LOADTL/2,LENGTH,100,MILL\nGOTO/0,0,0\nCUTTER/8\nLOADTL/3,LENGTH,120.5\nTLDATA/MILL,6,0,40\n"
                         "GOTO/0,0,0\nLOADTL/4,LENGTH,90\nGOTO/0,0,0\n");
  EXPECT_EQ(first_error(l.diags), "");
  EXPECT_THAT(l.ir, HasSubstr("tool T2 d 8 r 0 l 100\ntool T3 MILL d 6 r 0 l 40\ntool T4 d 0 r 0 l 90\n"));
  EXPECT_THAT(l.ir, HasSubstr("tool-change T2\n"));
  EXPECT_THAT(l.ir, Not(HasSubstr(" H100")));
  EXPECT_EQ(first_error(lower_text("LOADTL/2,LENGTH\n").diags), "1:16: LOADTL: LENGTH needs the tool's length, a number above 0");
}

TEST(Lower, ToolTableFromTldataCutterAndCreoCutter) {
  Lowered l = lower_text(
      "TOOL PATH/OP1,TOOL,EM10\nTLDATA/MILL,10,1,50,0,0\nLOAD/TOOL,3\nGOTO/0,0,0\nEND-OF-PATH\n"
      "LOADTL/4\nCUTTER/6,0.5\nGOTO/0,0,0\n$$-> FEATNO / 9\nLOADTL / 5\n$$-> CUTTER / 2.5\nGOTO/0,0,0\n");
  EXPECT_THAT(l.ir, HasSubstr("tool T3 \"EM10\" MILL d 10 r 1 l 50\ntool T4 d 6 r 0.5\ntool T5 d 2.5 r 0\n"));
}

TEST(Lower, NxToolByNameOnly) {
  Lowered l = lower_text("LOAD/TOOL,1\nFROM/0,0,0\nTOOL PATH/OP1,TOOL,BALL6\nTLDATA/MILL,6,3,40,0,0\nSPINDL/RPM,5000,CLW\nGOTO/1,1,1\n");
  EXPECT_THAT(l.ir, HasSubstr("tool T2 \"BALL6\" MILL d 6 r 3 l 40 (numbered by clpc)"));
  // The change comes at TOOL PATH, before the spindle starts.
  EXPECT_THAT(l.ir, HasSubstr("operation 2 \"OP1\" at 3:1\n  3:1\ttool-change T2\n  5:1\tspindle 5000 rpm cw"));
  ASSERT_EQ(count(l.diags, Severity::Warning), 1u);
  EXPECT_EQ(l.diags[0].message, "operation 'OP1' names tool 'BALL6' but loads no tool number; using T2");
}

// Two words of one record that say opposite things: the last one won, silently (SPINDL/1000,
// RPM,SMM turned at 31831 rpm; FEDRAT/100,MMPM,IPM fed 2540; UNITS/INCHES,MM read millimetres).
TEST(Lower, WordsThatContradictEachOtherAreRefused) {
  EXPECT_EQ(err("SPINDL/1000,RPM,SMM\n"), "1:17: SPINDL: RPM and SMM say opposite things in one record; which is meant is not known");
  EXPECT_EQ(err("SPINDL/1000,RPM,CLW,CCLW\n"), "1:21: SPINDL: CLW and CCLW say opposite things in one record; which is meant is not known");
  EXPECT_EQ(err("SPINDL/1000,RPM,ON,OFF\n"), "1:20: SPINDL: ON and OFF in one record; which is meant is not known");
  EXPECT_EQ(err("FEDRAT/100,MMPM,IPM\n"), "1:17: FEDRAT: MMPM and IPM say opposite things in one record; which is meant is not known");
  EXPECT_EQ(err("FEDRAT/100,MMPR,MMPM\n"), "1:17: FEDRAT: MMPR and MMPM say opposite things in one record; which is meant is not known");
  EXPECT_EQ(err("FEDRAT/100,INVERS,MMPM\n"), "1:19: FEDRAT: INVERS and MMPM say opposite things in one record; which is meant is not known");
  EXPECT_EQ(err("CUTCOM/LEFT,RIGHT\n"), "1:13: CUTCOM: LEFT and RIGHT in one record; which is meant is not known");
  EXPECT_EQ(err("UNITS/INCHES,MM\n"), "1:14: UNITS: INCHES and MM in one record; which unit the file is in is not known");
  // Words that agree stay read: a mode with a unit of its own mode, a word said twice.
  EXPECT_EQ(err("FEDRAT/100,PERMIN,MMPM\nFEDRAT/0.2,MMPR,PERREV\nSPINDL/RPM,1000,CLW,RPM\nUNITS/MM,MM\nCUTCOM/LEFT,LEFT\n"), "");
}

TEST(Lower, SpindleBothOrdersAndKinds) {
  EXPECT_THAT(instrs("SPINDL/RPM,1000,CLW\nSPINDL/2000,RPM,CCLW\nSPINDL/SMM,200,CLW,MAXRPM,3000\nSPINDL/SFM,500\n"
                     "SPINDL/OFF\nSPINDL/ON\nSPINDL/750\n"),
              ElementsAre("spindle 1000 rpm cw", "spindle 2000 rpm ccw", "spindle 200 m/min cw max 3000",
                          "spindle 152.4 m/min cw", "spindle off", "spindle 152.4 m/min cw", "spindle 750 rpm cw"));
  // No direction word: the one last given holds (a new speed never reverses the spindle; it
  // did, to clockwise, under a left-hand tool), also across a stop and a tool change.
  EXPECT_THAT(instrs("SPINDL/RPM,1000,CCLW\nSPINDL/RPM,500\nSPINDL/OFF\nSPINDL/800\nLOADTL/2\nSPINDL/SMM,90\n"),
              ElementsAre("spindle 1000 rpm ccw", "spindle 500 rpm ccw", "spindle off", "spindle 800 rpm ccw",
                          "tool-change T2", "spindle 90 m/min ccw"));
  // SPINDL/ON with a direction: the last speed, that way (the word was dropped).
  EXPECT_THAT(instrs("SPINDL/RPM,1000,CLW\nSPINDL/OFF\nSPINDL/ON,CCLW\nSPINDL/RPM,800\n"),
              ElementsAre("spindle 1000 rpm cw", "spindle off", "spindle 1000 rpm ccw", "spindle 800 rpm ccw"));
}

TEST(Lower, FeedBothOrdersAndUnits) {
  EXPECT_THAT(instrs("UNITS/MM\nFEDRAT/MMPM,250\nFEDRAT/10,IPM\nFEDRAT/0.2,MMPR\nFEDRAT/IPR,0.01\nFEDRAT/PERMIN,141\nFEDRAT/500\n"
                     "FEDRAT/INVERS,12\n"),
              ElementsAre("feed-rate 250 /min", "feed-rate 254 /min", "feed-rate 0.2 /rev", "feed-rate 0.254 /rev",
                          "feed-rate 141 /min", "feed-rate 500 /min", "feed-rate 12 inverse-time"));
}

TEST(Lower, FeedConvertsToInchPrograms) {
  EXPECT_THAT(instrs("UNITS/INCHES\nFEDRAT/254,MMPM\nFEDRAT/IPM,10\n"),
              ElementsAre("feed-rate 10 /min", "feed-rate 10 /min"));
}

TEST(Lower, CoolantCutcomDelayStops) {
  EXPECT_THAT(instrs("COOLNT/ON\nCOOLNT/FLOOD\nCOOLNT/MIST\nCOOLNT/THRU\nCOOLNT/OFF\nCUTCOM/LEFT,5\nCUTCOM/RIGHT\n"
                     "CUTCOM/OFF\nDELAY/1.5\nOPSTOP\nSTOP\n"),
              ElementsAre("coolant on", "coolant flood", "coolant mist", "coolant thru", "coolant off",
                          "cutter-comp left D5", "cutter-comp right", "cutter-comp off", "dwell 1.5 s", "optional-stop",
                          "stop"));
}

// A bare ON turns on the coolant last chosen (as SPINDL/ON and CUTCOM/ON resume theirs): after
// THRU, OFF, ON the cut went on with flood.
TEST(Lower, ABareCoolantOnResumesTheLastKind) {
  EXPECT_THAT(instrs("COOLNT/THRU\nCOOLNT/OFF\nCOOLNT/ON\nCOOLNT/MIST,ON\nCOOLNT/ON\n"),
              ElementsAre("coolant thru", "coolant off", "coolant thru", "coolant mist", "coolant mist"));
  // Another tool's bare ON is the default coolant: through-spindle coolant is the tool's.
  EXPECT_THAT(instrs("LOADTL/1\nCOOLNT/THRU\nCOOLNT/OFF\nLOADTL/1\nCOOLNT/ON\nLOADTL/2\nCOOLNT/ON\n"),
              ElementsAre("tool-change T1", "coolant thru", "coolant off", "tool-change T1", "coolant thru",
                          "tool-change T2", "coolant on"));
  // TAPKUL is ISO 4343's word for tapping coolant: it was passed through, the tap ran dry (helper-51).
  EXPECT_THAT(instrs("COOLNT/TAPKUL\nCOOLNT/TAP\n"), ElementsAre("coolant tap", "coolant tap"));
}

TEST(Lower, TextRecords) {
  EXPECT_THAT(instrs("PARTNO BRACKET\nPPRINT hello world\nINSERT/M100\nAUXFUN/8\nREMARK nothing\n"),
              ElementsAre("comment \"hello world\"", "insert \"M100\"", "insert \"M8\""));
  EXPECT_THAT(lower_text("PARTNO BRACKET\nGOTO/0,0,0\n").ir, HasSubstr("program \"BRACKET\""));
}

TEST(Lower, Frames) {
  EXPECT_THAT(instrs("MSYS/1,2,3,0,1,0,-1,0,0\nMSYS/1,2,13,0,1,0,-1,0,0\n$$-> CSYS / 1,0,0,10, 0,1,0,20, 0,0,1,30\n"
                     "CSYS/1,0,0,0,0,1,0,0,0,0,1,0\nCAMERA/0,0,-1,-7.874, 0,1,0,0, 1,0,0,0\n"),
              ElementsAre("frame msys origin (0, 0, 0) x (1, 0, 0) y (0, 1, 0) z (0, 0, 1)",
                          "frame msys origin (0, 0, 10) x (1, 0, 0) y (0, 1, 0) z (0, 0, 1)",
                          "frame csys origin (10, 20, 30) x (1, 0, 0) y (0, 1, 0) z (0, 0, 1)",
                          "frame csys origin (0, 0, 0) x (1, 0, 0) y (0, 1, 0) z (0, 0, 1)",
                          "frame camera origin (-7.874, 0, 0) x (0, 0, 1) y (0, 1, 0) z (-1, 0, 0)"));
}

// NX writes points and tool axes in the MSYS; the first MSYS is the program frame, and a GOTO
// without a tool axis has the frame's Z. Creo/APT frames leave the points as they are but give
// 3-value GOTOs their Z as the tool axis.
TEST(Lower, FramesApplyToPointsAndToolAxes) {
  EXPECT_THAT(instrs("MSYS/5,5,0,1,0,0,0,1,0\nGOTO/1,0,0\nMSYS/15,5,0,0.7071067812,0,-0.7071067812,0,1,0\nGOTO/0,0,5\n"
                     "GOTO/0,0,4,0,0,1\n"),
              ElementsAre("frame msys origin (0, 0, 0) x (1, 0, 0) y (0, 1, 0) z (0, 0, 1)", "feed (1, 0, 0)",
                          "frame msys origin (10, 0, 0) x (0.7071067811865475, 0, -0.7071067811865475) y (0, 1, 0) z "
                          "(0.7071067811865475, 0, 0.7071067811865475)",
                          "feed (13.535533905932738, 0, 3.5355339059327373) axis (0.7071067811865475, 0, 0.7071067811865475)",
                          "feed (12.82842712474619, 0, 2.82842712474619) axis (0.7071067811865475, 0, 0.7071067811865475)"));
  EXPECT_THAT(instrs("$$-> CSYS / 0,0,1,10, 0,1,0,0, -1,0,0,0\nGOTO/1,2,3\n"),
              ElementsAre("frame csys origin (10, 0, 0) x (0, 0, -1) y (0, 1, 0) z (1, 0, 0)", "feed (1, 2, 3) axis (1, 0, 0)"));
}

TEST(Lower, SetWorkOffsetAndMode) {
  EXPECT_THAT(instrs("SET/MODE,ABSOL\nSET/OFSETL,55\n"), ElementsAre("work-offset 55 (register 2)"));
}

TEST(Lower, RotateAndSubroutines) {
  EXPECT_THAT(instrs("DEFSUB/1\nGOTO/1,0,0\nGOTO/2,0,0\nENDSUB\nCALSUB/1\nROTATE/AAXIS,INCR,-36,CCLW\nCALSUB/1\n"),
              ElementsAre("feed (1, 0, 0)", "feed (2, 0, 0)", "rotary-index A -36 incremental ccw", "feed (1, 0, 0)",
                          "feed (2, 0, 0)"));
}

TEST(Lower, OperationsFromToolPathAndFeatno) {
  Lowered l = lower_text(
      "FROM/0,0,0\nTOOL PATH/ROUGH,TOOL,T\nGOTO/1,0,0\nEND-OF-PATH\n$$-> FEATNO / 32\nGOTO/2,0,0\n$$-> END /\nFINI\n");
  EXPECT_THAT(l.ir, HasSubstr("operation 1 at 1:1\n"));
  EXPECT_THAT(l.ir, HasSubstr("operation 2 \"ROUGH\" at 2:1\n"));
  EXPECT_THAT(l.ir, HasSubstr("operation 3 \"FEATNO 32\" at 5:6\n"));
}

TEST(Lower, DisplayRecordsDroppedSilently) {
  Lowered l = lower_text("PAINT/COLOR,3\nPPWORD/X,1\nMULTAX/ON\nMACHIN/MILL,1\n$$-> MFGNO / X\nGOTO/0,0,0\n");
  EXPECT_TRUE(l.diags.empty());
  EXPECT_EQ(l.ops.at(0).body.size(), 1u);
}

TEST(Lower, UnknownRecordWarnsAndPassesThrough) {
  // An unknown name that reads as motion (a misspelt GOTO, an arc, a helix, another system's
  // move) is refused: as a comment its move was lost, certified.
  for (const char* rec : {"GOTOO/10,30,-1", "GOT/1,2,3", "ARC/40,20,-1,0,0,1,10,ANGLE,180", "HELIX/0,0,-1,0,0,1,10,-5",
                          "MOVETO/1,2,3", "POSITN/1,2,3", "SPLINE/1,2,3", "PLUNGE/5"})
    EXPECT_THAT(err(std::string("GOTO/0,0,0\n") + rec + "\n"),
                ::testing::EndsWith("moves the tool and clpc does not read it: no CAM system's record of that name is "
                                    "known, and the name reads as motion (a misspelt GOTO, an arc, a helix, a spline?); "
                                    "have the CAM system write the motion as GOTO and CIRCLE records"))
        << rec;
  Lowered l = lower_text("GOTO/0,0,0\nFOO/1,BAR\n");
  ASSERT_EQ(l.diags.size(), 1u);
  EXPECT_EQ(l.diags[0].severity, Severity::Warning);
  EXPECT_EQ(l.diags[0].loc, (SourceLoc{2, 1}));
  EXPECT_EQ(l.diags[0].message, "unknown record 'FOO' (passed through as a comment)");
  EXPECT_THAT(l.ir, HasSubstr("passthrough \"FOO/1,BAR\""));
  // NX's optional skip says what it costs: the blocks run whatever the block-delete switch says.
  Lowered skip = lower_text("GOTO/0,0,0\nOPSKIP/ON\n");
  ASSERT_EQ(skip.diags.size(), 1u);
  EXPECT_EQ(skip.diags[0].message, "OPSKIP: clpc writes no block delete ('/'): the blocks between OPSKIP/ON and "
                                   "OPSKIP/OFF run whatever the operator's block-delete switch says (passed through "
                                   "as a comment)");
}

// Incremental CL data, however it is said, is refused where it stands: MODE/INCR was passed
// through as a comment and each step cut as an absolute point (certified). The absolute mode
// is what clpc reads: nothing to do. (helper-31's probe.)
TEST(Lower, IncrementalCLDataIsRefusedWhereverItIsSaid) {
  for (const char* rec : {"MODE/INCR", "MODE/INCREM", "MODE/INCREMENTAL", "MODE/RELATIVE", "MODE/ABSOL,OFF",
                          "MODE/MILL,INCR", "COORD/INCR", "INCR", "INCR/ON", "INCREMENTAL", "ABSOL/OFF", "ABSOL/INCR"})
    EXPECT_EQ(err(std::string("GOTO/0,0,0\n") + rec + "\nGOTO/10,0,0\n"),
              "2:1: '" + std::string(rec) +
                  "' makes the points that follow incremental (each a step from the one before), and clpc reads CL "
                  "points as absolute: have the CAM system write absolute points")
        << rec;
  for (const char* rec : {"MODE/ABSOL", "ABSOL", "ABSOL/ON", "INCR/OFF", "MODE/MILL", "REFSYS/NOMORE", "MODE/INCR,OFF",
                          "COORD/INCR,NOMORE", "REFSYS/OFF", "MODE/ABSOL,ON"}) {
    Lowered l = lower_text(std::string("GOTO/0,0,0\n") + rec + "\nGOTO/10,0,0\n");
    EXPECT_EQ(first_error(l.diags), "") << rec;
  }
  // A reference system or a rotary head set by record moves every later point: refused.
  EXPECT_THAT(err("GOTO/0,0,0\nREFSYS/1,0,0,10,0,1,0,0,0,0,1,0\nGOTO/10,0,0\n"),
              ::testing::StartsWith("2:1: 'REFSYS' moves the tool and clpc does not read it: a reference system"));
  EXPECT_THAT(err("GOTO/0,0,0\nROTHEAD/30,BAXIS\nGOTO/10,0,0\n"),
              ::testing::StartsWith("2:1: 'ROTHEAD' moves the tool and clpc does not read it: a rotary head"));
}

TEST(Lower, ChunksLongOperations) {
  std::string cl = "TOOL PATH/LONG,TOOL,T\n";
  for (int i = 0; i < 1000; ++i) cl += "GOTO/" + std::to_string(i) + ",0,0\n";
  SourceFile src;
  src.open_memory("t", cl);
  Diagnostics d(nullptr);
  ir::ProgramInfo info = prescan_program(src);
  struct Count : OperationSink {
    std::vector<std::pair<size_t, bool>> chunks;
    void operation(ir::Operation& op) override { chunks.emplace_back(op.body.size(), op.continued); }
  } c;
  LowerOptions opt;
  opt.chunk_size = 300;
  Lowerer low(info, d, c, opt);
  parse_cl(src, d, low);
  low.finish();
  // The auto tool change comes first in the first chunk.
  EXPECT_THAT(c.chunks, ElementsAre(std::make_pair(300u, false), std::make_pair(300u, true), std::make_pair(300u, true),
                                    std::make_pair(101u, true)));
}

// --- errors --------------------------------------------------------------------------------

TEST(LowerErrors, GotoWithFourValues) {
  EXPECT_EQ(err("GOTO/1,2,3\nGOTO/1,2,3,4\n"), "2:12: GOTO needs 3 or 6 values (x,y,z[,i,j,k]), found 4");
}

TEST(LowerErrors, GotoWithAWord) { EXPECT_EQ(err("GOTO/1,X,3\n"), "1:8: GOTO: expected a number, found 'X'"); }
TEST(LowerErrors, GotoWithAGroup) {
  EXPECT_EQ(err("GOTO/(1,2,3)\n"), "1:6: GOTO: expected a number, found a parameter group (...)");
  EXPECT_EQ(err("GOTO/(POINT/1,2,3)\n"), "1:6: GOTO: expected a number, found a parameter group (POINT/...)");
}

TEST(LowerErrors, ZeroToolAxis) { EXPECT_EQ(err("GOTO/1,2,3,0,0,0\n"), "1:12: GOTO: the tool axis (i,j,k) must not be zero"); }

TEST(LowerErrors, CircleWrongCount) {
  EXPECT_EQ(err("GOTO/1,0,0\nCIRCLE/0,0,0,0,0\nGOTO/0,1,0\n"), "2:16: CIRCLE needs 6, 7 or 11 values (xc,yc,zc,i,j,k[,r[,...]]), found 5");
}

TEST(LowerErrors, CircleWithoutEndPoint) {
  EXPECT_EQ(err("GOTO/1,0,0\nCIRCLE/0,0,0,0,0,1,1\nFINI\n"), "2:1: CIRCLE is not followed by a GOTO giving its end point");
}

TEST(LowerErrors, CircleWithoutStart) {
  EXPECT_EQ(err("CIRCLE/0,0,0,0,0,1,1\nGOTO/1,0,0\n"), "1:1: CIRCLE needs a start point: no motion comes before it");
}

TEST(LowerErrors, CircleEndOffTheCircle) {
  EXPECT_EQ(err("GOTO/1,0,0\nCIRCLE/0,0,0,0,0,1,1\nGOTO/0,2,0\n"),
            "2:1: CIRCLE: the arc's end point (GOTO at line 3) is 1 mm off its circle of radius 1 mm (at most 0.01 mm "
            "is taken: the control alarms, or cuts another arc)");
}

TEST(LowerErrors, SpindleAndFeedWords) {
  EXPECT_EQ(err("SPINDL/RPM,1000,SIDEWAYS\n"), "1:17: SPINDL: unknown word 'SIDEWAYS'");
  EXPECT_EQ(err("FEDRAT/MMPM\n"), "1:12: FEDRAT: no feed value");
  EXPECT_EQ(err("FEDRAT/-5,MMPM\n"), "1:1: FEDRAT: the feed must be greater than zero, found -5");
  EXPECT_EQ(err("FEDRAT/0.05,MMPT\n"),
            "1:13: FEDRAT: a feed per tooth (MMPT) needs the cutter's number of teeth, which the CL data does not give; have "
            "the CAM system write the feed per minute or per revolution");
}

TEST(LowerErrors, ToolNumber) {
  EXPECT_EQ(err("LOADTL/1.5\n"), "1:8: LOADTL: tool number must be a whole number from 0 to 99999, found 1.5");
  EXPECT_EQ(err("LOAD/1\n"), "1:6: LOAD: expected TOOL,n");
}

TEST(LowerErrors, FrameValues) {
  EXPECT_EQ(err("MSYS/0,0,0,1,0,0\n"), "1:6: MSYS needs 9 values (origin, X axis, Y axis), found 6");
  EXPECT_EQ(err("CSYS/1,0,0,0, 0,2,0,0, 0,0,1,0\n"), "1:1: CSYS: not a valid frame: its axes are not unit length and perpendicular");
}

TEST(LowerErrors, Subroutines) {
  EXPECT_EQ(err("CALSUB/3\n"), "1:8: CALSUB/3: no such subroutine (DEFSUB must come first)");
  EXPECT_EQ(err("DEFSUB/1\nDEFSUB/2\nENDSUB\n"), "2:1: DEFSUB inside DEFSUB/1: subroutine definitions cannot nest");
  EXPECT_EQ(err("DEFSUB/1\nGOTO/1,2,3\n"), "1:1: DEFSUB/1 has no ENDSUB");
  EXPECT_EQ(err("DEFSUB/1\nCALSUB/1\nENDSUB\nCALSUB/1\n"), "2:1: CALSUB/1: subroutine calls nest deeper than 16 (recursion?)");
  // A repeat count was dropped: the body ran once. (helper-36)
  EXPECT_EQ(err("DEFSUB/1\nGOTO/1,2,3\nENDSUB\nCALSUB/1,3\n"),
            "4:10: CALSUB/1: the words after the subroutine number (a repeat count?) are not read; write one CALSUB/1 "
            "for each call");
  // Calls inside calls multiply (11 levels of 20 calls: 2e14 moves, until the disk was full).
  std::string bomb = "DEFSUB/0\nGOTO/1,2,3\nENDSUB\n";
  for (int k = 1; k <= 6; ++k) {
    bomb += "DEFSUB/" + std::to_string(k) + "\n";
    for (int c = 0; c < 20; ++c) bomb += "CALSUB/" + std::to_string(k - 1) + "\n";
    bomb += "ENDSUB\n";
  }
  EXPECT_THAT(err(bomb + "CALSUB/6\n"), ::testing::EndsWith(": CALSUB and COPY replay more than 4194304 records "
                                                            "(calls and copies inside others multiply); clpc stops "
                                                            "replaying them"));
  // So do copies inside copies: 16 lines wrote 2.77 GB (helper-51).
  EXPECT_EQ(err("INDEX/1\nGOTO/1,0,0\nGOTO/0,0,0\nINDEX/1,NOMORE\nINDEX/2\nCOPY/1,TRANSL,0,0.001,0,10000\n"
                "INDEX/2,NOMORE\nCOPY/2,TRANSL,0.001,0,0,10000\n"),
            "8:1: CALSUB and COPY replay more than 4194304 records (calls and copies inside others multiply); clpc "
            "stops replaying them");
}

// Motion after FINI was ignored with a warning, and the program certified without its cuts (a
// second program in the file, a FINI inside an operation). Refused at its first record; other
// records after FINI are ignored with a warning. APT's jumps are refused as LOOP is. (helper-36)
TEST(LowerErrors, MotionAfterFiniAndJumpsAreRefused) {
  EXPECT_EQ(err("GOTO/0,0,0\nFINI\nPPRINT next\nGOTO/1,0,0\nGOTO/2,0,0\n"),
            "4:1: 'GOTO' after FINI: FINI ends the program, and the motion after it would be lost; remove the FINI "
            "before it, or post each program from a file of its own");
  Lowered quiet = lower_text("LOADTL/1\nGOTO/0,0,0\nFINI\nPPRINT next\nCOOLNT/OFF\nCYCLE/OFF\nLOADTL/0\nCUT\n");
  EXPECT_EQ(first_error(quiet.diags), "");
  EXPECT_EQ(std::count_if(quiet.diags.begin(), quiet.diags.end(),
                          [](const Diagnostic& d) { return d.message == "records after FINI are ignored"; }),
            1);
  for (const char* rec : {"LOOPST", "JUMPTO/L1", "LOOPND"})
    EXPECT_THAT(err(std::string("GOTO/0,0,0\n") + rec + "\n"),
                ::testing::StartsWith("2:1: '" + std::string(rec).substr(0, std::string(rec).find('/')) +
                                      "' moves the tool and clpc does not read it"))
        << rec;
  // A preselection moves nothing: one clpc cannot read is said, not refused.
  for (const char* rec : {"SELECT/TOOL", "SELECT/TOOL,abc", "SELECT/TOOL,99999999999"}) {
    Lowered l = lower_text(std::string("LOADTL/1\nGOTO/0,0,0\n") + rec + "\nGOTO/1,0,0\n");
    EXPECT_EQ(first_error(l.diags), "") << rec;
    EXPECT_TRUE(std::any_of(l.diags.begin(), l.diags.end(), [](const Diagnostic& d) {
      return d.message == "SELECT/TOOL with no tool number clpc can read: no preselection is written (the tool change "
                          "still loads the tool)";
    })) << rec;
  }
  // LOADTL/2,NEXT: a tool to get ready, or to load now? Loaded now, T1's cuts were made with T2.
  EXPECT_EQ(err("LOADTL/1\nGOTO/0,0,0\nLOADTL/2,NEXT\nGOTO/1,0,0\n"),
            "3:10: LOADTL: NEXT: the tool to get ready or the one to load now? Which is meant is not known; have the "
            "CAM system write SELECT/TOOL,2 for a tool to get ready");
}

TEST(LowerErrors, UnitsChange) {
  EXPECT_EQ(err("UNITS/MM\nGOTO/0,0,0\nUNITS/INCHES\n"),
            "3:7: UNITS changes to inch but the program is in mm: clpc needs one unit per file");
}

TEST(LowerErrors, Nurbs) {
  EXPECT_EQ(err("NURBS/1\n"),
            "1:1: 'NURBS' moves the tool and clpc does not read it: NURBS curves are not read; in NX set the operation's "
            "Machine Control > Motion Output to 'Linear Only' or 'Arcs' (or the post's NURBS output off) and write the "
            "CLSF again");
}

// TRACUT moves the motion after it by its matrix until TRACUT/NOMORE; COPY plays an INDEX block
// again, each copy moved from the last.
TEST(Lower, TracutAndCopy) {
  EXPECT_THAT(instrs("TRACUT/0,-1,0,10, 1,0,0,0, 0,0,1,5\nGOTO/1,0,0\nTRACUT/NOMORE\nGOTO/1,0,0\n"),
              ElementsAre("feed (10, 1, 5)", "feed (1, 0, 0)"));
  EXPECT_THAT(instrs("INDEX/7\nGOTO/1,0,0\nGOTO/2,0,0\nINDEX/7,NOMORE\nCOPY/7,TRANSL,0,10,0,2\n"),
              ElementsAre("feed (1, 0, 0)", "feed (2, 0, 0)", "feed (1, 10, 0)", "feed (2, 10, 0)", "feed (1, 20, 0)",
                          "feed (2, 20, 0)"));
  EXPECT_THAT(instrs("INDEX/1\nGOTO/1,0,0\nCOPY/1,XYROT,90,1\n"), ElementsAre("feed (1, 0, 0)", "feed (6.123233995736766e-17, 1, 0)"));
  EXPECT_EQ(first_error(lower_text("COPY/3,SAME,2\n").diags), "1:6: COPY/3: no INDEX/3 block before it");
  EXPECT_EQ(first_error(lower_text("TRACUT/2,0,0,0, 0,1,0,0, 0,0,1,0\n").diags),
            "1:8: TRACUT: the matrix must turn and move the motion, not scale or mirror it");
}

// MOVARC: the end point from the angle about the axis, the sense from its sign.
TEST(Lower, Movarc) {
  EXPECT_THAT(instrs("GOTO/10,0,0\nMOVARC/0,0,0,0,0,1,10,ANGLE,90\nGOTO/0,10,5\n"),
              ElementsAre("feed (10, 0, 0)",
                          "arc ? to (6.123233995736766e-16, 10, 0) center (0, 0, 0) axis (0, 0, 1) r 10 hint ccw movarc",
                          "feed (0, 10, 5)"));
  EXPECT_THAT(instrs("GOTO/10,0,0\nMOVARC/0,0,0,0,0,1,10,ANGLE,-450\n"),
              ElementsAre("feed (10, 0, 0)",
                          "arc ? to (3.061616997868383e-15, -10, 0) center (0, 0, 0) axis (0, 0, 1) r 10 hint cw movarc turns+1"));
}

// The CIRCLE convention by the CAM system that wrote the file, not by the count of values.
TEST(Lower, CircleConventionByCamSystem) {
  const std::string arc = "GOTO/10,0,0\nCIRCLE/0,0,0,0,0,1,10\nGOTO/0,10,0\n";
  EXPECT_THAT(instrs(arc), ElementsAre("feed (10, 0, 0)", "arc ? to (0, 10, 0) center (0, 0, 0) axis (0, 0, 1) r 10 hint ccw creo7"));
  // NX says clockwise about its axis whatever the layout.
  EXPECT_THAT(instrs("TOOL PATH/A,TOOL,T\n" + arc + "END-OF-PATH\n"),
              ElementsAre("tool-change T1", "feed (10, 0, 0)",
                          "arc ? to (0, 10, 0) center (0, 0, 0) axis (0, 0, 1) r 10 hint cw creo7"));
  Lowered l = lower_text("$$*CATIA0\n" + arc);
  EXPECT_EQ(l.info.cam, ir::CamSystem::Catia);
  EXPECT_EQ(l.info.cam_evidence, "line 1: $$*CATIA0");
}

// A record name of several words (blanks where APT wants a comma, or blanks inside a word)
// whose words name a motion: refused where it stands, never a comment that loses the move.
TEST(Lower, ARecordNameOfSeveralWordsThatMovesIsRefused) {
  const std::string why = ": a record name of several words, and ";
  EXPECT_EQ(err("GOTO/0,0,5\nRAPID GOTO/10,0,50\n"),
            "2:1: 'RAPID GOTO'" + why + "RAPID moves the tool or changes how it cuts: APT separates the words before the major "
            "word with commas (TLON,GOFWD/...) and ignores blanks inside a word; write the record as records of their own");
  EXPECT_EQ(err("GOTO/0,0,5\nGO TO/10,0,5\n"),
            "2:1: 'GO TO'" + why + "GOTO moves the tool or changes how it cuts: APT separates the words before the major "
            "word with commas (TLON,GOFWD/...) and ignores blanks inside a word; write the record as GOTO");
  EXPECT_THAT(err("GOTO/0,0,5\nTLON GOFWD/(CIRCLE/0,0,5,10),ON,(LINE/0,0,5,-1,1,5)\n"), HasSubstr("2:1: 'TLON GOFWD'" + why + "GOFWD"));
  // Words that name nothing that cuts stay a comment, with a warning.
  Lowered l = lower_text("GOTO/0,0,5\nMY WORDS/1,2\n");
  EXPECT_EQ(first_error(l.diags), "");
}

// A '$' at the end of a line joins the next line to it (CATIA's PPRINT at column 72, Creo's
// five-axis GOTO). A joined line that is a record of its own is refused where it stands, not
// lost in the text or the words of the record before: after free text, after a record that
// ignores words it does not know (PAINT, MACHIN, INTOL, CUTTER, an unknown record), after a
// '$$->' data comment. The plunge was cut as a diagonal, the retract fed (certified).
TEST(Lower, ALineContinuedIntoARecordIsRefused) {
  const std::string joins = "a '$' at the end of the line before joins this ";
  const std::string lost = " record to that line, where it would be lost in its text or words: end that line without '$'";
  for (const char* head : {"PPRINT COST IN $\n", "REMARK NOTE $\n", "INSERT/G04 $\n", "TPRINT/T1 $\n", "PPRINT $\n",
                           "PPRINT/$\n", "PARTNO $\n", "PAINT/COLOR,$\n", "PAINT/SPEED,10 $\n", "MACHIN/UNCX01,1,$\n",
                           "INTOL/0.01,$\n", "CUTTER/10,$\n", "COOLNT/ON,$\n", "FOOBAR/$\n", "$$-> MFGNO / X $\n",
                           "$$-> FOO / 1,$\n"}) {
    EXPECT_EQ(err(std::string("GOTO/0,0,5\n") + head + "GOTO/10,0,5\nGOTO/10,10,5\n"), "3:1: " + joins + "GOTO" + lost)
        << head;
  }
  EXPECT_EQ(err("PPRINT/(=========$\n=====)\nGOTO/0,0,5\n"), "");  // text continued by text
  // A record's head continued by its major word is one record.
  EXPECT_EQ(err("GOTO/0,0,5\nTLON,$\nGOFWD/(CIRCLE/0,0,5,10),ON,(LINE/0,0,5,-1,1,5)\n"),
            err("GOTO/0,0,5\nTLON,GOFWD/(CIRCLE/0,0,5,10),ON,(LINE/0,0,5,-1,1,5)\n"));
  EXPECT_EQ(err("GOTO/0,0,5\nPPRINT ROUGH,$\nGOTO/0,0,50\n"), "3:1: " + joins + "GOTO" + lost);
  EXPECT_EQ(err("SPINDL/1000,$\nCLW\nFEDRAT/MMPM,$\n250\nGOTO/0,0,5\n"), "");  // words continued by words
  EXPECT_EQ(err("GOTO/0,0,5\nPAINT/COLOR,$\nFEDRAT/250\nGOTO/0,0,50\n"), "3:1: " + joins + "FEDRAT" + lost);
  // A record with a head, one with a statement label, one whose word a '$' splits, and a
  // record that is its word alone: the arc was cut as a chord, the retract fed, the M00 lost.
  EXPECT_EQ(err("GOTO/0,0,5\nPPRINT COST IN $\nTLON,GOFWD/(CIRCLE/0,0,5,10),ON,(LINE/0,0,5,-1,1,5)\n"),
            "3:1: " + joins + "GOFWD" + lost);
  EXPECT_EQ(err("GOTO/0,0,5\nPPRINT COST IN $\nL1) GOTO/1,2,3\n"), "3:5: " + joins + "GOTO" + lost);
  EXPECT_EQ(err("GOTO/0,0,5\nPPRINT LINE $\nGO$\nTO/1,2,3\n"), "3:1: " + joins + "GOTO" + lost);
  EXPECT_EQ(err("GOTO/0,0,5\nPPRINT BUDGET $\n  RAPID  \nGOTO/0,0,50\n"), "3:3: " + joins + "RAPID" + lost);
  EXPECT_THAT(err("GOTO/0,0,5\nPPRINT MEASURE $\nSTOP\n"), HasSubstr("3:1: " + joins + "STOP"));
  EXPECT_EQ(err("GOTO/0,0,5\nPPRINT ROUGH, FINISH $\nPASS, ROUGH/FINISH\nGOTO/0,0,50\n"), "");  // words, no record
  EXPECT_EQ(err("GOTO/0,0,5\nPPRINT FIRST $\nPASS\nGOTO/0,0,50\n"), "");
  // A word alone that names a record but ends a sentence: text (only RAPID, STOP, OPSTOP and
  // GOHOME, in capitals, stand alone as records that change the program).
  EXPECT_EQ(err("GOTO/0,0,5\nPPRINT FINISH PASS, CHECK $\nThread\nPPRINT SEE $\nEND\nGOTO/0,0,50\n"), "");
  // NX's two-word TOOL PATH and hyphenated END-OF-PATH: the next operation's tool change was
  // lost, and it was cut with the last tool (certified).
  EXPECT_EQ(err("GOTO/0,0,5\nPPRINT NEXT, FINISH WITH $\nTOOL  PATH/FINISH,TOOL,OD_35_L\nGOTO/0,0,50\n"),
            "3:1: " + joins + "TOOL PATH" + lost);
  EXPECT_THAT(err("GOTO/0,0,5\nPPRINT DONE $\nEND-OF-PATH\n"), HasSubstr("3:1: " + joins + "END-OF-PATH"));
  EXPECT_THAT(err("GOTO/0,0,5\nPPRINT DONE $\nEND-OF-PATH  $$ op end\n"), HasSubstr("3:1: " + joins + "END-OF-PATH"));
  EXPECT_EQ(err("GOTO/0,0,5\nPPRINT SEE THE $\nTOOL PATHS, AND END-OF-PATH MARKS\nGOTO/0,0,50\n"), "");
}

// A carriage return alone in a file of line feeds is a line end to some editors and DNC
// programs and a blank to others: a record after one is refused, not lost in the comment, text
// or record before it (a pasted file; the plunge after '$$ note' was cut diagonally,
// certified). Text after one that is no record stays text.
TEST(Lower, ARecordAfterALoneCarriageReturnIsRefused) {
  const std::string why = " record: a line end to some editors and transfer programs, a blank to others, so whether it is a "
                          "record of its own or part of the text before is not known: end the line with a line feed";
  for (const char* head : {"$$ comment\r", "PAINT/COLOR,31\r", "PPRINT hello\r", "COOLNT/ON\r", "GOTO/0,0,5\r"})
    EXPECT_EQ(err(std::string("GOTO/0,0,5\n") + head + "GOTO/10,20,-2\nGOTO/10,10,5\n"),
              std::string("2:") + std::to_string(std::strlen(head) + 1) +
                  ": a carriage return alone (no line feed after it) stands before this GOTO" + why)
        << head;
  EXPECT_EQ(err("GOTO/0,0,5\r\nPPRINT hello\rworld\r\nGOTO/0,0,50\r\n"), "");
  EXPECT_EQ(err("GOTO/0,0,5\nPPRINT hello\r\r\nGOTO/0,0,50\n"), "");
}

// FROM says where the tool stands and moves nothing. After motion, a FROM elsewhere is a
// jump the CL does not give: refused after a cut. At the start, after a tool change, a rapid or
// a GOHOME (APT's GOHOME, then FROM at a new home), it is read.
// Tool changes the post cannot make as the CL means them. The tool in the spindle reloaded with
// another length register in the middle of a cut: the post takes it up and brings it back, so
// the cut after came back diagonally from up there (certified). A tool change with CUTCOM on:
// the new tool cut with the last one's D register. Tool 0 with no register: H00, no offset.
TEST(Lower, ToolChangesThePostCannotMakeAsTheClMeansThemAreRefused) {
  EXPECT_EQ(err("LOADTL/1\nRAPID\nGOTO/0,0,5\nGOTO/0,0,-1\nLOADTL/1,OSETNO,5\nGOTO/20,0,-1\n"),
            "6:1: this cut starts after the reload of T1 with another length register at line 5, which takes the tool "
            "up from where the CL left it and back: cut from there it would run along a line the CL does not have; have the CAM "
            "system write the move to where the cut starts (a RAPID GOTO)");
  EXPECT_EQ(err("LOADTL/1\nRAPID\nGOTO/0,0,5\nGOTO/0,0,-1\nLOADTL/1,OSETNO,5\nRAPID\nGOTO/0,0,5\nGOTO/20,0,-1\n"), "");
  EXPECT_EQ(err("LOADTL/1\nRAPID\nGOTO/0,0,5\nGOTO/0,0,-1\nLOADTL/1\nGOTO/20,0,-1\n"), "");
  EXPECT_EQ(err("LOADTL/1\nCUTCOM/LEFT\nGOTO/0,0,-1\nLOADTL/2\nGOTO/20,0,-1\n"),
            "4:1: a tool change with cutter compensation on (CUTCOM at line 2): the control keeps it with the last "
            "tool's register, so the new tool would cut offset by the last one's radius; CUTCOM/OFF before the "
            "change, CUTCOM/LEFT or RIGHT after it");
  EXPECT_EQ(err("LOADTL/1\nCUTCOM/LEFT\nGOTO/0,0,-1\nCUTCOM/OFF\nLOADTL/2\nGOTO/20,0,-1\n"), "");
  EXPECT_EQ(err("LOADTL/0\nGOTO/20,0,-1\n"),
            "1:1: tool 0 with no length register: its offset would be 0 (H00, T0000), which is none, so every cut after "
            "it would be off by the tool's length; number the tool in the CAM system, or give the register "
            "(LOAD/TOOL,n,ADJUST,h; LOADTL/n,OSETNO,h)");
  EXPECT_EQ(err("LOAD/TOOL,0,ADJUST,1\nGOTO/20,0,-1\n"), "");  // NX's unnumbered tool: T0 with H01, a warning
  // The same tool loaded again (NX and CATIA load it at each operation) keeps its D: no error.
  EXPECT_EQ(err("LOADTL/1\nCUTCOM/LEFT\nGOTO/0,0,-1\nLOADTL/1\nGOTO/20,0,-1\n"), "");
  // A FROM after the reload does not make the retract's way back a CL move.
  EXPECT_THAT(err("LOADTL/1\nRAPID\nGOTO/0,0,5\nGOTO/0,0,-1\nLOADTL/1,OSETNO,5\nFROM/0,0,-1\nGOTO/20,0,-1\n"),
              HasSubstr("7:1: this cut starts after the reload of T1"));
  // Reloaded after a rapid down to the part: the cut next was fed back from up there (certified).
  EXPECT_THAT(err("LOADTL/1\nRAPID\nGOTO/0,0,5\nLOADTL/1,OSETNO,5\nGOTO/0,0,-1\n"),
              HasSubstr("5:1: this cut starts after the reload of T1"));
  EXPECT_EQ(err("FROM/0,0,100\nLOADTL/1\nRAPID\nGOTO/0,0,5\nGOHOME\nLOADTL/1,OSETNO,5\nGOTO/0,0,5\n"), "");
  // A tool change inside a cycle: the GOTOs after it were drilled by the new tool as holes, or
  // the cycle was dropped with the rapid after it. Which the CL means, it does not say.
  EXPECT_EQ(err("LOADTL/1\nSPINDL/1000\nRAPID\nGOTO/0,0,50\nCYCLE/DRILL,10,3,100,MMPM\nGOTO/10,10,0\nLOADTL/2\n"
                "SPINDL/1000\nRAPID\nGOTO/30,30,50\n"),
            "7:1: a tool change while a CYCLE is on (no CYCLE/OFF before it): whether the GOTOs after it are holes for "
            "the new tool or its moves is not known; end the cycle with CYCLE/OFF before the change, and give the "
            "CYCLE again after it for the new tool's holes");
}

TEST(Lower, FromAfterMotionElsewhereIsRefused) {
  EXPECT_EQ(err("GOTO/20,0,5\nFROM/0,0,100\nGOTO/0,0,5\n"),
            "2:1: FROM after motion puts the tool at (0, 0, 100), but the CL left it at (20, 0, 5): the move between is not "
            "in the CL; have the CAM system write it (a GOTO)");
  EXPECT_EQ(err("GOTO/20,0,5\nFROM/20,0,5\nGOTO/0,0,5\n"), "");
  EXPECT_EQ(err("LOADTL/1\nGOTO/20,0,5\nLOADTL/2\nFROM/0,0,100\nGOTO/0,0,5\n"), "");
  EXPECT_EQ(err("FROM/0,0,100\nGOTO/20,0,5\nGOHOME\nFROM/0,0,120\nGOTO/0,0,5\n"), "");
  // After a rapid, a FROM elsewhere: a rapid next positions; a cut next would start where the
  // rapid left the tool and run diagonally where the CL plunges (it was certified). A RAPID
  // before the FROM is used up by it: the move after is a feed (it was a rapid into the part).
  EXPECT_EQ(err("RAPID\nGOTO/10,0,10\nFROM/50,50,10\nRAPID\nGOTO/50,50,2\nGOTO/50,50,-1\n"), "");
  EXPECT_EQ(err("RAPID\nGOTO/10,0,10\nFROM/50,50,10\nGOTO/50,50,-1\n"),
            "4:1: this cut starts by the FROM at line 3, elsewhere than the rapid before it left the tool, at (10, 0, "
            "10): cut from there it would run along a line the CL does not have; have the CAM system write the move to "
            "where the cut starts (a RAPID GOTO)");
  EXPECT_THAT(instrs("RAPID\nFROM/0,0,50\nGOTO/0,0,-5\n"), ElementsAre("from (0, 0, 50)", "rapid (0, 0, 50)", "feed (0, 0, -5)"));
  EXPECT_EQ(err("RAPID/OFF\nGOTO/0,0,-5\n"),
            "1:7: RAPID takes no words: 'OFF' may ask for something else than the next move at rapid, which the CL "
            "cannot be read without; write RAPID alone before the move");
}

// Records without motion never stop a post: SELECT/HEAD,FRONT and SELECT/OFF (a head chosen on
// machines with several) and CUTTER/OFF (APT: the cutter's display ended) stopped it with
// "expected TOOL,n" and "expected the tool diameter".
TEST(Lower, DwellIsReadAsDelay) {
  EXPECT_EQ(instrs("LOADTL/1\nGOTO/0,0,5\nDWELL/2\n"), instrs("LOADTL/1\nGOTO/0,0,5\nDELAY/2\n"));
  EXPECT_EQ(err("LOADTL/1\nGOTO/0,0,5\nDWELL/-1\n"), "3:1: DWELL needs a time of zero or more");
}

TEST(Lower, SelectWithoutToolAndCutterOffDoNotStopThePost) {
  EXPECT_EQ(err("SELECT/HEAD,FRONT\nLOADTL/1\nCUTTER/10\nGOTO/0,0,5\nSELECT/OFF\nCUTTER/OFF\nGOTO/10,0,5\n"), "");
  // A gear range alone: the control chooses it from the speed.
  EXPECT_EQ(err("LOADTL/1\nSPINDL/1000\nSPINDL/RANGE,2\nSPINDL/HIGH\nGOTO/0,0,5\n"), "");
  // APT's cutter display and the end of the post's retracts: no motion either.
  EXPECT_EQ(err("LOADTL/1\nCUTTER/DISPLY,ON\nGOTO/0,0,5\nGOTO/0,0,-1\nRETRCT/OFF\nGOTO/10,0,-1\n"), "");
  EXPECT_THAT(err("LOADTL/1\nGOTO/0,0,5\nGOTO/0,0,-1\nRETRCT\nGOTO/10,0,-1\n"), HasSubstr("4:1: RETRCT asks for a retract"));
  EXPECT_THAT(instrs("LOADTL/1\nSELECT/TOOL,2\nGOTO/0,0,5\n"), ::testing::Contains(HasSubstr("preselect")));
  // A CUTTER whose first value is a word: not read, said at the word (it stopped the post with a
  // caret past the line's end; helper-51).
  EXPECT_EQ(err("CUTTER/DIAMTR,10,RADIUS,2\nLOADTL/1\nGOTO/0,0,5\n"), "");
  EXPECT_THAT(warn("CUTTER/DIAMTR,10,RADIUS,2\n"),
              ::testing::StrEq("1:8: CUTTER: expected the tool diameter first, found 'DIAMTR': the tool's geometry is "
                               "not read\n"));
}

// The file's unit is its UNITS record's, wherever it stands. A UNITS/INCHES after moves fed in
// MMPM read those moves in inches (10 mm written as 10 in, certified with a warning).
TEST(Lower, AUnitsAfterMotionInTheOtherUnitIsRefused) {
  EXPECT_EQ(err("LOADTL/1\nRAPID\nGOTO/10,10,10\nFEDRAT/MMPM,100\nGOTO/10,10,0\nUNITS/INCHES\nFEDRAT/IPM,10\nGOTO/1,1,0\n"),
            "6:7: UNITS says inch after motion whose feed (line 4) is in mm: the moves before it would be read in the "
            "wrong unit; put the UNITS record first, or give --input-units");
  EXPECT_EQ(err("LOADTL/1\nRAPID\nGOTO/10,10,10\nFEDRAT/MMPM,100\nGOTO/10,10,0\nUNITS/MM\nGOTO/1,1,0\n"), "");
  EXPECT_EQ(err("UNITS/INCHES\nLOADTL/1\nRAPID\nGOTO/1,1,1\nFEDRAT/IPM,10\nGOTO/1,1,0\n"), "");
  // A cycle's own feed names the unit as well; a UNITS repeated after the first is no change.
  EXPECT_THAT(err("LOADTL/1\nRAPID\nGOTO/10,10,10\nCYCLE/DRILL,DEPTH,5,CLEAR,2,MMPM,100\nGOTO/10,10,0\nCYCLE/OFF\n"
                  "UNITS/INCHES\nGOTO/1,1,0\n"),
              HasSubstr("7:7: UNITS says inch after motion whose feed (line 4) is in mm"));
  EXPECT_EQ(err("UNITS/INCHES\nLOADTL/1\nRAPID\nGOTO/1,1,1\nFEDRAT/MMPM,250\nGOTO/1,1,0\nUNITS/INCHES\nGOTO/2,1,0\n"), "");
}

// FEDRAT/0 stopped the post even where only rapids followed it; under it a cut would have
// taken the feed before (a guess). Now the cut is refused, once, naming the FEDRAT.
TEST(Lower, AZeroFeedIsRefusedAtTheCutNotBeforeRapids) {
  EXPECT_EQ(err("LOADTL/1\nFEDRAT/0\nRAPID\nGOTO/0,0,50\nRAPID\nGOTO/10,0,50\nFEDRAT/100\nGOTO/10,0,0\n"), "");
  EXPECT_EQ(err("LOADTL/1\nFEDRAT/100\nGOTO/0,0,50\nFEDRAT/0,MMPM\nRAPID\nGOTO/10,0,50\nGOTO/10,0,0\n"),
            "7:1: this cut is fed at zero: the FEDRAT/0 at line 4 is in force (a feed of zero never moves the tool; it "
            "may stand before rapid moves only); give the cut its FEDRAT");
  EXPECT_THAT(err("LOADTL/1\nFEDRAT/0\nRAPID\nGOTO/5,0,50\nCIRCLE/0,0,50,0,0,1,5\nGOTO/0,5,50\n"),
              HasSubstr("5:1: this cut is fed at zero: the FEDRAT/0 at line 2"));
  // A cycle with its own feed drills at it; one without would take the feed before.
  EXPECT_EQ(err("LOADTL/1\nFEDRAT/0\nRAPID\nGOTO/0,0,19\nCYCLE/DRILL,FEDTO,10,RAPTO,3,MMPM,100\nGOTO/0,0,0\nCYCLE/OFF\n"), "");
  EXPECT_THAT(err("LOADTL/1\nFEDRAT/0\nRAPID\nGOTO/0,0,19\nCYCLE/DRILL,FEDTO,10,RAPTO,3\nGOTO/0,0,0\nCYCLE/OFF\n"),
              HasSubstr("6:1: this cut is fed at zero"));
  EXPECT_EQ(err("LOADTL/1\nFEDRAT/-1\n"), "2:1: FEDRAT: the feed must be greater than zero, found -1");
}

// A cycle with no feed of its own under FEDRAT/INVERS took the inverse-time F as its feed
// (G93 in force into G81 F2, certified).
TEST(Lower, ACycleWithoutAFeedUnderInverseTimeIsRefused) {
  EXPECT_EQ(err("LOADTL/1\nFEDRAT/INVERS,2\nGOTO/0,0,19\nCYCLE/DRILL,FEDTO,10,RAPTO,3\nGOTO/0,0,0\nCYCLE/OFF\n"),
            "4:1: CYCLE/DRILL with no feed of its own under an inverse-time feed (FEDRAT/INVERS): one move's time is no "
            "drilling feed; give the cycle its feed (MMPM, IPM, MMPR, IPR)");
  EXPECT_EQ(err("LOADTL/1\nFEDRAT/INVERS,2\nGOTO/0,0,19\nCYCLE/DRILL,FEDTO,10,RAPTO,3,MMPM,100\nGOTO/0,0,0\nCYCLE/OFF\n"), "");
}

// Probe findings: FIXTURE/2 selects a work offset (as a comment, the cuts landed in G54); an
// oriented stop clpc cannot write is refused (the moves after it rely on it); a corner radius
// beyond the tool's radius is said.
TEST(Lower, FixtureOrientAndACornerRadiusBeyondTheRadius) {
  EXPECT_THAT(err("FIXTURE/2\nGOTO/0,0,0\n"), ::testing::StartsWith("1:1: 'FIXTURE' moves the tool and clpc does not read it: it "
                                                                    "selects a work offset (a fixture)"));
  // OFSTNO/24 before CUTCOM/LEFT was a comment and the cut G41 D4 (helper-51): another
  // register than the tool's own is refused; the tool's own asks for nothing.
  EXPECT_EQ(err("LOADTL/3\nOFSTNO/24\nCUTCOM/LEFT\nGOTO/0,0,0\n"),
            "2:8: OFSTNO/24: an offset register for the tool's length or its radius by the post, which clpc does not "
            "read: it cuts T3 with length register 3 and radius register 3; if it is either, give the radius register "
            "on the CUTCOM (CUTCOM/LEFT,24) and the length register on the tool change (LOADTL/3,OSETNO,24)");
  EXPECT_EQ(err("OFSTNO/4\nLOADTL/4\n"),
            "1:8: OFSTNO/4 before any tool is loaded: an offset register for the tool's length or its radius by the "
            "post, which clpc does not read; if it is either, give the radius register on the CUTCOM (CUTCOM/LEFT,4) "
            "and the length register on the tool change (LOADTL/n,OSETNO,4)");
  EXPECT_EQ(err("LOADTL/4\nOFSTNO/4\nCUTCOM/LEFT\nGOTO/0,0,0\n"), "");
  // X given as a diameter (helper-54): passed through or ignored, every X was doubled.
  EXPECT_EQ(err("LATHE/DIAMETER\n"), "1:7: LATHE with DIAMETER says X is a diameter: clpc reads a lathe's X as the "
                                      "radius (the CL standard; the machine writes the diameter), so every X would be "
                                      "doubled; have the CAM system output X as the radius");
  EXPECT_THAT(err("MODE/TURN,DIAMETER\n"), ::testing::StartsWith("1:11: MODE with DIAMETER says X is a diameter"));
  EXPECT_THAT(err("MACHIN/TURN,1,XDIAM\n"), ::testing::StartsWith("1:15: MACHIN with XDIAM says X is a diameter"));
  EXPECT_THAT(err("DIAMTR/ON\n"), ::testing::StartsWith("1:1: DIAMTR says X is a diameter"));
  EXPECT_EQ(err("DIAMTR/OFF\nMODE/TURN\nLATHE/RADIUS\nCUTTER/DIAMTR,10\nLATHE/DIAMETER,OFF\nMODE/TURN,DIAMETER,OFF\n"), "");
  // The advice names only what the file does not say already, and never register 0 (helper-55).
  EXPECT_THAT(err("LOADTL/4,OSETNO,14\nOFSTNO/14\n"), HasSubstr("2:8: OFSTNO/14: an offset register for the tool's "
                                                                  "length or its radius by the post, which clpc does not "
                                                                  "read: it cuts T4 with length register 14 and radius "
                                                                  "register 4; if it is the radius, give the radius "
                                                                  "register on the CUTCOM (CUTCOM/LEFT,14)"));
  EXPECT_THAT(err("LOADTL/4\nOFSTNO/0\n"), HasSubstr("radius register 4; register 0 is no offset at all: remove the OFSTNO"));
  EXPECT_THAT(err("LOADTL/4\nOFSTNO/OFF\n"), HasSubstr("2:8: OFSTNO/OFF: cancels an offset register for the tool's length "
                                                         "or its radius by the post, which clpc does not read; clpc applies "
                                                         "the tool's length offset from LOADTL and its radius offset from "
                                                         "CUTCOM (CUTCOM/OFF cancels it)"));
  EXPECT_THAT(err("SPINDL/RPM,1000,CLW\nSPINDL/ORIENT\nGOTO/0,0,0\n"),
              ::testing::StartsWith("2:8: SPINDL/ORIENT (an oriented spindle stop): clpc's machines have no code for it, and "
                                    "the moves after it would be made with the spindle turning"));
  Lowered radius = lower_text("CUTTER/10,30\nLOADTL/1\nRAPID\nGOTO/0,0,0\n");
  ASSERT_EQ(radius.diags.size(), 1u);
  EXPECT_EQ(radius.diags[0].loc, (SourceLoc{1, 11}));
  EXPECT_EQ(radius.diags[0].message, "CUTTER: a corner radius of 30 is more than the tool's radius (5): are the numbers in the order CUTTER/d,r?");
  // A tool change between a CIRCLE and its end point: refused at the change (verify refused
  // the program with no word on why).
  EXPECT_EQ(err("LOADTL/1\nRAPID\nGOTO/10,0,0\nCIRCLE/0,0,0,0,0,1,10\nLOADTL/2\nGOTO/-10,0,0\n"),
            "5:1: a tool change between a CIRCLE (line 4) and the GOTO that ends it: the arc cannot be cut across it");
  // A CATIA contour with no INDIRV after a ramp: the plane tilted with the ramp, the arc rose
  // out of the circle's plane (certified). Refused; after a move in the plane it is read.
  const std::string ramp = "RAPID\nGOTO/10,-10,-1\nGOTO/10,0,0\n";
  const std::string contour = "TLON,GOFWD/(CIRCLE/0,0,0,10),ON,(LINE/0,0,0,-10,0,0)\n";
  EXPECT_EQ(err(ramp + contour), "4:1: TLON,GOFWD with no INDIRV: the plane the tool turns in is taken from the motion before "
                                 "it, which is not in the XY plane (a ramp, a plunge?); give INDIRV before the contour");
  EXPECT_THAT(err("RAPID\nGOTO/10,0,10\nGOTO/10,0,0\n" + contour), ::testing::HasSubstr("which is not in the XY plane"));
  EXPECT_EQ(err("RAPID\nGOTO/10,-10,0\nGOTO/10,0,0\n" + contour), "");
}
