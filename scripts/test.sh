#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test. With no arguments it runs all of what CI
# runs, in turn, and stops at the first part that fails:
#   1. the main suite: the components' gtests, the ROS conversions' gtests, the rostests and the
#      launch-file checks, all through ctest, in build/;
#   2. the sanitized suite: the ROS-free components and their tests built with AddressSanitizer
#      and UndefinedBehaviorSanitizer in build-sanitize/ (any report fails the test);
#   3. the fuzz targets (scripts/fuzz.sh), 20 s each, built with clang in build-fuzz/.
#
#   scripts/test.sh                     everything above
#   scripts/test.sh CTEST_ARGS...       the main suite only, e.g. scripts/test.sh -R grid
#   scripts/test.sh --sanitize [CTEST_ARGS...]
#                                       the sanitized suite only
#   scripts/test.sh --fuzz [SECONDS]    the fuzz targets only, SECONDS each (default 20)
# In a clean clone on this two-core machine the whole run (.ci/run) took 30 minutes: the main
# suite's build and 7 minutes of tests, the sanitized suite's build and 5, the fuzz targets' 4.5
# with their build. CI allows 45.
set -euo pipefail
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

main_suite() {
  "$here/scripts/setup.sh" --werror
  cmake --build "$here/build" --target tests -j "$(nproc)"
  # catkin's setup script reads unset variables.
  set +u
  # shellcheck disable=SC1091
  source "$here/build/devel/setup.bash"
  set -u
  local count
  count=$(cd "$here/build" && ctest -N "$@" | sed -n 's/^Total Tests: *//p')
  if [ -z "$count" ] || [ "$count" -eq 0 ]; then
    echo "test.sh: no tests found; that is a failure" >&2
    return 1
  fi
  # Sequential: each rostest starts its own master, and the machine has two cores.
  (cd "$here/build" && ctest --output-on-failure "$@")
}

sanitized_suite() {
  "$here/scripts/setup.sh" --no-build
  local build="$here/build-sanitize"
  cmake -S "$here" -B "$build" -DMULTIROBOT_AUDIO_ROS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DSANITIZE=address,undefined -DMULTIROBOT_AUDIO_WERROR=ON >/dev/null
  cmake --build "$build" --target tests -j "$(nproc)"
  (cd "$build" &&
    ASAN_OPTIONS="detect_leaks=1:abort_on_error=1" UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1" \
      ctest --output-on-failure "$@")
}

part() {
  echo "== test.sh: $1 =="
}

case "${1:-}" in
  --sanitize)
    shift
    sanitized_suite "$@"
    ;;
  --fuzz)
    "$here/scripts/fuzz.sh" all "${2:-20}"
    ;;
  "")
    start=$SECONDS
    part "main suite"; main_suite
    part "sanitized suite"; sanitized_suite
    part "fuzz targets, 20 s each"; "$here/scripts/fuzz.sh" all 20
    echo "test.sh: every part passed in $((SECONDS - start)) s"
    ;;
  *)
    main_suite "$@"
    ;;
esac
