#include "readback/gcode_interp.h"
#include "support/text.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>

#include "machine/format.h"
#include "machine/kinematics.h"
#include "machine/tilted_plane.h"
#include "support/decimal.h"
#include "ir/groove_model.h"
#include "ir/stock_model.h"
#include "ir/thread_model.h"

namespace clpc::gcode {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = 3.14159265358979323846;

struct Word {
  char letter;
  double value;     // converted: units (or degrees), radius for X on a diameter lathe
  double raw;       // as written, number of the word
  bool has_point;
};

enum class Motion { Rapid, Linear, Cw, Ccw, Thread, ThreadBox, None };

// The address words of one block, by letter (the last one of a letter counts). A fixed table
// rather than a map: the reader runs over every block of gigabyte programs.
struct Words {
  std::array<double, 26> value{};
  std::array<double, 26> raw{};  // as written (G76's P(m)(r)(a) is digits, not a length)
  std::array<bool, 26> has{};
  std::array<bool, 26> point{};
  void clear() {
    has.fill(false);
    point.fill(false);
  }
  void set(char c, double v, double r, bool p) {
    value[size_t(c - 'A')] = v;
    raw[size_t(c - 'A')] = r;
    has[size_t(c - 'A')] = true;
    point[size_t(c - 'A')] = p;
  }
  size_t count(char c) const { return has[size_t(c - 'A')] ? 1 : 0; }
  double operator[](char c) const { return value[size_t(c - 'A')]; }
  bool with_point(char c) const { return point[size_t(c - 'A')]; }
};

class Interp {
 public:
  Interp(const Machine& m, const Options& opt) : m_(m), opt_(opt) {
    res_.units = m.units;
    pos_ = Vec3(kNaN, m.is_lathe() ? 0.0 : kNaN, kNaN);  // a lathe has no Y
    // Where the rotaries stand when the program starts is as unknown as X, Y and Z: only a
    // word of the program says.
    for (const RotaryAxis& r : m.kinematics.rotaries)
      if (r.name.size() == 1 && r.name[0] >= 'A' && r.name[0] <= 'C') rotary_[size_t(r.name[0] - 'A')] = kNaN;
    // One increment of the coarser of the end point and centre words (on a diameter lathe X
    // is finer in radius terms than I and K).
    double inc = std::max({std::abs(dequantize(1, m.format('X'))), std::abs(dequantize(1, m.format('I'))),
                           std::abs(dequantize(1, m.format('K')))});
    radius_tol_ = opt.arc_radius_tolerance > 0 ? opt.arc_radius_tolerance : inc;
    if (m.is_lathe()) alias_lathe_codes();
  }

  Result run(std::string_view text) {
    size_t at = 0;
    while (at <= text.size()) {
      size_t nl = text.find('\n', at);
      feed(text.substr(at, nl == std::string_view::npos ? std::string_view::npos : nl - at));
      if (nl == std::string_view::npos) break;
      at = nl + 1;
    }
    return std::move(res_);
  }

  void feed(std::string_view l) {
    ++line_;
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    // After M30 / M02 the main program is over; what follows (subprograms such as the
    // offset macro) runs only when called.
    if (!res_.ended && !(stock_.collecting && collect_profile(l, line_))) block(l, line_);
  }

  Result& result() { return res_; }

 private:
  void problem(int line, std::string msg) { res_.problems.push_back({line, std::move(msg)}); }

  // Converts a word's number as the control would: a value without a decimal point on an
  // address whose format never writes one is in least-input increments, and so is a position
  // or an angle (X50 is 0.050 mm on a Fanuc or a Haas, whatever the machine's format says: a
  // hand edit that lost the point was read as 50 mm and certified; helper-62).
  double convert(char letter, double v, bool has_point) {
    const AddressFormat& f = m_.format(letter);
    const bool position = std::string_view("XYZUVWIJKRABC").find(letter) != std::string_view::npos;
    if (!has_point && (f.point == AddressFormat::Point::Never || position) && f.decimals > 0)
      v /= std::pow(10.0, f.decimals);
    return v;
  }

  bool parse(std::string_view l, int line, std::vector<Word>& words) {
    // A macro variable set by a block of its own (#100=1, an INSERT for a probing macro): it
    // moves nothing. A word that uses a variable is still no number the reader knows.
    if (!l.empty() && l.front() == '#' && l.find('=') != std::string_view::npos) [[unlikely]]
      return true;
    size_t i = 0;
    // '/' before a block: the operator's Block Delete switch may skip it. A stop written so
    // (an optional stop's other form, a routine shop edit) is read as run; anything else would
    // give two programs, one of them not checked (helper-70: "/M01" refused as a character).
    // It may follow the sequence number (N85 /M01) and name a switch (/2 M01).
    bool skippable = false;
    const size_t first_word = words.size();
    while (i < l.size()) {
      char c = l[i];
      if (c == ' ' || c == '\t' || c == '\r') { ++i; continue; }
      if (c == '/' && !skippable &&
          std::all_of(words.begin() + std::ptrdiff_t(first_word), words.end(), [](const Word& w) { return w.letter == 'N'; })) {
        skippable = true;
        ++i;
        while (i < l.size() && std::isdigit(static_cast<unsigned char>(l[i]))) ++i;
        continue;
      }
      if (c == '(') {
        size_t close = l.find(')', i);
        if (close == std::string_view::npos) {
          problem(line, "comment without ')'");
          return false;
        }
        i = close + 1;
        continue;
      }
      if (c == ';') break;  // end of block
      if (c == '%' ) { ++i; continue; }
      char letter = char(std::toupper(static_cast<unsigned char>(c)));
      if (letter < 'A' || letter > 'Z') {
        problem(line, std::string("unexpected character '") + c + "'");
        return false;
      }
      ++i;
      while (i < l.size() && l[i] == ' ') ++i;
      size_t start = i;
      if (i < l.size() && (l[i] == '+' || l[i] == '-')) ++i;
      bool point = false;
      while (i < l.size() && (std::isdigit(static_cast<unsigned char>(l[i])) || l[i] == '.')) {
        point |= l[i] == '.';
        ++i;
      }
      std::string_view num = l.substr(start, i - start);
      if (num.empty() || num == "-" || num == "+") {
        problem(line, std::string("address ") + letter + " without a number");
        return false;
      }
      Word w;
      w.letter = letter;
      w.has_point = point;
      read_decimal(num.data() + (num[0] == '+'), num.data() + num.size(), w.raw);
      w.value = convert(letter, w.raw, point);
      words.push_back(w);
    }
    if (skippable)
      for (size_t k = first_word; k < words.size(); ++k)
        if (words[k].letter != 'N' && !(words[k].letter == 'M' && (words[k].raw == 0 || words[k].raw == 1))) {
          problem(line, std::string("a block the Block Delete switch may skip ('/') holds ") + words[k].letter +
                            num_text(words[k].raw) + ": the program runs two ways, and only one could be checked; "
                                                     "only a stop (M00, M01) may be written so");
          return false;
        }
    return true;
  }

  static bool is_g(double v, double code) { return std::abs(v - code) < 1e-6; }

