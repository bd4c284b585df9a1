// Counts the heap allocations of the test program (its global operator new is replaced by
// allocation_tally.cc, linked into the test programs that include this header). The tests of
// message decoding use it to state "a corrupt length is rejected without allocating" as an
// assertion on bytes instead of on time.
#pragma once

#include <cstdint>

namespace slammtt {

struct AllocationTally {
  int64_t allocations = 0;
  int64_t bytes = 0;
};

// Allocations made by operator new since the program started.
AllocationTally CurrentAllocationTally();

// The allocations made while `f` runs.
template <class F>
AllocationTally AllocationsDuring(F&& f) {
  const AllocationTally before = CurrentAllocationTally();
  f();
  const AllocationTally after = CurrentAllocationTally();
  return {after.allocations - before.allocations, after.bytes - before.bytes};
}

}  // namespace slammtt
