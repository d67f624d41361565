#!/usr/bin/env bash
# scripts/soak_report.py on made-up runs (no ROS): a clean one passes; a robot that ran flat, a
# node that grew, one that roslaunch saw die, a short run and a lost lockstep participant each
# fail with a line that says so.
set -euo pipefail
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
report="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/scripts/soak_report.py"
out=$(mktemp -d /tmp/soak_report_test.XXXXXX)
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# A clean two-hour run of one robot: world_sim, its controller; RSS grows 1 % after the hour.
clean() {
  rm -rf "$out/m" && mkdir -p "$out/m"
  printf '/world_sim 11\n/robot_0/charging_demo 12\n' >"$out/m/pids"
  cat >"$out/m/samples.csv" <<'EOF'
sim_s,node,rss_kb,cpu_s
3600.0,/world_sim,60000,10.0
3600.0,/robot_0/charging_demo,20000,5.0
7199.0,/world_sim,60000,20.0
7199.0,/robot_0/charging_demo,20200,9.0
7199.0,/soak_monitor,30000,1.0
EOF
  : >"$out/m/events"
  echo 'robot_0 0.250' >"$out/m/batteries"
  cat >"$out/log" <<'EOF'
world_sim summary: robots 1, simulated 7200.0 s, distance driven 100.000 m, collisions 0
world_sim timing: wall 400.0 s, real-time factor 18.0, lockstep waiting 300.0 s (slowest /robot_0/charging_demo: 200.0 s), dropped 0
charging_demo summary: /robot_0 phase duty, battery 0.50, charges 2, give-ups 0
EOF
}
# run: the report on the made-up run; judge WORDS: it must exit 1 and say WORDS (an extended grep pattern) on stdout.
run() {
  status=0
  /usr/bin/python3 "$report" --log "$out/log" --dir "$out/m" --duration 7200 --baseline 3600 --max-growth 5 \
    --wall 400 >"$out/out" 2>&1 || status=$?
}
judge() {
  run
  [ "$status" -eq 1 ] || { cat "$out/out"; fail "exited with $status, expected 1 for '$1'"; }
  grep -Eq -- "$1" "$out/out" || { cat "$out/out"; fail "did not say '$1'"; }
}

clean
run
[ "$status" -eq 0 ] || { cat "$out/out"; fail "a clean run failed"; }
grep -Eq '^/robot_0/charging_demo +19.5 +19.7 +7199 +\+1.0% +9$' "$out/out" || { cat "$out/out"; fail "no row for the controller"; }
grep -q '^  /robot_0/charging_demo: charging_demo summary: /robot_0 phase duty' "$out/out" || fail "no counters"
grep -q '^soak: PASS$' "$out/out" || fail "no PASS"

clean
echo '5000.0 flat robot_0' >"$out/m/events"
judge '^soak: FAIL: robot_0 ran flat at 5000.0 s'

clean
sed -i 's/^7199.0,\/robot_0\/charging_demo,20200/7199.0,\/robot_0\/charging_demo,21200/' "$out/m/samples.csv"
judge '^soak: FAIL: /robot_0/charging_demo: resident memory grew 6.0 % after the baseline \(limit 5 %\)'

clean
printf '\033[31m[robot_0/charging_demo-2] process has died [pid 12, exit code -11, cmd x].\033[0m\n' >>"$out/log"
sed -i '/^charging_demo summary/d' "$out/log"
judge '^soak: FAIL: /robot_0/charging_demo died: roslaunch: process has died \(exit code -11\)$'
grep -q 'printed no summary' "$out/out" && fail "a dead node was also blamed for its missing summary"

clean
sed -i 's/simulated 7200.0 s/simulated 4000.0 s/; s/dropped 0/dropped 1/' "$out/log"
judge '^soak: FAIL: world_sim stopped at 4000.0 s of the 7200 s asked for'
judge '^soak: FAIL: world_sim dropped 1 participants from the lockstep'

echo "soak_report_test: ok"
