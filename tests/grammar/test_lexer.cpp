// Front end: the lexical rules and record forms of docs/cl-input.md, and every error path
// with its message, line and column.
#include "grammar/lexer.h"
#include "helpers.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::ElementsAre;

namespace {

std::vector<std::string> recs(const std::string& text) {
  Parsed p = parse_text(text);
  EXPECT_EQ(first_error(p.diags), "") << text;
  return p.records;
}

struct Ids : RecordSink {
  std::vector<MajorId> ids;
  void record(const Record& r) override { ids.push_back(r.id); }
};

}  // namespace

TEST(Lexer, MajorWithParameters) { EXPECT_THAT(recs("GOTO/1,2,3\n"), ElementsAre("1:1 GOTO/1,2,3")); }

TEST(Lexer, BareMajorsWithAndWithoutSlash) {
  EXPECT_THAT(recs("RAPID\nRAPID/\nFINI \nEND-OF-PATH\n"),
              ElementsAre("1:1 RAPID", "2:1 RAPID/", "3:1 FINI", "4:1 END-OF-PATH"));
}

TEST(Lexer, SpacesAnywhere) {
  EXPECT_THAT(recs("  GOTO / 1.0 ,2.0,  3 \n\tFEDRAT /  250.0,   MMPM\n"),
              ElementsAre("1:3 GOTO/1,2,3", "2:2 FEDRAT/250,MMPM"));
}

TEST(Lexer, NumberForms) {
  EXPECT_THAT(recs("GOTO/12,12.,.5\nGOTO/-1.5E-3,+3,-55.\nGOTO/1e-400,-.25,0.0000\n"),
              ElementsAre("1:1 GOTO/12,12,0.5", "2:1 GOTO/-0.0015,3,-55", "3:1 GOTO/0,-0.25,0"));
  // Fortran's double-precision exponent, in its strict form (a point, a signed exponent); a
  // name like 6D10 or 1.5D2 stays a name.
  EXPECT_THAT(recs("GOTO/0.1000000000000000D+02,-.25D-00,5.d+01\nTOOL PATH/A,TOOL,6D10,1.5D2,1D+2\n"),
              ElementsAre("1:1 GOTO/10,-0.25,50", "2:1 TOOL PATH/A,TOOL,6D10,1.5D2,1D+2"));
}

TEST(Lexer, ParameterLocations) {
  Parsed p = parse_text("GOTO / 1, $\n   2.5, x\n");
  ASSERT_EQ(p.records.size(), 1u);
  // The word lands on line 2, column 9.
  Ids ids;
  SourceFile src;
  std::string text = "GOTO / 1, $\n   2.5, x\n";
  src.open_memory("t", text);
  Diagnostics d(nullptr);
  struct Locs : RecordSink {
    std::vector<SourceLoc> locs;
    void record(const Record& r) override {
      for (auto& p : r.params) locs.push_back(p.loc);
    }
  } l;
  parse_cl(src, d, l);
  ASSERT_EQ(l.locs.size(), 3u);
  EXPECT_EQ(l.locs[0], (SourceLoc{1, 8}));
  EXPECT_EQ(l.locs[1], (SourceLoc{2, 4}));
  EXPECT_EQ(l.locs[2], (SourceLoc{2, 9}));
}

TEST(Lexer, DollarContinuation) {
  EXPECT_THAT(recs("CIRCLE / 0., 0., -1.5,  $\n0., 0., -1.,  1.5\nGOTO/1,$   \n 2,$\n3\n"),
              ElementsAre("1:1 CIRCLE/0,0,-1.5,0,0,-1,1.5", "3:1 GOTO/1,2,3"));
}

TEST(Lexer, ContinuationFollowedByComment) {
  EXPECT_THAT(recs("GOTO/1,2, $ $$ the rest follows\n3\n"), ElementsAre("1:1 GOTO/1,2,3"));
}

