// How far a held body can be from the parts that cannot move: a drag target out of reach, told
// before any iteration, and the nearest pose when the joints' lengths alone decide it. Internal to
// the engine (drag.cpp).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "dispcon/model/model.hpp"
#include "dispcon/solve/solver.hpp"

namespace dispcon {

// A drag target that no pose of the linkage can meet, by the triangle inequality: a point of the
// held body is joined to a point that cannot move (the world's, a fixed body's) through a path of
// point-to-point joints, so it is never farther from it than the path's length (the sum, over the
// bodies on the path, of the distance between the body's two joint points). A path may also end
// at a guide of a part that cannot move (a slider's segment, a ring, a ball, a circle: the flying
// snake's tail on its rod): its point then stays on that set, and the held point is never
// farther from the set than the path's length. Guides between moving parts, the other guides
// (cylinder, polyline) and joints without a point (couplings, angles alone) give no path; angle
// limits and closed loops only make the true reach shorter, so what this finds is certain,
// never all.
// Built once per model revision (the paths depend on the joints only; the ends that cannot move
// are read from the poses then).
class ReachBound {
 public:
  ReachBound(const Model& model, BodyId held, double time);

  struct Gap {
    double distance = 0;  // how far the held point stays from where the target puts it, at best
    JointId joint{-1};    // the held body's joint where the path begins (-1: none out of reach)
    int joints = 0;       // joints on that path
  };
  // The largest gap over the paths for the held body at `target`; `tolerance` is accepted per
  // joint of a path (a solve may leave each joint that much open), so a gap within it is none.
  Gap gap(const Pose& target, double tolerance) const;
  std::uint64_t revision() const { return revision_; }

  // The nearest pose of the held body's `point` (local) to `target` with the body free to turn,
  // when a path cannot stretch that far: the path's bodies turned, each by the least rotation,
  // so that its two joint points lie one after the other on the line from the anchor toward the
  // target, the held body's joint point and `point` last; whatever hangs off them (bodies joined
  // to them through bodies neither on the path nor unable to move) turned and moved with them.
  // No valid pose takes the point nearer than the path's length from the anchor (the triangle
  // inequality), and this one meets that bound: it is the nearest pose there is, found without
  // iterating. None when every path reaches, or when that pose breaks a joint (a loop, an angle,
  // a limit: the path alone does not say where the linkage goes then).
  struct Stretch {
    std::vector<Pose> poses;  // one per body: `poses` given, the path and what hangs off it moved
    std::vector<ConstraintReport> constraints;  // the model's joints there, all holding
    double distance = 0;                        // how far `point` stays from `target` there
    Gap gap;                                    // the path stretched (its distance: the bound, met)
  };
  std::optional<Stretch> stretch(const Model& model, const std::vector<Pose>& poses,
                                 const Vec3& point, const Vec3& target,
                                 const SolveOptions& options) const;

  // A pose with the held body at `target` for a target within reach of the path that comes
  // nearest its full stretch there, where Newton steps crawl (the first-order model of a nearly
  // straight path sees almost no way to change its reach): the path's shape straightened (or bent)
  // by one factor, each body's direction across the path keeping its component along the line
  // from the anchor to the path's end and the rest scaled by that factor, found so that the
  // path's end meets the held body's joint point at the target; the whole then turned about the
  // anchor onto it, what hangs off the path carried along, the held body at its target. The
  // path's shape changes continuously with the factor, so the linkage keeps its branch. None
  // when no path has a joint point on the held body, when a body on the path points back toward
  // the anchor, or when that pose breaks a joint (measured: a loop, an angle, a limit).
  std::optional<std::vector<Pose>> straighten(const Model& model, const std::vector<Pose>& poses,
                                              const Pose& target,
                                              const SolveOptions& options) const;

  // Moves each body that hangs off a moved one (joined to it through active joints between
  // parts that can move; moved_with[b] == b for the bodies moved, -1 for the rest) as that one
  // moved from `poses` to `out`, then measures every joint there: false when one is broken.
  bool carry(const Model& model, const std::vector<Pose>& poses, std::vector<Pose>& out,
             std::vector<int>& moved_with, const SolveOptions& options,
             std::vector<ConstraintReport>& constraints) const;

 private:
  // Where a path ends on what cannot move: a point, or the set a guide keeps its point on
  // (world coordinates, read from the poses when the bound was built).
  struct Anchor {
    Pose frame;                  // the pose of the part that cannot move
    Vec3 p1 = Vec3::Zero();      // the joint's point on it, local
    std::optional<Guide> guide;  // the set about p1 its point stays on; none: p1 alone
    Vec3 centre() const { return frame.apply(p1); }
    // The point of the set nearest to x (world; nearest_on_guide's, in the part's frame).
    Vec3 nearest(const Vec3& x) const;
  };
  struct Path {
    Vec3 held_point;  // on the held body, local
    Anchor anchor;    // what cannot move
    double length = 0;
    int joints = 0;
    JointId first{-1};
    int source = 0;  // the held body's joint point it leaves from (an index of from_)
    int end = 0;     // its joint point on what cannot move (a node)
  };
  // A joint point: where a point-to-point joint holds a body (each such joint makes two, one on
  // each body, joined at no length: node k's partner is k xor 1).
  struct Node {
    int body = 0;
    Vec3 local = Vec3::Zero();
    int joint = 0;
    bool guide = false;  // the joint guides body2's point on a set of body1 (which cannot move)
  };
  std::vector<Node> nodes_;
  // Per source, each node's predecessor on its shortest path (the node it was reached from, on
  // the body before it toward the held body), -1 where none.
  std::vector<std::vector<int>> from_;
  std::vector<std::vector<int>> joined_;  // per body, the bodies an active joint joins it to
  std::vector<Path> paths_;
  BodyId held_;

  // A body on a path: entered at `near` (local, toward the anchor), left at `far` (toward the
  // held body).
  struct Link {
    int body = 0;
    Vec3 near, far;
  };
  // The bodies of `path` from its anchor to the held body (the held body not included).
  std::vector<Link> links(const Path& path) const;
  std::uint64_t revision_ = 0;
};

}  // namespace dispcon
