#!/usr/bin/env bash
# Takes the pictures in docs/images/ from the running demos: for each scene it starts a master,
# the demo's launch file and rviz on a private Xvfb screen, waits until the demo shows what the
# picture is for, stops the simulated clock there (scripts/screenshot_moment.py), captures the
# screen, crops it to rviz's 3D view and writes docs/images/<scene>.png. Rerun it by hand when
# the look of the demos changes; it is not part of the tests. Needs a built workspace.
#
#   scripts/screenshots.sh              every scene
#   scripts/screenshots.sh SCENE...     some of them: sound_paths sounds_good charging_queue
#                                       delivery_map teammates
#
# Environment: BUILD_DIR (the catkin build folder, default build/), SHOTS_DISPLAY (the Xvfb
# display, default :91), SHOTS_PORT (the ROS master's port, default 11391), SHOTS_OUT (where the
# pictures go, default docs/images), SHOTS_KEEP (a folder to keep the logs and full screens in).
set -euo pipefail
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

build_dir="${BUILD_DIR:-$here/build}"
display="${SHOTS_DISPLAY:-:91}"
port="${SHOTS_PORT:-11391}"
out_dir="${SHOTS_OUT:-$here/docs/images}"
all_scenes=(sound_paths sounds_good charging_queue delivery_map teammates)

die() { echo "screenshots.sh: $*" >&2; exit 1; }

scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=("${all_scenes[@]}")
for s in "${scenes[@]}"; do
  case " ${all_scenes[*]} " in
    *" $s "*) ;;
    *) die "unknown scene '$s' (expected some of: ${all_scenes[*]})" ;;
  esac
done

[ -f "$build_dir/devel/setup.bash" ] ||
  die "no built workspace: $build_dir/devel/setup.bash is missing; run scripts/demo.sh or scripts/test.sh first (they build into build/), or set BUILD_DIR"
for tool in Xvfb import convert identify xwininfo; do
  command -v "$tool" >/dev/null || die "$tool is missing; run scripts/setup.sh --no-build"
done
[ -e "/tmp/.X11-unix/X${display#:}" ] && die "display $display is in use; set SHOTS_DISPLAY to a free one"

# catkin's setup script reads unset variables.
set +u
# shellcheck disable=SC1091
source "$build_dir/devel/setup.bash"
set -u
for tool in roslaunch roscore rosrun rviz; do
  command -v "$tool" >/dev/null || die "$tool is missing; run scripts/setup.sh --no-build"
done

export ROS_MASTER_URI="http://localhost:${port}"
export DISPLAY="$display"
# No GPU under Xvfb: Mesa's software renderer (llvmpipe).
export LIBGL_ALWAYS_SOFTWARE=1
/usr/bin/python3 -c "import rosgraph, sys; sys.exit(rosgraph.is_master_online())" ||
  die "a ROS master already answers on port $port; set SHOTS_PORT to a free one"

work="${SHOTS_KEEP:-$(mktemp -d)}"
mkdir -p "$work" "$out_dir"