TEST(Lexer, CommentsWholeLineAndTrailing) {
  EXPECT_THAT(recs("$$ centerline data\nLOADTL / 4,  OSETNO,  4 $$-> THREAD TOOL\n$$\n"),
              ElementsAre("1:1 $$ centerline data", "2:1 LOADTL/4,OSETNO,4", "2:25 $$-> THREAD TOOL", "3:1 $$"));
}

TEST(Lexer, CreoDataComments) {
  EXPECT_THAT(recs("$$-> FEATNO / 32\n$$-> CSYS / 1., 0., $\n   2., 3.\n$$-> END / \n$$-> SETSTART\n"),
              ElementsAre("1:6 $$-> FEATNO/32", "2:6 $$-> CSYS/1,0,2,3", "4:6 $$-> END/", "5:6 $$-> SETSTART"));
}

TEST(Lexer, DataCommentThatIsNotARecordIsAComment) {
  EXPECT_THAT(recs("$$-> 3D contour\n$$*  Pro/CLfile  Version 8.0\n"),
              ElementsAre("1:1 $$-> 3D contour", "2:1 $$*  Pro/CLfile  Version 8.0"));
}

TEST(Lexer, NxToolPathAndEndOfPath) {
  EXPECT_THAT(recs("TOOL PATH/ZLEVEL_FOLLOW_CORE,TOOL,MILL-20MM\nEND-OF-PATH\n"),
              ElementsAre("1:1 TOOL PATH/ZLEVEL_FOLLOW_CORE,TOOL,MILL-20MM", "2:1 END-OF-PATH"));
}

TEST(Lexer, WordsMayHoldSpacesBetweenCommas) {
  EXPECT_THAT(recs("TOOL PATH/CAVITY MILL,TOOL,EM 10\n"), ElementsAre("1:1 TOOL PATH/CAVITY MILL,TOOL,EM 10"));
}

TEST(Lexer, FreeTextAfterPartnoPprintInsertRemark) {
  EXPECT_THAT(recs("PARTNO MFG0004\nPARTNO / HOUSING 2\nPPRINT/APTCL-SPEC,MAKINO-FF,1\nINSERT/G65 P9000 (X)\nREMARK any $ text\n"),
              ElementsAre("1:1 PARTNO [MFG0004]", "2:1 PARTNO [HOUSING 2]", "3:1 PPRINT [APTCL-SPEC,MAKINO-FF,1]",
                          "4:1 INSERT [G65 P9000 (X)]", "5:1 REMARK [any $ text]"));
}

TEST(Lexer, MinorWordsStartingWithDigits) {
  EXPECT_THAT(recs("CYCLE/DEEP2,FEDTO,1.5,1STPECK,0.2,2NDPECK,0.1\n"),
              ElementsAre("1:1 CYCLE/DEEP2,FEDTO,1.5,1STPECK,0.2,2NDPECK,0.1"));
}

TEST(Lexer, QuotedStrings) { EXPECT_THAT(recs("TOOL PATH/'OP 1',TOOL,\"T,2\"\n"), ElementsAre("1:1 TOOL PATH/'OP 1',TOOL,'T,2'")); }

TEST(Lexer, CrLfLineEnds) {
  EXPECT_THAT(recs("GOTO/1,2,3\r\n$$ note\r\nRAPID\r\n\r\nGOTO/1,$\r\n2,3\r\n"),
              ElementsAre("1:1 GOTO/1,2,3", "2:1 $$ note", "3:1 RAPID", "5:1 GOTO/1,2,3"));
}

TEST(Lexer, BlankLinesAndNoFinalNewline) {
  EXPECT_THAT(recs("\n\n   \nGOTO/1,2,3\n\nFINI"), ElementsAre("4:1 GOTO/1,2,3", "6:1 FINI"));
}

TEST(Lexer, MajorWordsAreCaseInsensitive) {
  Ids ids;
  SourceFile src;
  std::string text = "goto/1,2,3\nLoadTl/1\ntool path/a\n";
  src.open_memory("t", text);
  Diagnostics d(nullptr);
  parse_cl(src, d, ids);
  EXPECT_THAT(ids.ids, ElementsAre(MajorId::Goto, MajorId::Loadtl, MajorId::ToolPath));
}