  // A lathe's G-code system (Fanuc A, B or C) renames its functions: G33 threads where system A
  // writes G32, G95 feeds per revolution where A writes G99, G92 clamps the spindle where A
  // writes G50. The reader runs system A's numbers; a G word the machine's own codes give to a
  // function is read as system A's number for it, so the program clpc wrote for a system B or C
  // lathe is read as that control runs it. (System A's own codes alias nothing.)
  void alias_lathe_codes() {
    const Codes& c = m_.codes;
    const std::pair<const CodeTemplate*, double> functions[] = {
        {&c.units_inch, 20},      {&c.units_mm, 21},        {&c.feed_per_minute, 98}, {&c.feed_per_rev, 99},
        {&c.spindle_rpm_mode, 97}, {&c.spindle_css_mode, 96}, {&c.spindle_clamp, 50},  {&c.thread, 32},
        {&c.thread_box, 92},      {&c.thread_multi, 76},    {&c.rough_turn, 71},      {&c.rough_face, 72},
        {&c.rough_finish, 70},    {&c.groove_face, 74},     {&c.groove_radial, 75},   {&c.absolute, 90},
        {&c.incremental, 91}};
    for (const auto& [t, a_number] : functions) {
      const std::string& text = t->text;
      if (text.size() < 2 || (text[0] != 'G' && text[0] != 'g')) continue;
      double g = 0;
      const char* end = text.data() + text.size();
      const char* stop = std::find_if(text.data() + 1, end, [](char ch) { return ch == ' ' || ch == '\t'; });
      if (read_decimal(text.data() + 1, stop, g).ec != std::errc() || is_g(g, a_number)) continue;  // (no double from_chars in the browser build)
      lathe_alias_.push_back({g, a_number});
    }
  }
  double lathe_code(double g) const {
    for (const auto& [code, a_number] : lathe_alias_)
      if (is_g(g, code)) return a_number;
    return g;
  }

