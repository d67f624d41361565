#!/usr/bin/env bash
# audio_scene_render and audio_channel_validate end to end on the test room with acoustics: a
# scene's recordings (float WAV, one per robot) whose packets nava_decode finds, the model's line
# per packet and listener; a few links validated (the table, the agreement line, the plot) and a
# --predict line; then the tools' answers to bad input. The decode table is a flat one written
# here (the tools' plumbing, not the model's numbers, is under test).
#   scene_tool_checks.sh AUDIO_SCENE_RENDER AUDIO_CHANNEL_VALIDATE NAVA_DECODE MAPS_DIR
set -uo pipefail
export PATH="/usr/bin:/bin:${PATH}"
render=$1
validate=$2
decode=$3
maps=$4
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
source "$(dirname "$0")/../../test/tool_checks.sh"
world="$maps/test_room_acoustic_world.yaml"

cell="[[[[0.5, 0.1, 0, 0]]]]"
cat >"$out/room.yaml" <<EOF
profile: room
packets: 1
whine_hz: 2500
band_hz: [600, 5400]
command: "written by scene_tool_checks.sh"
snr_db: [0]
drr_db: [0]
rt60: [0.5]
kinds: {white: $cell, pink: $cell, speech: $cell, whine: $cell, packet: $cell}
EOF

cat >"$out/scene.yaml" <<EOF
profile: room
duration: 5.5
robots:
  robot_0: [[0.0, 1.5, 1.0, 0.0]]
  robot_1: [[0.0, 1.5, 3.0, 0.0], [2.0, 2.0, 3.0, 0.0]]
  robot_2: [[0.0, 4.2, 2.0, 0.0]]
packets:
  - {time: 0.3, sender: robot_0, data: [1, 2, 3, 4]}
  - {time: 2.8, sender: robot_1, data: [250, 6, 7, 8]}
EOF
"$render" --world "$world" --scene "$out/scene.yaml" --out "$out/heard" --table "$out/room.yaml" >"$out/lines" 2>"$out/stderr" \
  || { cat "$out/stderr"; fail "audio_scene_render failed"; }
[ "$(grep -c '^packet ' "$out/lines")" -eq 4 ] || { cat "$out/lines"; fail "expected a line per packet and listener (2 x 2)"; }
grep -q "^packet 0 robot_0 -> robot_1: sent 0.300 s, path 2.00 m, 0 corners, .* p 0.50, rendered snr" "$out/lines" \
  || { cat "$out/lines"; fail "no model line for packet 0 at robot_1"; }
grep -q "^packet 1 robot_1 -> robot_2: .* [1-9] corners" "$out/lines" || { cat "$out/lines"; fail "robot_2 hears round the wall"; }
for robot in robot_0 robot_1 robot_2; do
  [ "$(soxi -t "$out/heard/$robot.wav" 2>/dev/null)" = wav ] || fail "$robot.wav is not a WAV"
  soxi "$out/heard/$robot.wav" 2>/dev/null | grep -q "32-bit Floating Point" || fail "$robot.wav is not float"
done
"$decode" --profile room "$out/heard/robot_1.wav" | grep -q '"kind": "packet".*"data": "01020304"' \
  || fail "robot_1 did not decode robot_0's packet"
"$decode" --profile room "$out/heard/robot_0.wav" | grep -q '"kind": "packet".*"data": "fa060708"' \
  || fail "robot_0 did not decode robot_1's packet"

"$validate" --world "$world" --profile room --table "$out/room.yaml" --links 4 --packets 1 --out "$out/v" \
  >"$out/validate" 2>"$out/stderr" || { cat "$out/stderr"; fail "audio_channel_validate failed"; }
grep -q "^agreement: max |model - rendered| = [0-9.]* points over 1 distance bins$" "$out/validate" \
  || { cat "$out/validate"; fail "no agreement line"; }
grep -Eq "^  [0-9]+-[0-9]+ +4 +50.0 " "$out/validate" || { cat "$out/validate"; fail "no bin of the 4 links at the table's 50 %"; }
grep -q "^cpu: " "$out/validate" || fail "no CPU time"
[ -s "$out/v/validate_room.png" ] || fail "no plot"
"$validate" --world "$world" --profile room --table "$out/room.yaml" --predict 1.5,1.0 1.5,3.0 >"$out/predict" \
  || fail "--predict failed"
