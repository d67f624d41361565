#!/usr/bin/env bash
# Runs the libFuzzer targets (fuzz/): each feeds one input a robot or a user can give the project
# (receivers' samples, frames, WAV files, maps, world files, decode tables, command lines) to its
# parser, built with AddressSanitizer and UndefinedBehaviorSanitizer in build-fuzz/.
#
#   scripts/fuzz.sh --list              the targets
#   scripts/fuzz.sh TARGET SECONDS      runs one target for that long
#   scripts/fuzz.sh all SECONDS         runs each target in turn for that long
#   scripts/fuzz.sh --build             only builds them (scripts/test.sh builds them early)
#
# Each run starts from a copy of the target's seeds (fuzz/corpus/TARGET/, never written to) in a
# scratch folder, with fuzz/dict/TARGET.dict when there is one, and fails on a crash, a sanitizer
# report, a leak, an input that takes over 1 s (-timeout=1; a receiver's longest input, 64 KB of
# samples plus its flush, takes about 0.25 s here) or more than 2 GB. Inputs that fail
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
if ! grep -q '^FUZZ:BOOL=ON' "$build/CMakeCache.txt" 2>/dev/null; then
  cmake -S "$here" -B "$build" -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFUZZ=ON \
    -DMULTIROBOT_AUDIO_ROS=OFF -DMULTIROBOT_AUDIO_TESTS=OFF >/dev/null
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
failed=0
for target in "${run[@]}"; do
  corpus="$scratch/$target"
  artifacts="$build/artifacts/$target"
  log="$build/logs/$target.log"
  mkdir -p "$corpus" "$artifacts"
  cp -r "$here/fuzz/corpus/$target/." "$corpus/"
  options=(-max_total_time="$seconds" -timeout=1 -rss_limit_mb=2048 -print_final_stats=1
           -artifact_prefix="$artifacts/")
  [ "$(max_len "$target")" -gt 0 ] && options+=(-max_len="$(max_len "$target")")
  [ -f "$here/fuzz/dict/$target.dict" ] && options+=(-dict="$here/fuzz/dict/$target.dict")
  marker="$scratch/$target.started"
  touch "$marker"
  start=$SECONDS
  status=0
  # The fuzzer's scratch files (the loaders' temporary maps and worlds) go to the scratch folder.
  TMPDIR="$scratch" ASAN_OPTIONS="detect_leaks=1:abort_on_error=1" \
    UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1" \
    "$build/fuzz/fuzz_$target" "${options[@]}" "$corpus" >"$log" 2>&1 || status=$?
  elapsed=$((SECONDS - start))
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  if [ "$status" -eq 0 ]; then
    echo "fuzz $target: ${runs:-0} executions in $elapsed s, no crash"
    continue
  fi
  failed=1
  artifact=$(find "$artifacts" -type f -newer "$marker" ! -name 'slow-unit-*' | head -n 1)
  what=$(grep -m 1 -E '^(==[0-9]+==ERROR|SUMMARY|.*runtime error|==[0-9]+== ERROR: libFuzzer)' "$log" || true)
  echo "fuzz $target: FAILED after ${runs:-?} executions in $elapsed s (exit $status): ${what:-see the log}"
  echo "  input: ${artifact:-none saved}; log: $log"
done
exit "$failed"
