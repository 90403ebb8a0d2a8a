// Counts in the one line a person reads. Internal to the solver.
#pragma once

#include <string>

namespace dispcon {

// `n` and `word`, with an s unless n is one: "1 iteration", "3 iterations", "0 steps".
std::string counted(long long n, const char* word);

}  // namespace dispcon
