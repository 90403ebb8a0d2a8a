// How far a held body can be from the parts that cannot move: a drag target out of reach, told
// before any iteration. Internal to the engine (drag.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include "dispcon/model/model.hpp"

namespace dispcon {

// A drag target that no pose of the linkage can meet, by the triangle inequality: a point of the
// held body is joined to a point that cannot move (the world's, a fixed body's) through a path of
// point-to-point joints, so it is never farther from it than the path's length (the sum, over the
// bodies on the path, of the distance between the body's two joint points). Joints that let a
// point slide (guides) or have no point (couplings, angles alone) give no path; angle limits and
// closed loops only make the true reach shorter, so what this finds is certain, never all.
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

 private:
  struct Path {
    Vec3 held_point;  // on the held body, local
    Vec3 anchor;      // the point that cannot move, world
    double length = 0;
    int joints = 0;
    JointId first{-1};
  };
  std::vector<Path> paths_;
  std::uint64_t revision_ = 0;
};

}  // namespace dispcon