// Every major word in majors.def lexes to its own id (the lexer's keyword rules and the
// list must not drift apart).
TEST(Lexer, KeywordRulesMatchMajorsDef) {
  std::vector<std::pair<MajorId, std::string>> all = {
#define X(id, spelling) {MajorId::id, spelling},
#include "grammar/majors.def"
#undef X
  };
  for (auto& [id, spelling] : all) {
    Ids ids;
    SourceFile src;
    std::string text = spelling + "/1\n";
    src.open_memory("t", text);
    Diagnostics d(nullptr);
    parse_cl(src, d, ids);
    ASSERT_EQ(ids.ids.size(), 1u) << spelling;
    EXPECT_EQ(ids.ids[0], id) << spelling;
  }
}

TEST(Lexer, UnknownMajorKeepsItsText) { EXPECT_THAT(recs("FOO BAR/1,X\n"), ElementsAre("1:1 FOO BAR/1,X")); }

TEST(Lexer, LongLinesAreFine) {
  std::string line = "GOTO/1";
  for (int i = 0; i < 500; ++i) line += ",1";
  Parsed p = parse_text(line + "\n");
  EXPECT_EQ(first_error(p.diags), "");
  EXPECT_EQ(p.records.size(), 1u);
}

// --- errors --------------------------------------------------------------------------------

// Names are names: a parameter that is not a number as a whole is a word; lowering says where
// a number was due (tests/lower/test_lower.cpp). The parse itself goes on.
TEST(Lexer, WhatIsNoNumberIsAWord) {
  EXPECT_THAT(recs("GOTO/1,2,3\nGOTO/1.2.3,4,5\nGOTO/--1,2E,3\nGOTO/1,2;3\nGOTO/1,$2,3\n"),
              ElementsAre("1:1 GOTO/1,2,3", "2:1 GOTO/1.2.3,4,5", "3:1 GOTO/--1,2E,3", "4:1 GOTO/1,2;3", "5:1 GOTO/1,$2,3"));
}

TEST(Lexer, NamesStartingWithDigitsOrHoldingAnyPrintableCharacter) {
  EXPECT_THAT(recs("TOOL PATH/6_KONTUR_125,TOOL,FACE_MILL\nTOOL PATH/1001,TOOL,12.5\nTPRINT/T1 End Mill D 0.393701\n"
                   "TOOL PATH/OP(1)/A #2,TOOL,D10 R0.5\n"),
              ElementsAre("1:1 TOOL PATH/6_KONTUR_125,TOOL,FACE_MILL", "2:1 TOOL PATH/1001,TOOL,12.5",
                          "3:1 TPRINT [T1 End Mill D 0.393701]", "4:1 TOOL PATH/OP(1)/A #2,TOOL,D10 R0.5"));
  // A number written as a name keeps its digits.
  SourceFile src;
  std::string text = "TOOL PATH/0010,TOOL,12.50\n";
  src.open_memory("t", text);
  Diagnostics d(nullptr);
  struct Texts : RecordSink {
    std::vector<std::string> t;
    void record(const Record& r) override {
      for (const Param& p : r.params) t.emplace_back(p.name());
    }
  } names;
  parse_cl(src, d, names);
  EXPECT_THAT(names.t, ElementsAre("0010", "TOOL", "12.50"));
}

TEST(Lexer, EmptyParametersAndTrailingCommas) {
  EXPECT_THAT(recs("TOOLNO/2,MILL,,90.,,1\nGOTO/1,2,3,\nGOTO/1.0,2.0,\nRAPID/\n"),
              ElementsAre("1:1 TOOLNO/2,MILL,,90,,1", "2:1 GOTO/1,2,3", "3:1 GOTO/1,2", "4:1 RAPID/"));
}

