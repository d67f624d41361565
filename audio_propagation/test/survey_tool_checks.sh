#!/usr/bin/env bash
# nava_survey end to end: room packets (its --write-train) played through a response written here with
# a known RT60 and DRR (nava_room, white noise at SNR 10 dB) are surveyed back to the figures
# audio_channel_predict reads from the response itself; the acoustics section it writes, in a
# world, makes the acoustic model give back the surveyed DRR and the recording's SNR at the
# surveyed distance; one measured room when ../shared/realrooms is beside the project (its
# survey_bench row); then the tool's answers to bad input.
#   survey_tool_checks.sh NAVA_SURVEY NAVA_DECODE NAVA_ROOM AUDIO_CHANNEL_PREDICT AUDIO_CHANNEL_VALIDATE MAPS_DIR
#                         [SURVEY_BENCH REALROOMS_DIR]
set -uo pipefail
export PATH="/usr/bin:/bin:${PATH}"
tool=$1 decode=$2 room=$3 predict=$4 validate=$5 maps=$6
bench=${7:-} realrooms=${8:-}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
source "$(dirname "$0")/../../test/tool_checks.sh"

# What the sending robot plays (random data, random gaps): every packet of it decodes.
"$tool" --write-train "$out/clean.wav" --packets 6 --gap 0.4 --seed 3 | grep -q '"packets": 6' || fail "--write-train"
decoded=$("$decode" --profile room "$out/clean.wav" | grep -c '"kind": "packet"')
[ "$decoded" = 6 ] || fail "the written train decodes to $decoded packets, expected 6"
wav "$out/response.wav" room 0.6 -3
"$room" --in "$out/clean.wav" --out "$out/recording.wav" --rir "$out/response.wav" --noise white --snr 10 --seed 2 \
  >/dev/null 2>&1 || fail "nava_room"
truth=$("$predict" --profile room --rir "$out/response.wav" --noise white --snr-db 10) || fail "audio_channel_predict"
line=$("$tool" --distance 1.5 --world-out "$out/section.yaml" --response-out "$out/estimate.wav" "$out/recording.wav") ||
  fail "the survey of a recording of 6 packets"
echo "$line"
[ "$(field packets "$line")" = 6 ] || fail "6 packets sent, $(field packets "$line") used"
rt60=$(field rt60_s "$truth")
near "$(field rt60_s "$line")" "$rt60" "$(awk -v r="$rt60" 'BEGIN { print 0.1 * r }')" ||
  fail "RT60 surveyed at $(field rt60_s "$line") s, the response gives $rt60"
near "$(field drr_db "$line")" "$(field drr_db "$truth")" 2.0 ||
  fail "DRR surveyed at $(field drr_db "$line") dB, the response gives $(field drr_db "$truth")"
echo "$line" | grep -q '"noise_kind": "white"' || fail "white noise not told as white"
[ -s "$out/estimate.wav" ] || fail "--response-out wrote nothing"

# predict_in SECTION X,Y: the model's prediction from (1, 1) to X,Y in a world of the test room
# with the surveyed SECTION and two robots 1.5 m apart (the surveyed distance).
predict_in() {
  { printf 'map: %s/test_room.yaml\nrobots:\n' "$maps"
    printf '  - {name: robot_0, pose: [1.0, 1.0, 0.0]}\n  - {name: robot_1, pose: [2.5, 1.0, 0.0]}\n'
    cat "$1"; } >"$out/world.yaml"
  "$validate" --world "$out/world.yaml" --profile room --predict 1,1 "$2" ||
    { cat "$out/world.yaml" >&2; fail "the surveyed section $1 does not load in a world"; }
}

grep -q "^acoustics:" "$out/section.yaml" || fail "--world-out wrote no acoustics section"
model=$(predict_in "$out/section.yaml" 2.5,1) || exit 1
echo "$model"
near "$(field drr_db "$model")" "$(field drr_db "$line")" 0.05 || fail "the world's DRR at 1.5 m: $(field drr_db "$model")"
near "$(field rt60 "$model")" "$(field rt60_s "$line")" 0.001 || fail "the world's RT60: $(field rt60 "$model")"
# nava_room's SNR is over the recording's whole band, as the model's is.
near "$(field snr_db "$model")" 10 2.0 || fail "the world gives SNR $(field snr_db "$model") dB where the recording had 10"

# A building surveyed room by room: the room above and a longer one, each its own region.
wav "$out/hall.wav" room 1.2 -6
"$room" --in "$out/clean.wav" --out "$out/hall_recording.wav" --rir "$out/hall.wav" --noise white --snr 10 --seed 4 \
  >/dev/null 2>&1 || fail "nava_room (hall)"
