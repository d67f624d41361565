#!/usr/bin/env bash
# The quick Sounds Good protocol end to end: it runs, writes every output, and the audio modes
# beat "no audio" over all its trials; a small run in shards merges into the whole run's report;
# then the tool's answers to bad input.
#   experiment_quick.sh SOUNDS_GOOD_EXPERIMENT MAPS_DIR [sanitized]
# With "sanitized" (the AddressSanitizer build, where a trial runs about five times slower) the
# run is 2 configurations x 1 trial and only what it writes and the bad input are checked: the
# statistics, the replay and the shards are the main suite's, and the sanitizers look for memory
# and undefined behaviour, which a smaller run reaches through the same code.
set -uo pipefail
tool=$1
maps=$2
sanitized=${3:-}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
source "$(dirname "$0")/../../test/tool_checks.sh"

run_args=(--quick)
[ "$sanitized" = sanitized ] && run_args+=(--configs 2 --trials 1)
"$tool" "${run_args[@]}" --out "$out/run" >"$out/stdout" 2>"$out/stderr" || { cat "$out/stderr"; fail "--quick exited $?"; }
cat "$out/stdout"
for f in trials.csv jobs.csv table_3_1.md table_3_2.md figure_3_6a.png figure_3_6b.png \
         configs/config_01.yaml configs/config_02.yaml; do
  [ -s "$out/run/$f" ] || fail "missing or empty $f"
done
[ "$(head -1 "$out/run/trials.csv")" = "config,mode,trial,seed,time_s,censored" ] || fail "trials.csv header"
for png in figure_3_6a.png figure_3_6b.png; do
  [ "$(head -c 4 "$out/run/$png" | tail -c 3)" = "PNG" ] || fail "$png is not a PNG"
done
grep -q '^| #02 |' "$out/run/table_3_1.md" || fail "Table 3.1 lacks configuration #02"
grep -q '^| none | omni | #02 |' "$out/run/table_3_2.md" || fail "Table 3.2 lacks none vs omni on #02"
rows=$(($(wc -l <"$out/run/trials.csv") - 1))

# What only the whole quick protocol shows.
whole_run_checks() {
  [ "$rows" -eq 54 ] || fail "trials.csv has $rows rows, expected 3 configs x 3 modes x 6 trials = 54"
  [ -s "$out/run/configs/config_03.yaml" ] || fail "missing or empty configs/config_03.yaml"
  grep -q '^| #03 |' "$out/run/table_3_1.md" || fail "Table 3.1 lacks configuration #03"
  grep -q '^| none | omni | #03 |' "$out/run/table_3_2.md" || fail "Table 3.2 lacks none vs omni on #03"
  # Both audio modes significantly faster than none, the configurations' tests combined.
  local mode line
  for mode in bidirectional omni; do
    line=$(grep "^combined $mode vs none:" "$out/stdout") || fail "no combined line for $mode"
    awk -v l="$line" 'BEGIN { n = split(l, w, " "); for (i = 1; i <= n; ++i) { if (w[i] == "gain") g = w[i + 1]; if (w[i] == "p") p = w[i + 1] }
                       exit !(g > 0 && p < 0.05) }' || fail "$mode not significantly faster than none: $line"
  done
  # A configuration saved by the run replays through --worlds.
  "$tool" --worlds "$out/run/configs/config_02.yaml" --trials 1 --jobs 2 --modes bidirectional \
    --out "$out/replay" >/dev/null 2>&1 || fail "replaying a saved configuration failed"

  # Over machines: shards 1/2 and 2/2 of a small run merge into the whole run's report, to the byte.
  report_args=(--out @OUT@)
  check_shards --quick --configs 2 --trials 2 --jobs 3
}

if [ "$sanitized" = sanitized ]; then
  [ "$rows" -eq 6 ] || fail "trials.csv has $rows rows, expected 2 configs x 3 modes x 1 trial = 6"
else
  whole_run_checks
fi

# Directions as a real array reports them: the acoustic channel draws every microphone's report
# from the profile's direction table. (The sanitized build checks that path in less time in
# audio_propagation_test's channel test.)
directions=(--quick --configs 1 --trials 1 --jobs 2 --modes omni --channel acoustic --profile room
            --acoustics "$maps/office_world.yaml" --directions measured)
if [ "$sanitized" != sanitized ]; then
  status=0
  "$tool" "${directions[@]}" --out "$out/directions" >"$out/directions.out" 2>"$out/stderr" || status=$?
  [ "$status" -eq 0 ] || { cat "$out/stderr"; fail "--directions measured exited $status"; }
  grep -q "trials on .*, directions measured" "$out/stderr" || { cat "$out/stderr"; fail "--directions measured: the trials ran without the table"; }
  [ "$(($(wc -l <"$out/directions/trials.csv") - 1))" -eq 1 ] || fail "--directions measured: expected 1 trial"
fi

# Bad input: a clear message and exit status 1 (expect_error).
expect_error "--directions: expected exact or measured, got west" --quick --directions west --out "$out/x"
expect_error "--directions is for --channel acoustic" --quick --directions measured --out "$out/x"
expect_error "--direction-table goes with --directions measured" --quick --channel acoustic \
  --acoustics "$maps/office_world.yaml" --direction-table "$out/x.yaml" --out "$out/x"
cat >"$out/holes.yaml" <<YAML
profile: room
cells:
  - {rt60_s: 0.5, drr_db: 0, omni: [[10, 12, 0.5]], bidirectional: [[10, 5, 0.5]]}
  - {rt60_s: 1.0, drr_db: 6, omni: [[10, 12, 0.5]], bidirectional: [[10, 5, 0.5]]}
YAML
expect_error "holes.yaml: cells: the grid has a hole" "${directions[@]}" --direction-table "$out/holes.yaml" --out "$out/x"
expect_error "expected none, bidirectional or omni, got 'loud'" --quick --modes loud --out "$out/x"
expect_error "--robots: expected a whole number from 1" --quick --robots 0 --out "$out/x"
expect_error "--jobs: expected a whole number from 1" --quick --jobs 0 --out "$out/x"
expect_error "give --map, --worlds or --quick" --out "$out/x"
expect_error "map file not found" --map "$out/nothing.yaml" --out "$out/x"
expect_error "--worlds: expected world files" --worlds , --out "$out/x"
expect_error "--robots makes configurations" --worlds "$out/run/configs/config_01.yaml" --robots 3 --out "$out/x"
cat >"$out/unreachable.yaml" <<YAML
map: $maps/test_room.yaml
robots: [{name: robot_0, pose: [1.0, 1.0, 0.0]}]
markers: [{id: 1, position: [2.98, 1.0]}, {id: 2, position: [1.0, 3.0]}]
YAML
expect_error "marker 1 at (2.98, 1) cannot be reached" --worlds "$out/unreachable.yaml" --out "$out/x"
cat >"$out/nosink.yaml" <<YAML
map: $maps/test_room.yaml
robots: [{name: robot_0, pose: [1.0, 1.0, 0.0]}]
markers: [{id: 1, position: [1.0, 3.0]}]
YAML
expect_error "expected a marker with id 2 (the sink)" --worlds "$out/nosink.yaml" --out "$out/x"
echo "experiment_quick: all checks passed"