TEST(Lexer, NumbersApartByBlanks) {
  EXPECT_THAT(recs("GOTO/1.0 2.0   3.5\nLOADTL/4 5\nSPINDL/ 1200 RPM\n"),
              ElementsAre("1:1 GOTO/1,2,3.5", "2:1 LOADTL/4,5", "3:1 SPINDL/1200 RPM"));
}

TEST(Lexer, ParameterGroupsAndWordsBeforeTheMajor) {
  EXPECT_THAT(recs("TLON,GOFWD/ (CIRCLE/ 25., 0., -30., 4.6), ON, 2, INTOF, (LINE/ 1,2,3, 4,5,6)\n"
                   "STOP/(INSTALL TEST STRIP LARGE END UP)\n"),
              ElementsAre("1:1 TLON,GOFWD/(CIRCLE/25,0,-30,4.6),ON,2,INTOF,(LINE/1,2,3,4,5,6)",
                          "2:1 STOP/(INSTALL TEST STRIP LARGE END UP)"));
  Parsed p = parse_text("TLON,GOFWD/(CIRCLE/1,2\nRAPID\n");
  EXPECT_EQ(first_error(p.diags), "1:23: record ends too early: expected ')' or ','");
  EXPECT_THAT(p.records, ElementsAre("2:1 RAPID"));
}

// CATIA cuts records at column 72 wherever it is: inside a number, a word or free text.
TEST(Lexer, ContinuationJoinsWhatItCuts) {
  EXPECT_THAT(recs("FROM  / -26.370000,   0.000000,  46.745000,  -1.000000,   0.000000,   0$\r\n.000000\r\n"
                   "FEDRAT/ 1000.0000,MMP$\nM\nPPRINT/(USING 3 ALMEN STRIPS  $\n       )\nGOTO/7\n"),
              ElementsAre("1:1 FROM/-26.37,0,46.745,-1,0,0", "3:1 FEDRAT/1000,MMPM",
                          "5:1 PPRINT [(USING 3 ALMEN STRIPS         )]", "7:1 GOTO/7"));
  // A parameter after the cut is located on its own line.
  Parsed p = parse_text("GOTO/1,2,3,0.0,0$\n.0,1.0, x\n");
  EXPECT_EQ(first_error(p.diags), "");
}

TEST(Lexer, TextThatIsNoRecordIsSkippedWithAWarning) {
  Parsed p = parse_text("Date 18-Dec-2021 21:07:42\nGOTO/1,2,3\nsome words: here\n");
  EXPECT_EQ(first_error(p.diags), "");
  ASSERT_EQ(p.diags.size(), 2u);
  EXPECT_EQ(p.diags[0].loc, (SourceLoc{1, 1}));
  EXPECT_EQ(p.diags[0].message,
            "not a CL record (a word that is no major word, then neither '/' nor the line end): the line is ignored");
  EXPECT_EQ(p.diags[1].loc, (SourceLoc{3, 1}));
  EXPECT_THAT(p.records, ElementsAre("2:1 GOTO/1,2,3"));
  // A known major word written wrong stays an error.
  EXPECT_EQ(first_error(parse_text("GOTO 1,2,3\n").diags), "1:6: expected '/' or the end of the record, found '1'");
  // A line skipped so must hold no move: 'label: GOTO/...' lost its plunge (exit 0, certified).
  EXPECT_EQ(first_error(parse_text("GOTO/1,2,3\nlabel: GOTO/20,0,-1\n").diags),
            "2:1: not a CL record, yet the line holds GOTO/ further on: skipped, its motion would be lost (an APT "
            "statement label is written 'NAME)' before the record)");
  // So must it hold no record that stands alone: the rapid after 'Date 12-Jan RAPID' was fed,
  // the return home lost. A sentence with the word inside, or in lower case, is text.
  const std::pair<const char*, const char*> hidden[] = {
      {"Date 12-Jan RAPID", "RAPID"}, {"sfsdf, RAPID", "RAPID"}, {"Date 12-Jan GOHOME  $$ home", "GOHOME"}, {"note: STOP", "STOP"}};
  for (const auto& [line, word] : hidden)
    EXPECT_EQ(first_error(parse_text(std::string("GOTO/1,2,3\n") + line + "\nGOTO/1,2,5\n").diags),
              std::string("2:1: not a CL record, yet the line holds ") + word +
                  " further on: skipped, its motion would be lost (an APT statement label is written 'NAME)' before "
                  "the record)")
        << line;
  EXPECT_EQ(first_error(parse_text("GOTO/1,2,3\nCheck RAPID overrides\nWait for stop\nGOTO/1,2,5\n").diags), "");
}

