#pragma once
// A line for the user through an optional Log (vksplat/jobs/cluster_prune.hpp): a job run
// without one says nothing.
#include <string>

#include "vksplat/jobs/cluster_prune.hpp"

namespace vksplat::jobs {

inline void say(const Log& log, const std::string& line) {
    if (log) log(line);
}

}  // namespace vksplat::jobs
