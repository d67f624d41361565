# The environment for a standalone install of multirobot_audio (cmake --install build --prefix
# DIR, installed as DIR/setup.bash): `source DIR/setup.bash`, then rosrun and roslaunch find the
# package, its nodes and tools, and Python finds its messages. (A catkin workspace's install
# space has catkin's own setup.bash instead.) It finds DIR from its own place, so the install can
# be moved.
_multirobot_audio_prefix="$(builtin cd "$(dirname "${BASH_SOURCE[0]}")" >/dev/null && pwd)"
export ROS_PACKAGE_PATH="$_multirobot_audio_prefix/share${ROS_PACKAGE_PATH:+:$ROS_PACKAGE_PATH}"
export CMAKE_PREFIX_PATH="$_multirobot_audio_prefix${CMAKE_PREFIX_PATH:+:$CMAKE_PREFIX_PATH}"
export PYTHONPATH="$_multirobot_audio_prefix/lib/python3/dist-packages${PYTHONPATH:+:$PYTHONPATH}"
export PKG_CONFIG_PATH="$_multirobot_audio_prefix/lib/pkgconfig${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
export ROS_MASTER_URI="${ROS_MASTER_URI:-http://localhost:11311}"
unset _multirobot_audio_prefix