  void block(std::string_view l, int line) {
    std::vector<Word>& words = words_;
    words.clear();
    if (!parse(l, line, words) || words.empty()) return;
    if (words[0].letter == 'O') return;  // program number
    ++res_.blocks;

    Words& a = a_;  // address -> value (last one)
    a.clear();
    std::vector<double>& gs = gs_;
    std::vector<double>& ms = ms_;
    gs.clear();
    ms.clear();
    for (const Word& w : words) {
      if (w.letter == 'G') gs.push_back(w.raw);
      else if (w.letter == 'M') ms.push_back(w.raw);
      else if (w.letter != 'N') a.set(w.letter, w.value, w.raw, w.has_point);
    }
    auto has = [&](char c) { return a.count(c) != 0; };

    bool g53 = false, g28 = false, g04 = false, g10 = false, g65 = false, g50 = false, new_cycle = false;
    bool motion_word = false, plane_set = false, plane_cancel = false, g92 = false, g76 = false, g70 = false;
    int g71 = 0;
    int new_offset = 0;
    bool lathe = m_.is_lathe();
    if (!lathe_alias_.empty()) [[unlikely]]
      for (double& g : gs) g = lathe_code(g);
    for (double g : gs) {
      if (is_g(g, 0)) motion_ = Motion::Rapid, motion_word = true;
      else if (is_g(g, 1)) motion_ = Motion::Linear, motion_word = true;
      else if (is_g(g, 2)) motion_ = Motion::Cw, motion_word = true;
      else if (is_g(g, 3)) motion_ = Motion::Ccw, motion_word = true;
      else if (is_g(g, 4)) g04 = true;
      else if (is_g(g, 10)) g10 = true;
      else if (is_g(g, 17)) plane_ = 17;
      else if (is_g(g, 18)) plane_ = 18;
      else if (is_g(g, 19)) plane_ = 19;
      else if (is_g(g, 20)) set_units(ir::Units::Inch, line);
      else if (is_g(g, 21)) set_units(ir::Units::Mm, line);
      else if (is_g(g, 28)) g28 = true;
      else if (is_g(g, 40)) comp_ = 0;
      else if (is_g(g, 41) || is_g(g, 42)) comp_ = is_g(g, 41) ? 1 : 2;
      else if (is_g(g, 43)) length_comp_ = true, length_register_ = has('H') ? int(std::round(a['H'])) : length_register_;
      else if (is_g(g, 49)) length_comp_ = false, tcp_ = false, length_register_ = 0;
      else if (is_g(g, 234) || is_g(g, 43.4) || is_g(g, 43.5))
        tcp_ = true, length_comp_ = true, length_register_ = has('H') ? int(std::round(a['H'])) : length_register_;
      else if (is_g(g, 187) || is_g(g, 5.1)) {}  // smoothing (Haas), AI contour control (Fanuc): the path is the same
      // Codes that change how fast the tool goes along the path, never where: exact stop (G09
      // one block, G61 modal), cutting mode (G64), tapping mode (G63), automatic corner override
      // (G62), look-ahead (G08 P1/P0; Haas G103 P limits it), high-speed contouring (Fanuc
      // G05 P10000/P0; other P values run stored high-speed cycles, and Haas's G05 turns the
      // spindle by R: neither is this), polar coordinates off (G15). CAM users write them with
      // INSERT or PREFUN.
      else if (is_g(g, 9) || is_g(g, 61) || is_g(g, 62) || is_g(g, 63) || is_g(g, 64) || is_g(g, 8) ||
               is_g(g, 103) || is_g(g, 15) ||
               (is_g(g, 5) && has('P') && !has('R') && (std::abs(a['P'] - 10000) < 1e-9 || a['P'] == 0))) {}
      else if (is_g(g, 68.2) || is_g(g, 268)) plane_set = true;
      else if (is_g(g, 69) || is_g(g, 269)) plane_cancel = true;
      else if (is_g(g, 53.1)) {}
      else if (is_g(g, 92) && !lathe) g92 = true;
      else if (is_g(g, 32) && lathe) motion_ = Motion::Thread, motion_word = true;
      else if (is_g(g, 92) && lathe) motion_ = Motion::ThreadBox, motion_word = true;
      else if ((is_g(g, 71) || is_g(g, 72)) && lathe) g71 = int(std::round(g));
      else if (is_g(g, 70) && lathe) g70 = true;
      else if (is_g(g, 76) && lathe) g76 = true;  // renames positions (a winding rotary's, by whole turns)  // turns the rotaries to the plane: the program positioned them already
      else if (is_g(g, 254)) dwo_ = true;
      else if (is_g(g, 255)) dwo_ = false;
      else if (is_g(g, 50) && lathe) g50 = true;  // spindle clamp (with S)
      else if (is_g(g, 53)) g53 = true;
      else if (g >= 54 - 1e-6 && g <= 59 + 1e-6 && is_g(g, std::round(g))) new_offset = int(std::round(g)) - 53;
      else if (is_g(g, 54.1) || is_g(g, 154)) new_offset = -1;  // P gives the register
      else if (is_g(g, 65)) g65 = true;
      else if (is_g(g, 80)) cycle_ = 0, cycle_on_ = false;
      else if (lathe && (is_g(g, 74) || is_g(g, 75))) groove_ = int(std::round(g));
      else if (!lathe && (is_g(g, 73) || is_g(g, 74) || is_g(g, 76) || (g > 80.5 && g < 89.5 && is_g(g, std::round(g))))) {
        cycle_ = int(std::round(g));
        new_cycle = true;
      }
      else if (is_g(g, 90)) absolute_ = true;
      else if (is_g(g, 91)) absolute_ = false;
      else if (is_g(g, 93)) { inverse_time_ = true; }
      else if (is_g(g, 94) && !lathe) { inverse_time_ = false; per_rev_ = false; }
      else if (is_g(g, 95) && !lathe) { inverse_time_ = false; per_rev_ = true; }
      else if (is_g(g, 98) && lathe) per_rev_ = false;
      else if (is_g(g, 99) && lathe) per_rev_ = true;
      else if ((is_g(g, 98) || is_g(g, 99)) && !lathe) cycle_return_initial_ = is_g(g, 98);
      else if (is_g(g, 96) && lathe) css_ = true;
      else if (is_g(g, 97) && lathe) css_ = false;
      else
        problem(line, "G" + fmt(g) + " is not a code clpc's reader knows, so the program cannot be checked against the "
                      "CL (written by an INSERT or PREFUN? compile with --no-verify to take it unchecked)");
    }
    if (motion_word && !new_cycle) cycle_ = 0, cycle_on_ = false;  // a motion code cancels a canned cycle
    // A mill drills along the axis square to the plane, and compensates in the plane: clpc's
    // reader follows both in G17 only.
    if (!lathe && plane_ != 17 && (new_cycle || (cycle_on_ && (has('X') || has('Y')))))
      problem(line, "a drilling cycle in G" + std::to_string(plane_) + ": the control drills along the axis square to that "
                    "plane, not Z; G17 first");
    const bool comp_off_plane = !lathe && plane_ != 17 && comp_ != 0;
    if (comp_off_plane && !comp_off_plane_said_)
      problem(line, "cutter compensation (G41/G42) in G" + std::to_string(plane_) + ": the control offsets the path in that "
                    "plane; G17 first");
    comp_off_plane_said_ = comp_off_plane;  // once until compensation or the plane is right again
    if (new_offset > 0) work_offset_ = new_offset;
    if (new_offset < 0) {
      if (!has('P')) problem(line, "G54.1/G154 without P");
      else work_offset_ = 6 + int(std::round(a['P']));
    }

    for (double mc : ms) {
      int code = int(std::round(mc));
      switch (code) {
        // M00 stops the spindle and the coolant; M01 too with the operator's switch on, which is
        // how it is read: a cut after it with no M03 would be made with the spindle stopped.
        case 0: case 1: spindle_on_ = false; res_.events.push_back({Event::Kind::Stop, line, double(code)}); break;
        case 2: case 30: res_.ended = true; break;
        case 3: case 4: spindle_on_ = true; spindle_code_ = code; res_.events.push_back({Event::Kind::Spindle, line, code == 3 ? 1.0 : -1.0}); break;
        case 5: case 19:  // M19 orients the spindle: it stops turning
          spindle_on_ = false;
          res_.events.push_back({Event::Kind::Spindle, line, 0});
          break;
        case 6:
          if (!has('T') && pending_tool_ <= 0) problem(line, "M06 without a tool");
          tool_ = has('T') ? int(std::round(a['T'])) : pending_tool_;
          ++res_.tool_changes;
          length_comp_ = false;  // must be applied again for the new tool
          length_register_ = 0;
          spindle_on_ = false;
          res_.events.push_back({Event::Kind::ToolChange, line, double(tool_)});
          break;
        // Each coolant has its on and off (M09 stops mist and flood; Haas M89 and M84 stop
        // through-spindle coolant and air). Read leniently: a code that may stop more (a Fanuc's
        // M09) stops only its own.
        case 7: case 8: case 88: case 83:
          coolant_ |= code == 88 ? 2 : code == 83 ? 4 : 1;
          res_.events.push_back({Event::Kind::Coolant, line, double(code)});
          break;
        case 9: case 89: case 84:
          coolant_ &= code == 89 ? ~2 : code == 84 ? ~4 : ~1;
          res_.events.push_back({Event::Kind::Coolant, line, 0});
          break;
        // A subprogram call runs blocks the reader does not have (M98 P9000 passed, where G65 was
        // refused): what they move is not known.
        case 97: case 98:
          problem(line, "M" + std::to_string(code) + " calls a subprogram the reader does not have, so the program cannot be "
                        "checked against the CL (written by an INSERT or AUXFUN? compile with --no-verify to take it unchecked)");
          break;
        default: break;  // machine functions (clamps, ...) carry no motion
      }
    }
    if (lathe && has('T') && !g04) {
      // T0101: tool and offset, changed at once.
      int t = int(std::round(a['T']));
      tool_ = t / 100;
      length_register_ = t % 100;  // the offset register: length and wear
      ++res_.tool_changes;
      res_.events.push_back({Event::Kind::ToolChange, line, double(tool_)});
    } else if (!lathe && has('T') && std::find_if(ms.begin(), ms.end(), [](double v) { return std::round(v) == 6; }) == ms.end()) {
      pending_tool_ = int(std::round(a['T']));
    }
    if (has('S')) (g50 ? max_rpm_ : spindle_) = a['S'];
    if (has('F')) {
      // Without a point, F counts the increments of the feed's own format (feeds.per_rev, .lead,
      // .tap ...), not format.F's: a per-rev feed of 4 implied decimals was read 10^4 too fast.
      const bool thread = motion_ == Motion::Thread || motion_ == Motion::ThreadBox || g76;
      const AddressFormat& f = thread ? m_.feeds.lead
                               : !lathe && (cycle_ == 84 || cycle_ == 74) ? m_.feeds.tap
                               : m_.feed_format(inverse_time_ ? ir::FeedMode::InverseTime
                                                : per_rev_    ? ir::FeedMode::PerRev
                                                              : ir::FeedMode::PerMinute);
      feed_ = a['F'];
      if (!a.with_point('F')) {
        feed_ = a.raw['F' - 'A'];
        if (f.point == AddressFormat::Point::Never && f.decimals > 0) feed_ /= std::pow(10.0, f.decimals);
      }
    }

    // A mill's D is modal, in any block: D33 before G41, or D13 mid-contour, is the register
    // the radius is taken from from then on.
    if (!lathe && has('D') && !g10) comp_register_ = int(std::round(a['D']));
    if (g04) {
      // P with a point is seconds (Haas), without one milliseconds (Fanuc, Haas); X and U are
      // seconds, whatever X's scale on a diameter lathe.
      double secs = has('P') ? dwell_p(a, line) : has('X') ? a['X'] : has('U') ? a['U'] : 0;
      res_.events.push_back({Event::Kind::Dwell, line, secs});
      pending_dwell_ += secs;
      return;
    }
    if (g10) {
      offset_set(a, line);
      return;
    }
    if (plane_set || plane_cancel) {
      tilt(a, plane_set);
      return;
    }
    if (g92) {
      rename_axes(a, line);
      return;
    }
    if (g65) {
      macro_call(a, line);
      return;
    }
    if (g71 != 0 || g70) {
      if (stock_.replaying) problem(line, std::string("G") + (g70 ? "70" : std::to_string(g71)) + " inside a G70's profile: the control alarms");
      else if (g70) finish_profile(a, line);
      else stock_cycle(g71, a, line);
      return;
    }

    // Axis words -> target.
    Vec3 target = pos_;
    bool any_axis = false;
    const double xs = m_.format('X').scale;
    auto axis = [&](char letter, char inc, int i) {
      if (has(letter)) {
        double v = a[letter] / (letter == 'X' ? xs : 1.0);
        target[i] = absolute_ || g53 ? v : (std::isnan(pos_[i]) ? kNaN : pos_[i] + v);
        any_axis = true;
      }
      if (lathe && inc && has(inc)) {
        double v = a[inc] / (inc == 'U' ? xs : 1.0);
        target[i] = std::isnan(pos_[i]) ? kNaN : pos_[i] + v;
        any_axis = true;
      }
    };
    axis('X', 'U', 0);
    axis('Y', 0, 1);
    axis('Z', 'W', 2);
    std::array<double, 3> rot_target = rotary_;
    for (int i = 0; i < 3; ++i) {
      char letter = char('A' + i);
      if (has(letter)) {
        rot_target[size_t(i)] = absolute_ ? a[letter] : rotary_[size_t(i)] + a[letter];
        any_axis = true;
      }
    }

    bool turns = false;
    for (int i = 0; i < 3; ++i)
      if (has(char('A' + i)) && !(rot_target[size_t(i)] == rotary_[size_t(i)])) turns = true;
    if (tilted_ && turns)
      problem(line, "a rotary axis moves in a tilted working plane (G68.2 / G268): the control refuses it; cancel the "
                    "plane (G69 / G269) first");
    if (groove_ != 0) {
      lathe_groove(a, target, line);
      groove_ = 0;
      return;
    }
    if (g76) {
      thread_multi(a, target, any_axis, line);
      return;
    }
    if (motion_ == Motion::ThreadBox && any_axis && !g53 && !g28) {
      thread_box(a, target, line);
      return;
    }
    if (cycle_ != 0 && !g53 && !g28) {
      hole(a, new_cycle, target, line);
      return;
    }
    if (g53 && !absolute_ && any_axis) {
      // A Fanuc ignores G53 in G91 (machine coordinates are absolute only): nothing moves.
      problem(line, "G53 in G91: the control ignores machine coordinates in incremental mode, so the tool does not "
                    "move; G90 G53");
      return;
    }
    if (g53) {
      // Machine coordinates: where that is in the work frame is unknown to the reader.
      for (int i = 0; i < 3; ++i)
        if (has("XYZ"[i])) pos_[i] = kNaN;
      rotary_ = rot_target;
      return;
    }
    if (g28) {
      // Home through the intermediate point: the axes named end up at the reference point. With
      // none named a Haas homes every axis (a Fanuc alarms): where the tool is, is not known.
      for (int i = 0; i < 3; ++i)
        if (has("XYZ"[i]) || (lathe && has("UVW"[i])) || !any_axis) pos_[i] = kNaN;
      if (!any_axis) problem(line, "G28 with no axis named: every axis returns home on some controls, an alarm on "
                                   "others; name the axes (G91 G28 Z0.)");
      return;
    }
    if (!any_axis) {
      if ((has('I') || has('J') || has('K')) && (motion_ == Motion::Cw || motion_ == Motion::Ccw)) {
        // A full circle: no end point, only the centre.
        target = pos_;
      } else {
        return;
      }
    }
    if (motion_ == Motion::None) {
      problem(line, "axis words with no motion mode (G00/G01/G02/G03) in effect");
      return;
    }
    move(target, rot_target, a, line);
  }

