#!/usr/bin/env bash
# local_mutex_sim's random trials, sweep and failure bound over machines: shards 1/2 and 2/2 of a small run merge
# into the whole run's report, to the byte; then the tool's answers to bad shard options.
#   sim_quick.sh LOCAL_MUTEX_SIM
set -uo pipefail
tool=$1
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
source "$(dirname "$0")/../../test/tool_checks.sh"

check_shards --trials 7 --robots 2..4 --noise 0.1
check_shards --sweep 2 --robots 2..3
check_shards --bound 2 --robots 2..3 --noise 0.2 --rho 0.01
# The acoustic channel on the open floor with the test room's acoustics, links keeping their fate.
maps=$(dirname "$0")/../../maps
check_shards --trials 5 --robots 2..4 --channel acoustic --profile room --acoustics "$maps/open_floor_world.yaml" --link-fate

expect_error "--shard: for --trials N, --sweep N and --bound N, not --scenario" --scenario single --shard 1/2 --out "$out/x"
expect_error "give exactly one of --scenario, --trials N, --sweep N, --bound N" --bound 3 --trials 3
expect_error "--bound: a team needs at least 2 robots to lose a request, got --robots 1" --bound 3 --robots 1..3
expect_error "--rho: expected a failure rate in (0, 1), got 1" --bound 3 --rho 1
expect_error "--shard: give --out DIR for the shard's files" --trials 3 --shard 1/2
expect_error "--out: for --shard only (the report is printed)" --trials 3 --out "$out/x"
expect_error "--timeline draws one trial: give it without --shard" --trials 1 --timeline "$out/t.png" --shard 1/1 --out "$out/x"
expect_error "--merge takes the options from the shards' manifests: drop --timeline" --merge "$out/shards/1" --timeline "$out/t.png"
expect_error "--acoustics: acoustics: --channel acoustic needs an acoustics section" --trials 2 --channel acoustic
# The office's server fan stands at (28, 11), off the 20 m floor.
expect_error "office_world.yaml: acoustics.noise_sources\[1\].position: noise source 'server_fan'" --trials 2 --channel acoustic --acoustics "$maps/office_world.yaml"
expect_error "--table is for --channel acoustic" --trials 2 --table "$maps/x.yaml"
expect_error "--fate-distance goes with --link-fate" --trials 2 --channel acoustic --acoustics "$maps/open_floor_world.yaml" --fate-distance 0.1
expect_error "--fate-distance: expected a number from 0.000001" --trials 2 --channel acoustic --acoustics "$maps/open_floor_world.yaml" --link-fate --fate-distance 0
expect_error "--profile: expected nava or room" --trials 2 --profile fsk
echo "local_mutex_sim_quick: all checks passed"
