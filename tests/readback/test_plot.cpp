// clpc plot: the SVG parses (Python's XML parser, tests/tools/svg_check.py) with its four
// views, arcs drawn as arcs and tool changes marked; headless Chromium renders it to a PNG in
// which the path's colours are drawn (tests/tools/png_colours.py).
#include "helpers.h"

using namespace clpc;
using namespace clpc::test;
using ::testing::HasSubstr;

TEST(Plot, SvgHasFourViewsArcsAndToolChanges) {
  TempDir t;
  const std::string svg = t.path("nx_mill.svg");
  RunResult r = run_clpc("plot " + std::string(CLPC_SOURCE_DIR) + "/tests/golden/nx_mill.cls -t fanuc-mill -o " + svg);
  ASSERT_EQ(r.status, 0) << r.err;
  RunResult c = run_shell("python3 " + source_path("tests/tools/svg_check.py") + " " + svg);
  ASSERT_EQ(c.status, 0) << c.err;
  // nx_mill: two tools; two slot-end arcs and a full circle (drawn as two halves) in the XY
  // plane, so four SVG arcs where the view sees that plane (top, isometric) and none edge-on.
  EXPECT_EQ(c.out,
            "size 1200 900\n"
            "views top,isometric,front,side\n"
            "top feed rapid arcs 4 tools T1 T4\n"
            "isometric feed rapid arcs 4 tools T1 T4\n"
            "front feed rapid arcs 0 tools T1 T4\n"
            "side feed rapid arcs 0 tools T1 T4\n");
}

TEST(Plot, CorpusFiveAxisAndLathe) {
  if (corpus_dir().empty()) GTEST_SKIP() << "no corpus";
  TempDir t;
  RunResult r = run_clpc("plot " + corpus_dir() + "/nist/multi_axis1.ncl.2 -t haas-umc750 -o " + t.path("ma.svg"));
  ASSERT_EQ(r.status, 0) << r.err;
  RunResult c = run_shell("python3 " + source_path("tests/tools/svg_check.py") + " " + t.path("ma.svg"));
  ASSERT_EQ(c.status, 0) << c.err;
  EXPECT_THAT(c.out, HasSubstr("top feed rapid arcs 0 tools T3\n"));
  RunResult l = run_clpc("plot " + corpus_dir() + "/nist/b_turn_groove2.ncl.1 -t fanuc-lathe -o " + t.path("lathe.svg"));
  ASSERT_EQ(l.status, 0) << l.err;
  RunResult lc = run_shell("python3 " + source_path("tests/tools/svg_check.py") + " " + t.path("lathe.svg"));
  ASSERT_EQ(lc.status, 0) << lc.err;
  EXPECT_THAT(lc.out, HasSubstr("views XZ\nXZ feed rapid arcs 2 tools T3\n"));  // the two corner radii
}

TEST(Plot, ErrorsLeaveNoFile) {
  TempDir t;
  write_file(t.path("empty.cls"), "UNITS/MM\nFINI\n");
  RunResult r = run_clpc("plot " + t.path("empty.cls") + " -t fanuc-mill -o " + t.path("empty.svg"));
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.err, HasSubstr("error: nothing to post"));
  EXPECT_FALSE(std::filesystem::exists(t.path("empty.svg")));
}

// Headless Chromium (Debian's chromium, installed by scripts/setup.sh --tests) draws the plot:
// the feed blue, the rapid orange and the tool-change green are all on the page.
TEST(Plot, ChromiumRendersItToPng) {
  RunResult which = run_shell("command -v chromium");
  ASSERT_EQ(which.status, 0) << "chromium is not installed: run scripts/setup.sh --tests";
  TempDir t;
  const std::string svg = t.path("plot.svg"), png = t.path("plot.png");
  RunResult r = run_clpc("plot " + std::string(CLPC_SOURCE_DIR) + "/tests/golden/nx_mill.cls -t fanuc-mill -o " + svg);
  ASSERT_EQ(r.status, 0) << r.err;
  RunResult c = run_shell("cd " + t.path("") + " && HOME=" + t.path("") +
                      " timeout 120 chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size=1200,900 "
                      "--screenshot=" + png + " file://" + svg);
  ASSERT_EQ(c.status, 0) << c.err;
  ASSERT_TRUE(std::filesystem::exists(png)) << c.err;
  RunResult p = run_shell("python3 " + source_path("tests/tools/png_colours.py") + " " + png + " 1565c0 e65100 2e7d32");
  ASSERT_EQ(p.status, 0) << p.err;
  std::istringstream in(p.out);
  std::string size, name;
  long feed = 0, rapid = 0, tools = 0;
  in >> size >> name >> feed >> name >> rapid >> name >> tools;
  EXPECT_EQ(size, "1200x900");
  EXPECT_GT(feed, 500);   // about 1200 pixels of toolpath
  EXPECT_GT(rapid, 20);   // thin dashes
  EXPECT_GT(tools, 200);  // markers and labels
}
