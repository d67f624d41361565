#!/usr/bin/env bash
# ranging_bench end to end on the test room with acoustics: two and three robots rendered at
# 16 kHz, every pair that a path joins ranged, the summary and target lines, the PNG; then its
# answers to bad input.
#   ranging_bench_checks.sh RANGING_BENCH MAPS_DIR
set -uo pipefail
export PATH="/usr/bin:/bin:${PATH}"
tool=$1
maps=$2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
source "$(dirname "$0")/../../test/tool_checks.sh"
world="$maps/test_room_acoustic_world.yaml"

"$tool" --worlds "$world" --teams 2,3 --scenes 1 --rounds 2 --rate 16000 --plot "$out/error.png" >"$out/lines" 2>"$out/err" ||
  { cat "$out/lines" "$out/err"; fail "ranging_bench failed"; }
grep -q " 2 robots, .*; 2 of 2 pairs ranged" "$out/lines" || { cat "$out/lines"; fail "expected both pairs of two robots ranged"; }
grep -q " 3 robots, .*; 6 of 6 pairs ranged" "$out/lines" || { cat "$out/lines"; fail "expected the six pairs of three robots ranged"; }
grep -q "^ranging: line of sight median .* cm, p90 .* cm; round corners median" "$out/lines" || { cat "$out/lines"; fail "no ranging line"; }
grep -q "^target: line of sight median <= 3 cm" "$out/lines" || { cat "$out/lines"; fail "no target line"; }
[ -s "$out/error.png" ] || fail "no PNG written"

expect_error "--teams: expected robot counts from 2 to 100" --worlds "$world" --teams 1
expect_error "$out/none.yaml: world file not found" --worlds "$out/none.yaml"
expect_error "acoustics: missing" --worlds "$maps/test_room_world.yaml"
expect_error "--rounds: expected a whole number from 1 to 100, got 0" --rounds 0
echo "ranging bench checks passed"