// APT statement labels: up to six letters and digits and ')' before the record (APT-360's
// 'L1) GOTO/...'); the record is read as if the label were not there.
TEST(Lexer, AptStatementLabelsAreReadPast) {
  Parsed p = parse_text("L1) GOTO/20,0,-1\nLAB1)GOTO/40,0,-1\n  P2) FEDRAT/100,MMPM\n");
  EXPECT_EQ(first_error(p.diags), "");
  EXPECT_TRUE(p.diags.empty());
  EXPECT_THAT(p.records, ElementsAre("1:5 GOTO/20,0,-1", "2:6 GOTO/40,0,-1", "3:7 FEDRAT/100,MMPM"));
  // A note that only looks like one ('A) cutter 10mm': no record after it) stays a line of text.
  Parsed note = parse_text("A) cutter 10mm\nGOTO/1,2,3\n");
  EXPECT_EQ(first_error(note.diags), "");
  EXPECT_THAT(note.records, ElementsAre("2:1 GOTO/1,2,3"));
}

// NX's information window: the header and the last line are no records (nx-course/).
TEST(Lexer, NxListingLinesAreSkippedSilently) {
  Parsed p = parse_text(
      "\nInformation listing created by\tphill\nDate\t18-Dec-2021 21:07:42\n"
      "Current work part\tC:\\Users\\phill\\part.prt\nNode name\tlaptop-1\n\nGOTO/1,2,3\nTool Path Listing has 81 lines.");
  EXPECT_TRUE(p.diags.empty());
  EXPECT_THAT(p.records, ElementsAre("7:1 GOTO/1,2,3"));
}

TEST(LexerErrors, UnterminatedContinuation) {
  Parsed p = parse_text("GOTO/1,2,$");
  EXPECT_EQ(first_error(p.diags), "1:10: unterminated continuation: '$' at the end of the file");
  Parsed q = parse_text("GOTO/1,2,  $   \n");
  EXPECT_EQ(first_error(q.diags), "1:12: unterminated continuation: '$' at the end of the file");
}

TEST(LexerErrors, NumberOutOfRange) {
  EXPECT_EQ(first_error(parse_text("GOTO/1e999,2,3\n").diags), "1:6: number out of range: '1e999'");
}

TEST(LexerErrors, NoMajorWord) {
  EXPECT_EQ(first_error(parse_text("1.0, 2.0\n").diags),
            "1:1: expected a major word at the start of a record, found '1'");
}

TEST(LexerErrors, NulByte) {
  std::string text = std::string("GOTO/1,2,3") + '\0' + "\n";
  EXPECT_EQ(first_error(parse_text(text).diags), "1:11: unexpected NUL byte in a record");
}

TEST(LexerErrors, ErrorInsideDataCommentIsAWarning) {
  Parsed p = parse_text("$$-> CSYS / 1, 'x\nRAPID\n");
  EXPECT_EQ(first_error(p.diags), "");
  ASSERT_EQ(count(p.diags, Severity::Warning), 1u);
  EXPECT_EQ(p.diags[0].message, "malformed '$$->' data comment ignored: unterminated string");
  EXPECT_THAT(p.records, ElementsAre("2:1 RAPID"));
}

