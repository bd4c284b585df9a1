// Compiled only by the purity tests (cmake/SlammttTargets.cmake, slammtt_purity_tests): linked
// to a pure library, this include must not resolve.
#include "runtime/config.h"
