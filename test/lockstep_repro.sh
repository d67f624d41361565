#!/usr/bin/env bash
# Lockstep runs are reproducible: runs a simulated team twice with the same seed at speed 0
# (lockstep on), recording every robot's audio traffic, and checks that the two runs give the
# same `world_sim summary` figures (what the world simulated; how many messages brought the
# commands may differ, none of them rejected or dropped) and the same bag, topic by topic and
# message for message.
#
#   test/lockstep_repro.sh [ROBOTS=3] [DURATION=30] [LAUNCH ARGS...] [-- FIRST RUN'S ARGS -- SECOND RUN'S ARGS]
#
# (lockstep:=false as a launch argument shows what the lockstep prevents: the runs differ.
# `-- update:=every_step -- update:=events` checks that audio_propagation working only while
# something is in the air gives the same run as working at every step; `-- one_process:=false --
# one_process:=true` that one process driving the team gives the same run as a wanderer a robot.)
# Starts a roscore of its own on a free port and stops it (and the recorders) by PID.
set -euo pipefail
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
robots=${1:-3}
duration=${2:-30}
shift $(($# < 2 ? $# : 2))
common=() first=() second=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do common+=("$1"); shift; done
if [ $# -gt 0 ]; then
  shift
  while [ $# -gt 0 ] && [ "$1" != "--" ]; do first+=("$1"); shift; done
  [ $# -gt 0 ] && shift
  second=("$@")
fi

dir=$(mktemp -d /tmp/lockstep_repro.XXXXXX)
core=""
recorder=""
cleanup() {
  for pid in $recorder $core; do kill "$pid" 2>/dev/null || true; wait "$pid" 2>/dev/null || true; done
  [ -n "${KEEP:-}" ] || rm -rf "$dir"
}
trap cleanup EXIT

# shellcheck disable=SC1091
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/private_master.sh"
start_private_master "$dir/roscore.log"

topics=()
for ((k = 0; k < robots; ++k)); do
  topics+=("/robot_$k/audio/tx" "/robot_$k/audio/rx" "/robot_$k/audio/carrier")
done

for run in 1 2; do
  if [ "$run" = 1 ]; then own=("${first[@]}"); else own=("${second[@]}"); fi
  # The recorder subscribes before the team starts, so it is connected before the first step.
  # rosrun starts rosbag's recorder itself (not the `rosbag record` wrapper), so that waiting
  # for its PID after SIGINT waits until the bag is closed.
  rosrun rosbag record -O "$dir/run$run.bag" "${topics[@]}" __name:=lockstep_recorder >"$dir/record$run.log" 2>&1 &
  recorder=$!
  sleep 2
  # The world waits 3 s once the team is ready, for the recorder to connect to its publishers
  # (on a busy machine that took more than the whole run once).
  roslaunch multirobot_audio sim_team.launch robots:="$robots" duration:="$duration" speed:=0 seed:=1 \
    announce_period:=2 lockstep_start_delay:=3 "${common[@]}" "${own[@]}" >"$dir/run$run.log" 2>&1
  kill -INT "$recorder"
  wait "$recorder" || true
  recorder=""
  [ -f "$dir/run$run.bag" ] || { echo "lockstep_repro: run $run: the recorder left no bag" >&2; tail -5 "$dir/record$run.log" >&2; exit 1; }
  grep '^world_sim summary:' "$dir/run$run.log" >"$dir/summary$run" || {
    echo "lockstep_repro: run $run printed no world_sim summary:" >&2
    tail -20 "$dir/run$run.log" >&2
    exit 1
  }
done

grep -h '^audio_propagation summary:' "$dir/run1.log" "$dir/run2.log" | sed 's/^/  /' || true
echo "run 1: $(cat "$dir/summary1")"
echo "run 2: $(cat "$dir/summary2")"
for run in 1 2; do
  grep -q 'rejected 0, dropped 0$' "$dir/summary$run" || { echo "lockstep_repro: run $run: world_sim rejected or lost commands" >&2; exit 1; }
  sed 's/; inputs .*//' "$dir/summary$run" >"$dir/simulated$run"
done
if ! cmp -s "$dir/simulated1" "$dir/simulated2"; then
  echo "lockstep_repro: the two runs' world_sim summaries differ" >&2
  exit 1
fi

/usr/bin/python3 - "$dir/run1.bag" "$dir/run2.bag" <<'PY'
import sys
import rosbag

def per_topic(path):
    out = {}
    with rosbag.Bag(path) as bag:
        for topic, raw, _ in bag.read_messages(raw=True):
            out.setdefault(topic, []).append(raw[1])
    return out

a, b = per_topic(sys.argv[1]), per_topic(sys.argv[2])
packets = sum(len(v) for t, v in a.items() if t.endswith('/audio/rx'))
if packets == 0:
    sys.exit('lockstep_repro: no audio traffic recorded: nothing compared')
for topic in sorted(set(a) | set(b)):
    x, y = a.get(topic, []), b.get(topic, [])
    if x != y:
        first = next((i for i, (p, q) in enumerate(zip(x, y)) if p != q), min(len(x), len(y)))
        sys.exit('lockstep_repro: %s differs: %d and %d messages, first difference at message %d'
                 % (topic, len(x), len(y), first))
print('lockstep_repro: same audio traffic in both runs: %d topics, %d messages (%d receptions)'
      % (len(a), sum(len(v) for v in a.values()), packets))
PY