  // A canned-cycle block: (re)defines the cycle's words, and drills at X Y if given (or at the
  // current position when the cycle is new).
  void hole(const Words& a, bool new_cycle, const Vec3& target, int line) {
    if (new_cycle && !cycle_on_) {
      initial_z_ = pos_.z();
      cycle_on_ = true;
    }
    if (a.count('Z')) cyc_bottom_ = a['Z'];
    if (a.count('R')) cyc_r_ = a['R'];
    if (a.count('Q')) cyc_q_ = a['Q'];
    // P is the dwell at the bottom (it was taken as seconds: G82 P500 counted 500 s).
    if (a.count('P')) cyc_p_ = (cycle_ == 82 || cycle_ == 89) ? dwell_p(a, line) : a['P'];
    // K (Fanuc) or L (Haas) repeats the hole: K0 stores the cycle without drilling, K3 drills it
    // three times (G91: three holes a step apart). clpc writes neither; the reader does not follow.
    // A count, not a length: as written.
    for (char repeat : {'K', 'L'})
      if (const double n = a.raw[size_t(repeat - 'A')]; a.count(repeat) && n != 1)
        problem(line, std::string(1, repeat) + fmt(n) + " in a canned cycle: the control " +
                          (n == 0 ? std::string("stores the cycle and drills no hole") : "drills the hole " + fmt(n) + " times") +
                          "; clpc's reader does not follow repeats, so the program cannot be checked against the CL");
    bool xy = a.count('X') || a.count('Y');
    if (!xy && !new_cycle) return;
    if (std::isnan(cyc_bottom_) || std::isnan(cyc_r_)) {
      problem(line, "canned cycle without Z or R");
      return;
    }
    if (!(feed_ > 0)) problem(line, "canned cycle with no feed rate (F)");
    if (std::isnan(initial_z_)) initial_z_ = std::max(cyc_r_, pos_.z());
    if (cyc_bottom_ > cyc_r_) problem(line, "canned cycle bottom (Z) above its R plane");
    ++res_.cycles;
    res_.events.push_back({Event::Kind::CycleStart, line, double(cycle_)});
    auto seg = [&](Segment::Kind k, const Vec3& to) {
      Segment s = segment(k, to, rotary_, line);
      s.from_cycle = true;
      s.cycle = uint8_t(cycle_);
      res_.segments.push_back(s);
      pos_ = to;
    };
    Vec3 over(target.x(), target.y(), pos_.z());
    if (!m_.is_lathe() && tool_ > 0 && !length_comp_ && !m_.codes.length_offset.empty())
      problem(line, "canned cycle with no tool length compensation (G43) for the tool in the spindle");
    seg(Segment::Kind::Rapid, over);
    auto z = [&](double zz) { return Vec3(target.x(), target.y(), zz); };
    seg(Segment::Kind::Rapid, z(cyc_r_));
    double d = m_.cycles.peck_clearance;
    if ((cycle_ == 83 || cycle_ == 73) && cyc_q_ > 0 && (cyc_r_ - cyc_bottom_) / cyc_q_ > 100000) {
      problem(line, "peck cycle with Q so small it would peck more than 100000 times");
      seg(Segment::Kind::Feed, z(cyc_bottom_));
    } else if (cycle_ == 83 || cycle_ == 73) {
      if (!(cyc_q_ > 0)) problem(line, "peck cycle without Q");
      double depth = cyc_r_;
      while (cyc_q_ > 0 && depth > cyc_bottom_ + 1e-9) {
        double next = std::max(cyc_bottom_, depth - cyc_q_);
        if (next == depth) next = cyc_bottom_;  // a peck lost in the rounding of large coordinates
        if (depth < cyc_r_ && cycle_ == 83) seg(Segment::Kind::Rapid, z(depth + d));
        seg(Segment::Kind::Feed, z(next));
        depth = next;
        if (depth > cyc_bottom_ + 1e-9) seg(Segment::Kind::Rapid, z(cycle_ == 83 ? cyc_r_ : depth + d));
      }
    } else {
      seg(Segment::Kind::Feed, z(cyc_bottom_));
    }
    if (cycle_ == 82 || cycle_ == 89) {
      res_.events.push_back({Event::Kind::Dwell, line, cyc_p_});
      res_.segments.back().dwell = float(cyc_p_);  // at the bottom: the feed just made
    }
    double ret = cycle_return_initial_ ? std::max(initial_z_, cyc_r_) : cyc_r_;
    bool feed_out = cycle_ == 84 || cycle_ == 74 || cycle_ == 85 || cycle_ == 89;
    if (feed_out) {
      seg(Segment::Kind::Feed, z(cyc_r_));
      if (ret != cyc_r_) seg(Segment::Kind::Rapid, z(ret));
    } else {
      seg(Segment::Kind::Rapid, z(ret));
    }
  }

  // G74/G75, two blocks: "G75 R(e)" sets the pull-out; "G75 X Z P Q [R] F" runs the cycle
  // from where the tool is, as groove::expand models a Fanuc doing it.
  void lathe_groove(const Words& a, const Vec3& target, int line) {
    bool second = a.count('X') || a.count('Z') || a.count('U') || a.count('W');
    if (!second) {
      groove_retract_ = a.count('R') ? a['R'] : 0;
      return;
    }
    if (std::isnan(pos_.x()) || std::isnan(pos_.z())) {
      problem(line, "G" + std::to_string(groove_) + " from an unknown position");
      return;
    }
    if (!(feed_ > 0)) problem(line, "groove cycle with no feed rate (F)");
    groove::Params p;
    p.face = groove_ == 74;
    p.retract = groove_retract_;
    p.x_amount = a.count('P') ? a['P'] : 0;
    p.z_amount = a.count('Q') ? a['Q'] : 0;
    p.relief = a.count('R') ? a['R'] : 0;
    Vec3 start = pos_;
    Vec3 end(std::isnan(target.x()) ? start.x() : target.x(), 0, std::isnan(target.z()) ? start.z() : target.z());
    ++res_.cycles;
    res_.events.push_back({Event::Kind::CycleStart, line, double(groove_)});
    const std::vector<groove::Step> steps = groove::expand(start, end, p);
    if (steps.empty()) {
      problem(line, "G" + std::to_string(groove_) + ": P and Q so small the cycle would make more than a million moves");
      return;
    }
    for (const groove::Step& st : steps) {
      Segment s = segment(st.cut ? Segment::Kind::Feed : Segment::Kind::Rapid, st.to, rotary_, line);
      s.from_cycle = true;
      res_.segments.push_back(s);
      pos_ = st.to;
    }
  }

