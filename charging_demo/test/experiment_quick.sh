#!/usr/bin/env bash
# charging_experiment end to end on the test room: every output, the summary line with no double
# docking and no robot run flat, a saved world replays; a small run in shards merges into the
# whole run's report; then the tool's answers to bad input.
#   experiment_quick.sh CHARGING_EXPERIMENT MAPS_DIR [sanitized]
# With "sanitized" (the AddressSanitizer build, where a trial runs several times slower) the
# main run has two seeds, the shards' runs a third of their hours, the acoustic channel one seed,
# and the acoustic shards are left to the main suite.
set -uo pipefail
tool=$1
maps=$2
sanitized=${3:-}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
source "$(dirname "$0")/../../test/tool_checks.sh"

seeds=3 shard_hours=0.3
[ "$sanitized" = sanitized ] && seeds=2 shard_hours=0.1
"$tool" --map "$maps/test_room.yaml" --robots 4 --chargers 1 --hours 2 --seeds "$seeds" --out "$out/run" \
  --timeline "$out/timeline.png" >"$out/stdout" 2>"$out/stderr" || { cat "$out/stderr"; fail "exited $?"; }
cat "$out/stdout"
for f in trials.csv robots.csv worlds/seed_001.yaml "worlds/seed_00$seeds.yaml"; do
  [ -s "$out/run/$f" ] || fail "missing or empty $f"
done
[ "$(head -c 4 "$out/timeline.png" | tail -c 3)" = "PNG" ] || fail "the timeline is not a PNG"
rows=$(($(wc -l <"$out/run/trials.csv") - 1))
[ "$rows" -eq "$seeds" ] || fail "trials.csv has $rows rows, expected $seeds"
rows=$(($(wc -l <"$out/run/robots.csv") - 1))
[ "$rows" -eq $((seeds * 4)) ] || fail "robots.csv has $rows rows, expected $seeds seeds x 4 robots"
# Every robot charged at least once (column 3 of robots.csv).
awk -F, 'NR > 1 && $3 < 1 { bad = 1 } END { exit bad }' "$out/run/robots.csv" || fail "a robot never charged"
line=$(tail -1 "$out/stdout")
echo "$line" | grep -Eq '^double_dockings 0 robots_flat 0 charges [0-9]+ utilisation 0\.[0-9]+ mean_wait_s [0-9.]+$' \
  || fail "summary line: $line"
# A saved world replays through --world.
"$tool" --world "$out/run/worlds/seed_002.yaml" --hours 0.5 --seeds 1 --out "$out/replay" >"$out/replay.out" 2>&1 \
  || { cat "$out/replay.out"; fail "replaying a saved world failed"; }

# Over machines: shards 1/2 and 2/2 of a small run merge into the whole run's report (the
# timeline too), to the byte.
report_args=(--out @OUT@ --timeline @OUT@/timeline.png)
check_shards --map "$maps/test_room.yaml" --robots 3 --hours "$shard_hours" --seeds 3
# The acoustic channel (the test room's acoustics, links keeping their fate): the run finishes
# with no double docking, its saved worlds carry the acoustics, and its shards merge to the byte.
acoustic=(--map "$maps/test_room.yaml" --robots 3 --hours 0.2 --channel acoustic
          --acoustics "$maps/test_room_acoustic_world.yaml" --link-fate)
acoustic_seeds=2
[ "$sanitized" = sanitized ] && acoustic_seeds=1
"$tool" "${acoustic[@]}" --seeds "$acoustic_seeds" --out "$out/acoustic" >"$out/acoustic.out" 2>"$out/stderr" \
  || { cat "$out/stderr"; fail "the acoustic channel's run failed"; }
grep -Eq '^double_dockings 0 ' "$out/acoustic.out" || fail "acoustic channel: $(tail -1 "$out/acoustic.out")"
grep -q '^acoustics:' "$out/acoustic/worlds/seed_001.yaml" || fail "a saved world lost the acoustics it ran with"
[ "$sanitized" = sanitized ] || check_shards "${acoustic[@]}" --seeds 3
expect_error "--timeline: give it to --merge" --map "$maps/test_room.yaml" --shard 1/2 --timeline "$out/t.png" --out "$out/x"

# Bad input: a clear message and exit status 1 (expect_error).
expect_error "low_battery must be within (0, 1), got 1.5" --map "$maps/test_room.yaml" --low 1.5 --out "$out/x"
expect_error "low_battery must be within (0, 1), got 0" --map "$maps/test_room.yaml" --low 0 --out "$out/x"
expect_error "cannot fit 250 robots" --map "$maps/test_room.yaml" --robots 250 --out "$out/x"
expect_error "--robots: expected a whole number from 1 to 255" --robots 300 --out "$out/x"
expect_error "cannot place 2 chargers" --map "$maps/test_room.yaml" --chargers 2 --out "$out/x"
expect_error "map file not found" --map "$out/nothing.yaml" --out "$out/x"
expect_error "--acoustics: acoustics: --channel acoustic needs an acoustics section" --map "$maps/test_room.yaml" --channel acoustic --out "$out/x"
expect_error "test_room_world.yaml: acoustics: expected an acoustics section" --map "$maps/test_room.yaml" --channel acoustic --acoustics "$maps/test_room_world.yaml" --out "$out/x"
expect_error "--link-fate is for --channel acoustic" --map "$maps/test_room.yaml" --link-fate --out "$out/x"
expect_error "--channel: expected threshold or acoustic" --map "$maps/test_room.yaml" --channel loud --out "$out/x"
expect_error "drop --robots" --world "$out/run/worlds/seed_001.yaml" --robots 3 --out "$out/x"
cat >"$out/nocharger.yaml" <<YAML
map: $maps/test_room.yaml
robots: [{name: robot_0, pose: [1.0, 1.0, 0.0]}, {name: robot_1, pose: [2.0, 1.0, 0.0]}]
YAML
expect_error "nocharger.yaml: chargers: the charging trial needs at least one charger" --world "$out/nocharger.yaml" --out "$out/x"
cat >"$out/unmarked.yaml" <<YAML
map: $maps/test_room.yaml
robots: [{name: robot_0, pose: [1.0, 1.0, 0.0]}]
chargers: [{pose: [1.6, 2.0, 0.0]}]
YAML
expect_error "chargers\[0\].marker: every charger needs a fiducial marker" --world "$out/unmarked.yaml" --out "$out/x"
echo "charging_experiment_quick: all checks passed"
