#!/usr/bin/env bash
# Installs what is missing, builds and runs every test on lavapipe with Vulkan validation on.
#   tools/test.sh             release build (RelWithDebInfo) in build/
#   tools/test.sh --sanitize  AddressSanitizer + UndefinedBehaviorSanitizer build in build-asan/
set -euo pipefail
cd "$(dirname "$0")/.."

mode=release
[ "${1:-}" = "--sanitize" ] && mode=sanitize

bash tools/setup-debian.sh
echo "test.sh: setup took $SECONDS s"
# The house format (.clang-format) holds for every C++ file in the repository.
git ls-files -z '*.cpp' '*.h' | xargs -0 clang-format --dry-run -Werror
jobs=$(nproc)
# Line tables only (-g1): sanitizer reports and crashes still name file and line, and each
# build compiles a fifth faster than with full -g (CI builds the tree twice; BENCHMARKS.md).
# The tests' own sources compile at -Og in both builds (FACESKETCH_TEST_OPT, top CMakeLists.txt).
lines=-g1
testopt=-Og

if [ "$mode" = sanitize ]; then
  dir=build-asan
  # A unity build (CMake joins the sources of each target in batches of 8): the sanitizer build
  # is CI's longest step, and most of a test file's compile time is the Catch2 and Eigen headers
  # it shares with its neighbours (BENCHMARKS.md, "CI time"). The release build below joins only
  # the test sources (and the app's command files, always joined: app/CMakeLists.txt): the engine
  # stays one file per compile, as the README's main command builds it, so an engine file missing
  # an include of its own still fails there.
  cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="$lines -O1" \
        -DFACESKETCH_SANITIZE=ON -DFACESKETCH_WERROR=ON -DCMAKE_UNITY_BUILD=ON -DFACESKETCH_TEST_OPT="$testopt"
  # Mesa's drivers and the validation layer keep process-lifetime allocations that LeakSanitizer
  # would report; everything else (ours) must be leak-free.
  export LSAN_OPTIONS="suppressions=$PWD/tools/lsan.supp:print_suppressions=0"
  export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
else
  dir=build
  cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 $lines -DNDEBUG" \
        -DFACESKETCH_WERROR=ON -DFACESKETCH_UNITY_TESTS=ON -DFACESKETCH_TEST_OPT="$testopt"
fi
built=$SECONDS
cmake --build "$dir" -j"$jobs"
echo "test.sh: the $mode build took $((SECONDS - built)) s"
# Under a virtual X display (xvfb-run -a picks a free one): the swapchain and window tests open
# real windows and present to them (tests/test_window.h); without DISPLAY they skip with a warning.
# -noreset: by default Xvfb resets when its last client leaves, and a client connecting during the
# reset is refused ("Can't open display"), which failed a window test once when two ran side by
# side (BENCHMARKS.md, "CI time"). The gui scripts start their Xvfb the same way.
xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest --test-dir "$dir" --output-on-failure -j"$jobs"