  // Stock removal: the profiles read (G70 runs them again by P and Q) and the cycle reading one.
  static constexpr size_t kMaxProfileBlocks = 100000;
  struct Profile {
    int p = -1, q = -1;
    std::vector<std::pair<int, std::string>> lines;  // G-code line, text
  };
  struct StockCycle {
    double depth = 0, retract = 0;  // G71 U R / G72 W R
    bool collecting = false;        // the lines after G71 P Q are its profile, up to N(Q)
    bool replaying = false;         // running a profile's blocks
    int code = 71, line = 0;
    Vec3 start = Vec3::Zero();
    double allow_x = 0, allow_z = 0;  // radius
    Profile profile;
  };

  // --- lathe stock removal (stock_model: the control's rules) ---------------------------------
  // G71/G72, two blocks: "G71 U(Δd) R(e)" sets the depth of cut and the pull-out (G72: W(Δd));
  // "G71 P(ns) Q(nf) U(Δu) W(Δw) F" names the profile, the blocks N(ns) to N(nf), which must
  // follow it: they are read, not run; the cycle runs over them, and the program goes on after
  // N(nf). "G70 P Q" runs a profile read so, then returns to where it started.
  void stock_cycle(int code, const Words& a, int line) {
    if (!a.count('P') && !a.count('Q')) {
      stock_.depth = code == 71 ? (a.count('U') ? a['U'] : stock_.depth) : (a.count('W') ? a['W'] : stock_.depth);
      if (a.count('R')) stock_.retract = a['R'];
      return;
    }
    if (!a.count('P') || !a.count('Q')) {
      problem(line, "G" + std::to_string(code) + " with P but no Q, or Q but no P: which blocks are its profile is unknown");
      return;
    }
    if (std::isnan(pos_.x()) || std::isnan(pos_.z())) {
      problem(line, "G" + std::to_string(code) + " from an unknown position");
      return;
    }
    if (!(feed_ > 0)) problem(line, "stock removal cycle with no feed rate (F)");
    stock_.collecting = true;
    stock_.code = code;
    stock_.line = line;
    stock_.start = pos_;
    stock_.allow_x = (a.count('U') ? a['U'] : 0) / m_.format('X').scale;
    stock_.allow_z = a.count('W') ? a['W'] : 0;
    // P and Q are sequence numbers, not lengths in increments.
    stock_.profile = Profile{int(std::lround(a.raw['P' - 'A'])), int(std::lround(a.raw['Q' - 'A'])), {}};
  }

  // The number of the block's N word, -1 without one; whether it ends the program.
  static int block_number(std::string_view l) {
    size_t i = l.find_first_not_of(" \t");
    if (i == std::string_view::npos || (l[i] != 'N' && l[i] != 'n')) return -1;
    int n = 0;
    bool any = false;
    for (++i; i < l.size() && std::isdigit(static_cast<unsigned char>(l[i])); ++i) n = n * 10 + (l[i] - '0'), any = true;
    return any && n < 100000000 ? n : -1;
  }
  static bool blank(std::string_view l) {
    for (size_t i = 0; i < l.size(); ++i) {
      if (l[i] == '(') {
        i = l.find(')', i);
        if (i == std::string_view::npos) return false;
      } else if (l[i] != ' ' && l[i] != '\t' && l[i] != '\r' && l[i] != '%') {
        return false;
      }
    }
    return true;
  }

  // A line while a G71/G72 reads its profile: kept, not run. False when the line is to run
  // after all (the profile is not there).
  bool collect_profile(std::string_view l, int line) {
    Profile& pr = stock_.profile;
    const std::string g = "G" + std::to_string(stock_.code) + " P" + std::to_string(pr.p) + " Q" + std::to_string(pr.q);
    const int n = block_number(l);
    if (pr.lines.empty() && n < 0 && blank(l)) return true;
    if (pr.lines.empty() && n != pr.p) {
      problem(stock_.line, g + ": the block after it is not N" + std::to_string(pr.p) +
                               ": clpc's reader takes the profile only where it follows its cycle");
      stock_.collecting = false;
      return false;
    }
    if (l.find("M30") != std::string_view::npos || l.find("M02") != std::string_view::npos ||
        pr.lines.size() >= kMaxProfileBlocks) {
      problem(stock_.line, g + ": no block N" + std::to_string(pr.q) + " ends the profile before line " + std::to_string(line));
      stock_.collecting = false;
      return false;
    }
    pr.lines.emplace_back(line, std::string(l));
    if (n == pr.q) {
      stock_.collecting = false;
      run_stock_cycle();
    }
    return true;
  }

  // The profile's moves from where the cycle starts, as the control reads them (the blocks run
  // dry: the program's state is as before afterwards).
  std::vector<stock::Element> read_profile(const Profile& pr, int line, bool& first_rapid) {
    const Vec3 pos = pos_;
    const Motion motion = motion_;
    const double feed = feed_, spindle = spindle_;
    const bool absolute = absolute_, per_rev = per_rev_, css = css_;
    const int comp = comp_, plane = plane_, tool = tool_, reg = length_register_, changes = res_.tool_changes;
    const size_t events = res_.events.size();
    std::vector<Segment> kept;
    kept.swap(res_.segments);
    stock_.replaying = true;
    for (const auto& [ln, text] : pr.lines) block(text, ln);
    stock_.replaying = false;
    std::vector<Segment> moves;
    moves.swap(res_.segments);
    res_.segments.swap(kept);
    res_.events.resize(events);
    res_.tool_changes = changes;
    pos_ = pos, motion_ = motion, feed_ = feed, spindle_ = spindle, absolute_ = absolute, per_rev_ = per_rev, css_ = css;
    comp_ = comp, plane_ = plane, tool_ = tool, length_register_ = reg;
    std::vector<stock::Element> out;
    for (const Segment& s : moves) {
      if (s.kind == Segment::Kind::Arc && !(s.normal == Vec3::UnitY())) {
        problem(s.line, "an arc of a stock removal profile outside the ZX plane (G18)");
        return {};
      }
      if (s.thread) {
        problem(s.line, "a thread cut in a stock removal profile");
        return {};
      }
      out.push_back({s.start, s.end, s.kind == Segment::Kind::Arc, s.center, s.ccw, s.line});
    }
    if (out.empty()) problem(line, "a stock removal profile with no moves");
    first_rapid = !moves.empty() && moves.front().kind == Segment::Kind::Rapid;
    return out;
  }

  void run_stock_cycle() {
    Profile& pr = stock_.profile;
    const int line = stock_.line;
    const std::string g = "G" + std::to_string(stock_.code);
    bool first_rapid = true;
    const std::vector<stock::Element> profile = read_profile(pr, line, first_rapid);
    profiles_.push_back(std::move(pr));
    if (profile.empty()) return;
    stock::Params p;
    p.facing = stock_.code == 72;
    p.depth = stock_.depth;
    p.retract = stock_.retract;
    p.allow_x = stock_.allow_x;
    p.allow_z = stock_.allow_z;
    // The first block's own motion enters each level: G00 at rapid, G01 at feed.
    p.infeed_rapid = first_rapid;
    std::string why;
    const std::vector<stock::Step> steps = stock::expand(stock_.start, profile, p, why);
    if (steps.empty()) {
      problem(line, g + ": " + why + "; the control alarms");
      return;
    }
    ++res_.cycles;
    res_.events.push_back({Event::Kind::CycleStart, line, double(stock_.code)});
    for (const stock::Step& st : steps) {
      Segment s = segment(st.kind == stock::Step::Kind::Rapid ? Segment::Kind::Rapid : Segment::Kind::Feed, st.to, rotary_, line);
      s.from_cycle = true;
      if (st.kind == stock::Step::Kind::Arc) set_arc(s, st.center, st.ccw);
      res_.segments.push_back(s);
      pos_ = st.to;
    }
  }

