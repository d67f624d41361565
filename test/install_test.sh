#!/usr/bin/env bash
# The package used from its install space, as a user of a built (or binary) package has it:
# installs the build into a temporary prefix, checks that every node and tool is there as
# lib/multirobot_audio/NAME with the data under share/multirobot_audio/ and that no installed
# program names the source tree; then, with the source tree (and the build and devel spaces in it)
# hidden behind an empty folder, runs from the install space alone:
#   nava_encode | nava_decode, sounds_good_experiment --quick, and a short
#   sim_team.launch channel_model:=acoustic under rostest (a robot hears a teammate).
#
#   install_test.sh SOURCE_DIR BUILD_DIR
# Hiding the tree takes a mount namespace (unshare -rm); where the machine refuses one the runs
# happen with the tree in place, after the check that nothing installed names it.
set -uo pipefail
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
src=$(cd "$1" && pwd -P)
build=$(cd "$2" && pwd -P)
work=$(mktemp -d /tmp/multirobot_audio_install.XXXXXX)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" >"$work/install.log" 2>&1 || { tail -20 "$work/install.log"; fail "cmake --install failed"; }

programs=(world_sim wanderer audio_propagation nava_modem local_mutex mutex_client sounds_good_explorer task_monitor
          charging_demo nava_encode nava_decode nava_room nava_bench survey_bench audio_propagation_query audio_propagation_bench
          audio_scene_render audio_channel_validate audio_channel_predict nava_survey decode_table_bench ranging_bench world_sim_bench
          local_mutex_sim sounds_good_experiment charging_experiment)
for p in "${programs[@]}"; do
  [ -x "$prefix/lib/multirobot_audio/$p" ] || fail "lib/multirobot_audio/$p is not installed"
done
share=$prefix/share/multirobot_audio
for f in package.xml tables/nava.yaml tables/room.yaml launch/sim_team.launch maps/office.yaml maps/office_world.yaml \
         rviz/sim.rviz make_speech.sh msg/AudioReception.msg action/AcquireLock.action; do
  [ -e "$share/$f" ] || fail "share/multirobot_audio/$f is not installed"
done
[ -f "$prefix/include/multirobot_audio/AudioReception.h" ] || fail "the messages' C++ headers are not installed"
# Nothing installed may lead back into the source tree (a path compiled in, a link).
if grep -rlF "$src/" "$prefix/lib/multirobot_audio" "$share" >"$work/named" 2>/dev/null; then
  fail "installed files name the source tree $src: $(tr '\n' ' ' <"$work/named")"
fi
if find "$share" -type l | grep -q .; then fail "the share folder holds links: $(find "$share" -type l | head -3)"; fi
echo "install_test: every program and the data installed under $prefix; none names $src"

# The runs, from the install space alone. rostest runs a .test file of a package: a package of
# the test's own holds it.
mkdir -p "$work/install_check"
cat >"$work/install_check/package.xml" <<'EOF'
<?xml version="1.0"?>
<package format="2">
  <name>install_check</name>
  <version>0.0.0</version>
  <description>multirobot_audio's install test: a team launched from the install space</description>
  <maintainer email="nobody@example.com">nobody</maintainer>
  <license>BSD</license>
  <exec_depend>multirobot_audio</exec_depend>
</package>
EOF
cat >"$work/install_check/team.test" <<'EOF'
<launch>
  <include file="$(find multirobot_audio)/launch/sim_team.launch">
    <arg name="robots" value="3"/>
    <arg name="speed" value="4"/>
    <arg name="channel_model" value="acoustic"/>
    <arg name="announce_period" value="1.0"/>
  </include>
  <test test-name="a_robot_hears_a_teammate" pkg="rostest" type="publishtest" time-limit="120">
    <rosparam>
      topics:
        - {name: /robot_0/audio/rx, timeout: 60}
        - {name: /robot_1/audio/rx, timeout: 60}
    </rosparam>
  </test>
</launch>
EOF
cat >"$work/runs.sh" <<EOF
set -euo pipefail
cd "$work"
env -i HOME="$work" PATH=/usr/bin:/bin bash -euo pipefail -c '
  set +u; source "$prefix/setup.bash"; set -u
  export ROS_PACKAGE_PATH="\$ROS_PACKAGE_PATH:$work/install_check"
  export ROS_HOME="$work/ros" ROS_LOG_DIR="$work/ros/log"
  [ "\$(rospack find multirobot_audio)" = "$share" ] || { echo "rospack finds \$(rospack find multirobot_audio)"; exit 1; }
  lib="$prefix/lib/multirobot_audio"
  "\$lib/nava_encode" --out "$work/p.wav" 0badc0de 12345678 >/dev/null
  "\$lib/nava_decode" "$work/p.wav" >"$work/decoded"
  grep -q "\"data\": \"0badc0de\"" "$work/decoded" && grep -q "\"data\": \"12345678\"" "$work/decoded" \
    || { cat "$work/decoded"; echo "nava_decode did not read nava_encode'"'"'s packets"; exit 1; }
  echo "install_test: nava_encode | nava_decode read both packets back"
  "\$lib/sounds_good_experiment" --quick --out "$work/experiment" >"$work/experiment.out" 2>"$work/experiment.err" \
    || { tail "$work/experiment.err"; echo "sounds_good_experiment --quick failed"; exit 1; }
  [ -s "$work/experiment/table_3_1.md" ] || { echo "sounds_good_experiment wrote no table"; exit 1; }
  echo "install_test: sounds_good_experiment --quick ran"
  rostest install_check team.test >"$work/rostest.out" 2>&1 || { tail -40 "$work/rostest.out"; echo "the team launched from the install space failed"; exit 1; }
  # rostest calls a run whose test node was shut down (say, by a required node that died) a
  # success with no tests: the test must have run.
  grep -q "^ \* TESTS: 1\$" "$work/rostest.out" && grep -q "^ \* FAILURES: 0\$" "$work/rostest.out" \
    || { tail -40 "$work/rostest.out"; echo "the team launched from the install space did not run its test"; exit 1; }
  echo "install_test: sim_team.launch channel_model:=acoustic from the install space, robots heard each other"
'
EOF
empty=$work/empty
mkdir -p "$empty"
if unshare -rm true 2>/dev/null; then
  unshare -rm bash -c "mount --bind '$empty' '$src' && [ -z \"\$(ls -A '$src')\" ] && echo 'install_test: the source tree $src is hidden' && bash '$work/runs.sh'" \
    || fail "a run from the install space failed (above)"
else
  echo "install_test: this machine refuses a mount namespace; running with the source tree in place"
  bash "$work/runs.sh" || fail "a run from the install space failed (above)"
fi
echo "install_test: passed"
