// The description language (.dcl, format.md): writing a Model so that reading it back gives the
// same bodies, poses and joints (assemble --write round-trips).
#pragma once

#include <string>

#include "dispcon/model/model.hpp"

namespace dispcon {

std::string write_dcl(const Model& model);

}  // namespace dispcon