grep -q '^{"path_length": 2.000, "corners": 0, .*"rt60": 0.300, "kind": "pink", "probability": 0.500}$' "$out/predict" \
  || { cat "$out/predict"; fail "--predict line"; }
# The links' fate: the table's 50 % everywhere, so every pair counts; held, each static pair is
# all or nothing; drawn anew, 20 packets at one half are never 18 alike.
"$validate" --world "$world" --profile room --table "$out/room.yaml" --static-pairs 5 --pair-packets 20 >"$out/fate" \
  || fail "--static-pairs failed"
grep -q "^static: 5 of 5 pairs deliver under 10 % or over 90 % of their packets in steady noise$" "$out/fate" \
  || { cat "$out/fate"; fail "static pairs with their fate held"; }
grep -q "^static, the sources on their duty cycles: 5 of 5 pairs deliver under 10 % or over 90 %$" "$out/fate" \
  || { cat "$out/fate"; fail "static pairs with their fate held, the sources on their duty cycles"; }
grep -q "^static: 0 of 5 pairs deliver under 10 % or over 90 % of their packets in steady noise (every packet drawn anew)$" "$out/fate" \
  || { cat "$out/fate"; fail "static pairs drawn anew"; }
grep -Eq "^moving: 5 pairs, mean delivery [0-9.]+ % against the model's 50.0 %$" "$out/fate" \
  || { cat "$out/fate"; fail "moving pairs"; }

# Bad input: one line naming the file, field or flag and the value, and exit status 1.
tool=$render
ok=(--world "$world" --out "$out/x" --table "$out/room.yaml")
expect_error "audio_scene_render: $out/none.yaml: scene file not found" "${ok[@]}" --scene "$out/none.yaml"
expect_error "$out/nope.yaml: world file not found" --world "$out/nope.yaml" --scene "$out/scene.yaml" --out "$out/x"
expect_error "acoustics: missing" --world "$maps/test_room_world.yaml" --scene "$out/scene.yaml" --out "$out/x"
sed 's/robot_2: /robot_9: /' "$out/scene.yaml" >"$out/stranger.yaml"
expect_error "stranger.yaml: robots.robot_9: no robot named 'robot_9' in the world" "${ok[@]}" --scene "$out/stranger.yaml"
sed 's/\[0.0, 4.2, 2.0, 0.0\]/[0.0, 3.07, 1.0, 0.0]/' "$out/scene.yaml" >"$out/wall.yaml"
expect_error "wall.yaml: robots.robot_2\[0\]: (3.07, 1) is not in the map's free space" "${ok[@]}" --scene "$out/wall.yaml"
sed 's/data: \[1, 2, 3, 4\]/data: [1, 2, 3]/' "$out/scene.yaml" >"$out/short.yaml"
expect_error "short.yaml: packets\[0\].data: expected 4 bytes (whole numbers 0-255), got \[1, 2, 3\]" "${ok[@]}" --scene "$out/short.yaml"
sed 's/profile: room/profile: loud/' "$out/scene.yaml" >"$out/profile.yaml"
expect_error "profile.yaml: profile: expected nava or room, got 'loud'" "${ok[@]}" --scene "$out/profile.yaml"
expect_error "--profile: expected nava or room, got loud" "${ok[@]}" --scene "$out/scene.yaml" --profile loud
expect_error "the table is for 'room', but the link runs 'nava'" "${ok[@]}" --scene "$out/scene.yaml" --profile nava
tool=$validate
expect_error "--predict: (3.07, 1) is not in the map's free space" --world "$world" --profile room --table "$out/room.yaml" \
  --predict 3.07,1.0 1.5,3.0
expect_error "--predict: expected two points X1,Y1 X2,Y2 in m, got '1.5;1.0'" --world "$world" --profile room \
  --table "$out/room.yaml" --predict "1.5;1.0" 1.5,3.0
expect_error "--links: expected a whole number from 1 to 100000, got 0" --world "$world" --links 0
expect_error "--fate-distance: expected a number from 0.001000 to 100.000000, got 0" --world "$world" --static-pairs 5 \
  --fate-distance 0
expect_error "--predict and --static-pairs: expected one of them" --world "$world" --static-pairs 5 --predict 1.5,1.0 1.5,3.0
echo "scene tool checks passed"
