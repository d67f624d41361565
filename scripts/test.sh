#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test. With no arguments it runs all of what CI
# runs, in turn, and stops at the first part that fails:
#   1. the main suite but for its over-the-air tests: the components' gtests, the ROS conversions'
#      gtests, the rostests and the launch-file checks, all through ctest, in build/;
#   2. the sanitized suite: the ROS-free components and their tests built with AddressSanitizer
#      and UndefinedBehaviorSanitizer in build-sanitize/ (any report fails the test), two at a time;
#   3. the fuzz targets (scripts/fuzz.sh), 20 s each, two at a time, built with clang in build-fuzz/;
#   4. the main suite's over-the-air tests (label "air"), alone, last.
#
#   scripts/test.sh                     everything above
#   scripts/test.sh CTEST_ARGS...       the main suite only, e.g. scripts/test.sh -R grid
#   scripts/test.sh --sanitize [CTEST_ARGS...]
#                                       the sanitized suite only
#   scripts/test.sh --fuzz [SECONDS]    the fuzz targets only, SECONDS each (default 20)
# In a clean clone on a two-core machine the whole run (.ci/run) took 40 minutes: the main build
# (-Werror) 13, the main suite's tests 10 (the over-the-air ones alone, then the others with the
# sanitized tree building beside them), the rest of that build and the sanitized tests 14 with
# the fuzz targets building beside them, the fuzz runs 3. With the ranging tests it took 46
# (2781 s), and at the end of issue 29 56 (3387 s), of which the sanitized
# sounds_good_experiment_quick alone took 342 s (70 s in the main suite). With that test's
# sanitized run made small it took 51 (3034 s): the main build and tests 31, the wait for the
# sanitized build 9, its tests 6.5, the fuzz runs 3.5. With the sanitized build at -O1 and line
# tables it took 48 (2859 s): the main build 14, the over-the-air tests 4, the others 10.5, the
# wait for the sanitized build 7.5 (it took 18 minutes beside the tests, 23 before), its tests 8
# (6.5 at -O2), the fuzz runs 3.5. With the sanitized experiment checks made smaller (sounds_good
# 77 -> 50 s, charging 93 -> 73 s) and the survey's tests added (sanitized nava_modem_test 69 ->
# 92 s) it took 46 (2753 s), the sanitized tests 7.3. Later clean clones: 42.9 (2574 s), 45.7
# (2740 s, the survey's slowing-hall test at 10 packets) and 43.9 (2633 s, at 6). The aim is under
# 45; what is left to cut: the sanitized nava_modem_test (about 3 minutes: the direction
# estimator's reverberant room 25 s, each survey test 14-16 s) and charging_experiment_quick.
# Every tree now compiles through ccache (CMakeLists.txt), and the run ends with each part's time:
# a clean clone whose main objects were cached but not the sanitized and fuzz trees' took 43.4
# (2602 s: main build 102, over the air 235, the others 816, sanitized 1262, fuzz 182); one with
# all three cached but for the files of one day's commits 30.0 (1798 s: 104, 235, 658, 617, 180;
# 69 compiled, 650 from the cache). With test files at -O0 and the sanitized tree building from
# the start: warm 31.9 (1911 s: 254, 308, 641, 483, 220; 168 compiled after a day that changed
# world_sim/acoustics.h); from an empty cache the main build took about 14 minutes, but that run
# and the one before it each lost an over-the-air test to stalls (capture 0.1 s behind) with the
# sanitized build paused, which the warm runs never did. With a sync before the over-the-air
# tests, a clean clone from an empty cache passed in 51.7 (3101 s: main build 823, over the air
# 353, the others 695, sanitized 843 of which its build's wait about 330, fuzz 382 of which its
# build about 200; 810 compiled): over the 45 aimed at. One tree for both the sanitized tests and
# the fuzz targets (clang, the fuzzer's coverage hooks in every library) was tried: its sanitized
# tests ran 35 % slower (1121 s against 826 s for the same tests), which ate what it saved. Now
# every tree is a unity build (CMakeLists.txt) and the fuzz targets build right after the
# sanitized tree in the same background job, not beside the sanitized tests.
set -euo pipefail
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

