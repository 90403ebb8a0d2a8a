// The reach bound of a held body: shortest paths through point-to-point joints, and the pose
// stretched along one (reach.hpp).
#include "dispcon/solve/reach.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

#include "dispcon/solve/state.hpp"

namespace dispcon {

namespace {

// A guide whose set ReachBound::Anchor can hold: a point is kept on it, whatever the rotations.
bool bounds_a_point(GuideKind kind) {
  return kind == GuideKind::Axial || kind == GuideKind::Planar || kind == GuideKind::Sphere ||
         kind == GuideKind::Circle;
}

}  // namespace

Vec3 ReachBound::Anchor::nearest(const Vec3& x) const {
  if (!guide) return centre();
  const Vec3 local = frame.q.conjugate() * (x - frame.x);
  return frame.apply(nearest_on_guide(p1, &*guide, local).q);
}

ReachBound::ReachBound(const Model& model, BodyId held, double time)
    : held_(held), revision_(model.revision()) {
  std::vector<Node>& nodes = nodes_;
  joined_.resize(static_cast<size_t>(model.body_count()));
  auto immovable = [&](int body) { return body == 0 || model.body(BodyId{body}).fixed; };
  for (int c = 0; c < model.joint_count(); ++c) {
    const Joint& j = model.joint(JointId{c});
    if (!j.active_at(time)) continue;
    joined_[static_cast<size_t>(j.body1.value)].push_back(j.body2.value);
    joined_[static_cast<size_t>(j.body2.value)].push_back(j.body1.value);
    // A guide is a path's end only where its set cannot move: between moving parts the set's
    // points are at any distance from each other.
    const bool guide = j.guide && bounds_a_point(j.guide->kind) && immovable(j.body1.value) &&
                       !immovable(j.body2.value);
    if (!(j.has_hinge || guide) || (j.guide && !guide)) continue;
    nodes.push_back(Node{j.body1.value, j.p1, c, guide});
    nodes.push_back(Node{j.body2.value, j.p2, c, guide});
  }
  // The nodes of each body, so a path crosses a body from any of its points to any other.
  std::vector<std::vector<int>> on_body(static_cast<size_t>(model.body_count()));
  for (size_t k = 0; k < nodes.size(); ++k)
    on_body[static_cast<size_t>(nodes[k].body)].push_back(static_cast<int>(k));
  // What a path ending at node n (on a part that cannot move) ends on.
  auto anchor = [&](const Node& n) {
    Anchor a{model.body(BodyId{n.body}).pose, n.local, std::nullopt};
    if (n.guide) a.guide = model.joint(JointId{n.joint}).guide;
    return a;
  };

  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> dist(nodes.size());
  std::vector<int> hops(nodes.size()), first(nodes.size());
  using Item = std::pair<double, int>;
  for (int source : on_body[static_cast<size_t>(held.value)]) {
    std::fill(dist.begin(), dist.end(), inf);
    std::vector<int>& from = from_.emplace_back(nodes.size(), -1);
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    // Leaving the held body through the source's joint: its node on the other body, at no length.
    const int out = source ^ 1;
    dist[static_cast<size_t>(out)] = 0;
    hops[static_cast<size_t>(out)] = 1;
    first[static_cast<size_t>(out)] = nodes[static_cast<size_t>(source)].joint;
    queue.push({0.0, out});
    while (!queue.empty()) {
      const auto [d, k] = queue.top();
      queue.pop();
      const Node& n = nodes[static_cast<size_t>(k)];
      if (d > dist[static_cast<size_t>(k)] || n.body == held.value) continue;
      if (immovable(n.body)) {
        paths_.push_back(Path{nodes[static_cast<size_t>(source)].local, anchor(n), d,
                              hops[static_cast<size_t>(k)], JointId{first[static_cast<size_t>(k)]},
                              static_cast<int>(from_.size()) - 1, k});
        continue;  // a path through what cannot move says nothing more
      }
      // Across the body to each of its other points, then through that point's joint.
      for (int other : on_body[static_cast<size_t>(n.body)]) {
        if (other == k) continue;
        const int next = other ^ 1;
        const double nd = d + (nodes[static_cast<size_t>(other)].local - n.local).norm();
        if (nd < dist[static_cast<size_t>(next)]) {
          dist[static_cast<size_t>(next)] = nd;
          hops[static_cast<size_t>(next)] = hops[static_cast<size_t>(k)] + 1;
          first[static_cast<size_t>(next)] = first[static_cast<size_t>(k)];
          from[static_cast<size_t>(next)] = k;
          queue.push({nd, next});
        }
      }
    }
  }
}

ReachBound::Gap ReachBound::gap(const Pose& target, double tolerance) const {
  Gap worst;
  for (const Path& p : paths_) {
    const Vec3 x = target.apply(p.held_point);
    const double g = (x - p.anchor.nearest(x)).norm() - p.length;
    if (g > p.joints * tolerance && g > worst.distance) worst = Gap{g, p.first, p.joints};
  }
  return worst;
}

std::optional<ReachBound::Stretch> ReachBound::stretch(const Model& model,
                                                       const std::vector<Pose>& poses,
                                                       const Vec3& point, const Vec3& target,
                                                       const SolveOptions& options) const {
  // The path that falls shortest of the target with the held body free to turn: its joint point
  // and `point` add their distance to the path's length.
  const Path* path = nullptr;
  double worst = 0;
  for (const Path& p : paths_) {
    const double g =
        (target - p.anchor.nearest(target)).norm() - p.length - (point - p.held_point).norm();
    if (g > p.joints * options.tolerance && g > worst) worst = g, path = &p;
  }
  if (!path) return std::nullopt;
  // On a guide's set the path leaves from the set's point nearest the target: no valid pose
  // takes the point nearer than the path's length from it.
  const Vec3 from = path->anchor.nearest(target);
  const Vec3 u = (target - from).normalized();
  Stretch out;
  out.poses = poses;
  out.gap = Gap{worst, path->first, path->joints};
  // Each body's motion (its old pose to its new), for what hangs off it: -1 for a body that
  // keeps its pose, else the path body whose motion it takes.
  std::vector<int> moved_with(poses.size(), -1);
  auto turn = [&](int body, const Vec3& near, const Vec3& far, const Vec3& at) {
    // `near` (local) goes to `at`, `far` (local) beyond it along u.
    Pose& p = out.poses[static_cast<size_t>(body)];
    const Vec3 v = p.q * (far - near);
    if (v.norm() > 0) p.q = (Quat::FromTwoVectors(v, u) * p.q).normalized();
    p.x = at - p.q * near;
    moved_with[static_cast<size_t>(body)] = body;
    return at + (far - near).norm() * u;
  };
  Vec3 at = from;
  for (const Link& l : links(*path)) at = turn(l.body, l.near, l.far, at);
  at = turn(held_.value, path->held_point, point, at);
  if (!carry(model, poses, out.poses, moved_with, options, out.constraints)) return std::nullopt;
  out.distance = (out.poses[static_cast<size_t>(held_.value)].apply(point) - target).norm();
  return out;
}

std::vector<ReachBound::Link> ReachBound::links(const Path& path) const {
  // From the anchor back to the held body: body k is entered at node from[cur] (toward the held
  // body) and left at node cur ^ 1 (toward the anchor), which the joint ties to cur.
  const std::vector<int>& from = from_[static_cast<size_t>(path.source)];
  std::vector<Link> out;
  int cur = path.end;
  while (from[static_cast<size_t>(cur)] >= 0) {
    const int k = from[static_cast<size_t>(cur)];
    const Node& leave = nodes_[static_cast<size_t>(cur ^ 1)];
    out.push_back(Link{leave.body, leave.local, nodes_[static_cast<size_t>(k)].local});
    cur = k;
  }
  return out;
}

bool ReachBound::carry(const Model& model, const std::vector<Pose>& poses, std::vector<Pose>& out,
                       std::vector<int>& moved_with, const SolveOptions& options,
                       std::vector<ConstraintReport>& constraints) const {
  // What hangs off the path moves with the path body it hangs from (the first reached).
  std::vector<int> queue;
  for (size_t b = 0; b < moved_with.size(); ++b) {
    if (moved_with[b] >= 0) queue.push_back(static_cast<int>(b));
  }
  for (size_t next = 0; next < queue.size(); ++next) {
    const int b = queue[next];
    for (int o : joined_[static_cast<size_t>(b)]) {
      if (o == 0 || model.body(BodyId{o}).fixed || moved_with[static_cast<size_t>(o)] >= 0) {
        continue;
      }
      moved_with[static_cast<size_t>(o)] = moved_with[static_cast<size_t>(b)];
      queue.push_back(o);
    }
  }
  for (size_t b = 0; b < moved_with.size(); ++b) {
    const int w = moved_with[b];
    if (w < 0 || w == static_cast<int>(b)) continue;
    // The motion of w: its old pose to its new, applied to b.
    const Pose& old_w = poses[static_cast<size_t>(w)];
    const Pose& new_w = out[static_cast<size_t>(w)];
    const Quat turned = new_w.q * old_w.q.conjugate();
    Pose& p = out[b];
    p.x = new_w.x + turned * (poses[b].x - old_w.x);
    p.q = (turned * poses[b].q).normalized();
  }
  constraints = measure(model, out, options);
  for (const ConstraintReport& c : constraints) {
    if (!c.satisfied) return false;
  }
  return true;
}

std::optional<std::vector<Pose>> ReachBound::straighten(const Model& model,
                                                        const std::vector<Pose>& poses,
                                                        const Pose& target,
                                                        const SolveOptions& options) const {
  // The path with the least slack at the target.
  const Path* path = nullptr;
  double least = HUGE_VAL;
  for (const Path& p : paths_) {
    // (A path that ends on a guide's set is straightened about no point: left out.)
    if (p.anchor.guide) continue;
    const double slack = p.length - (target.apply(p.held_point) - p.anchor.centre()).norm();
    if (slack < least) least = slack, path = &p;
  }
  if (!path) return std::nullopt;
  const std::vector<Link> path_links = links(*path);
  // Each body's length along the path and direction now, split along u (the line from the
  // anchor to the path's end) and across it.
  const size_t n = path_links.size();
  std::vector<double> length(n), along(n);
  std::vector<Vec3> across(n), dir(n);
  Vec3 end = Vec3::Zero();
  for (size_t k = 0; k < n; ++k) {
    const Link& l = path_links[k];
    const Vec3 v = poses[static_cast<size_t>(l.body)].q * (l.far - l.near);
    length[k] = v.norm();
    dir[k] = length[k] > 0 ? Vec3(v / length[k]) : Vec3::Zero();
    end += v;
  }
  const Vec3 goal = target.apply(path->held_point) - path->anchor.centre();
  if (!(end.norm() > 0) || !(goal.norm() > 0)) return std::nullopt;
  const Vec3 u = end.normalized();
  for (size_t k = 0; k < n; ++k) {
    along[k] = dir[k].dot(u);
    across[k] = dir[k] - along[k] * u;
    if (length[k] > 0 && !(along[k] > 0)) return std::nullopt;  // points back: no straightening
  }
  // The path's end with the across parts scaled by a: its distance from the anchor falls from
  // the path's length (a = 0, straight) as a grows; and its derivative.
  auto reach = [&](double a, double* slope) {
    Vec3 e = Vec3::Zero(), de = Vec3::Zero();
    for (size_t k = 0; k < n; ++k) {
      if (!(length[k] > 0)) continue;
      const Vec3 w = along[k] * u + a * across[k];
      const double r = w.norm();
      e += length[k] / r * w;
      de += length[k] * (across[k] / r - w * (w.dot(across[k]) / (r * r * r)));
    }
    const double d = e.norm();
    if (slope) *slope = d > 0 ? e.dot(de) / d : 0;
    return d;
  };
  // Safeguarded Newton from a = 1 (the shape now) on reach(a) = |goal|, bracketed by [lo, hi].
  const double want = goal.norm();
  double lo = 0, hi = 1, a = 1;
  if (reach(0, nullptr) < want) return std::nullopt;  // beyond this path's reach
  while (reach(hi, nullptr) > want) {
    if (hi > 1e3) return std::nullopt;
    lo = hi, hi *= 2;
  }
  for (int it = 0; it < 100; ++it) {
    double slope = 0;
    const double f = reach(a, &slope) - want;
    if (f > 0)
      lo = a;
    else
      hi = a;
    if (std::abs(f) <= 1e-3 * options.tolerance || hi - lo <= 1e-15 * hi) break;
    double next = slope < 0 ? a - f / slope : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    a = next;
  }
  // The shape at a, turned about the anchor so that its end is on the goal.
  Vec3 e = Vec3::Zero();
  for (size_t k = 0; k < n; ++k) {
    if (length[k] > 0) dir[k] = length[k] * (along[k] * u + a * across[k]).normalized();
    e += dir[k];
  }
  const Quat onto = Quat::FromTwoVectors(e, goal);
  std::vector<Pose> out = poses;
  std::vector<int> moved_with(poses.size(), -1);
  Vec3 at = path->anchor.centre();
  for (size_t k = 0; k < n; ++k) {
    const Link& l = path_links[k];
    Pose& p = out[static_cast<size_t>(l.body)];
    Quat turn = onto;
    if (length[k] > 0) {
      turn = onto * Quat::FromTwoVectors(p.q * (l.far - l.near), dir[k]);
    }
    p.q = (turn * p.q).normalized();
    p.x = at - p.q * l.near;
    at += onto * dir[k];
    moved_with[static_cast<size_t>(l.body)] = l.body;
  }
  out[static_cast<size_t>(held_.value)] = target;
  moved_with[static_cast<size_t>(held_.value)] = held_.value;
  std::vector<ConstraintReport> constraints;
  if (!carry(model, poses, out, moved_with, options, constraints)) return std::nullopt;
  return out;
}

}  // namespace dispcon
