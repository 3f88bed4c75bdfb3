#!/usr/bin/env bash
# Builds the test suite with clang and ThreadSanitizer into ./build-tsan and runs the tests that
# run threads of their own: the lane exchange, batches, sweeps, the determinism tests, the
# speculative search, and droplets sharing an image medium's distance field. Any race report fails
# the run. Tests that evaluate a search generation's candidates in a oneTBB arena on 2 or more
# threads are left out: libtbb is not instrumented, so ThreadSanitizer cannot see its
# synchronisation and reports races that are not there.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export CCACHE_DIR="${CCACHE_DIR:-$PWD/.ccache}"
cmake --preset tsan  # CMakePresets.json
cmake --build build-tsan -j "$(nproc)" --target softdrop_tests
TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1" build-tsan/tests/softdrop_tests \
  --gtest_filter='Interleaved.*:Sweep*:Determinism.*:Search.Speculative*:Search.Predicted*:Search.PredictionsAhead*:Search.EvolutionStrategySpeculates*:Search.ASlowCompletion*:Islands.Driven*:Objective.TheRobust*:Objective.ARobust*:TwoDroplets.ABatchOfPairs*:ImageMedium.NoMassStaysDeeper*'
