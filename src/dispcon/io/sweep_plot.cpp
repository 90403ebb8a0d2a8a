#include "dispcon/io/sweep_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace dispcon {

std::string write_sweep_svg(const Model& model, const SweepResult& r) {
  const double W = 760, H = 420, left = 60, right = 170, top = 30, bottom = 50;
  double x0 = 0, x1 = 1, y0 = 0, y1 = 0;
  bool any = false;
  if (!r.samples.empty()) {
    x0 = r.samples.front().value;
    x1 = r.samples.back().value;
    if (x1 == x0) x1 = x0 + 1;
  }
  for (const SweepSample& s : r.samples) {
    for (double v : s.joint_values) {
      if (!std::isfinite(v)) continue;
      y0 = any ? std::min(y0, v) : v;
      y1 = any ? std::max(y1, v) : v;
      any = true;
    }
  }
  if (y1 - y0 < 1e-9) y0 -= 1, y1 += 1;
  const double pw = W - left - right, ph = H - top - bottom;
  auto X = [&](double x) { return left + (x - x0) / (x1 - x0) * pw; };
  auto Y = [&](double y) { return top + (y1 - y) / (y1 - y0) * ph; };
  const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                           "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f"};
  std::ostringstream out;
  char buf[512];
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" "
         "fill=\"white\"/>\n";
  std::snprintf(buf, sizeof buf,
                "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" "
                "stroke=\"#888\"/>\n",
                left, top, pw, ph);
  out << buf;
  std::snprintf(buf, sizeof buf,
                "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">driven angle (rad)</text>\n",
                left + pw / 2, H - 12);
  out << buf;
  std::snprintf(buf, sizeof buf,
                "<text x=\"10\" y=\"%.1f\" transform=\"rotate(-90 10 %.1f)\" "
                "text-anchor=\"middle\">joint value (rad or length)</text>\n",
                top + ph / 2, top + ph / 2);
  out << buf;
  for (int t = 0; t <= 4; ++t) {
    const double xv = x0 + (x1 - x0) * t / 4, yv = y0 + (y1 - y0) * t / 4;
    std::snprintf(buf, sizeof buf,
                  "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">%.3g</text>\n", X(xv),
                  top + ph + 16, xv);
    out << buf;
    std::snprintf(buf, sizeof buf, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">%.3g</text>\n",
                  left - 4, Y(yv) + 4, yv);
    out << buf;
  }
  const size_t joints = r.samples.empty() ? 0 : r.samples.front().joint_values.size();
  int legend = 0;
  for (size_t j = 0; j < joints; ++j) {
    std::string path;
    for (const SweepSample& s : r.samples) {
      const double v = s.joint_values[j];
      if (!std::isfinite(v)) continue;
      std::snprintf(buf, sizeof buf, "%.1f,%.1f ", X(s.value), Y(v));
      path += buf;
    }
    if (path.empty()) continue;
    const char* colour = colours[j % 10];
    out << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"2\" points=\""
        << path << "\"/>\n";
    const Joint& jt = model.joint(JointId{static_cast<int>(j)});
    // Names can be long: no fixed buffer for them.
    out << "<text x=\"" << W - right + 10 << "\" y=\"" << top + 14.0 * ++legend << "\" fill=\""
        << colour << "\">#" << j << " " << model.body(jt.body1).name << "/"
        << model.body(jt.body2).name << "</text>\n";
  }
  for (const SweepSample& s : r.samples) {
    if (s.limits_active.empty()) continue;
    std::snprintf(buf, sizeof buf,
                  "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"2\" fill=\"#000\"><title>limit in "
                  "contact</title></circle>\n",
                  X(s.value), top + ph - 4);
    out << buf;
  }
  if (r.locked) {
    std::snprintf(
        buf, sizeof buf,
        "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"red\" "
        "stroke-dasharray=\"6 4\"/>\n"
        "<text x=\"%.1f\" y=\"%.1f\" fill=\"red\" text-anchor=\"end\">locks at %.4g</text>\n",
        X(r.lock_value), top, X(r.lock_value), top + ph, X(r.lock_value) - 4, top + ph - 8,
        r.lock_value);
    out << buf;
  }
  out << "</svg>\n";
  return out.str();
}

}  // namespace dispcon
