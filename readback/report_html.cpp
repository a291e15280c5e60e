#include "readback/report_html.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "support/text.h"

namespace clpc {

namespace {

std::string fixed(double v, int decimals) {
  if (std::isinf(v)) return "never reached";
  return fixed_text(v, decimals);
}

// Within half the tolerance, within it, beyond it.
const char* colour(double d, double tol) {
  if (d <= 0.5 * tol) return "#1a9850";
  if (d <= tol) return "#f39c12";
  return "#d73027";
}

// One view of the samples: axes (u, v) of the points, drawn in a w x h box.
void map_view(std::ostream& o, const VerifyReport& r, int u, int v, const char* title, int w, int h) {
  double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi[2] = {-lo[0], -lo[1]};
  for (const DeviationSample& s : r.samples) {
    const double p[2] = {s.point[u], s.point[v]};
    for (int k = 0; k < 2; ++k)
      if (std::isfinite(p[k])) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  }
  o << "<figure><figcaption>" << title << "</figcaption><svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << w
    << "\" height=\"" << h << "\" viewBox=\"0 0 " << w << " " << h << "\">"
    << "<rect width=\"100%\" height=\"100%\" fill=\"#fafafa\" stroke=\"#ccc\"/>";
  if (!(lo[0] <= hi[0])) {
    o << "</svg></figure>\n";
    return;
  }
  const double pad = 12, span = std::max({hi[0] - lo[0], hi[1] - lo[1], 1e-9});
  const double scale = std::min((w - 2 * pad) / std::max(hi[0] - lo[0], span * 1e-3), (h - 2 * pad) / std::max(hi[1] - lo[1], span * 1e-3));
  auto x = [&](const DeviationSample& s) { return pad + (s.point[u] - lo[0]) * scale; };
  auto y = [&](const DeviationSample& s) { return h - pad - (s.point[v] - lo[1]) * scale; };
  // The CL path through the points, faint; then the points, good ones first, the worst on top.
  o << "<path fill=\"none\" stroke=\"#bbb\" stroke-width=\"0.6\" d=\"";
  bool pen = false;
  for (const DeviationSample& s : r.samples) {
    if (!std::isfinite(s.point[u]) || !std::isfinite(s.point[v])) {
      pen = false;
      continue;
    }
    char b[64];
    std::snprintf(b, sizeof b, "%c%.1f %.1f ", pen ? 'L' : 'M', x(s), y(s));
    o << b;
    pen = true;
  }
  o << "\"/>";
  for (int pass = 0; pass < 3; ++pass) {
    for (const DeviationSample& s : r.samples) {
      const double d = s.deviation;
      const int kind = d <= 0.5 * r.tolerance ? 0 : d <= r.tolerance ? 1 : 2;
      if (kind != pass || !std::isfinite(s.point[u]) || !std::isfinite(s.point[v])) continue;
      char b[160];
      std::snprintf(b, sizeof b, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%s\" fill=\"%s\"/>", x(s), y(s), kind ? "2.5" : "1.2",
                    colour(d, r.tolerance));
      o << b;
    }
  }
  o << "</svg></figure>\n";
}

}  // namespace

void write_report_html(std::ostream& o, const VerifyReport& r, const std::string& backplot_svg) {
  const char* u = r.units == ir::Units::Inch ? "in" : "mm";
  const int dec = r.units == ir::Units::Inch ? 5 : 4;
  std::ostringstream summary;
  print_report(summary, r);
  o << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>clpc verify: " << xml_text(r.input) << "</title>\n"
    << "<style>body{font-family:sans-serif;margin:2em;color:#222}table{border-collapse:collapse}"
       "td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}td.l,th.l{text-align:left}"
       "pre{background:#f4f4f4;padding:1em}figure{display:inline-block;margin:0 1em 1em 0}"
       ".key span{display:inline-block;width:1em;height:1em;margin:0 .3em 0 1em;vertical-align:middle}</style></head><body>\n";
  o << "<h1>clpc verify: " << xml_text(r.input) << " on " << xml_text(r.machine) << " — " << (r.ok ? "PASS" : "FAIL") << "</h1>\n";
  o << "<pre>" << xml_text(summary.str()) << "</pre>\n";

  o << "<h2>Operations</h2>\n<table><tr><th>#</th><th class=\"l\">operation</th><th>tool</th><th>CL line</th><th>points</th>"
       "<th>arcs</th><th>holes</th><th>groove cuts</th><th>max deviation (" << u << ")</th><th>at CL line</th><th>G-code line</th>"
       "<th>problems</th></tr>\n";
  for (const OperationCheck& op : r.operations) {
    o << "<tr><td>" << op.number << "</td><td class=\"l\">" << xml_text(op.name.empty() ? "(unnamed)" : op.name) << "</td><td>"
      << (op.tool ? "T" + std::to_string(op.tool) : std::string()) << "</td><td>" << op.loc.line << "</td><td>" << op.points
      << "</td><td>" << op.arcs << "</td><td>" << op.holes << "</td><td>" << op.groove_points << "</td><td style=\"background:"
      << colour(op.max_deviation, r.tolerance) << "33\">" << fixed(op.max_deviation, dec) << "</td><td>"
      << (op.max_loc.valid() ? std::to_string(op.max_loc.line) : "") << "</td><td>"
      << (op.max_gcode_line ? std::to_string(op.max_gcode_line) : "") << "</td><td>" << op.problems << "</td></tr>\n";
  }
  o << "</table>\n";

  if (!r.problems.empty()) {
    o << "<h2>Problems</h2>\n<table><tr><th>CL line</th><th>G-code line</th><th class=\"l\">what</th></tr>\n";
    for (const VerifyProblem& p : r.problems)
      o << "<tr><td>" << p.loc.line << "</td><td>" << (p.gcode_line ? std::to_string(p.gcode_line) : "") << "</td><td class=\"l\">"
        << xml_text(p.message) << "</td></tr>\n";
    o << "</table>\n";
    if (r.problem_count > long(r.problems.size())) o << "<p>… and " << r.problem_count - long(r.problems.size()) << " more.</p>\n";
  }

  o << "<h2>Deviation at each CL point</h2>\n<p class=\"key\"><span style=\"background:#1a9850\"></span>within half the "
       "tolerance<span style=\"background:#f39c12\"></span>within the tolerance (" << fixed(r.tolerance, dec) << " " << u
    << ")<span style=\"background:#d73027\"></span>beyond it";
  if (r.sample_stride > 1) o << " — every " << r.sample_stride << "th point shown";
  o << "</p>\n";
  map_view(o, r, 0, 1, "top (X right, Y up)", 560, 420);
  map_view(o, r, 0, 2, "front (X right, Z up)", 560, 420);

  if (!backplot_svg.empty()) {
    // The backplot as clpc plot draws it, its XML declaration dropped to sit inline.
    std::string svg = backplot_svg;
    if (svg.rfind("<?xml", 0) == 0) svg.erase(0, svg.find("?>") + 2);
    svg.erase(0, svg.find_first_not_of(" \r\n"));
    o << "<h2>Backplot</h2>\n" << svg << "\n";
  }
  o << "</body></html>\n";
}

}  // namespace clpc
