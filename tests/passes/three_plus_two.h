// A 3+2 CL file shared by the five-axis machine tests (test_tilted_plane.cpp,
// test_machine_layouts.cpp).
#pragma once

namespace clpc::test {

// Two operations, one tool axis each: 30 degrees towards +X, then 45 degrees towards +Y.
inline const char* const kThreePlusTwo =
    "TOOL PATH/SIDE_A,TOOL,T1\nUNITS/MM\nLOADTL/1\nSPINDL/RPM,3000,CLW\nRAPID\nGOTO/10,0,50,0.5,0,0.8660254\n"
    "FEDRAT/MMPM,500\nGOTO/10,10,45,0.5,0,0.8660254\nGOTO/20,10,40,0.5,0,0.8660254\nRAPID\n"
    "GOTO/20,10,80,0.5,0,0.8660254\nEND-OF-PATH\nTOOL PATH/SIDE_B,TOOL,T1\nRAPID\nGOTO/0,30,80,0,0.7071068,0.7071068\n"
    "FEDRAT/MMPM,400\nGOTO/0,40,50,0,0.7071068,0.7071068\nGOTO/10,40,50,0,0.7071068,0.7071068\nRAPID\n"
    "GOTO/10,40,90,0,0.7071068,0.7071068\nEND-OF-PATH\n";

}  // namespace clpc::test
