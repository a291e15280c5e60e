// Machine descriptions: a user's machine in TOML alone; every validation error of the
// loader with file, line and key; --machines overriding; explain; every built-in machine on
// the corpus files it applies to.
#include "helpers.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;

namespace {

std::string load_error(const std::string& toml, const std::string& name = "m") { return machine_errors(toml, name); }

std::string first_line(const std::string& s) { return s.substr(0, s.find('\n')); }

const char* kMinimal = "[m]\nfamily = \"mill\"\n";

}  // namespace

TEST(Machines, UserMachineFromTomlAloneGivesExactlyTheExpectedProgram) {
  std::string dir = std::string(CLPC_SOURCE_DIR) + "/tests/machines/";
  RunResult r = run_clpc("compile " + dir + "shop_part.cls -t " + dir + "shop_mill.toml -o -");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, read_file(dir + "shop_part.shop-mill.nc"));
  // The same machine through --machines and its name.
  RunResult named = run_clpc("compile " + dir + "shop_part.cls -t shop-mill --machines " + dir + "shop_mill.toml -o -");
  EXPECT_EQ(named.out, r.out);
}

TEST(Machines, MinimalMachineGetsSaneDefaults) {
  std::ostringstream err;
  Diagnostics d(&err);
  MachineRegistry reg(pass_contracts());
  ASSERT_TRUE(reg.load_text("shop.toml", kMinimal, d));
  auto m = reg.resolve("m", d);
  ASSERT_TRUE(m) << err.str();
  EXPECT_EQ(m->units, ir::Units::Mm);
  EXPECT_EQ(m->codes.tool_change.text, "T{tool} M06");
  EXPECT_EQ(m->pipeline, (std::vector<std::string>{"arc-direction", "helix", "arc-legalise", "drill-cycles", "rapid-split", "offset-table"}));
}

TEST(MachineErrors, WrongType) {
  EXPECT_EQ(first_line(load_error("[m]\nfamily = \"mill\"\n[m.format]\nX = { decimals = \"4\" }\n")),
            "shop.toml:4:18: error: m.format.X.decimals: expected an integer from 0 to 9, found a string");
}

TEST(MachineErrors, ValueOutOfRange) {
  EXPECT_EQ(first_line(load_error("[m]\nfamily = \"mill\"\n[m.format]\nX = { decimals = -1 }\n")),
            "shop.toml:4:18: error: m.format.X.decimals: expected an integer from 0 to 9, found -1");
  EXPECT_EQ(first_line(load_error("[m]\nfamily = \"mill\"\n[m.arcs]\ntolerance = 0\n")),
            "shop.toml:4:13: error: m.arcs.tolerance: expected a number at least 1e-06 and at most 1000, found 0");
}

TEST(MachineErrors, UnknownKey) {
  EXPECT_EQ(first_line(load_error("[m]\nfamily = \"mill\"\nunits = \"mm\"\ncolour = \"red\"\n")),
            "shop.toml:4:1: error: unknown key 'colour' in m");
  EXPECT_EQ(first_line(load_error("[m]\nfamily = \"mill\"\n[m.format]\nX = { decimal = 4 }\n")),
            "shop.toml:4:7: error: unknown key 'decimal' in m.format.X; did you mean 'decimals'?");
}

TEST(MachineErrors, BadFormatSpec) {
  EXPECT_EQ(first_line(load_error("[m]\nfamily = \"mill\"\n[m.format]\nX = { point = \"sometimes\" }\n")),
            "shop.toml:4:15: error: m.format.X.point: expected one of \"always\", \"never\", \"if-fraction\", found \"sometimes\"");
  EXPECT_EQ(first_line(load_error("[m]\nfamily = \"mill\"\n[m.format]\nXX = { decimals = 3 }\n")),
            "shop.toml:4:1: error: m.format.XX: expected an address letter A-Z");
  EXPECT_EQ(first_line(load_error("[m]\nfamily = \"mill\"\n[m.format]\nX = { scale = 0 }\n")),
            "shop.toml:4:15: error: m.format.X.scale: expected a number from 0.001 to 1000 (or -1000 to -0.001), found 0");
}