TEST(LexerErrors, ContinuationCarriesRecoveryToTheRecordEnd) {
  // The bad number is on the first line; the continuation line must not parse as a record.
  Parsed p = parse_text("GOTO/1e999,$\n4,5\nRAPID\n");
  EXPECT_EQ(count(p.diags, Severity::Error), 1u);
  EXPECT_THAT(p.records, ElementsAre("3:1 RAPID"));
}

TEST(LexerErrors, TooManyErrorsStops) {
  std::string text;
  for (int i = 0; i < 200; ++i) text += "GOTO/1e999\n";
  Parsed p = parse_text(text);
  EXPECT_EQ(count(p.diags, Severity::Error), Diagnostics::kErrorLimit);
}

// A window refill in the middle of tokens: a file much larger than the 1 MiB read window.
TEST(Lexer, RecordsAcrossReadWindowRefills) {
  std::string text;
  int n = 0;
  while (text.size() < 3u * 1024 * 1024) {
    text += "GOTO / " + std::to_string(n) + ".125, -2.5, $\n   3.75\n";
    ++n;
  }
  Parsed p = parse_text(text);
  EXPECT_EQ(first_error(p.diags), "");
  ASSERT_EQ(p.records.size(), size_t(n));
  EXPECT_EQ(p.records.back(), std::to_string(2 * n - 1) + ":1 GOTO/" + std::to_string(n - 1) + ".125,-2.5,3.75");
}

// The lexer reads simple records (GOTO/numbers...) without the parser: every record of every
// corpus file, and of lines made to sit on the fast path's edges, is the same either way —
// major, parameters with their columns, start and end.
namespace {

struct Dump : RecordSink {
  std::string out;
  void record(const Record& r) override {
    out += std::to_string(r.loc.line) + ":" + std::to_string(r.loc.col) + "-" + std::to_string(r.end.line) + ":" +
           std::to_string(r.end.col) + " " + std::to_string(int(r.kind)) + " " + std::string(r.major) +
           (r.has_slash ? "/" : " ") + std::string(r.text) + (r.data_comment ? " data" : "");
    for (const Param& p : r.params) {
      char b[64];
      std::snprintf(b, sizeof b, " [%d %.17g %u:%u ", int(p.kind), p.number, p.loc.line, p.loc.col);
      // Numbers' text is kept only on the grammar's path (simple records skip it).
      out += b + std::string(p.is_number() ? std::string_view() : p.text) + "]";
    }
    out += "\n";
  }
};

std::string dump(const std::string& name, const std::string& text, bool simple, std::string& diags) {
  SourceFile src;
  src.open_memory(name, text);
  std::ostringstream err;
  Diagnostics d(&err);
  d.set_source(&src);
  Dump sink;
  try {
    ParseOptions o;
    o.simple_records = simple;
    parse_cl(src, d, sink, o);
  } catch (const FatalError&) {
  }
  diags = err.str();
  return sink.out;
}

}  // namespace

TEST(Lexer, SimpleRecordsEqualTheGrammarsOnTheCorpus) {
  if (corpus_dir().empty()) GTEST_SKIP() << "no corpus";
  size_t records = 0;
  for (const std::string& f : corpus_files()) {
    std::string text = read_file(f), d1, d2;
    std::string fast = dump(f, text, true, d1), slow = dump(f, text, false, d2);
    EXPECT_EQ(fast, slow) << f;
    EXPECT_EQ(d1, d2) << f;
    records += size_t(std::count(fast.begin(), fast.end(), '\n'));
  }
  EXPECT_GT(records, 10000u);
}

