// Every file of ../shared/corpus, the machine it is posted on, and what must come of it: a
// program that `clpc verify` passes (and, on the three-axis Fanuc mill, that LinuxCNC's rs274
// reads), or the located error of a file that truly cannot be cut. Shared by the corpus sweep
// (test_corpus.cpp) and the rs274 test (test_rs274.cpp). A new corpus file without a line here
// fails the sweep.
#pragma once

#include <string>
#include <vector>

namespace clpc::test {

struct CorpusCase {
  const char* file;     // under the corpus folder
  const char* machine;  // a built-in machine, or one of tests/machines/*.toml
  const char* error;    // "" to be posted; else the located error (":line:col: error: ...")
  const char* why;      // for a refusal, or a machine that is not a built-in
  const char* input_units = "";  // "mm" or "inch": the file's UNITS record is wrong
  bool machine_error = false;    // the error is the backend's (what a machine needs), not the front end's
};

inline const std::vector<CorpusCase>& corpus_cases() {
  static const std::vector<CorpusCase> cases = {
      // CATIA V5 APT
      {"catia/karlo_DEMO1.aptsource", "fanuc-lathe", "", "turning, constant surface speed"},
      {"catia/karlo_DEMO2.aptsource", "fanuc-mill", ":32:1: error: CYCLE/TAP: no thread pitch (TPI, PITCH, a feed per revolution, or a feed per minute with the spindle's rpm before the cycle)",
       "a tap with no pitch, no feed and 0.398 rpm: nothing says how far it advances per turn"},
      {"catia/karlo_DEMO3.aptsource", "fanuc-lathe", "", "turning, centre drilling, grooving; ROTABL to 0"},
      {"catia/karlo_DEMO4.aptsource", "fanuc-mill", "", "peck drilling written as moves"},
      {"catia/karlo_DEMO5.aptsource", "fanuc-lathe", "", "profile turning with TLON,GOFWD circles"},
      {"catia/karlo_dwelltest.aptsource", "fanuc-mill", "", ""},
      {"catia/peening.aptsource", "haas-umc750", "", "five-axis"},
      {"catia/spif_hole_flanging_tool_r10.aptsource", "fanuc-mill", "", "400 TLON,GOFWD circles"},
      {"catia/spif_machining_hole_d58.aptsource", "fanuc-mill", "", ""},
      {"catia/vtx550_CVZ1234567.aptsource", "haas-umc750", ":34:8: error: SPINDL: unknown word '900CCLW'",
       "text typed into the file by hand (MANIFEST.md): the spindle records cannot be read"},
      // Creo NCL
      {"creopost/bohren_1.ncl.8", "fanuc-mill", "", ""},
      {"creopost/profilfraesen_2.ncl.1", "fanuc-mill", "", ""},
      {"creopost/schruppen_1.ncl.1", "fanuc-mill", "", ""},
      {"nist/b270_alldrill.ncl", "haas-umc750", "", "3+2 drilling"},
      {"nist/b45_face.ncl", "haas-umc750", "", "3+2 facing"},
      {"nist/b_turn_1.ncl.1", "fanuc-lathe", "", ""},
      {"nist/b_turn_groove2.ncl.1", "fanuc-lathe", "", ""},
      {"nist/b_turn_innr.ncl.4", "fanuc-lathe", "", ""},
      {"nist/basic_turning_cycle.ncl", "fanuc-lathe",
       ":4:1: error: cutting with no tool loaded: the CL loads none before this move (LOADTL, LOAD/TOOL, TURRET), so the "
       "program would select no turret station and no offset (no T word)",
       "a fragment of turning passes with no tool: posted, it cut with the station and offset the last program left", "",
       true},
      {"nist/casting_drill_tap.ncl.1", "haas-umc750", "", "3+2 drilling and tapping"},
      {"nist/dwnhole.ncl.3", "a-rotary-5x", "", "ten flutes at ten A positions (ROTATE/AAXIS): a continuous A about X"},
      {"nist/helical.ncl.1", "haas-umc750", "", "UNITS/INCHES, but its numbers are millimetres (a 10-inch cutter at 5 rpm)",
       "mm"},
      {"nist/holemaking_cycle.ncl", "fanuc-mill",
       ":4:1: error: cutting with no tool loaded: the CL loads none before this move (LOADTL, LOAD/TOOL, TURRET), so no "
       "tool length offset is in force",
       "a ten-line fragment: two feeds down with no tool and no spindle; posted, the gauge line would go to the hole", "",
       true},
      {"nist/look.ncl.1", "haas-umc750", "", "the milling of a mill-turn part, about X and Z"},
      {"nist/multi_axis1.ncl.2", "haas-umc750", "", "five-axis"},
      {"nist/thread_mill.ncl", "fanuc-mill", "", ""},
      {"nist/turn_op10.ncl.4", "fanuc-lathe", "", ""},
      // NX CLSF from NX's information window
      {"nx-course/APT_Project2.cls", "haas-umc750", "", "five-axis and 3+2"},
      {"nx-course/APT_SimpleMillPlane.cls", "fanuc-mill", "", ""},
      {"nx-course/APT_SimpleMillPlane_ZIG.cls", "fanuc-mill", "", ""},
      {"nx-course/APT_Variable_Axis.cls", "haas-umc750", "", "five-axis"},
      {"nx-course/APT_Zig_Zag_Smoothed.cls", "fanuc-mill", "", ""},
      {"nx-course/APT_Zig_Zag_Smoothed_Toolpath.cls", "fanuc-mill", "", ""},
      {"nx-course/APT_code.cls", "haas-umc750", "", "five-axis"},
      // NX CLSF, Makino FFCAM
      {"stepnode/Plane_1.cldata", "fanuc-mill", "", ""},
      {"stepnode/Plane_2.cldata", "fanuc-mill", "", ""},
      {"stepnode/coremill.cls", "fanuc-mill", "", ""},
      {"stepnode/simple_block.cls", "fanuc-mill", "", ""},
  };
  return cases;
}

}  // namespace clpc::test
