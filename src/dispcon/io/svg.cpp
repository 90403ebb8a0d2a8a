#include "dispcon/io/svg.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace dispcon {

namespace {

// Every body's drawing points, local: its centre and the points its joints hold.
std::vector<std::vector<Vec3>> outlines(const Model& model) {
  std::vector<std::vector<Vec3>> pts(static_cast<size_t>(model.body_count()));
  for (int i = 1; i < model.body_count(); ++i)
    pts[static_cast<size_t>(i)].push_back(model.body(BodyId{i}).center);
  for (const Joint& j : model.joints()) {
    if (!j.has_translation()) continue;
    if (j.body1.value > 0) pts[static_cast<size_t>(j.body1.value)].push_back(j.p1);
    pts[static_cast<size_t>(j.body2.value)].push_back(j.p2);
  }
  return pts;
}

const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                          "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f"};

}  // namespace

std::string write_poses_svg(const Model& model, const std::vector<std::vector<Pose>>& frames,
                            double seconds) {
  const auto pts = outlines(model);
  // The plane of largest extent: drop the axis along which the drawing moves least.
  Eigen::AlignedBox3d box;
  for (const auto& poses : frames) {
    for (int i = 1; i < model.body_count(); ++i) {
      for (const Vec3& p : pts[static_cast<size_t>(i)])
        box.extend(poses[static_cast<size_t>(i)].apply(p));
    }
  }
  if (box.isEmpty()) box.extend(Vec3::Zero());
  const Vec3 size = box.sizes();
  int drop = 0;
  for (int k = 1; k < 3; ++k) {
    if (size[k] < size[drop]) drop = k;
  }
  const int u = drop == 0 ? 1 : 0;
  const int v = drop == 2 ? 1 : 2;
  const double w = std::max(size[u], 1e-9), h = std::max(size[v], 1e-9);
  const double scale = 560.0 / std::max(w, h);
  const double W = w * scale + 40, H = h * scale + 40;
  auto project = [&](const Vec3& p, double& x, double& y) {
    x = 20 + (p[u] - box.min()[u]) * scale;
    y = 20 + (box.max()[v] - p[v]) * scale;  // up is up
  };
  std::ostringstream out;
  char buf[128];
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
      << "\" viewBox=\"0 0 " << W << " " << H << "\">\n";
  out << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  const double dur = std::max(seconds, 0.1);
  for (int i = 1; i < model.body_count(); ++i) {
    const auto& local = pts[static_cast<size_t>(i)];
    auto points = [&](const std::vector<Pose>& poses) {
      std::string s;
      // A star from the centre to every held point: how a link looks.
      for (size_t k = 1; k < local.size() || k == 1; ++k) {
        double x0, y0, x1, y1;
        project(poses[static_cast<size_t>(i)].apply(local[0]), x0, y0);
        project(poses[static_cast<size_t>(i)].apply(local[std::min(k, local.size() - 1)]), x1, y1);
        std::snprintf(buf, sizeof buf, "%.1f,%.1f %.1f,%.1f ", x0, y0, x1, y1);
        s += buf;
        if (local.size() <= 1) break;
      }
      return s;
    };
    const char* colour = kColours[(i - 1) % 10];
    out << "<polyline fill=\"none\" stroke=\"" << colour
        << "\" stroke-width=\"4\" stroke-linecap=\"round\" stroke-linejoin=\"round\" points=\""
        << (frames.empty() ? "" : points(frames.front())) << "\">";
    if (frames.size() > 1) {
      out << "<animate attributeName=\"points\" dur=\"" << dur
          << "s\" repeatCount=\"indefinite\" values=\"";
      for (size_t f = 0; f < frames.size(); ++f) out << (f ? ";" : "") << points(frames[f]);
      out << "\"/>";
    }
    out << "<title>" << model.body(BodyId{i}).name << "</title></polyline>\n";
  }
  out << "</svg>\n";
  return out.str();
}

std::string write_animation_svg(const Model& model, const AnimateResult& result) {
  std::vector<std::vector<Pose>> frames;
  for (const Frame& f : result.frames) frames.push_back(f.poses);
  return write_poses_svg(model, frames, result.frames.empty() ? 1.0 : result.frames.back().time);
}

}  // namespace dispcon
