#!/usr/bin/env bash
# roslaunch's env-loader for a robot's machine (launch/team_robots.launch, <machine env-loader>):
# roslaunch runs it over ssh as `robot_env.sh roslaunch --child ...`, in a non-interactive shell
# that has read none of the user's profile. It sets up this workspace's ROS environment, then
# the machine's own settings, and runs its arguments.
#
#   scripts/robot_env.sh COMMAND [ARGS...]      e.g. scripts/robot_env.sh rosnode list
#
# The machine's own settings (ROS_IP or ROS_HOSTNAME: the address the other machines reach this
# one at; anything else it needs) go into ~/.ros/robot_env, or the file named by
# $MULTIROBOT_AUDIO_ROBOT_ENV, a shell file of `export` lines read after the workspace.
# roslaunch passes ROS_MASTER_URI itself.
set -eo pipefail
# Debian's python3 and ROS tools ahead of any private ones, as in the other scripts.
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"

if [ $# -lt 1 ]; then
  echo "usage: $0 COMMAND [ARGS...]" >&2
  exit 2
fi

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# scripts/setup.sh keeps the devel space beside build/; a plain catkin build has it inside.
setup=""
for candidate in "$here/devel/setup.bash" "$here/build/devel/setup.bash"; do
  if [ -f "$candidate" ]; then setup=$candidate; break; fi
done
if [ -z "$setup" ]; then
  echo "robot_env.sh: no devel/setup.bash under $here (build the workspace on this machine first)" >&2
  exit 1
fi
# A sourced script sees our arguments unless it is given its own: keep them aside.
command=("$@")
set --
# shellcheck disable=SC1090
source "$setup"

machine_env="${MULTIROBOT_AUDIO_ROBOT_ENV:-$HOME/.ros/robot_env}"
if [ -f "$machine_env" ]; then
  # shellcheck disable=SC1090
  source "$machine_env"
fi

exec "${command[@]}"
