#!/usr/bin/env bash
# Installs every Debian package multirobot_audio needs (only what is missing), then configures
# and builds the package in Release into build/.
#
#   scripts/setup.sh [--no-build | --werror]
# --werror: a compiler warning fails the build (scripts/test.sh, and so CI, build this way).
set -euo pipefail

# A pyenv or conda python3 ahead of Debian's breaks catkin and roslaunch: Debian's first.
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

packages=(
  # toolchain; ccache keeps compiled objects between builds (CMakeLists.txt uses it when found),
  # so that CI's clean clones compile only what changed
  build-essential cmake git pkg-config ccache
  # ROS 1 as Debian packages it: core, build tools, and both halves of each message package
  catkin ros-environment ros-cmake-modules libroscpp-dev librosconsole-dev
  ros-message-generation ros-message-runtime
  ros-std-msgs libstd-msgs-dev ros-geometry-msgs libgeometry-msgs-dev
  ros-sensor-msgs libsensor-msgs-dev ros-nav-msgs libnav-msgs-dev
  ros-visualization-msgs libvisualization-msgs-dev ros-rosgraph-msgs libros-rosgraph-msgs-dev
  ros-std-srvs libstd-srvs-dev ros-actionlib-msgs libactionlib-msgs-dev libactionlib-dev
  ros-diagnostic-msgs libdiagnostic-msgs-dev
  libtf2-dev libtf2-ros-dev libtf2-msgs-dev libtf2-geometry-msgs-dev ros-tf2-msgs
  python3-roslaunch python3-rosmaster python3-rosgraph python3-rosnode python3-rosparam
  python3-rosservice rosout rosbash python3-rostopic python3-rosbag librosbag-dev
  # roslaunch's <machine> tags (launch/team_robots.launch) ssh through paramiko, which Debian's
  # python3-roslaunch only recommends
  python3-paramiko
  librostest-dev python3-rostest rviz
  # Python halves of the messages, for rostopic, rosbag and other command-line tools
  python3-std-msgs python3-geometry-msgs python3-sensor-msgs python3-nav-msgs
  python3-visualization-msgs python3-rosgraph-msgs python3-tf2-msgs python3-tf2-ros
  python3-diagnostic-msgs python3-actionlib-msgs python3-std-srvs
  # libraries the ROS-free components use
  libyaml-cpp-dev libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev
  libeigen3-dev libgtest-dev libgmock-dev libbenchmark-dev libboost-dev
  # the audio link: sound files, ALSA, diagnostics; PulseAudio and ALSA's pulse plugin as the
  # air for tests on machines without a sound card; minimodem to check we talk to others
  libsndfile1-dev libasound2-dev libdiagnostic-updater-dev
  pulseaudio pulseaudio-utils libasound2-plugins alsa-utils minimodem
  # the room profile and the room channel: FEC (libfec: Viterbi, Reed-Solomon), FFTs (FFTW),
  # resampling for clock offsets (libsamplerate); espeak-ng and sox make test speech at run time
  libfec-dev libfftw3-dev libsamplerate0-dev espeak-ng sox
  # scripts/screenshots.sh: xwininfo finds rviz's 3D view on the screen; its Python helpers use
  # PyYAML and rospy
  x11-utils python3-yaml python3-rospy
  # headless rviz and screenshots
  xvfb x11-apps imagemagick mesa-utils libgl1-mesa-dri
  # scripts/fuzz.sh: libFuzzer needs clang; the sanitizers' and the fuzzer's runtimes
  clang-14 libclang-rt-14-dev libfuzzer-14-dev
  # real recorded noises (running water, CC0; a fire, CC BY 3.0) for the model's calibration in
  # recorded noise (docs/audio_link.md), read from /usr/share/games/minetest, never copied
  minetest-data
  # scripts/get_thesis_map.sh downloads the thesis's map from Stage's repository
  curl ca-certificates
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -gt 0 ]; then
  sudo_cmd=()
  [ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
  echo "setup.sh: installing ${#missing[@]} missing packages: ${missing[*]}"
  "${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
  "${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

[ "${1:-}" = "--no-build" ] && exit 0
werror=OFF
[ "${1:-}" = "--werror" ] && werror=ON

# The devel space lives beside build/, not in it: rosrun skips everything below a package's
# build/ folder, so executables there cannot be rosrun. build/devel links to it, so that
# `source build/devel/setup.bash` works as usual.
cmake -S "$here" -B "$here/build" -DCMAKE_BUILD_TYPE=Release -DCATKIN_DEVEL_PREFIX="$here/devel" \
  -DMULTIROBOT_AUDIO_WERROR="$werror" >/dev/null
ln -sfn ../devel "$here/build/devel"
cmake --build "$here/build" -j "$(nproc)"
