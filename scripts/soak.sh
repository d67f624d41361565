#!/usr/bin/env bash
# Soak: runs the charging demo (launch/charging_sim.launch, four robots sharing one charger: the
# longest-lived task) in lockstep as fast as it goes for HOURS simulated hours on a ROS master of
# its own, and prints per node its resident memory (VmRSS) at the first simulated hour and at the
# end with the growth, every node's exit counters, each robot's lowest battery, and the nodes that
# died. Exits 1 if a node died, a robot ran flat or a node's memory grew more than the limit after
# the first hour (runs shorter than an hour compare against the first sample after a warm-up of a
# quarter of the run instead, and say so), and if world_sim stopped short, dropped a participant
# from the lockstep, or a node printed no summary (scripts/soak_report.py); 2 on bad arguments.
#
#   scripts/soak.sh HOURS [--max-growth PERCENT] [--seed N] [--keep]
#
#   --max-growth PERCENT  RSS growth allowed after the baseline (default 5)
#   --seed N              world seed (default 1)
#   --keep                keep the logs (they are kept anyway when the soak fails)
#
# Needs the built workspace (scripts/test.sh or scripts/demo.sh build it). Stops everything it
# started (roscore, roslaunch and its nodes, the monitor) by PID.
set -euo pipefail
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

usage() {
  echo "usage: scripts/soak.sh HOURS [--max-growth PERCENT] [--seed N] [--keep]" >&2
  exit 2
}
die_usage() {
  echo "soak.sh: $*" >&2
  usage
}
# A positive finite decimal number (no exponent: nothing a user means needs one).
positive() { [[ $1 =~ ^[0-9]*\.?[0-9]+$ ]] && awk -v v="$1" 'BEGIN { exit !(v > 0) }'; }

[ $# -ge 1 ] || die_usage "missing HOURS (simulated hours to run)"
hours=$1
shift
positive "$hours" || die_usage "HOURS: expected a positive number of simulated hours, got '$hours'"
max_growth=5
seed=1
keep=""
kill_node=""  # for the tests (test/soak_test.sh): SIGKILL this node half way through
while [ $# -gt 0 ]; do
  case $1 in
    --max-growth)
      [ $# -ge 2 ] || die_usage "--max-growth: missing PERCENT"
      positive "$2" || die_usage "--max-growth: expected a positive percentage, got '$2'"
      max_growth=$2
      shift 2 ;;
    --seed)
      [ $# -ge 2 ] || die_usage "--seed: missing N"
      [[ $2 =~ ^[0-9]+$ ]] || die_usage "--seed: expected a whole number >= 0, got '$2'"
      seed=$2
      shift 2 ;;
    --keep) keep=1; shift ;;
    --kill-node)
      [ $# -ge 2 ] || die_usage "--kill-node: missing NAME"
      kill_node=$2
      shift 2 ;;
    *) die_usage "unknown argument '$1'" ;;
  esac
done

[ -f "$here/build/devel/setup.bash" ] || {
  echo "soak.sh: $here/build/devel/setup.bash not found: build the workspace first (scripts/test.sh)" >&2
  exit 2
}
set +u
# shellcheck disable=SC1091
source "$here/build/devel/setup.bash"
set -u

robots=4
# Schedule, in simulated s: the whole run, the baseline sample (the first hour, or a quarter of a
# shorter run) and the samples every minute (or every twentieth of a short run).
read -r duration baseline interval < <(awk -v h="$hours" 'BEGIN {
  d = h * 3600; b = (d > 3600) ? 3600 : d / 4; i = (d > 3600) ? 60 : d / 20
  printf "%.1f %.1f %.1f\n", d, b, i }')

dir=$(mktemp -d /tmp/soak.XXXXXX)
export ROS_LOG_DIR="$dir/ros_log"  # the nodes' log files go with the rest, not into ~/.ros
core="" launch="" monitor="" status=1
cleanup() {
  for pid in $monitor $launch $core; do kill -INT "$pid" 2>/dev/null || true; wait "$pid" 2>/dev/null || true; done
  if [ -z "$keep" ] && [ "$status" -eq 0 ]; then rm -rf "$dir"; else echo "soak: logs kept in $dir" >&2; fi
}
trap cleanup EXIT

# shellcheck disable=SC1091
source "$here/scripts/private_master.sh"
start_private_master "$dir/roscore.log"

# The monitor starts first: /use_sim_time must still be unset when it starts (soak_monitor.py).
mkdir -p "$dir/monitor"
kill_args=()
[ -z "$kill_node" ] || kill_args=(--kill-node "$kill_node" --kill-at "$(awk -v d="$duration" 'BEGIN { print d / 2 }')")
/usr/bin/python3 "$here/scripts/soak_monitor.py" --robots "$robots" --duration "$duration" --baseline "$baseline" \
  --interval "$interval" --out "$dir/monitor" "${kill_args[@]}" >"$dir/monitor.log" 2>&1 &
monitor=$!
for _ in $(seq 150); do [ -e "$dir/monitor/ready" ] || ! kill -0 "$monitor" 2>/dev/null && break; sleep 0.2; done
[ -e "$dir/monitor/ready" ] || { echo "soak.sh: the monitor did not start:" >&2; cat "$dir/monitor.log" >&2; exit 1; }

echo "soak: charging_sim.launch, $robots robots, lockstep at full speed, $hours simulated hours ($duration s), seed $seed"
start=$(date +%s.%N)
roslaunch multirobot_audio charging_sim.launch robots:="$robots" speed:=0 lockstep:=true duration:="$duration" \
  seed:="$seed" >"$dir/launch.log" 2>&1 &
launch=$!
wait "$launch" || true
launch=""
wall=$(awk -v s="$start" -v e="$(date +%s.%N)" 'BEGIN { printf "%.1f", e - s }')
# The monitor ends by itself once world_sim has gone; SIGINT in case it waits for nodes that
# never registered.
kill -INT "$monitor" 2>/dev/null || true
wait "$monitor" || { echo "soak.sh: the monitor failed:" >&2; tail -5 "$dir/monitor.log" >&2; }
monitor=""

status=0
/usr/bin/python3 "$here/scripts/soak_report.py" --log "$dir/launch.log" --dir "$dir/monitor" --duration "$duration" \
  --baseline "$baseline" --max-growth "$max_growth" --wall "$wall" || status=$?
exit "$status"
