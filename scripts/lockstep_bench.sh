#!/usr/bin/env bash
# Benchmark of the lockstep: a simulated team of ROBOTS wanderers announcing themselves every
# 5 s (as sim_team.launch does), run at speed 0 (lockstep) for SECONDS simulated seconds, on a
# roscore of its own. Prints the run's world_sim lines, the real-time factor, and what each
# participant kept the world waiting (audio_propagation, and the wanderers' total and worst).
# With REAL_SECONDS > 0 it also runs at speed 1 for that long and compares the distance driven
# per simulated second (the lockstep must drive the same: within 10 %).
#
#   scripts/lockstep_bench.sh [ROBOTS=20] [SECONDS=120] [REAL_SECONDS=0] [LAUNCH ARGS...]
#
# The world: maps/office_team20_world.yaml up to 20 robots, maps/campus_team60_world.yaml up to
# 60, maps/campus_team100_world.yaml up to 100, and beyond that one written for the run by
# scripts/make_team_world.py on the campus map. Launch arguments go to sim_team.launch (for
# example channel_model:=acoustic, update:=every_step for audio_propagation's old cadence, or
# one_process:=false for a wanderer node per robot instead of one process driving the team).
# Needs the built workspace (scripts/demo.sh or scripts/test.sh build it).
set -euo pipefail
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
robots=${1:-20}
seconds=${2:-120}
real_seconds=${3:-0}
shift $(($# < 3 ? $# : 3))
case "$robots" in '' | *[!0-9]*) echo "lockstep_bench: ROBOTS '$robots': expected a whole number" >&2; exit 2 ;; esac

set +u
# shellcheck disable=SC1091
source "$here/build/devel/setup.bash"
set -u
dir=$(mktemp -d /tmp/lockstep_bench.XXXXXX)
core=""
cleanup() {
  if [ -n "$core" ]; then kill "$core" 2>/dev/null || true; wait "$core" 2>/dev/null || true; fi
  rm -rf "$dir"
}
trap cleanup EXIT

if [ "$robots" -le 20 ]; then
  world="$here/maps/office_team20_world.yaml"
elif [ "$robots" -le 60 ]; then
  world="$here/maps/campus_team60_world.yaml"
elif [ "$robots" -le 100 ]; then
  world="$here/maps/campus_team100_world.yaml"
else
  /usr/bin/python3 "$here/scripts/make_team_world.py" "$here/maps/campus.yaml" "$robots" "$dir/world.yaml"
  sed -i "s|^map: campus.yaml|map: $here/maps/campus.yaml|" "$dir/world.yaml"
  world="$dir/world.yaml"
fi

# shellcheck disable=SC1091
source "$here/scripts/private_master.sh"
start_private_master "$dir/roscore.log"

run() {  # name speed duration
  if ! roslaunch multirobot_audio sim_team.launch world:="$world" robots:="$robots" speed:="$2" duration:="$3" "${@:4}" \
    >"$dir/$1.log" 2>&1; then
    echo "lockstep_bench: the $1 run failed:" >&2
    tail -20 "$dir/$1.log" >&2
    exit 1
  fi
  grep -E '^world_sim (summary|timing):' "$dir/$1.log" | sed "s/^/$1: /"
}
echo "lockstep_bench: $robots robots, $(basename "$world"), $seconds s simulated${*:+, $*}"
run lockstep 0 "$seconds" "$@"
[ "$real_seconds" != 0 ] && run realtime 1 "$real_seconds" "$@"

/usr/bin/python3 - "$dir/lockstep.log" "$( [ "$real_seconds" != 0 ] && echo "$dir/realtime.log")" <<'PY'
import re, sys
def figures(path):
    text = open(path).read()
    s = re.search(r'world_sim summary: robots \d+, simulated ([\d.]+) s, distance driven ([\d.]+) m', text)
    t = re.search(r'world_sim timing: wall ([\d.]+) s, real-time factor ([\d.]+)', text)
    if not s or not t:
        sys.exit('lockstep_bench: no world_sim summary in ' + path)
    return float(s.group(1)), float(s.group(2)), float(t.group(1)), float(t.group(2)), text
sim0, dist0, wall0, rtf0, text = figures(sys.argv[1])
waits = re.search(r'world_sim lockstep waits \(wall s\):(.*)', text)
pairs = re.findall(r'(\S+) ([\d.]+)', waits.group(1)) if waits else []
audio = sum(float(s) for n, s in pairs if n == '/audio_propagation')
wanderers = [float(s) for n, s in pairs if n.endswith('/wanderer') or n == '/wanderers']
updates = re.search(r'audio_propagation summary:.*updates (\d+)', text)
print('real_time_factor %.1f (wall %.1f s for %.0f s simulated)' % (rtf0, wall0, sim0))
print('kept_waiting audio_propagation %.1f s%s; wanderers %.1f s in all, worst %.2f s'
      % (audio, ' (%s updates)' % updates.group(1) if updates else '', sum(wanderers), max(wanderers, default=0.0)))
if len(sys.argv) > 2 and sys.argv[2]:
    sim1, dist1, _, _, _ = figures(sys.argv[2])
    per0, per1 = dist0 / sim0, dist1 / sim1
    print('distance_per_sim_s lockstep %.3f realtime %.3f ratio %.3f (target 0.9-1.1)' % (per0, per1, per0 / per1))
PY