TEST(MachineErrors, UnknownPassName) {
  EXPECT_EQ(first_line(load_error("[m]\nfamily = \"mill\"\npipeline = [\"arc-direction\", \"make-it-good\"]\n")),
            "shop.toml:3:30: error: m.pipeline: unknown pass 'make-it-good' (passes: arc-direction, helix, arc-legalise, "
            "drill-cycles, rapid-split, thread-cycles, rough-cycles, groove-cycles, offset-table, kinematics, limits)");
}

// The only error: with no family there is no default pipeline to judge (a second error said
// the pipeline was missing).
TEST(MachineErrors, MissingRequiredKey) {
  EXPECT_EQ(load_error("[m]\nunits = \"mm\"\n"),
            "shop.toml:1:1: error: m: missing required key 'family' (\"mill\" or \"lathe\")\n 1 | [m]\n   | ^\n");
}

TEST(MachineErrors, BadCodeTemplates) {
  EXPECT_EQ(first_line(load_error("[m]\nfamily = \"mill\"\n[m.codes]\ntool_change = \"T{toll} M06\"\n")),
            "shop.toml:4:15: error: m.codes.tool_change: bad code template: unknown placeholder {toll}");
  EXPECT_EQ(first_line(load_error("[m]\nfamily = \"mill\"\n[m.codes]\nspindle_cw = \"M03 S{tool}\"\n")),
            "shop.toml:4:14: error: m.codes.spindle_cw: placeholder {tool} cannot be used here (this code takes none)");
}

TEST(MachineErrors, InheritanceCycleAndUnknownParent) {
  EXPECT_EQ(first_line(load_error("[a]\ninherits = \"b\"\nfamily = \"mill\"\n[b]\ninherits = \"a\"\nfamily = \"mill\"\n", "a")),
            "shop.toml:5:12: error: b.inherits: inheritance cycle: a -> b -> a");
  EXPECT_EQ(first_line(load_error("[a]\ninherits = \"nobody\"\nfamily = \"mill\"\n", "a")),
            "shop.toml:2:12: error: a.inherits: no machine named 'nobody'");
  EXPECT_EQ(first_line(load_error("[a]\ninherits = \"fanuc-mil\"\n", "a")),
            "shop.toml:2:12: error: a.inherits: no machine named 'fanuc-mil'; did you mean 'fanuc-mill'?");
}

// A shop's [fanuc-mill] replaces the built-in whole (its M29 rigid tap, F format and max_feed
// gone): a note says so and how to keep them; inheriting from the name it replaces is a cycle
// that says what to do.
TEST(MachineErrors, ReplacingAMachineByItsNameIsSaid) {
  const std::string replaced = load_error("[fanuc-mill]\nfamily = \"mill\"\nmax_rpm = 8000.0\n", "fanuc-mill");
  EXPECT_EQ(first_line(replaced),
            "shop.toml:1:2: note: machine 'fanuc-mill' replaces the built-in one whole, keeping none of its keys; to change "
            "only some, give it a name of its own with inherits = \"fanuc-mill\"");
  EXPECT_THAT(load_error("[fanuc-mill]\ninherits = \"fanuc-mill\"\n", "fanuc-mill"),
              HasSubstr("shop.toml:2:12: error: fanuc-mill.inherits: inheritance cycle: fanuc-mill -> fanuc-mill (a machine "
                        "that replaces 'fanuc-mill' cannot inherit from it: give yours a name of its own)"));
}

TEST(MachineErrors, AbsurdValues) {
  EXPECT_EQ(first_line(load_error("[m]\nfamily = \"mill\"\n[m.sequence]\nstart = 100\nmax = 10\n")),
            "shop.toml:5:7: error: m.sequence.max: must not be less than start (100)");
  EXPECT_EQ(first_line(load_error("[m]\nfamily = \"mill\"\n[m.arcs]\nmin_radius = 5.0\nmax_radius = 1.0\n")),
            "shop.toml:5:14: error: m.arcs.max_radius: must not be less than min_radius (5)");
}