  // G70 P Q: the profile read with its G71/G72, run as written (its F and S), then back to the
  // start at rapid.
  void finish_profile(const Words& a, int line) {
    const int p = a.count('P') ? int(std::lround(a.raw['P' - 'A'])) : -1, q = a.count('Q') ? int(std::lround(a.raw['Q' - 'A'])) : -1;
    const Profile* pr = nullptr;
    for (const Profile& x : profiles_)
      if (x.p == p && x.q == q) pr = &x;
    if (!pr) {
      problem(line, "G70 P" + std::to_string(p) + " Q" + std::to_string(q) +
                        ": no profile of those blocks was read with a G71/G72 before it");
      return;
    }
    if (std::isnan(pos_.x()) || std::isnan(pos_.z())) {
      problem(line, "G70 from an unknown position");
      return;
    }
    const Vec3 start = pos_;
    const size_t first = res_.segments.size();
    const Profile copy = *pr;  // block() may read more profiles
    stock_.replaying = true;
    for (const auto& [ln, text] : copy.lines) block(text, ln);
    stock_.replaying = false;
    for (size_t i = first; i < res_.segments.size(); ++i) res_.segments[i].from_cycle = true;
    ++res_.cycles;
    res_.events.push_back({Event::Kind::CycleStart, line, 70});
    Segment back = segment(Segment::Kind::Rapid, start, rotary_, line);
    back.from_cycle = true;
    res_.segments.push_back(back);
    pos_ = start;
  }

  // --- lathe threading (thread_model: the control's rules) ------------------------------------

  // F of a thread block is its lead per revolution, whatever G98/G99 say; the spindle must
  // turn at one speed (G97), or the passes would not meet.
  bool thread_ready(int line) {
    if (std::isnan(pos_.x()) || std::isnan(pos_.z())) {
      problem(line, "thread cut from an unknown position");
      return false;
    }
    if (!(feed_ > 0)) problem(line, "thread cut with no lead (F)");
    if (css_) problem(line, "thread cut under constant surface speed (G96): the passes would not meet; G97 first");
    if (!spindle_on_) problem(line, "thread cut with the spindle stopped");
    return true;
  }

  void thread_segments(const std::vector<thread_model::Step>& steps, int line) {
    for (const thread_model::Step& st : steps) {
      Segment s = segment(st.cut ? Segment::Kind::Feed : Segment::Kind::Rapid, st.to, rotary_, line);
      s.from_cycle = true;
      if (st.cut) {
        s.thread = true;
        s.per_rev = true;
        s.feed = feed_;
      } else {
        s.feed = 0;
      }
      res_.segments.push_back(s);
      pos_ = st.to;
    }
  }

  // G92 X(U) Z(W) [R] F: one box from where the tool is; modal, a following X repeats it.
  void thread_box(const Words& a, const Vec3& target, int line) {
    if (!thread_ready(line)) return;
    if (a.count('R') && a['R'] != 0) {
      problem(line, "G92 with R (a tapered thread): clpc's reader does not run it");
      return;
    }
    Vec3 end(std::isnan(target.x()) ? pos_.x() : target.x(), 0, std::isnan(target.z()) ? pos_.z() : target.z());
    ++res_.cycles;
    res_.events.push_back({Event::Kind::CycleStart, line, 92});
    std::vector<thread_model::Step> steps;
    thread_model::box(pos_, end, steps);
    thread_segments(steps, line);
  }

  // G76, two blocks: "G76 P(m)(r)(a) Q(Δdmin) R(d)" sets the cycle; "G76 X Z [R] P(k) Q(Δd) F"
  // runs it from where the tool is.
  void thread_multi(const Words& a, const Vec3& target, bool any_axis, int line) {
    if (!any_axis) {
      if (a.count('P')) {
        const long p = std::lround(a.raw['P' - 'A']);
        multi_.finish_passes = int(p / 10000);
        if ((p / 100) % 100 != 0) problem(line, "G76 with a thread chamfer (P..rr..): clpc's reader does not run it");
        if (p % 100 != 0) problem(line, "G76 with a tool angle (P....aa, flank infeed): clpc's reader runs radial infeed only");
      }
      if (a.count('Q')) multi_.min_step = a['Q'];
      if (a.count('R')) multi_.allowance = a['R'];
      return;
    }
    if (!thread_ready(line)) return;
    if (a.count('R') && a['R'] != 0) {
      problem(line, "G76 with R (a tapered thread): clpc's reader does not run it");
      return;
    }
    thread_model::Multi p = multi_;
    p.height = a.count('P') ? a['P'] : 0;
    p.first = a.count('Q') ? a['Q'] : 0;
    Vec3 end(std::isnan(target.x()) ? pos_.x() : target.x(), 0, std::isnan(target.z()) ? pos_.z() : target.z());
    const std::vector<thread_model::Step> steps = thread_model::multi(pos_, end, p);
    if (steps.empty()) {
      problem(line, "G76 makes no passes (P, Q, R, or m out of range, or more than 10000 passes)");
      return;
    }
    ++res_.cycles;
    res_.events.push_back({Event::Kind::CycleStart, line, 76});
    thread_segments(steps, line);
  }

  // A dwell's P (G04, G82, G89): whole milliseconds without a point (Fanuc, Haas), whatever
  // format.P's implied decimals (the lathe's P500 was read 0.0005 s); seconds with one, on a
  // control whose P takes a point (Haas: format.P writes one). Fanuc's takes none: P0.5 there is
  // a problem, not half a second.
  double dwell_p(const Words& a, int line) {
    if (!a.with_point('P')) return a.raw['P' - 'A'] / 1000.0;
    if (m_.format('P').point == AddressFormat::Point::Never)
      problem(line, "P" + fmt(a.raw['P' - 'A']) + " with a decimal point: this control takes a dwell's P in whole "
                    "milliseconds (its P is written without a point)");
    return a.raw['P' - 'A'];
  }

  // A program is read in its machine's units (every format and limit is in them). A G20 or G21
  // saying the other unit is an error, not a conversion: G21 made G20 on a millimetre machine
  // was read as millimetres and passed, and the control would move every axis 25.4 times as far.
  void set_units(ir::Units u, int line) {
    if (res_.units_set && u != res_.units) problem(line, "units change in the middle of the program");
    else if (u != m_.units)
      problem(line, std::string(u == ir::Units::Inch ? "G20 (inches)" : "G21 (millimetres)") + " on a machine described in " +
                        (m_.units == ir::Units::Inch ? "inches" : "millimetres") + ": the control would read every "
                        "number 25.4 times " + (u == ir::Units::Inch ? "larger" : "smaller") + " than the program means");
    res_.units = u;
    res_.units_set = true;
  }

  void offset_set(const Words& a, int line) {
    if (!a.count('L') || !a.count('P')) {
      problem(line, "G10 needs L and P");
      return;
    }
    Event e{Event::Kind::OffsetSet, line};
    int L = int(std::round(a['L'])), P = int(std::round(a['P']));
    e.reg = L == 2 ? P : L == 20 ? 6 + P : 0;
    if (e.reg == 0) {
      problem(line, "G10 L" + std::to_string(L) + " is not a work-offset setting the reader knows");
      return;
    }
    e.v = Vec3(a.count('X') ? a['X'] : 0, a.count('Y') ? a['Y'] : 0, a.count('Z') ? a['Z'] : 0);
    res_.events.push_back(e);
  }

