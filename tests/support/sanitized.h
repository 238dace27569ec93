// How many cases a fuzzing loop runs: all of them in the optimised build, a spread of fewer
// under the sanitizers, where each case costs five to ten times as much and the release
// pass has already run the whole set on the same code. (The test files are compiled without
// instrumentation there, so tests/CMakeLists.txt says so with MOORSIM_SANITIZED.)
#pragma once

namespace moorsim::testing {

#if defined(MOORSIM_SANITIZED)
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif

/// `full` in the optimised build, `sanitized` under the sanitizers.
constexpr int CaseCount(int full, int sanitized) { return kSanitized ? sanitized : full; }

}  // namespace moorsim::testing
