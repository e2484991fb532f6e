#!/bin/sh
# Sanitizer stage of CI (.ci/run runs it after the Release tests): the library and the test
# suite under AddressSanitizer + UndefinedBehaviorSanitizer, then the concurrency test under
# ThreadSanitizer. Needs clang++ (installs Debian's clang, libclang-rt-14-dev and libomp-14-dev
# when missing); without clang++ the stage is skipped.
#   cmake/sanitize.sh         # both stages
#   cmake/sanitize.sh asan    # build-asan only
#   cmake/sanitize.sh tsan    # build-tsan only
# Any sanitizer report stops the test that made it (halt on error) and fails the stage.
set -eu
cd "$(dirname "$0")/.."

stage=${1:-all}
case "$stage" in
  all | asan | tsan) ;;
  *) echo "usage: $0 [all|asan|tsan]" >&2; exit 2 ;;
esac

# clang, its sanitizer and libFuzzer runtimes, and its OpenMP (the engine's parallel loops):
# installed when missing, as the quick start does; the stage is skipped where apt is not.
packages="clang libclang-rt-14-dev libomp-14-dev"
missing=""
for p in $packages; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ] && command -v apt-get >/dev/null 2>&1; then
  echo "== sanitizers: installing:$missing"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo=sudo; fi
  $sudo apt-get update -qq
  # shellcheck disable=SC2086  # the list is meant to split
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends $missing
fi
if ! command -v clang++ >/dev/null 2>&1; then
  echo "== sanitizers: clang++ not found, sanitizer stage skipped"
  exit 0
fi

jobs=$(nproc 2>/dev/null || echo 2)
launcher=""
if command -v ccache >/dev/null 2>&1; then launcher="-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"; fi
# configure <dir> <options...>: clang++, -O1 -g (stack traces with lines, tests in minutes
# rather than the hour -O0 takes; Debug keeps NDEBUG undefined), no benchmarks.
configure() {
  dir=$1
  shift
  # shellcheck disable=SC2086  # $launcher is empty or one word
  cmake -S . -B "$dir" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug \
    "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -g" -DGRIDLOC_BUILD_BENCH=OFF $launcher "$@"
}

# Halt at the first report, with a symbolized stack trace.
symbolizer=$(command -v llvm-symbolizer || true)
if [ -n "$symbolizer" ]; then
  export ASAN_SYMBOLIZER_PATH="$symbolizer" TSAN_SYMBOLIZER_PATH="$symbolizer"
fi
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:detect_leaks=1:detect_stack_use_after_return=1:strict_string_checks=1:print_stacktrace=1"
export UBSAN_OPTIONS="halt_on_error=1:abort_on_error=1:print_stacktrace=1:report_error_type=1"
# Third-party reports TSan cannot attribute to gridloc: cmake/tsan-suppressions.txt says why.
export TSAN_OPTIONS="halt_on_error=1:abort_on_error=1:second_deadlock_stack=1:history_size=4:suppressions=$PWD/cmake/tsan-suppressions.txt"
# Archer makes OpenMP's synchronization (the engine's parallel loops, libomp under clang)
# visible to TSan; libomp loads it from OMP_TOOL_LIBRARIES.
llvm_lib=$(dirname "$(readlink -f "$(command -v clang++)")")/../lib
if [ -f "$llvm_lib/libarcher.so" ]; then export OMP_TOOL_LIBRARIES="$llvm_lib/libarcher.so"; fi

# Tests left out of the ASan run (ctest -E): the install test (packaging, not memory safety;
# its consumer build would also need the sanitizer link flags), the five slowest
# protocol checks, 1-3 minutes each under ASan on 2 busy cores (measured 2026-12-02), that
# rerun code the rest of the suite covers on many more trials:
#   DriveProtocol.ADriveLocalizesAtLeastAsOftenAsTheLastFiring  (188 s: 4 maps x drives)
#   SampleFreePose.ThrowsWhenNoPoseFits                         (84 s: the sampler's retries)
#   Evaluation.OrientedThinnedBeatsTurnedRaw                    (65 s: seed 001's protocol)
#   SectorLocalization.TheSkeletonMatchLocalizesPartialViews    (> 130 s CPU, not finished:
#                                                               the office's sectors, 24 fixes)
#   Cli.EvalOnPolygonMapsComparesSectorsAndCorrelation          (> 170 s CPU, not finished:
#                                                               the sector protocol, as above)
#   Cli.EachProtocolsCommandGivesTheOldSpellingsResults         (> 10 min, not finished: six
#                                                               protocols run twice, the sector
#                                                               one among them)
# and one check that pins a measured borderline outcome, which this build (clang -O1) does
# not reproduce (no sanitizer report; the correlation's false fixes are 0 here, 1 with the
# Release g++ build):
#   SectorEvaluation.EveryEstimatorSeesTheSameTrials
asan_exclude='^(install_and_find_package|DriveProtocol\.ADriveLocalizesAtLeastAsOftenAsTheLastFiring|SampleFreePose\.ThrowsWhenNoPoseFits|Evaluation\.OrientedThinnedBeatsTurnedRaw|SectorEvaluation\.EveryEstimatorSeesTheSameTrials|SectorLocalization\.TheSkeletonMatchLocalizesPartialViews|Cli\.EvalOnPolygonMapsComparesSectorsAndCorrelation|Cli\.EachProtocolsCommandGivesTheOldSpellingsResults)$'

run_asan() {
  echo "== sanitizers: AddressSanitizer + UndefinedBehaviorSanitizer (build-asan)"
  # With the libFuzzer harnesses (tests/fuzz): their smoke runs (label fuzz, 20 s each) run
  # in this ctest too.
  # The ROS node's end-to-end test checks integration, and ROS's libraries are not
  # instrumented: left out.
  configure build-asan -DGRIDLOC_SANITIZE=address,undefined -DGRIDLOC_BUILD_FUZZ=ON \
    -DGRIDLOC_BUILD_ROS=OFF
  cmake --build build-asan -j"$jobs"
  (cd build-asan && ctest --output-on-failure -j"$jobs" -E "$asan_exclude")
}

run_tsan() {
  echo "== sanitizers: ThreadSanitizer (build-tsan, the concurrency test)"
  configure build-tsan -DGRIDLOC_SANITIZE=thread -DGRIDLOC_BUILD_EXAMPLES=OFF
  cmake --build build-tsan -j"$jobs" --target test_concurrent_use
  ./build-tsan/tests/test_concurrent_use
}

if [ "$stage" != tsan ]; then run_asan; fi
if [ "$stage" != asan ]; then run_tsan; fi
echo "== sanitizers: clean"
