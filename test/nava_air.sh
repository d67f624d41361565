#!/usr/bin/env bash
# Runs an over-the-air rostest of nava_modem links:
#
#   test/nava_air.sh TEST_FILE [rostest arguments]     e.g. test/nava_air.sh nava_air.test
#
# starts a private PulseAudio server whose null sink is the shared "air" (norewinds=1, or its
# monitor drops audio), points ALSA's pulse device at it, runs TEST_FILE (a .test file of this
# package) with rostest, and stops the server by its PID.
set -euo pipefail
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"

if [ $# -lt 1 ]; then
  echo "usage: $0 TEST_FILE [rostest arguments]" >&2
  exit 2
fi
test_file=$1
shift

dir=$(mktemp -d /tmp/nava_air.XXXXXX)
pa_pid=""
cleanup() {
  if [ -n "$pa_pid" ]; then kill "$pa_pid" 2>/dev/null || true; wait "$pa_pid" 2>/dev/null || true; fi
  rm -rf "$dir"
}
trap cleanup EXIT

cat >"$dir/air.pa" <<PA
load-module module-native-protocol-unix auth-anonymous=1 socket=$dir/native
load-module module-null-sink sink_name=air norewinds=1 rate=48000 channels=1
set-default-sink air
set-default-source air.monitor
PA
mkdir -p "$dir/home" "$dir/run"
HOME="$dir/home" XDG_RUNTIME_DIR="$dir/run" pulseaudio -n --daemonize=no --exit-idle-time=-1 \
  --disable-shm=yes --log-target=file:"$dir/pulse.log" -F "$dir/air.pa" &
pa_pid=$!
for _ in $(seq 50); do [ -S "$dir/native" ] && break; sleep 0.1; done
if [ ! -S "$dir/native" ]; then
  echo "nava_air.sh: PulseAudio did not start:" >&2
  cat "$dir/pulse.log" >&2 || true
  exit 1
fi
export PULSE_SERVER="unix:$dir/native"
rostest multirobot_audio "$test_file" "$@"
