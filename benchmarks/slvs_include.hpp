// SolveSpace's C header uses memset without including <cstring>.
#pragma once

// clang-format off
#include <cstring>
#include <slvs.h>
// clang-format on
