#pragma once
// The speculating drive's seam for tests, compiled only with -DSOFTDROP_TEST_HOOKS=ON (the builds
// of the test scripts): a build for users has none of it.
#include <functional>

#if defined(SOFTDROP_TEST_HOOKS)
namespace softdrop::test_seam {
/// Called by the speculating drive after it takes a generation's candidates and before it completes
/// the generation, while the workers go on (tests slow it down there to check that no worker sees a
/// generation half-completed). Read as a drive begins; empty: nothing. Set it only while no drive
/// runs.
std::function<void()>& before_completion();
}  // namespace softdrop::test_seam
#endif
