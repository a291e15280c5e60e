// clpc plot. The program is read back twice (readback/program_reader.cpp): once for the extent of the
// path, once to draw it, so memory does not grow with the program. Each view is an
// orthographic projection of the part frame; a circular arc projects to an elliptical arc,
// which SVG draws exactly (rx = r, ry = r |n . d|, turned to the projected major axis); arcs
// seen edge-on and helices are drawn as polylines. Points closer than a third of a pixel to
// the last one drawn are merged, so the file stays the size of the drawing, not the program.
#include "readback/plot.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <vector>

#include "support/output.h"
#include "readback/program_reader.h"
#include "ir/arc_geometry.h"
#include "support/text.h"
#include "support/source.h"

namespace clpc {

using ir::Vec3;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMergePx = 0.33;

const char* kFeedColour = "#1565c0";
const char* kRapidColour = "#e65100";
const char* kToolColour = "#2e7d32";

bool finite(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

void num(std::string& o, double v) {
  char b[32];
  int n = std::snprintf(b, sizeof b, "%.1f", std::abs(v) < 0.05 ? 0.0 : v);
  o.append(b, size_t(n));
}

struct Box {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = Vec3::Constant(-std::numeric_limits<double>::infinity());
  void add(const Vec3& p) {
    if (!finite(p)) return;
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool empty() const { return !(lo.x() <= hi.x()); }
};

// One view: screen right u, screen up v (part frame), toward the viewer d = u x v.
class View {
 public:
  View(std::string name, Vec3 u, Vec3 v, double x, double y, double w, double h) : name_(std::move(name)), u_(u), v_(v), d_(u.cross(v)), x_(x), y_(y), w_(w), h_(h) {}

  void fit(const Box& b) {
    double ulo = 1e300, uhi = -1e300, vlo = 1e300, vhi = -1e300;
    for (int i = 0; i < 8; ++i) {
      Vec3 c((i & 1) ? b.hi.x() : b.lo.x(), (i & 2) ? b.hi.y() : b.lo.y(), (i & 4) ? b.hi.z() : b.lo.z());
      ulo = std::min(ulo, c.dot(u_)), uhi = std::max(uhi, c.dot(u_));
      vlo = std::min(vlo, c.dot(v_)), vhi = std::max(vhi, c.dot(v_));
    }
    const double margin = 24, top = 22;  // room for the view's name
    double sw = std::max(uhi - ulo, 1e-9), sh = std::max(vhi - vlo, 1e-9);
    scale_ = std::min((w_ - 2 * margin) / sw, (h_ - 2 * margin - top) / sh);
    if (!std::isfinite(scale_) || scale_ <= 0) scale_ = 1;
    // Centred in the panel.
    ox_ = x_ + w_ / 2 - (ulo + uhi) / 2 * scale_;
    oy_ = y_ + top / 2 + h_ / 2 + (vlo + vhi) / 2 * scale_;
  }

  double sx(const Vec3& p) const { return ox_ + p.dot(u_) * scale_; }
  double sy(const Vec3& p) const { return oy_ - p.dot(v_) * scale_; }

  // Adds a segment to the feed or rapid path.
  void line(const Vec3& a, const Vec3& b, bool rapid) {
    Pen& pen = rapid ? rapid_ : feed_;
    move_to(pen, a);
    pen_to(pen, sx(b), sy(b), false);
  }

  // A circular arc (part frame): an SVG elliptical arc where the projection is one.
  void arc(const Vec3& start, const Vec3& end, const Vec3& centre, const Vec3& normal, double r, bool ccw, double sweep_deg,
           bool helical) {
    Pen& pen = feed_;
    move_to(pen, start);
    const double nd = normal.dot(d_);
    const bool edge_on = std::abs(nd) < 1e-3;
    if (helical || edge_on || r * scale_ < 1.0) {
      const int n = std::max(2, int(std::ceil(sweep_deg / 5)));
      ir::Arc a;
      a.start = start;
      a.end = end;
      a.center = centre;
      a.axis = normal;
      a.radius = r;
      a.dir = ccw ? ir::ArcDir::Ccw : ir::ArcDir::Cw;
      a.sweep = sweep_deg;
      for (int i = 1; i <= n; ++i) {
        Vec3 p = arcgeo::point_at(a, double(i) / n);
        pen_to(pen, sx(p), sy(p), false);
      }
      return;
    }
    flush(pen);
    // The circle's diameter perpendicular to the view direction keeps its length: the major
    // axis; the minor is shortened by |n . d|.
    Vec3 w = normal.cross(d_);
    double rotation = 0;
    if (w.norm() > 1e-9) {
      w.normalize();
      rotation = std::atan2(-w.dot(v_), w.dot(u_)) * 180 / kPi;
    }
    const double rx = r * scale_, ry = r * std::abs(nd) * scale_;
    // Counter-clockwise about n looks counter-clockwise from the viewer when n faces them;
    // the screen's y points down, so that is SVG's negative sweep.
    const bool ccw_on_screen = ccw == (nd > 0);
    const int sweep_flag = ccw_on_screen ? 0 : 1;
    auto arc_to = [&](const Vec3& p, bool large) {
      pen.d += 'A';
      num(pen.d, rx);
      pen.d += ' ';
      num(pen.d, ry);
      pen.d += ' ';
      num(pen.d, rotation);
      pen.d += large ? " 1 " : " 0 ";
      pen.d += char('0' + sweep_flag);
      pen.d += ' ';
      num(pen.d, sx(p));
      pen.d += ' ';
      num(pen.d, sy(p));
      pen.x = sx(p);
      pen.y = sy(p);
    };
    if (sweep_deg >= 359.999) {
      // A full circle: two halves (an SVG arc to its own start draws nothing).
      Vec3 half = centre + Eigen::AngleAxisd((ccw ? 1 : -1) * kPi, normal) * (start - centre);
      arc_to(half, false);
      arc_to(end, false);
    } else {
      arc_to(end, sweep_deg > 180);
    }
    ++arcs_drawn_;
  }

  void marker(const Vec3& p, const std::string& label) {
    if (!finite(p)) return;
    markers_ += "<circle cx=\"";
    num(markers_, sx(p));
    markers_ += "\" cy=\"";
    num(markers_, sy(p));
    markers_ += "\" r=\"4\"/><text x=\"";
    num(markers_, sx(p) + 6);
    markers_ += "\" y=\"";
    num(markers_, sy(p) - 6);
    markers_ += "\">" + xml_text(label) + "</text>";
  }

  void write(std::string& o) {
    flush(feed_);
    flush(rapid_);
    o += "<g class=\"view\" id=\"" + name_ + "\">\n<rect class=\"panel\" x=\"";
    num(o, x_ + 4);
    o += "\" y=\"";
    num(o, y_ + 4);
    o += "\" width=\"";
    num(o, w_ - 8);
    o += "\" height=\"";
    num(o, h_ - 8);
    o += "\"/>\n<text class=\"label\" x=\"";
    num(o, x_ + 14);
    o += "\" y=\"";
    num(o, y_ + 22);
    o += "\">" + name_ + "</text>\n";
    if (!rapid_.d.empty()) o += "<path class=\"rapid\" d=\"" + rapid_.d + "\"/>\n";
    if (!feed_.d.empty()) o += "<path class=\"feed\" d=\"" + feed_.d + "\"/>\n";
    if (!markers_.empty()) o += "<g class=\"tool\">" + markers_ + "</g>\n";
    o += "</g>\n";
  }

  long arcs_drawn() const { return arcs_drawn_; }

 private:
  struct Pen {
    std::string d;
    double x = std::nan(""), y = std::nan("");  // where the path is
    bool pending = false;                        // a merged point not yet written
    double px = 0, py = 0;
  };

  void move_to(Pen& pen, const Vec3& a) {
    double x = sx(a), y = sy(a);
    double cx = pen.pending ? pen.px : pen.x, cy = pen.pending ? pen.py : pen.y;
    if (std::isfinite(cx) && std::hypot(x - cx, y - cy) <= kMergePx) return;  // continues
    flush(pen);
    pen.d += 'M';
    num(pen.d, x);
    pen.d += ' ';
    num(pen.d, y);
    pen.x = x;
    pen.y = y;
  }

  void pen_to(Pen& pen, double x, double y, bool force) {
    if (!force && std::hypot(x - pen.x, y - pen.y) < kMergePx) {
      pen.pending = true;
      pen.px = x;
      pen.py = y;
      return;
    }
    pen.pending = false;
    pen.d += 'L';
    num(pen.d, x);
    pen.d += ' ';
    num(pen.d, y);
    pen.x = x;
    pen.y = y;
  }

  void flush(Pen& pen) {
    if (pen.pending && std::hypot(pen.px - pen.x, pen.py - pen.y) >= 0.05) pen_to(pen, pen.px, pen.py, true);
    pen.pending = false;
  }

  std::string name_;
  Vec3 u_, v_, d_;
  double x_, y_, w_, h_;
  double scale_ = 1, ox_ = 0, oy_ = 0;
  Pen feed_, rapid_;
  std::string markers_;
  long arcs_drawn_ = 0;
};

}  // namespace

PlotResult plot_program(const std::string& program, const std::string& input, const ir::ProgramInfo& info,
                        const std::string& output, const Machine& m, const PlotOptions& opt, std::ostream& err) {
  PlotResult res;
  std::string why;

  // Pass 1: the extent.
  Box box;
  {
    ProgramReader rd(m, info);
    if (!rd.open(program, why)) {
      err << "clpc: error: " << why << "\n";
      return res;
    }
    TipSegment s;
    while (rd.next(s)) {
      if (!finite(s.start)) continue;
      box.add(s.start);
      box.add(s.end);
      if (s.raw.kind == gcode::Segment::Kind::Arc) {
        // The arc's extreme points lie within its circle's box.
        for (int i = 0; i < 3; ++i) {
          Vec3 e = Vec3::Zero();
          e[i] = s.raw.start_radius * std::sqrt(std::max(0.0, 1 - s.normal[i] * s.normal[i]));
          box.add(s.center + e);
          box.add(s.center - e);
        }
      }
    }
  }
  if (box.empty()) {
    err << "clpc: error: the program has no motion to plot\n";
    return res;
  }

  // The views: four panels for a mill, one for a lathe (Z across, X up, seen from +Y).
  const double W = opt.width, H = opt.height, top = 40;
  std::vector<View> views;
  if (m.is_lathe()) {
    views.emplace_back("XZ", Vec3::UnitZ(), Vec3::UnitX(), 0, top, W, H - top);
  } else {
    const double w = W / 2, h = (H - top) / 2;
    views.emplace_back("top", Vec3::UnitX(), Vec3::UnitY(), 0, top, w, h);
    views.emplace_back("isometric", Vec3(1, 1, 0).normalized(), Vec3(-1, 1, 2).normalized(), w, top, w, h);
    views.emplace_back("front", Vec3::UnitX(), Vec3::UnitZ(), 0, top + h, w, h);
    views.emplace_back("side", Vec3::UnitY(), Vec3::UnitZ(), w, top + h, w, h);
  }
  for (View& v : views) v.fit(box);

  // Pass 2: draw.
  ProgramReader rd(m, info);
  if (!rd.open(program, why)) {
    err << "clpc: error: " << why << "\n";
    return res;
  }
  TipSegment s;
  int tool = -1;
  while (rd.next(s)) {
    const bool rapid = s.raw.kind == gcode::Segment::Kind::Rapid;
    if (s.raw.tool != tool && finite(s.end)) {
      tool = s.raw.tool;
      for (View& v : views) v.marker(s.end, "T" + std::to_string(tool));
    }
    if (!finite(s.start) || !finite(s.end)) continue;
    if (s.raw.kind == gcode::Segment::Kind::Arc) {
      const bool helical = std::abs((s.end - s.start).dot(s.normal)) > 1e-9;
      for (View& v : views) v.arc(s.start, s.end, s.center, s.normal, s.raw.start_radius, s.raw.ccw, s.raw.sweep, helical);
    } else if (s.rotates && !rapid) {
      // Five-axis without TCPC: the tip's path curves as the rotaries turn.
      Vec3 a = s.start;
      for (int i = 1; i <= 8; ++i) {
        Vec3 b = rd.tip_at(s, i / 8.0);
        for (View& v : views) v.line(a, b, false);
        a = b;
      }
    } else {
      for (View& v : views) v.line(s.start, s.end, rapid);
    }
  }
  const ProgramTotals& t = rd.totals();
  res.feeds = t.feeds;
  res.rapids = t.rapids;
  res.arcs = t.arcs;
  res.tool_changes = t.tool_changes;

  std::string o;
  o.reserve(1 << 16);
  o += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  o += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(opt.width) + "\" height=\"" +
       std::to_string(opt.height) + "\" viewBox=\"0 0 " + std::to_string(opt.width) + " " + std::to_string(opt.height) + "\">\n";
  o += "<style>\n"
       "text { font: 13px sans-serif; fill: #333; }\n"
       ".panel { fill: #fafafa; stroke: #ccc; }\n"
       ".label { font-weight: bold; }\n"
       ".feed { fill: none; stroke: " + std::string(kFeedColour) + "; stroke-width: 1; stroke-linejoin: round; }\n"
       ".rapid { fill: none; stroke: " + std::string(kRapidColour) + "; stroke-width: 0.8; stroke-dasharray: 4 3; }\n"
       ".tool circle { fill: " + std::string(kToolColour) + "; }\n"
       ".tool text { fill: " + std::string(kToolColour) + "; font-size: 11px; }\n"
       "</style>\n";
  o += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  const char* u = m.units == ir::Units::Inch ? "in" : "mm";
  std::string base = input;
  if (size_t sl = base.rfind('/'); sl != std::string::npos) base = base.substr(sl + 1);
  char extent[160];
  std::snprintf(extent, sizeof extent, "X %.3f..%.3f  Y %.3f..%.3f  Z %.3f..%.3f %s", box.lo.x(), box.hi.x(), box.lo.y(), box.hi.y(),
                box.lo.z(), box.hi.z(), u);
  o += "<text x=\"12\" y=\"18\"><tspan font-weight=\"bold\">" + xml_text(base) + "</tspan> on " + xml_text(m.name) + " — " +
       std::to_string(t.feeds) + " feeds, " + std::to_string(t.arcs) + " arcs, " + std::to_string(t.rapids) + " rapids, " +
       std::to_string(t.tool_changes) + " tool changes</text>\n";
  o += "<text x=\"12\" y=\"34\">" + std::string(extent) + " (part frame)</text>\n";
  // Legend.
  const double lx = W - 330;
  o += "<g class=\"legend\"><line x1=\"" + std::to_string(int(lx)) + "\" y1=\"14\" x2=\"" + std::to_string(int(lx + 30)) +
       "\" y2=\"14\" class=\"feed\"/><text x=\"" + std::to_string(int(lx + 36)) + "\" y=\"18\">feed</text>";
  o += "<line x1=\"" + std::to_string(int(lx + 90)) + "\" y1=\"14\" x2=\"" + std::to_string(int(lx + 120)) +
       "\" y2=\"14\" class=\"rapid\"/><text x=\"" + std::to_string(int(lx + 126)) + "\" y=\"18\">rapid</text>";
  o += "<g class=\"tool\"><circle cx=\"" + std::to_string(int(lx + 190)) + "\" cy=\"14\" r=\"4\"/><text x=\"" +
       std::to_string(int(lx + 198)) + "\" y=\"18\">tool change</text></g></g>\n";
  for (View& v : views) v.write(o);
  o += "</svg>\n";

  OutputFile out;
  if (!out.open(output, why)) {
    err << "clpc: error: " << why << "\n";
    return res;
  }
  out.write(o);
  if (!out.commit(why)) {
    err << "clpc: error: " << why << "\n";
    return res;
  }
  res.ok = true;
  return res;
}

}  // namespace clpc
