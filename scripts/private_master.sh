# Sourced by scripts and tests that need a ROS master of their own:
#   source scripts/private_master.sh; start_private_master LOG_FILE
# starts roscore on a free port, exports ROS_MASTER_URI, sets `core` to its PID (stop it by that
# PID) and returns once the master answers, so that a roscore already running is left alone.
start_private_master() {
  local port try
  # The port is free when chosen, but another process (a node of a test running beside this one)
  # can take it before roscore binds it: roscore then exits with "Address already in use". Three
  # ports are tried, each given 20 s to answer.
  for try in 1 2 3; do
    port=$(/usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
    export ROS_MASTER_URI="http://127.0.0.1:${port}"
    roscore -p "$port" >"$1" 2>&1 &
    core=$!
    for _ in $(seq 100); do
      rosparam get /run_id >/dev/null 2>&1 && return 0
      kill -0 "$core" 2>/dev/null || break  # it exited: the port was taken
      sleep 0.2
    done
    kill "$core" 2>/dev/null
    wait "$core" 2>/dev/null
    echo "start_private_master: roscore on port $port did not answer (try $try of 3; log: $1)" >&2
  done
  return 1
}