  // G65: the one macro the reader knows is the seed paper's work-offset macro (docs/offsets.md),
  // under the number the machine description gives it, as a control knows the macros in its
  // memory; #503 is the description's reference height. Its arithmetic, evaluated here from
  // the published text rather than from clpc's offset code.
  void macro_call(const Words& a, int line) {
    const OffsetSettings& o = m_.offsets;
    if (!a.count('P') || std::lround(a['P']) != o.macro) {
      problem(line, "G65 calls a macro the reader does not know (it knows the offset macro, P" + std::to_string(o.macro) +
                        "), so the program cannot be checked against the CL (written by an INSERT? compile with "
                        "--no-verify to take it unchecked)");
      return;
    }
    for (char c : {'A', 'B', 'C', 'X', 'Y', 'Z'}) {
      if (!a.count(c)) {
        problem(line, std::string("G65 P") + std::to_string(o.macro) + " without its " + c + " argument");
        return;
      }
      if (!a.with_point(c)) problem(line, std::string("G65 argument ") + c + " without a decimal point");
    }
    const double deg = 3.14159265358979323846 / 180;
    const double n1 = a['A'], n2 = a['B'], n3 = a['C'], n24 = a['X'], n25 = a['Y'], n26 = a['Z'];
    const double n503 = o.reference_height;
    const double n16 = n26 + n503;
    const double n104 = n24 * std::cos(-n3 * deg) - n25 * std::sin(-n3 * deg);
    const double n105 = n24 * std::cos(-n1 * deg) * std::sin(-n3 * deg) + n25 * std::cos(-n1 * deg) * std::cos(-n3 * deg) -
                        n16 * std::sin(-n1 * deg);
    const double n106 = n24 * std::sin(-n1 * deg) * std::sin(-n3 * deg) + n25 * std::sin(-n1 * deg) * std::cos(-n3 * deg) +
                        n16 * std::cos(-n1 * deg);
    Event e{Event::Kind::OffsetSet, line};
    e.reg = int(std::lround(n2));
    if (e.reg < 1 || e.reg > 6) {
      problem(line, "the offset macro's G10 L2 P#2 takes registers 1-6, not " + fmt(n2));
      return;
    }
    e.v = Vec3(n104, n105, n106);
    res_.events.push_back(e);
  }

  // G68.2 X Y Z I J K (G268 alike): a tilted plane, its angles in the machine's order
  // (kinematics.plane_euler); G69 / G269: none. The position the reader keeps is re-expressed
  // in the new frame, so the next move starts where the tool is.
  void tilt(const Words& a, bool set) {
    Vec3 part = tilted_ ? Vec3(tilted_->origin + tilted_->rotation * pos_) : pos_;
    if (!set) {
      tilted_ = nullptr;
      pos_ = part;
      return;
    }
    PlaneFrame f;
    for (int i = 0; i < 3; ++i) f.origin[i] = a.count("XYZ"[i]) ? a["XYZ"[i]] : 0.0;
    Vec3 angles(a.count('I') ? a['I'] : 0.0, a.count('J') ? a['J'] : 0.0, a.count('K') ? a['K'] : 0.0);
    f.rotation = plane::rotation(angles, m_.kinematics.plane_euler);
    tilted_ = std::make_shared<const PlaneFrame>(f);
    pos_ = tilted_->rotation.transpose() * (part - tilted_->origin);
  }

  // G92 with rotary words: the control calls the axis's position by another name, no motion.
  // Only whole turns keep the part where it was; linear words (a work shift) are not followed.
  void rename_axes(const Words& a, int line) {
    for (char c : {'X', 'Y', 'Z'})
      if (a.count(c)) problem(line, std::string("G92 with ") + c + " (a work coordinate shift) is not followed by clpc's reader");
    for (int i = 0; i < 3; ++i) {
      const char l = char('A' + i);
      if (!a.count(l)) continue;
      const double was = rotary_[size_t(i)], now = a[l];
      const double turns = (was - now) / 360;
      if (was == was && std::abs(turns - std::round(turns)) > 1e-6)
        problem(line, "G92 renames " + std::string(1, l) + fmt(was) + " as " + std::string(1, l) + fmt(now) +
                          ": not whole turns, so the part's angle would change");
      rotary_[size_t(i)] = now;
    }
  }

  // A segment from where the tool is, with the modal state it runs in.
  Segment segment(Segment::Kind k, const Vec3& to, const std::array<double, 3>& rot, int line) const {
    Segment s;
    s.kind = k;
    s.start = pos_;
    s.end = to;
    s.rotary_start = rotary_;
    s.rotary = rot;
    s.line = line;
    s.tool = tool_;
    s.length_register = length_register_;
    s.work_offset = work_offset_;
    s.inverse_time = inverse_time_;
    s.tcp = tcp_;
    s.dwo = dwo_;
    s.plane = tilted_;
    s.feed = k == Segment::Kind::Rapid ? 0 : feed_;
    s.dwell_before = float(pending_dwell_);
    pending_dwell_ = 0;
    spindle_info(s);
    return s;
  }

  void move(const Vec3& target, const std::array<double, 3>& rot, const Words& a, int line) {
    Segment s = segment(Segment::Kind::Feed, target, rot, line);
    bool moves_z = (a.count('Z') || a.count('W')) && !(std::abs(target.z() - pos_.z()) < 1e-12);
    if (!m_.is_lathe() && tool_ > 0 && !length_comp_ && moves_z && !m_.codes.length_offset.empty())
      problem(line, "Z moves with no tool length compensation (G43) for the tool in the spindle");
    if (motion_ == Motion::Rapid) {
      s.kind = Segment::Kind::Rapid;
      s.feed = 0;
    } else if (motion_ == Motion::Thread) {
      if (!thread_ready(line)) {
        pos_ = target;
        return;
      }
      s.kind = Segment::Kind::Feed;
      s.thread = true;
      s.per_rev = true;
    } else {
      if (!(feed_ > 0)) problem(line, "cutting move with no feed rate (F)");
      if (!rotary_unknown_reported_)
        for (const RotaryAxis& r : m_.kinematics.rotaries)
          if (r.name.size() == 1 && std::isnan(rot[size_t(r.name[0] - 'A')])) {
            problem(line, "cutting move with the " + r.name + " axis where the program has not put it (no " + r.name +
                              " word since the start)");
            rotary_unknown_reported_ = true;
            break;
          }
      if (inverse_time_ && !a.count('F')) problem(line, "inverse time (G93) needs F in every cutting block");
      s.feed = feed_;
      if (motion_ == Motion::Linear) {
        s.kind = Segment::Kind::Feed;
      } else if (!arc(s, a, line)) {
        pos_ = target;
        rotary_ = rot;
        return;
      }
    }
    res_.segments.push_back(s);
    pos_ = target;
    rotary_ = rot;
  }

  // An arc in the ZX plane (G18) with its centre given: radii and sweep as arc() computes them.
  void set_arc(Segment& s, const Vec3& center, bool ccw) const {
    s.kind = Segment::Kind::Arc;
    s.normal = Vec3::UnitY();
    s.ccw = ccw;
    s.center = center;
    s.start_radius = std::hypot(s.start.z() - center.z(), s.start.x() - center.x());
    s.end_radius = std::hypot(s.end.z() - center.z(), s.end.x() - center.x());
    const double a0 = std::atan2(s.start.x() - center.x(), s.start.z() - center.z());
    const double a1 = std::atan2(s.end.x() - center.x(), s.end.z() - center.z());
    double d = a1 - a0;
    while (d < 0) d += 2 * kPi;
    while (d >= 2 * kPi) d -= 2 * kPi;
    s.sweep = (ccw ? d : (d == 0 ? 0 : 2 * kPi - d)) * 180 / kPi;
  }

