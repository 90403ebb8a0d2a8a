// The reach bound of a held body: shortest paths through point-to-point joints (reach.hpp).
#include "dispcon/solve/reach.hpp"

#include <algorithm>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace dispcon {

namespace {

// A joint point: where a point-to-point joint holds a body (each such joint makes two, one on
// each body, joined at no length).
struct Node {
  int body = 0;
  Vec3 local = Vec3::Zero();
  int joint = 0;  // the joint, and the node on its other body (its index xor 1)
};

}  // namespace

ReachBound::ReachBound(const Model& model, BodyId held, double time) : revision_(model.revision()) {
  std::vector<Node> nodes;
  for (int c = 0; c < model.joint_count(); ++c) {
    const Joint& j = model.joint(JointId{c});
    if (!j.has_hinge || j.guide || !j.active_at(time)) continue;
    nodes.push_back(Node{j.body1.value, j.p1, c});
    nodes.push_back(Node{j.body2.value, j.p2, c});
  }
  // The nodes of each body, so a path crosses a body from any of its points to any other.
  std::vector<std::vector<int>> on_body(static_cast<size_t>(model.body_count()));
  for (size_t k = 0; k < nodes.size(); ++k)
    on_body[static_cast<size_t>(nodes[k].body)].push_back(static_cast<int>(k));
  auto immovable = [&](int body) { return body == 0 || model.body(BodyId{body}).fixed; };

  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> dist(nodes.size());
  std::vector<int> hops(nodes.size()), first(nodes.size());
  using Item = std::pair<double, int>;
  for (int source : on_body[static_cast<size_t>(held.value)]) {
    std::fill(dist.begin(), dist.end(), inf);
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
        const Body& b = model.body(BodyId{n.body});
        paths_.push_back(Path{nodes[static_cast<size_t>(source)].local, b.pose.apply(n.local), d,
                              hops[static_cast<size_t>(k)],
                              JointId{first[static_cast<size_t>(k)]}});
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
          queue.push({nd, next});
        }
      }
    }
  }
}

ReachBound::Gap ReachBound::gap(const Pose& target, double tolerance) const {
  Gap worst;
  for (const Path& p : paths_) {
    const double g = (target.apply(p.held_point) - p.anchor).norm() - p.length;
    if (g > p.joints * tolerance && g > worst.distance) worst = Gap{g, p.first, p.joints};
  }
  return worst;
}

}  // namespace dispcon
