// Counts heap allocations, so tests can prove that a hot path allocates nothing.
//
// Linking this library replaces the global operator new/delete of the test binary with
// counting versions (defined in their own translation unit, so the compiler never sees
// a malloc paired with a delete).
#pragma once

#include <cstdint>

namespace flat2d::testing {

// Calls to operator new (any form) since the program started.
std::uint64_t AllocationCount();

}  // namespace flat2d::testing
