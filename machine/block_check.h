// Whether a line of text is a block a G-code control reads (INSERT records): what may reach
// the program raw, and what must become a comment (docs/cl-input.md, "INSERT"); and what such
// a block may do to the axes (the backends and the passes that keep a position both ask).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace clpc {

// True for a block of address words (a letter and a number, a #variable or a [bracketed
// expression]), comments in parentheses, an optional block delete '/' and N number, and the
// Fanuc macro statements (#n = ..., IF, WHILE, END, GOTO). Otherwise false, with `why` the
// first thing that is none of these.
bool is_control_block(std::string_view text, std::string& why);

// A block as a control reads its words: capitals, without comments and without the blanks
// between an address and its number ("g 28 z 0." is "G28 Z0.").
std::string control_words(std::string_view block);

// Why a machine's fixed block (program start or finish, a park, a retract, a tool change) may
// take the tool to a position in the part's coordinates, which clpc cannot know is clear of the
// part; "" when it cannot. What may stand: a move in machine coordinates (G53; Siemens' G153
// and SUPA; Heidenhain's M91, M92), a dwell, and G28/G30 whose intermediate point is where the
// tool is (G91 with every axis 0; U, V, W 0, incremental on a lathe and a Mazak). "G28 Z0." in
// G90 rapids down to the part's Z0 before going home (helper-67). `incremental` is G91 in
// force, carried from block to block; axes in `free_axes` may go anywhere but
// through a G28's intermediate point (a park from home, a lathe's tool change position).
std::string part_position_in(std::string_view block, bool lathe, bool& incremental, std::string_view free_axes = "");

// The axis letters (X Y Z A B C U V W) that stand as address words in a control block, outside
// comments, in the order met ("" for none). A dwell (G04 X1.5) has none: its X is a time.
std::string axis_words(std::string_view block);

// The system variable holding offsets or positions that a macro statement in the block sets
// ("#5221" for `#5221=100.`, "#[...]" for one set through an expression, whose number cannot
// be told), or "": tool offsets (#2000-#2999, #10000 up), modal state, positions and work
// offsets (#4000-#5999, #7000-#7999). #1-#999 are the program's; #1000-#1999, #3000-#3999
// (signals, alarms, message stops, counters, timers) and #6000-#6999 move nothing.
std::string system_variable_set(std::string_view block);

// The numbers of the address words with `letter` (G or M) in a control block, outside comments,
// in the order met (G68.2 -> 68.2).
std::vector<double> code_numbers(std::string_view block, char letter);

// Whether a control block may move the machine's axes: any axis word (B-10., B#101), a return
// to a reference point (G27-G30: Haas's bare G28 homes every axis), a move in machine
// coordinates (G53), a macro call (G65, G66, G66.1), which may do anything, or an M code other
// than the stops, spindle, coolant, orient, rigid tap and override codes (M60 changes pallets).
bool may_move_axes(std::string_view block);

// Whether the block itself moves the axes: an axis word, a return to a reference point
// (G27-G30), a move in machine coordinates (G53) or a macro call (G65, G66, G66.1). (An M code
// that may move them, which may_move_axes also fears, moves nothing the CL's next move does
// not undo: the post writes that move whole.)
bool moves_axes_by_itself(std::string_view block);

// Whether the block takes Z alone up to its home and nothing else (G53 Z0., G91 G28 Z0., G30
// Z0.): no other axis word, no macro call, no M code that may move axes. X and Y then stand
// where they stood, and the tool above the part. (G00 Z-5. or G53 Z-100. moves Z alone, to
// where the CL does not know.)
bool returns_z_home(std::string_view block);

}  // namespace clpc