TEST(Lexer, SimpleRecordsEqualTheGrammarsOnTheEdges) {
  const std::string text =
      "GOTO/1,2,3\nGOTO/1 , 2 ,3  \r\nGOTO/+1.,-.5,1e3\nGOTO/1,2,3 $$ comment\nGOTO/1,2,$\n3\nGOTO/1,,2\nGOTO/1,2,\n"
      "GOTO/\nGOTO/1.2.3\nGOTO/1e\nGOTO/1,2X\nGOTO/1e999\nGOTO/1e-999\ngoto/1,2,3\nCIRCLE/1,2,3,0,0,1,5,0.01,0.5,10,0\n"
      "FROM/0,0,50\nGODLTA/0,0,-5\nGOTO/1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17\nGOTO/1\t,2\n  GOTO/1,2,3\n"
      // Creo: blanks before the slash, records continued over lines.
      "GOTO / 1.5, -2.25, 3.0\nGOTO / 0.5, 0.25, 0.75,  $\n0.0, -0.6, 0.8\nCIRCLE / 1, 2, 3,  $\n0, 0, 1,  5\n"
      "GOTO  /1,2,3\nGOTO\t/ 1,2,3\nGOTOX/1\nGOTO 1,2,3\nGOTO / 1, $\n2, $\n3\nGOTO / 1, 2, $\n1e999\n"
      "GOTO / 1, 2$\n, 3\nGOTO / $\n1,2,3\nFROM / 0.0, 0.0, 50.0,  $\n0.0, 0.0, 1.0\nGOTO/1.5D+01,2.D-1,6D10\n"
      "GOTO/1.0D+999\nGOTO/1,2,3";
  std::string d1, d2;
  std::string fast = dump("edges.cls", text, true, d1), slow = dump("edges.cls", text, false, d2);
  EXPECT_EQ(fast, slow);
  EXPECT_EQ(d1, d2);
  EXPECT_THAT(d1, ::testing::HasSubstr("edges.cls:13:6: error: number out of range: '1e999'"));  // the grammar reports, as before
}

// APT's card-image form: every line 80 columns, 73-80 an identification or sequence field.
// Read as text, the field made FROM four values and GOTO/10,20 a point at Z110, and refused
// every file with messages that never named it (helper-43). Columns 73-80 are not read, as APT
// reads its cards, with one note; the records and their columns are the free form's. A file
// whose lines are 80 columns for another reason (the field is no sequence) is free form.
TEST(Lexer, CardImageFilesIgnoreColumns73To80) {
  const std::vector<std::string> lines = {"UNITS/MM", "FROM/0,0,50", "GOTO/10,20,$", "    5", "CUTTER/10.0", "FINI"};
  std::string card;
  for (size_t i = 0; i < lines.size(); ++i) {
    std::string l = lines[i];
    l.resize(72, ' ');
    card += l + (i == 2 ? "APT00030" : "000000" + std::to_string((i + 1) * 10)) + "\n";
  }
  Parsed p = parse_text(card);
  EXPECT_EQ(first_error(p.diags), "");
  ASSERT_FALSE(p.diags.empty());
  EXPECT_EQ(p.diags[0].loc, (SourceLoc{1, 73}));
  EXPECT_EQ(p.diags[0].message,
            "a card-image file (every line 80 columns, 73-80 a sequence field): columns 73-80 are not read, as APT reads its cards");
  EXPECT_THAT(p.records, ElementsAre("1:1 UNITS/MM", "2:1 FROM/0,0,50", "3:1 GOTO/10,20,5", "5:1 CUTTER/10", "6:1 FINI"));
  // 80 columns that end in no sequence field: free form, read whole (here an error, as before).
  std::string wide = "GOTO/1.00000000,2.00000000,3.00000000,0.00000000,0.00000000,1.000000000000000000\n";
  ASSERT_EQ(wide.size(), 81u);
  EXPECT_EQ(first_error(parse_text(wide + wide).diags), "");
  EXPECT_FALSE(grammar::Lexer::looks_like_card_image(wide + wide));
  EXPECT_FALSE(grammar::Lexer::looks_like_card_image(card.substr(0, 81)));  // one card is no deck
  // Fixed columns after a blank, but numbers that do not grow from line to line: free form.
  std::string same = "GOTO / 10.0, 20.0, 30.0";
  same.resize(72, ' ');
  same += "12345678\n";
  EXPECT_FALSE(grammar::Lexer::looks_like_card_image(same + same + same));
}
