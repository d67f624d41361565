#!/usr/bin/env bash
# Benchmark of the lockstep: a simulated team of ROBOTS wanderers in the office, run at speed 0
# (lockstep) for SECONDS simulated seconds and at speed 1 for REAL_SECONDS, on a roscore of its
# own. Prints each run's world_sim lines, then the distance driven per simulated second in both
# and their ratio (the lockstep must drive the same: within 10 %), and the lockstep run's
# real-time factor (target: at least 10 for 20 robots on two cores).
#
#   scripts/lockstep_bench.sh [ROBOTS=20] [SECONDS=300] [REAL_SECONDS=60]
#
# Needs the built workspace (scripts/demo.sh or scripts/test.sh build it).
set -euo pipefail
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
robots=${1:-20}
seconds=${2:-300}
real_seconds=${3:-60}
world="$here/maps/office_team20_world.yaml"

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
# shellcheck disable=SC1091
source "$here/scripts/private_master.sh"
start_private_master "$dir/roscore.log"

run() {  # name speed duration
  roslaunch multirobot_audio sim_team.launch world:="$world" robots:="$robots" speed:="$2" duration:="$3" \
    >"$dir/$1.log" 2>&1
  grep -E '^world_sim (summary|timing):' "$dir/$1.log" | sed "s/^/$1: /"
}
run lockstep 0 "$seconds"
run realtime 1 "$real_seconds"

/usr/bin/python3 - "$dir/lockstep.log" "$dir/realtime.log" <<'PY'
import re, sys
def figures(path):
    text = open(path).read()
    s = re.search(r'world_sim summary: robots \d+, simulated ([\d.]+) s, distance driven ([\d.]+) m', text)
    t = re.search(r'world_sim timing: wall ([\d.]+) s, real-time factor ([\d.]+)', text)
    if not s or not t:
        sys.exit('lockstep_bench: no world_sim summary in ' + path)
    return float(s.group(1)), float(s.group(2)), float(t.group(2))
sim0, dist0, rtf0 = figures(sys.argv[1])
sim1, dist1, rtf1 = figures(sys.argv[2])
per0, per1 = dist0 / sim0, dist1 / sim1
print('distance_per_sim_s lockstep %.3f realtime %.3f ratio %.3f (target 0.9-1.1)' % (per0, per1, per0 / per1))
print('lockstep_real_time_factor %.1f (target >= 10)' % rtf0)
PY
