// Heavy numerical runs (a converged cantilever, a validation over hundreds of steps) take minutes
// under AddressSanitizer and find nothing there that the smaller tests of the same code do not:
// they skip themselves in sanitizer builds and run in the optimised pass (docs/TESTING.md,
// "Heavy runs"). ctest counts a skipped case as "Not Run", so the ASan totals show them.
#pragma once

#include <gtest/gtest.h>

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define TACTA_SANITIZER_BUILD 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define TACTA_SANITIZER_BUILD 1
#endif
#endif

#ifdef TACTA_SANITIZER_BUILD
#define TACTA_HEAVY_RUN() GTEST_SKIP() << "heavy numerical run: checked in the optimised pass"
#else
#define TACTA_HEAVY_RUN() static_cast<void>(0)
#endif
