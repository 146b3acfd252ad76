// The environment a target expects when libFuzzer starts it bare: MPGC_SHARED_DATA (ship model
// tables) as CTest and ./mpgc set it.
#pragma once

#include <cstdlib>

#ifndef MPGC_FUZZ_SHARED_DATA
#define MPGC_FUZZ_SHARED_DATA ""
#endif

namespace mpgc::fuzz {
inline void default_env() { setenv("MPGC_SHARED_DATA", MPGC_FUZZ_SHARED_DATA, 0); }
}  // namespace mpgc::fuzz