  bool arc(Segment& s, const Words& a, int line) {
    s.kind = Segment::Kind::Arc;
    s.ccw = motion_ == Motion::Ccw;
    // A lathe control that views its arcs from -Y (lathe.arcs_seen_from) turns G02 the other way.
    if (m_.is_lathe() && m_.lathe.arcs_from_minus_y) s.ccw = !s.ccw;
    int u, v;
    char cu, cv;
    if (plane_ == 17) { u = 0; v = 1; cu = 'I'; cv = 'J'; s.normal = Vec3::UnitZ(); }
    else if (plane_ == 18) { u = 2; v = 0; cu = 'K'; cv = 'I'; s.normal = Vec3::UnitY(); }
    else { u = 1; v = 2; cu = 'J'; cv = 'K'; s.normal = Vec3::UnitX(); }
    if (std::isnan(s.start[u]) || std::isnan(s.start[v])) {
      problem(line, "arc from an unknown position");
      return false;
    }
    double su = s.start[u], sv = s.start[v], eu = s.end[u], ev = s.end[v];
    double c_u, c_v;
    if (a.count('R')) {
      double r = a['R'];
      double du = eu - su, dv = ev - sv, d = std::hypot(du, dv);
      if (d < 1e-12 || std::abs(r) * 2 < d - radius_tol_) {
        problem(line, "R arc with no centre (end point too far, or a full circle)");
        return false;
      }
      double h = std::sqrt(std::max(0.0, r * r - d * d / 4));
      // Centre left of the chord (seen from the normal) for a ccw arc under 180 degrees.
      double side = (s.ccw ? 1 : -1) * (r > 0 ? 1 : -1);
      c_u = (su + eu) / 2 - side * h * dv / d;
      c_v = (sv + ev) / 2 + side * h * du / d;
    } else {
      bool abs_center = m_.arcs.center == ArcCenter::Absolute;
      double iu = a.count(cu) ? a[cu] : 0, iv = a.count(cv) ? a[cv] : 0;
      // I, J, K are never diameter values, even on a diameter lathe (the reader divided X only).
      c_u = abs_center ? iu : su + iu;
      c_v = abs_center ? iv : sv + iv;
      if (!a.count(cu) && !a.count(cv)) {
        problem(line, "arc with neither centre (I/J/K) nor radius (R)");
        return false;
      }
    }
    s.center = s.start;
    s.center[u] = c_u;
    s.center[v] = c_v;
    s.start_radius = std::hypot(su - c_u, sv - c_v);
    s.end_radius = std::hypot(eu - c_u, ev - c_v);
    if (std::abs(s.start_radius - s.end_radius) > radius_tol_ * 1.0000001)
      problem(line, "arc start and end radius differ by " + fmt(std::abs(s.start_radius - s.end_radius)) +
                        " (the control alarms above " + fmt(radius_tol_) + ")");
    double a0 = std::atan2(sv - c_v, su - c_u), a1 = std::atan2(ev - c_v, eu - c_u);
    double ccw = a1 - a0;
    while (ccw < 0) ccw += 2 * kPi;
    while (ccw >= 2 * kPi) ccw -= 2 * kPi;
    bool closed = std::abs(eu - su) < 1e-12 && std::abs(ev - sv) < 1e-12;
    double sweep = closed ? 2 * kPi : (s.ccw ? ccw : 2 * kPi - ccw);
    if (!closed && sweep == 0) sweep = 2 * kPi;
    s.sweep = sweep * 180 / kPi;
    return true;
  }

  // Feed per revolution and the spindle speed, for times: with constant surface speed (G96)
  // the speed at the segment's middle diameter, within the G50 clamp.
  void spindle_info(Segment& s) const {
    s.coolant = coolant_ != 0;
    s.comp = comp_;
    s.comp_register = comp_register_;
    s.per_rev = per_rev_;
    s.spindle = spindle_on_;
    s.spindle_code = spindle_on_ ? spindle_code_ : 0;
    s.rpm = spindle_on_ ? spindle_ : 0;
    if (css_ && spindle_on_) {
      double r = std::abs((s.start.x() + s.end.x()) / 2);
      double surface = res_.units == ir::Units::Inch ? spindle_ * 12 : spindle_ * 1000;  // per minute, in X's units
      s.rpm = r > 1e-9 ? surface / (2 * kPi * r) : 0;
      if (max_rpm_ > 0 && (s.rpm > max_rpm_ || r <= 1e-9)) s.rpm = max_rpm_;
    }
  }

  static std::string fmt(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.6g", v);
    return b;
  }

  const Machine& m_;
  const Options opt_;
  Result res_;
  int line_ = 0;
  std::vector<Word> words_;  // per block, kept for their capacity
  Words a_;
  std::vector<double> gs_, ms_;
  double radius_tol_;
  Vec3 pos_;
  std::array<double, 3> rotary_{0, 0, 0};
  Motion motion_ = Motion::None;
  int plane_ = 17;
  bool absolute_ = true;
  bool inverse_time_ = false;
  bool per_rev_ = false;
  bool css_ = false;
  bool length_comp_ = false;
  int length_register_ = 0;
  bool rotary_unknown_reported_ = false;  // H of the G43 in force (lathe: the T word's offset)
  bool tcp_ = false, dwo_ = false;
  std::shared_ptr<const PlaneFrame> tilted_;  // the plane in force
  int comp_ = 0;
  int comp_register_ = 0;  // the D word of G41/G42 (0: none given)
  bool comp_off_plane_said_ = false;
  int cycle_ = 0;
  int groove_ = 0;
  double groove_retract_ = 0;
  std::vector<Profile> profiles_;
  StockCycle stock_;
  thread_model::Multi multi_;  // G76's first block
  std::vector<std::pair<double, double>> lathe_alias_;  // a lathe code -> system A's number for its function
  bool cycle_on_ = false;
  bool cycle_return_initial_ = true;
  double initial_z_ = kNaN, cyc_bottom_ = kNaN, cyc_r_ = kNaN, cyc_q_ = 0, cyc_p_ = 0;
  mutable double pending_dwell_ = 0;
  int coolant_ = 0;  // the coolants on: 1 flood or mist (M08, M07), 2 through the spindle (M88), 4 air (M83)  // G04 seconds since the last segment (handed to the next one)
  int work_offset_ = 1;
  int tool_ = 0;
  int pending_tool_ = 0;
  double feed_ = 0;
  double spindle_ = 0;
  double max_rpm_ = 0;  // G50 S (lathe)
  bool spindle_on_ = false;
  int spindle_code_ = 0;  // M03 or M04, the last that started the spindle
};

}  // namespace

double combined_length(const Segment& s, const KinematicsSettings& k) {
  double sq = (s.end - s.start).squaredNorm();
  for (size_t i = 0; i < 3; ++i) {
    double d = s.rotary[i] - s.rotary_start[i];
    if (d != d) continue;  // an axis never written (NaN) did not move
    for (const RotaryAxis& r : k.rotaries)
      if (r.name.size() == 1 && size_t(r.name[0] - 'A') == i) d = kin::travel(r, s.rotary_start[i], s.rotary[i]);
    sq += d * d;
  }
  return std::sqrt(sq);
}

struct Reader::Impl : Interp {
  using Interp::Interp;
};

Reader::Reader(const Machine& m, const Options& opt) : impl_(std::make_unique<Impl>(m, opt)) {}
Reader::~Reader() = default;
void Reader::line(std::string_view text) { impl_->feed(text); }
Result& Reader::result() { return impl_->result(); }

Result interpret(std::string_view program, const Machine& m, const Options& opt) {
  Interp in(m, opt);
  return in.run(program);
}

}  // namespace clpc::gcode
