#!/usr/bin/env bash
# Runs the libFuzzer targets (fuzz/): each feeds one input a robot or a user can give the project
# (receivers' samples, frames, WAV files, maps, world files, decode tables, command lines) to its
# parser, built with AddressSanitizer and UndefinedBehaviorSanitizer in build-fuzz/.
#
#   scripts/fuzz.sh --list              the targets
#   scripts/fuzz.sh TARGET SECONDS      runs one target for that long
#   scripts/fuzz.sh all SECONDS         runs every target for that long, two at a time (the
#                                       machine has two cores; each fuzzer uses one)
#   scripts/fuzz.sh --build             only builds them (scripts/test.sh builds them early)
#
# Each run starts from a copy of the target's seeds (fuzz/corpus/TARGET/, never written to) in a
# scratch folder, with fuzz/dict/TARGET.dict when there is one, and fails on a crash, a sanitizer
# report, a leak, an input that hangs (-timeout=10) or more than 2 GB. The timeout catches hangs,
# not slowness (speed lives in the benchmarks): with the sanitizers, a receiver's longest input
# (64 KB of a tone at 48 kHz) takes 1.3 s here when it is the first to need its ~60 symbol-window
# FFT sizes planned, and a CI machine running two fuzzers at once failed one such input at
# -timeout=1. Inputs that fail
# are saved in build-fuzz/artifacts/TARGET/ (replay one: build-fuzz/fuzz/fuzz_TARGET FILE), the
# whole log in build-fuzz/logs/TARGET.log. One line per target:
#   fuzz TARGET: N executions in S s, no crash
# and the exit status is 1 when any target failed.
set -euo pipefail
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$here/build-fuzz"

usage() {
  echo "usage: scripts/fuzz.sh --list | --build | TARGET SECONDS | all SECONDS" >&2
  exit 2
}

targets() {
  local f
  for f in "$here"/fuzz/*.cpp; do
    f=$(basename "$f" .cpp)
    [ "$f" = make_corpus ] || echo "$f"
  done
}

# The largest input each target is given: a receiver's must hold a whole packet (room: 1.92 s
# of 16-bit samples at 12 kHz, 46 KB); the rest take libFuzzer's default (4 KB or the largest seed).
max_len() {
  case "$1" in
    fsk_receiver | room_receiver) echo 65536 ;;
    *) echo 0 ;;
  esac
}

[ $# -ge 1 ] || usage
if [ "$1" = "--list" ]; then
  targets
  exit 0
fi
build_only=false
if [ "$1" = "--build" ] && [ $# -eq 1 ]; then
  build_only=true
  set -- all 1
fi
[ $# -eq 2 ] || usage
which=$1 seconds=$2
[[ "$seconds" =~ ^[1-9][0-9]*$ ]] || { echo "fuzz.sh: SECONDS: expected a whole number above 0, got '$seconds'" >&2; exit 2; }
if [ "$which" = all ]; then
  mapfile -t run < <(targets)
elif [[ " $(targets | tr '\n' ' ') " == *" $which "* ]]; then
  run=("$which")
else
  echo "fuzz.sh: no fuzz target '$which'; expected all or one of: $(targets | tr '\n' ' ')" >&2
  exit 2
fi

"$here/scripts/setup.sh" --no-build
# -O1 and line tables: what libFuzzer's and the sanitizers' documentation ask for, and an eighth
# less compiling than -O2 -g (11.8 s against 13.7 s for fsk_equalizer.cpp; CI waits for this
# tree). A tree configured otherwise is configured again.
flags="-O1 -gline-tables-only -DNDEBUG"
if ! grep -q '^FUZZ:BOOL=ON' "$build/CMakeCache.txt" 2>/dev/null ||
   ! grep -qx "CMAKE_CXX_FLAGS_RELWITHDEBINFO:STRING=$flags" "$build/CMakeCache.txt"; then
  cmake -S "$here" -B "$build" -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFUZZ=ON \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=$flags" -DMULTIROBOT_AUDIO_ROS=OFF -DMULTIROBOT_AUDIO_TESTS=OFF >/dev/null
fi
# Two jobs: the machine has two cores.
cmake --build "$build" --target fuzz_targets -j 2 >"$build/build.log" 2>&1 || { tail -n 40 "$build/build.log"; echo "fuzz.sh: the build failed" >&2; exit 1; }
$build_only && exit 0

# In memory where there is a tmpfs: the loaders' targets write a file per input, and a busy disk
# can stall a write past the timeout.
shm=/tmp
[ -d /dev/shm ] && [ -w /dev/shm ] && shm=/dev/shm
scratch=$(mktemp -d "$shm/multirobot_fuzz_run.XXXXXX")
trap 'rm -rf "$scratch"' EXIT
mkdir -p "$build/logs"

# Runs one target for $seconds and prints its line; fails when it failed.
fuzz_one() {
  local target=$1
  local corpus="$scratch/$target" artifacts="$build/artifacts/$target" log="$build/logs/$target.log"
  mkdir -p "$corpus" "$artifacts"
  cp -r "$here/fuzz/corpus/$target/." "$corpus/"
  local options=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1
                 -artifact_prefix="$artifacts/")
  [ "$(max_len "$target")" -gt 0 ] && options+=(-max_len="$(max_len "$target")")
  [ -f "$here/fuzz/dict/$target.dict" ] && options+=(-dict="$here/fuzz/dict/$target.dict")
  local marker="$scratch/$target.started"
  touch "$marker"
  local start=$SECONDS status=0
  # The fuzzer's scratch files (the loaders' temporary maps and worlds) go to its own folder.
  mkdir -p "$scratch/$target.tmp"
  TMPDIR="$scratch/$target.tmp" ASAN_OPTIONS="detect_leaks=1:abort_on_error=1" \
    UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1" \
    "$build/fuzz/fuzz_$target" "${options[@]}" "$corpus" >"$log" 2>&1 || status=$?
  local elapsed=$((SECONDS - start))
  local runs
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  if [ "$status" -eq 0 ]; then
    echo "fuzz $target: ${runs:-0} executions in $elapsed s, no crash"
    return 0
  fi
  local artifact what
  artifact=$(find "$artifacts" -type f -newer "$marker" ! -name 'slow-unit-*' | head -n 1)
  what=$(grep -m 1 -E '^(==[0-9]+==ERROR|SUMMARY|.*runtime error|==[0-9]+== ERROR: libFuzzer)' "$log" || true)
  echo "fuzz $target: FAILED after ${runs:-?} executions in $elapsed s (exit $status): ${what:-see the log}"
  echo "  input: ${artifact:-none saved}; log: $log"
  return 1
}

# Two at a time; each line is printed when its target ends.
failed=0
running=0
for target in "${run[@]}"; do
  if [ "$running" -ge 2 ]; then
    wait -n || failed=1
    running=$((running - 1))
  fi
  fuzz_one "$target" &
  running=$((running + 1))
done
while [ "$running" -gt 0 ]; do
  wait -n || failed=1
  running=$((running - 1))
done
exit "$failed"
