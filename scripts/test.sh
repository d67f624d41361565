#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test: the components' gtests, the ROS
# conversions' gtests, the rostests and the launch-file checks, all through ctest.
#
#   scripts/test.sh [CTEST_ARGS...]     e.g. scripts/test.sh -R grid
#   scripts/test.sh --sanitize [CTEST_ARGS...]
#       the ROS-free components and their tests built with AddressSanitizer and
#       UndefinedBehaviorSanitizer in build-sanitize/ (any report fails the test)
set -euo pipefail
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

if [ "${1:-}" = "--sanitize" ]; then
  shift
  "$here/scripts/setup.sh" --no-build
  build="$here/build-sanitize"
  cmake -S "$here" -B "$build" -DMULTIROBOT_AUDIO_ROS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DSANITIZE=address,undefined >/dev/null
  cmake --build "$build" --target tests -j "$(nproc)"
  cd "$build"
  export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1" UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
  exec ctest --output-on-failure "$@"
fi

"$here/scripts/setup.sh"
cmake --build "$here/build" --target tests -j "$(nproc)"

# catkin's setup script reads unset variables.
set +u
# shellcheck disable=SC1091
source "$here/build/devel/setup.bash"
set -u

cd "$here/build"
count=$(ctest -N "$@" | sed -n 's/^Total Tests: *//p')
if [ -z "$count" ] || [ "$count" -eq 0 ]; then
  echo "test.sh: no tests found; that is a failure" >&2
  exit 1
fi
# Sequential: each rostest starts its own master, and the machine has two cores.
ctest --output-on-failure "$@"
