#!/usr/bin/env bash
# The private PulseAudio server that is the shared "air" of the over-the-air tests (nava_air.sh
# runs it around a rostest):
#
#   test/nava_air_server.sh start DIR   starts it on the socket DIR/native and waits for it
#   test/nava_air_server.sh stop DIR    stops it (SIGTERM) and waits until it has gone
#   test/nava_air_server.sh kill DIR    kills it (SIGKILL, as a crash would) and waits
#
# Its PID is kept in DIR/pulse.pid. Started again after a stop or a kill, it serves the same
# socket, which is how ALSA's pulse plugin finds it again when a client reopens the device. Its
# null sink is the air: streams played into it mix, and its monitor captures the mix
# (norewinds=1, or the monitor drops audio).
set -euo pipefail
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"

if [ $# -ne 2 ] || { [ "$1" != start ] && [ "$1" != stop ] && [ "$1" != kill ]; }; then
  echo "usage: $0 start|stop|kill DIR" >&2
  exit 2
fi
action=$1
dir=$2

# Whether a PID is a live process; a killed server that nobody has reaped yet (it is not this
# script's child) is a zombie, and gone.
alive() {
  local state
  state=$(awk '{print $3}' "/proc/$1/stat" 2>/dev/null || true)
  [ -n "$state" ] && [ "$state" != Z ] && [ "$state" != X ]
}

running_pid() {
  local pid
  pid=$(cat "$dir/pulse.pid" 2>/dev/null || true)
  if [ -n "$pid" ] && alive "$pid"; then echo "$pid"; fi
}

case $action in
start)
  if [ -n "$(running_pid)" ]; then
    echo "nava_air_server.sh: already running as PID $(running_pid)" >&2
    exit 1
  fi
  mkdir -p "$dir/home" "$dir/run"
  cat >"$dir/air.pa" <<PA
load-module module-native-protocol-unix auth-anonymous=1 socket=$dir/native
load-module module-null-sink sink_name=air norewinds=1 rate=48000 channels=1
set-default-sink air
set-default-source air.monitor
PA
  rm -f "$dir/native"  # a killed server leaves its socket behind
  log="$dir/pulse.$(date +%s%N).log"
  # Detached from this script's output: a server outliving it must not hold a caller's pipe.
  # No PID file: a killed server may linger as a zombie until reaped, and look alive to it.
  HOME="$dir/home" XDG_RUNTIME_DIR="$dir/run" pulseaudio -n --daemonize=no --use-pid-file=no --exit-idle-time=-1 \
    --disable-shm=yes --log-target=file:"$log" -F "$dir/air.pa" </dev/null >/dev/null 2>&1 &
  echo $! >"$dir/pulse.pid"
  for _ in $(seq 50); do [ -S "$dir/native" ] && exit 0; sleep 0.1; done
  echo "nava_air_server.sh: PulseAudio did not start:" >&2
  cat "$log" >&2 || true
  kill "$(cat "$dir/pulse.pid")" 2>/dev/null || true
  exit 1
  ;;
stop | kill)
  pid=$(running_pid)
  if [ -z "$pid" ]; then exit 0; fi
  kill "-$([ "$action" = kill ] && echo KILL || echo TERM)" "$pid"
  for _ in $(seq 100); do alive "$pid" || break; sleep 0.02; done
  if alive "$pid"; then
    echo "nava_air_server.sh: PID $pid did not go" >&2
    exit 1
  fi
  rm -f "$dir/pulse.pid"
  ;;
esac
