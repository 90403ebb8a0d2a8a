// An animation a person can watch: every body drawn as lines from its centre to its constrained
// points, projected on the plane where the motion is largest, animated with SMIL so a browser
// plays it.
#pragma once

#include <string>

#include "dispcon/model/model.hpp"
#include "dispcon/solve/dynamics.hpp"

namespace dispcon {

std::string write_animation_svg(const Model& model, const AnimateResult& result);
// The same from any sequence of poses (a drag, a sweep), `seconds` long.
std::string write_poses_svg(const Model& model, const std::vector<std::vector<Pose>>& frames,
                            double seconds);

}  // namespace dispcon
