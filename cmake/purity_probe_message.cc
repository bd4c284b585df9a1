// Compiled only by the purity tests (cmake/SlammttTargets.cmake, slammtt_purity_tests): linked
// to a pure library, this include must not resolve.
#include "slammtt_msgs/pose_t.hpp"