main_build() {
  "$here/scripts/setup.sh" --werror
  cmake --build "$here/build" --target tests -j "$(nproc)"
}

main_tests() {
  # catkin's setup script reads unset variables.
  set +u
  # shellcheck disable=SC1091
  source "$here/build/devel/setup.bash"
  set -u
  local count
  count=$(cd "$here/build" && ctest -N "$@" | sed -n 's/^Total Tests: *//p')
  if [ -z "$count" ] || [ "$count" -eq 0 ]; then
    echo "test.sh: no tests found; that is a failure" >&2
    return 1
  fi
  # Sequential: each rostest starts its own master, and the machine has two cores.
  (cd "$here/build" && ctest --output-on-failure "$@")
}

main_suite() {
  main_build
  main_tests "$@"
}

sanitized_build() {
  "$here/scripts/setup.sh" --no-build
  # -O1 and line tables: what AddressSanitizer's own documentation asks for, and a third less
  # compiling than -O2 -g (4.4 s against 7.1 s for fsk_receiver.cpp); CI waits for this build.
  # The test files compile at -O0, instrumented (CMakeLists.txt says why).
  cmake -S "$here" -B "$here/build-sanitize" -DMULTIROBOT_AUDIO_ROS=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" \
    -DSANITIZE=address,undefined -DMULTIROBOT_AUDIO_WERROR=ON >/dev/null
  cmake --build "$here/build-sanitize" --target tests -j "$(nproc)"
}

