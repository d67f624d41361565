#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job on shipped defaults: a simulated team
# in the office world, headless and faster than real time, then prints a summary.
#
#   scripts/demo.sh                 headless, 120 simulated seconds at 20x real time
#   scripts/demo.sh --rviz          the same team in real time, shown in rviz (Ctrl-C to stop)
#   scripts/demo.sh [--rviz] [roslaunch args...]   e.g. speed:=50 duration:=300
set -euo pipefail
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

rviz=false
args=()
for a in "$@"; do
  case "$a" in
    --rviz) rviz=true ;;
    -h|--help) sed -n '2,8p' "$0"; exit 0 ;;
    *) args+=("$a") ;;
  esac
done

"$here/scripts/setup.sh"
set +u
# shellcheck disable=SC1091
source "$here/build/devel/setup.bash"
set -u

if $rviz; then
  exec roslaunch multirobot_audio sim_team.launch rviz:=true "${args[@]}"
fi

log=$(mktemp)
trap 'rm -f "$log"' EXIT
# A master of our own on a free port, so that a roscore already running is left alone.
port=$(/usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
export ROS_MASTER_URI="http://127.0.0.1:${port}"
roslaunch --port "$port" multirobot_audio sim_team.launch speed:=20 duration:=120 "${args[@]}" >"$log" 2>&1 || {
  cat "$log" >&2
  echo "demo.sh: the simulated team failed" >&2
  exit 1
}
summary=$(grep -m1 '^world_sim summary:' "$log" || true)
if [ -z "$summary" ]; then
  cat "$log" >&2
  echo "demo.sh: the team ran but world_sim printed no summary" >&2
  exit 1
fi
echo "$summary"