# Every process started here, stopped on the way out whatever happens. world_sim is not ours
# directly (roslaunch started it), but we stop its clock with SIGSTOP and must let it go on.
started=()
frozen=""
stop_pid() {  # pid: SIGINT (roslaunch and roscore stop their children on it), then harder
  local pid=$1
  kill -INT "$pid" 2>/dev/null || return 0
  for _ in $(seq 1 100); do
    kill -0 "$pid" 2>/dev/null || return 0
    sleep 0.1
  done
  kill -TERM "$pid" 2>/dev/null || return 0
  sleep 3
  kill -KILL "$pid" 2>/dev/null || true
}
stop_all() {
  if [ -n "$frozen" ]; then kill -CONT "$frozen" 2>/dev/null || true; frozen=""; fi
  local k
  for ((k = ${#started[@]} - 1; k >= 0; k--)); do stop_pid "${started[k]}"; done
  started=()
}
cleanup() {
  local status=$?
  stop_all
  [ -n "${xvfb_pid:-}" ] && stop_pid "$xvfb_pid"
  [ -z "${SHOTS_KEEP:-}" ] && rm -rf "$work"
  exit "$status"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# A fixed screen, so that every run draws the same number of pixels.
Xvfb "$display" -screen 0 1280x800x24 -nolisten tcp >"$work/xvfb.log" 2>&1 &
xvfb_pid=$!
for _ in $(seq 1 100); do
  xwininfo -root >/dev/null 2>&1 && break
  kill -0 "$xvfb_pid" 2>/dev/null || { cat "$work/xvfb.log" >&2; die "Xvfb did not start on $display"; }
  sleep 0.1
done

# Writes the rviz config for one picture: the demo's config from rviz/ with a fixed window, no
# panels (so that the 3D view fills the window; "Hide Left Dock" does not hide a panel before
# the window is shown), a fixed top-down view, a lower frame rate (software rendering shares
# the two cores with the simulation), and marker namespaces hidden as DISPLAY/NAMESPACE.
screenshot_config() {  # base out width height scale x y [DISPLAY/NAMESPACE...]
  /usr/bin/python3 - "$@" <<'EOF'
import sys, yaml
base, out, width, height, scale, x, y = sys.argv[1:8]
with open(base) as f:
    config = yaml.safe_load(f)
config["Panels"] = []
config["Window Geometry"].update({"Width": int(width), "Height": int(height), "X": 0, "Y": 0})
manager = config["Visualization Manager"]
manager["Global Options"]["Frame Rate"] = 10
manager["Views"]["Current"].update({"Scale": float(scale), "X": float(x), "Y": float(y)})
for hidden in sys.argv[8:]:
    display, namespace = hidden.split("/")
    matches = [d for d in manager["Displays"] if d["Name"] == display]
    if not matches:
        sys.exit("screenshots.sh: no display '%s' in %s" % (display, base))
    matches[0]["Namespaces"] = {namespace: False}
with open(out, "w") as f:
    yaml.safe_dump(config, f, sort_keys=False)
EOF
}

# Waits until node $1 has subscribed to topic $2 (at most $3 s).
wait_subscribed() {
  /usr/bin/python3 - "$@" <<'EOF'
import sys, time, rosgraph
node, topic, timeout = sys.argv[1], sys.argv[2], float(sys.argv[3])
master = rosgraph.Master("/screenshots")
deadline = time.monotonic() + timeout
while time.monotonic() < deadline:
    _, subscribers, _ = master.getSystemState()
    if any(t == topic and node in nodes for t, nodes in subscribers):
        sys.exit(0)
    time.sleep(0.5)
sys.exit(1)
EOF
}

alive_or_die() {  # pid name log
  kill -0 "$1" 2>/dev/null || { tail -n 30 "$3" >&2; die "$2 stopped early (log above: $3)"; }
}

# One picture: scene name, launch file and its arguments, the rviz config it is drawn with,
# the window and view (scale x y, then marker namespaces to hide), the moment to wait for, and
# parameters set before the launch.
shoot() {
  local name=$1 launch=$2 launch_args=$3 rviz_base=$4 window=$5 view=$6 moment=$7 params=$8
  local log="$work/$name"
  echo "screenshots.sh: $name: roslaunch multirobot_audio $launch $launch_args"

  roscore -p "$port" >"$log.roscore.log" 2>&1 &
  started+=($!)
  for _ in $(seq 1 300); do
    /usr/bin/python3 -c "import rosgraph, sys; sys.exit(not rosgraph.is_master_online())" && break
    alive_or_die "${started[-1]}" roscore "$log.roscore.log"
    sleep 0.1
  done
  # Parameters the launch file leaves alone but the picture needs (roslaunch keeps them).
  local p
  for p in $params; do rosparam set "${p%%=*}" "${p#*=}"; done

  # shellcheck disable=SC2086
  roslaunch multirobot_audio "$launch" $launch_args rviz:=false >"$log.launch.log" 2>&1 &
  local launch_pid=$!
  started+=("$launch_pid")
  timeout 120 rostopic echo -n1 /clock >/dev/null 2>&1 ||
    { alive_or_die "$launch_pid" roslaunch "$log.launch.log"; die "$name: no /clock after 120 s"; }
  local world_pid
  world_pid=$(rosnode info /world_sim 2>/dev/null | sed -n 's/^Pid: //p')
  [ -n "$world_pid" ] || die "$name: no pid for /world_sim"

  # rviz after the launch file has set /use_sim_time, so that it runs on the simulated clock.
  # shellcheck disable=SC2086
  screenshot_config "$here/rviz/$rviz_base" "$log.rviz" $window $view
  rviz -d "$log.rviz" __name:=screenshots_rviz >"$log.rviz.log" 2>&1 &
  local rviz_pid=$!
  started+=("$rviz_pid")
  wait_subscribed /screenshots_rviz /map 120 ||
    { alive_or_die "$rviz_pid" rviz "$log.rviz.log"; die "$name: rviz did not subscribe to /map in 120 s"; }
  sleep 15  # rviz loads its displays and draws the map

  # From here on world_sim may be stopped (SIGCONT does no harm to a running process).
  frozen=$world_pid
  # In the background and waited for, so that a TERM stops the script at once.
  # shellcheck disable=SC2086
  /usr/bin/python3 "$here/scripts/screenshot_moment.py" $moment --freeze "$world_pid" >"$log.moment.log" 2>&1 &
  started+=($!)
  local status=0
  wait "${started[-1]}" || status=$?
  unset 'started[-1]'  # waited for: its pid is free for others now
  if [ "$status" -ne 0 ]; then
    cat "$log.moment.log" >&2
    alive_or_die "$launch_pid" roslaunch "$log.launch.log"
    die "$name: the scene never came"
  fi
  cat "$log.moment.log"
  sleep 10  # rviz draws the frozen moment
  alive_or_die "$rviz_pid" rviz "$log.rviz.log"

  # Crop to rviz's 3D view: the largest unnamed window, the one OGRE draws in.
  import -window root "$log.screen.png"
  local crop
  crop=$(xwininfo -root -tree | awk '/\(has no name\): \(\)/ {
      split($(NF-1), s, /[x+]/); split($NF, a, /\+/);
      if (s[1] * s[2] > best) { best = s[1] * s[2]; g = s[1] "x" s[2] "+" a[2] "+" a[3] } }
    END { print g }')
  [ -n "$crop" ] || die "$name: rviz's 3D view not found on $display"
  convert "$log.screen.png" -crop "$crop" +repage -strip "$log.png"

  # A picture with only a few colours is a blank or black view, not a scene: it does not replace
  # the last good one.
  local colours
  colours=$(identify -format '%k' "$log.png")
  [ "$colours" -gt 32 ] || die "$name: the capture has only $colours colours: rviz drew nothing (DISPLAY $display)"
  mv "$log.png" "$out_dir/$name.png"
  echo "screenshots.sh: wrote $out_dir/$name.png ($(identify -format '%wx%h' "$out_dir/$name.png"), $colours colours, $(du -k "$out_dir/$name.png" | cut -f1) KB)"
  stop_all
}

for s in "${scenes[@]}"; do
  case "$s" in
    sound_paths)
      # Most of the office (28 x 16 m), five wanderers announcing themselves every 5 s: wait for
      # sound that reaches two robots round door jambs while every sound path drawn lies well
      # inside the view, so that no robot is cut off at the edge.
      shoot sound_paths sim_team.launch "seed:=1 speed:=1" sim.rviz "1280 800" "44 17 7" \
        "paths --robots 5 --count 2 --within 4.5 0.5 29.5 13.5 --after 20 --timeout 1200" "" ;;
    sounds_good)
      # The whole office after a minute and a half of simulated time, the robots still spread
      # out: every explorer's local map, plan and goal.
      shoot sounds_good sounds_good.launch "seed:=1 speed:=3" sounds_good.rviz "1280 640" "36 17 7" \
        "plans --robots 5 --count 4 --after 90 --timeout 900" "" ;;
    charging_queue)
      # The 6 x 4 m room: robot_0 charges first (from about 400 s), and robot_1 and robot_2 wait
      # for the lock on the ring. When they wait side by side their labels overlap; then, once
      # that first queue is over, one robot waiting while another charges will do.
      # world_sim's 0.4 m names would cover the controllers' labels, which name the robots too.
      # At speed:=10 the four controllers' markers (10 a simulated second each) come faster than
      # a software-rendering rviz takes them through TF; it drops some, and a robot's label can
      # be missing from the picture. speed:=3 is slower to get there, and keeps every label.
      shoot charging_queue charging_sim.launch "seed:=1 speed:=3" charging.rviz "1280 760" \
        "160 3 2 World/names" \
        "queue --robots 4 --count 2 --fallback 1 --fallback-after 1200 --hold 10 --after 60 --timeout 1200" "" ;;
    delivery_map)
      # The acoustic channel model: where robot_0 is heard (the delivery map), and sound paths
      # coloured by their chance of being decoded.
      shoot delivery_map sim_team.launch \
        "seed:=1 speed:=1 channel_model:=acoustic delivery_map_robot:=robot_0" sim.rviz "1280 640" \
        "36 17 7" "paths --robots 5 --count 1 --after 20 --timeout 900" "/audio_propagation/path_display_time=2.0" ;;
    teammates)
      # Each robot's estimate of where its teammates are, from two-way ranging and the bearing
      # of their packets, beside the true robots: after a minute every pair that hears each
      # other has exchanged packets both ways.
      shoot teammates sim_team.launch "seed:=1 speed:=1" sim.rviz "1280 800" "44 17 7" \
        "paths --robots 5 --count 1 --after 60 --timeout 900" "" ;;
  esac
done
echo "screenshots.sh: done"