sanitized_tests() {
  # Two at a time: the sanitized tests are processor-bound and the machine has two cores; the
  # longest (nava_modem_test, 200 s sanitized) runs as two shards, and the longest start first
  # (their COST).
  (cd "$here/build-sanitize" &&
    ASAN_OPTIONS="detect_leaks=1:abort_on_error=1" UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1" \
      ctest --output-on-failure --parallel "$(nproc)" "$@")
}

sanitized_suite() {
  sanitized_build
  sanitized_tests "$@"
}

# Runs a build in the background in a session of its own (so that it can be stopped whole), its
# output in LOG; its PID in background_pid. (Not through $(...): the build must be this shell's
# child to be waited for.) It takes only the processor time nothing else wants: SCHED_IDLE
# (chrt --idle) where the kernel allows it, else nice 19, and, where the kernel groups each
# session's processes to share the processor fairly between sessions (autogroup, on by default
# in Debian's kernels, which would give the build half the machine whatever its own priority),
# its session's group at nice 19 too.
background_build() {
  local log=$1
  shift
  local idle=(nice -n 19)
  chrt --idle 0 true 2>/dev/null && idle=(chrt --idle 0)
  setsid "${idle[@]}" "$@" >"$log" 2>&1 &
  background_pid=$!
  # Only once the build leads its own session: before, its group is still this script's.
  local _
  for _ in $(seq 100); do
    if [ "$(ps -o sid= -p "$background_pid" | tr -d ' ')" = "$background_pid" ]; then
      echo 19 >"/proc/$background_pid/autogroup" 2>/dev/null || true
      break
    fi
    sleep 0.01
  done
}

# Stops the background builds still running (when a part fails before they are waited for).
stop_background_builds() {
  [ -n "${builds_pid:-}" ] || return 0
  kill -- -"$builds_pid" 2>/dev/null || true
}

# The sanitized tree, then the fuzz targets, one after the other (so that the first is not
# slowed by the second), their outputs in build-logs/; the first's end marked by sanitize.done.
background_builds() {
  rm -f "$here/build-logs/sanitize.done"
  background_build "$here/build-logs/builds.log" bash -c "$(declare -f sanitized_build); here='$here'
    set -euo pipefail
    sanitized_build >'$here/build-logs/sanitize.log' 2>&1
    : >'$here/build-logs/sanitize.done'
    '$here/scripts/fuzz.sh' --build >'$here/build-logs/fuzz.log' 2>&1"
  builds_pid=$background_pid
}

# Waits until the sanitized tree is built; fails, showing the end of its log, when the
# background builds ended without building it.
await_sanitized_build() {
  local log="$here/build-logs/sanitize.log"
  until [ -e "$here/build-logs/sanitize.done" ]; do
    if ! kill -0 "$builds_pid" 2>/dev/null; then
      tail -n 40 "$log"
      echo "test.sh: the sanitized build failed (all of it in $log)" >&2
      return 1
    fi
    sleep 1
  done
}

# Waits for a background build; on failure shows the end of its log and fails.
await_build() {
  local pid=$1 log=$2 what=$3
  if ! wait "$pid"; then
    tail -n 40 "$log"
    echo "test.sh: the $what build failed (all of it in $log)" >&2
    return 1
  fi
}

# Each part's name and when it began, for the timings printed at the end.
parts=()
part_starts=()
part() {
  echo "== test.sh: $1 =="
  parts+=("$1")
  part_starts+=("$SECONDS")
}

# How long each part took, and how much of the compiling ccache saved (its counters before the
# run in ccache_before; none where ccache is not installed).
timings() {
  local i end
  for i in "${!parts[@]}"; do
    end=$SECONDS
    [ $((i + 1)) -lt ${#parts[@]} ] && end=${part_starts[$((i + 1))]}
    printf 'test.sh: %-28s %5d s\n' "${parts[$i]}" $((end - part_starts[i]))
  done
  if [ -n "${ccache_before:-}" ]; then
    local after
    after=$(ccache_counts)
    # shellcheck disable=SC2086
    set -- $ccache_before $after
    echo "test.sh: ccache: $(($4 - $1)) compiled, $(($5 - $2)) from the cache (direct), $(($6 - $3)) (preprocessed)"
  fi
}

# ccache's misses and hits so far: three numbers.
ccache_counts() {
  ccache --print-stats | awk '$1 == "cache_miss" {m = $2} $1 == "direct_cache_hit" {d = $2}
    $1 == "preprocessed_cache_hit" {p = $2} END {print m + 0, d + 0, p + 0}'
}

case "${1:-}" in
  --sanitize)
    shift
    sanitized_suite "$@"
    ;;
  --fuzz)
    "$here/scripts/fuzz.sh" all "${2:-20}"
    ;;
  "")
    # The sanitized tree and then the fuzz targets build in the background from the start, taking
    # only the processor time the main build and the main suite leave (the main build's links and
    # configuring, the ROS nodes that wait on simulated and real time, the sanitized tests' last
    # one running alone).
    start=$SECONDS
    mkdir -p "$here/build-logs"
    # setup.sh installs ccache with everything else; counted from before the first build.
    "$here/scripts/setup.sh" --no-build
    command -v ccache >/dev/null && ccache_before=$(ccache_counts)
    background_builds
    trap stop_background_builds EXIT
    part "main build"
    main_build
    part "main suite, all but over the air"
    main_tests -LE air
    part "sanitized suite"
    await_sanitized_build
    sanitized_tests
    part "fuzz targets, 20 s each"
    await_build "$builds_pid" "$here/build-logs/fuzz.log" fuzz
    trap - EXIT
    "$here/scripts/fuzz.sh" all 20
    # The over-the-air tests (label "air") last, with nothing beside them: their links stream
    # through a sound server in real time with 10 ms buffers, and a stalled process cuts their
    # packets. Run first after the main build, with the background builds paused, they lost a test
    # to captures 0.1 s behind in three of four runs from an empty cache (the first test, for a
    # minute and more after a build that had filled memory) and in one warm run, where the same
    # tests run again on a quiet machine passed; their place at the start also kept the
    # background builds paused for their six minutes. The build's objects go to disk first.
    sync
    part "main suite, over the air"
    main_tests -L air
    timings
    echo "test.sh: every part passed in $((SECONDS - start)) s"
    ;;
  *)
    main_suite "$@"
    ;;
esac
