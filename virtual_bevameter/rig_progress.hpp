#pragma once
// Progress of a long rig run: the rig calls it now and then with the simulated time reached and the
// time the run will end at; the command line prints it, tests pass nothing.
#include <functional>
#include <string>

namespace terracal::rigs {

using RigProgress = std::function<void(const std::string& what, double t, double t_end)>;

}  // namespace terracal::rigs