hall_truth=$("$predict" --profile room --rir "$out/hall.wav" --noise white --snr-db 10) || fail "audio_channel_predict (hall)"
cat >"$out/building.yaml" <<EOT
rooms:
  - {name: office, box: [0, 0, 3, 4], distance: 1.5, recordings: [recording.wav]}
  - {name: hall, box: [3, 0, 6, 4], distance: 1.5, recordings: [hall_recording.wav]}
EOT
lines=$("$tool" --building "$out/building.yaml" --world-out "$out/building_section.yaml") || fail "the building survey"
echo "$lines"
[ "$(echo "$lines" | grep -c '"room": "office"')" = 1 ] && [ "$(echo "$lines" | grep -c '"room": "hall"')" = 1 ] ||
  fail "a line per recording, each naming its room"
hall_line=$(echo "$lines" | grep '"room": "hall"')
hall_rt60=$(field rt60_s "$hall_truth")
near "$(field rt60_s "$hall_line")" "$hall_rt60" "$(awk -v r="$hall_rt60" 'BEGIN { print 0.1 * r }')" ||
  fail "the hall's RT60 surveyed at $(field rt60_s "$hall_line") s, its response gives $hall_rt60"
cat "$out/building_section.yaml"
grep -q "^    - {name: hall, box: \[3, 0, 6, 4\], rt60: " "$out/building_section.yaml" || fail "no region for the hall"
grep -q "^  rooms:" "$out/building_section.yaml" || fail "no rooms section"
# The test room's wall leaves a 1.45 m gap: doors up to 1.6 m wide divide it into the two rooms.
printf '    door_half_width: 0.8\n' >>"$out/building_section.yaml"
model=$(predict_in "$out/building_section.yaml" 3.5,1) || exit 1
echo "$model"
near "$(field rt60 "$model")" "$(field rt60_s "$hall_line")" 0.001 || fail "the world's RT60 in the hall: $(field rt60 "$model")"
office_line=$(echo "$lines" | grep '"room": "office"')
model=$(predict_in "$out/building_section.yaml" 2,1) || exit 1
near "$(field rt60 "$model")" "$(field rt60_s "$office_line")" 0.001 || fail "the world's RT60 in the office: $(field rt60 "$model")"
printf 'rooms:\n  - {name: a, box: [0, 0, 1, 1], distance: 2, recordings: [gone.wav]}\n' >"$out/bad_building.yaml"
expect_error "rooms.0.\.recordings: no such file: $out/gone.wav" --building "$out/bad_building.yaml" --world-out "$out/x.yaml"
printf 'rooms:\n  - {name: a, box: [1, 0, 0, 1], distance: 2, recordings: [recording.wav]}\n' >"$out/bad_building.yaml"
expect_error "rooms.0.\.box: expected min_x < max_x" --building "$out/bad_building.yaml" --world-out "$out/x.yaml"
expect_error "--building needs --world-out" --building "$out/building.yaml"
expect_error "--building names the recordings room by room" --building "$out/building.yaml" --world-out "$out/x.yaml" "$out/recording.wav"

if [ -n "$bench" ] && [ -n "$realrooms" ] && [ -f "$realrooms/rir_clap.wav" ]; then
  mkdir -p "$out/rooms" && ln -s "$realrooms/rir_clap.wav" "$out/rooms/"
  report=$("$bench" --rir-dir "$out/rooms" --threads 1) || fail "survey_bench"
  echo "$report"
  echo "$report" | grep -q "^survey: 1 of 1 rooms within 10 % of their RT60 and 2 dB of their DRR" ||
    fail "the measured seminar room surveyed outside the target"
else
  echo "no measured rooms beside the project: the seminar room's survey is skipped"
fi

wav "$out/silent.wav" silent
expect_error "$out/silent.wav: no room packet decoded" "$out/silent.wav"
expect_error "$out/nothing.wav" "$out/nothing.wav"
expect_error "a survey needs the room profile" --profile nava "$out/recording.wav"
expect_error "--world-out needs --distance" --world-out "$out/x.yaml" "$out/recording.wav"
expect_error "channel 2 asked for" --channel 2 "$out/recording.wav"
expect_error "--response-out takes one recording" --response-out "$out/x.wav" "$out/recording.wav" "$out/recording.wav"
expect_error "expected at least one recording"
expect_error "--write-train writes the packets to play; it takes no recordings" --write-train "$out/t.wav" "$out/recording.wav"
expect_error "--rate 8000: profile room: sample rate 8000 Hz cannot carry its band" --write-train "$out/t.wav" --rate 8000
echo "survey_tool_checks: all checks passed"