TEST(MachineErrors, TomlSyntax) {
  EXPECT_THAT(first_line(load_error("[m]\nfamily = \"mill\n")), HasSubstr("shop.toml:2:"));
  EXPECT_THAT(first_line(load_error("[m]\nfamily = \"mill\n")), HasSubstr("error: invalid TOML: "));
}

TEST(MachineErrors, TheSourceLineIsShown) {
  std::string e = load_error("[m]\nfamily = \"mill\"\n[m.format]\nX = { decimals = \"4\" }\n");
  EXPECT_THAT(e, HasSubstr("\n 4 | X = { decimals = \"4\" }\n   |                  ^\n"));
}

TEST(Machines, MachinesFileOverridesByName) {
  TempDir t;
  write_file(t.path("over.toml"), "[fanuc-mill]\ninherits = \"haas-umc750\"\ndescription = \"my fanuc\"\n");
  RunResult r = run_clpc("machines --machines " + t.path("over.toml"));
  EXPECT_THAT(r.out, HasSubstr("fanuc-mill\tmy fanuc\n"));
}

TEST(Machines, ExplainPrintsTheResolvedDescription) {
  RunResult r = run_clpc("explain fanuc-lathe");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("[fanuc-lathe]\ndescription = \"Fanuc 0i-TF lathe"));
  EXPECT_THAT(r.out, HasSubstr("X = { decimals = 3, point = \"always\", leading_zero = true, trailing_zeros = false, digits = 0, scale = 2, plus = false }"));
  EXPECT_THAT(r.out, HasSubstr("tool_change = \"T{tool:2}{offset:2}\""));
  // What explain prints loads back as the same machine.
  TempDir t;
  write_file(t.path("again.toml"), r.out);
  RunResult again = run_clpc("explain " + t.path("again.toml"));
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_EQ(again.out.substr(again.out.find('[')), r.out.substr(r.out.find('[')));
  // The UMC's C winds on without end: explain printed min = -360, max = 360, a range it has
  // not (a copy of it refused a 390-degree finish the built-in machine posts).
  RunResult umc = run_clpc("explain haas-umc750");
  ASSERT_EQ(umc.status, 0) << umc.err;
  EXPECT_THAT(umc.out, HasSubstr("name = \"C\"\naxis = [0, 0, 1]\nside = \"table\"\ndirection = -1\ncyclic = \"wind\"\n"
                                 "center = [0, 0, 0]\n"));
  EXPECT_THAT(umc.out, HasSubstr("cyclic = \"no\"\nmin = -35\nmax = 120\n"));
}


// The family defaults are the abstract bases `mill` and `lathe` of machines.toml: inherited by
// every machine without a parent, never posted for, never listed.
TEST(Machines, AbstractBasesGiveTheFamilyDefaults) {
  RunResult r = run_clpc("compile - -t lathe -o -", "UNITS/MM\nLOADTL/1\nGOTO/1,0,1\nFINI\n");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "clpc: error: machine 'lathe' is an abstract base (the defaults of its family): post for a machine that "
                   "inherits from it, or write one with inherits = \"lathe\" (docs/machines.md)\n");
  RunResult list = run_clpc("machines");
  EXPECT_EQ(list.out.find("mill\tgeneric"), std::string::npos) << list.out;
  const Machine lathe = machine("my-lathe", "[my-lathe]\nfamily = \"lathe\"\nunits = \"inch\"\n");
  EXPECT_EQ(lathe.codes.tool_change.text, "T{tool:2}{offset:2}");
  EXPECT_EQ(lathe.format('X').scale, 2);
  EXPECT_EQ(lathe.format('X').decimals, 4);  // inch: the loader's, not the base's
  EXPECT_FALSE(lathe.arcs.xy);
  EXPECT_EQ(lathe.pipeline.back(), "groove-cycles");
}
