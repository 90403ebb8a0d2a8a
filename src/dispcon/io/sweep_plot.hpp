// Range of motion as a picture: every joint's value against the driven angle, with the lock-up
// and the limits in contact marked.
#pragma once

#include <string>

#include "dispcon/model/model.hpp"
#include "dispcon/solve/diagnostics.hpp"

namespace dispcon {

std::string write_sweep_svg(const Model& model, const SweepResult& result);

}  // namespace dispcon
