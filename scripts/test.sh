#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test: the components' gtests, the ROS
# conversions' gtests, the rostests and the launch-file checks, all through ctest.
#
#   scripts/test.sh [CTEST_ARGS...]     e.g. scripts/test.sh -R grid
set -euo pipefail
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

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
