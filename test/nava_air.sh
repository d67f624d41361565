#!/usr/bin/env bash
# Runs an over-the-air rostest of nava_modem links:
#
#   test/nava_air.sh TEST_FILE [rostest arguments]     e.g. test/nava_air.sh nava_air.test
#
# starts a private PulseAudio server whose null sink is the shared "air"
# (test/nava_air_server.sh), points ALSA's pulse device at it, runs TEST_FILE (a .test file of
# this package) with rostest, and stops the server by its PID. A test that fails the air on
# purpose runs "$NAVA_AIR_CONTROL kill" (the server dies as in a crash) and later
# "$NAVA_AIR_CONTROL start" (it comes back on the same socket).
set -euo pipefail
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"

if [ $# -lt 1 ]; then
  echo "usage: $0 TEST_FILE [rostest arguments]" >&2
  exit 2
fi
test_file=$1
shift

server="$(cd "$(dirname "$0")" && pwd)/nava_air_server.sh"
dir=$(mktemp -d /tmp/nava_air.XXXXXX)
cleanup() {
  "$server" stop "$dir" || true
  rm -rf "$dir"
}
trap cleanup EXIT

"$server" start "$dir"
cat >"$dir/control" <<CONTROL
#!/bin/sh
# start | stop | kill this run's air
exec "$server" "\$1" "$dir"
CONTROL
chmod +x "$dir/control"
export NAVA_AIR_CONTROL="$dir/control"
export PULSE_SERVER="unix:$dir/native"
rostest multirobot_audio "$test_file" "$@"
