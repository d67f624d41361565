#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on shipped defaults: the Sounds Good
# team (thesis chapter 3), five robots with bidirectional microphones carrying loads between
# two markers in the office world, headless and faster than real time, then prints how many
# simulated seconds the team took to finish 20 jobs (about two minutes of wall time).
#
#   scripts/demo.sh                 headless at 30x real time until the team has done 20 jobs
#   scripts/demo.sh --rviz          the same team at 3x real time, shown in rviz (Ctrl-C to stop)
#   scripts/demo.sh [--rviz] [roslaunch args...]   e.g. mode:=omni goal:=10 seed:=4 speed:=20
set -euo pipefail
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

rviz=false
args=()
for a in "$@"; do
  case "$a" in
    --rviz) rviz=true ;;
    -h|--help) sed -n '2,9p' "$0"; exit 0 ;;
    *) args+=("$a") ;;
  esac
done

"$here/scripts/setup.sh"
set +u
# shellcheck disable=SC1091
source "$here/build/devel/setup.bash"
set -u

if $rviz; then
  exec roslaunch multirobot_audio sounds_good.launch rviz:=true speed:=3 "${args[@]}"
fi

log=$(mktemp)
trap 'rm -f "$log"' EXIT
# A master of our own on a free port, so that a roscore already running is left alone.
port=$(/usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
export ROS_MASTER_URI="http://127.0.0.1:${port}"
# 30x is about as fast as the explorers keep up with the simulated clock on two cores; faster,
# their commands come late, the robots stall and the team takes longer. The duration bounds a
# team that never finishes (20 jobs usually take 1500 to 4000 simulated seconds).
roslaunch --port "$port" multirobot_audio sounds_good.launch speed:=30 duration:=20000 "${args[@]}" >"$log" 2>&1 || {
  cat "$log" >&2
  echo "demo.sh: the Sounds Good team failed" >&2
  exit 1
}
# "task_monitor: team finished 20 jobs in T s", or "... finished N of 20 jobs by T s" when the
# simulation ran out first.
result=$(grep -m1 '^task_monitor: team finished' "$log" || true)
if [ -z "$result" ]; then
  cat "$log" >&2
  echo "demo.sh: the team ran but task_monitor printed no result" >&2
  exit 1
fi
echo "$result"
grep -E '^world_sim (summary|timing):' "$log" || true
