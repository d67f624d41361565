#!/usr/bin/env bash
# nava_room end to end: a modem WAV through mild rooms still decodes, a speech interferer made by
# make_speech.sh is resampled and mixed, the summary line; a 4-microphone render; the room
# profile through a room where the reverberation is louder than the direct sound; 64-byte room
# frames at each rate and the ladder listed; a render
# through a measured response (--rir); nava_decode's trace of each break (--diagnostics); then
# the tools' answers to bad input.
#   room_tool_checks.sh NAVA_ROOM NAVA_ENCODE NAVA_DECODE MAKE_SPEECH NAVA_BENCH
# (nava_bench for its --arrival, --likeness, --splice and --direction modes: room packets timed
# through measured responses; measured responses beside the renderer's; directions by RT60 and DRR)
set -uo pipefail
export PATH="/usr/bin:/bin:${PATH}"
tool=$1
encode=$2
decode=$3
make_speech=$4
bench=$5
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
source "$(dirname "$0")/../../test/tool_checks.sh"

"$encode" --out "$out/clean.wav" 01020304 a0b0c0d0 || fail "nava_encode failed"

# decodes FILE: both packets come out of nava_decode.
decodes() {
  "$decode" "$1" >"$out/decoded" || fail "nava_decode $1 failed"
  for p in 01020304 a0b0c0d0; do
    grep -q "\"kind\": \"packet\".*\"data\": \"$p\"" "$out/decoded" || { cat "$out/decoded"; fail "$1: packet $p not decoded"; }
  done
}

"$tool" --in "$out/clean.wav" --out "$out/mild.wav" --tilt -6 --clock 0.5 --noise white --snr 15 \
  --whine 600 --whine-sir 15 --seed 4 2>"$out/stderr" || { cat "$out/stderr"; fail "mild room failed"; }
decodes "$out/mild.wav"

# nava_decode --diagnostics: a trace of each break as one valid JSON array, the events on stdout
# the same as without it, both packets' breaks traced as read on a clock; and a packet cut short
# traced to the stage that lost it (clocks read, then the equaliser; not read).
"$decode" --diagnostics "$out/trace.json" "$out/mild.wav" >"$out/traced" 2>"$out/stderr" \
  || { cat "$out/stderr"; fail "nava_decode --diagnostics failed"; }
cmp -s "$out/traced" "$out/decoded" || { diff "$out/decoded" "$out/traced"; fail "--diagnostics changed what nava_decode printed"; }
/usr/bin/python3 -m json.tool "$out/trace.json" >/dev/null || { cat "$out/trace.json"; fail "--diagnostics wrote invalid JSON"; }
[ "$(grep -c '"outcome": "packet_on_clock", "event": {"t": ' "$out/trace.json")" -eq 2 ] \
  || { cat "$out/trace.json"; fail "--diagnostics: expected both packets traced as read on a clock"; }
sox "$out/clean.wav" "$out/cut.wav" trim 0 0.75 pad 0 0.5 || fail "sox could not cut the packet"
"$decode" --diagnostics "$out/cut.json" "$out/cut.wav" >"$out/decoded" || fail "nava_decode --diagnostics on a cut packet failed"
/usr/bin/python3 -m json.tool "$out/cut.json" >/dev/null || { cat "$out/cut.json"; fail "--diagnostics wrote invalid JSON for a cut packet"; }
grep -q '"equalizer": \[{"shift_bits": 0, .*"outcome": "not_read", "event": {"t": [0-9.]*, "kind": "noise"' "$out/cut.json" \
  || { cat "$out/cut.json"; fail "--diagnostics: the cut packet was not traced as not read"; }
"$tool" --in "$out/clean.wav" --out "$out/room.wav" --rt60 0.3 --drr 20 2>"$out/stderr" \
  || { cat "$out/stderr"; fail "reverberant room failed"; }
grep -q "measured DRR 20.00 dB" "$out/stderr" || { cat "$out/stderr"; fail "summary line without the measured DRR"; }
decodes "$out/room.wav"

"$make_speech" "$out/speech.wav" 5 2 2>"$out/stderr" || { cat "$out/stderr"; fail "make_speech.sh failed"; }
"$tool" --in "$out/clean.wav" --out "$out/talk.wav" --interferer "$out/speech.wav" --sir -6 2>"$out/stderr" \
  || { cat "$out/stderr"; fail "speech interferer failed"; }
grep -q "resampling the interferer .* from 22050 Hz to 48000 Hz" "$out/stderr" || { cat "$out/stderr"; fail "no resampling note"; }
grep -q "(SIR -6 dB)" "$out/stderr" || { cat "$out/stderr"; fail "summary line without the SIR"; }
[ "$(grep -c . "$out/stderr")" -eq 2 ] || { cat "$out/stderr"; fail "expected the resampling note and one summary line"; }

# A 4-microphone array: a 4-channel file, the source placed in the summary line, and each
# channel alone still decodes.
mics=0.05,0,0,0.05,-0.05,0,0,-0.05
"$tool" --in "$out/clean.wav" --out "$out/array.wav" --mics "$mics" --bearing 30 --distance 1.5 --rt60 0.3 --drr 20 \
  --noise white --snr 20 --seed 5 2>"$out/stderr" || { cat "$out/stderr"; fail "4-microphone render failed"; }
[ "$(soxi -c "$out/array.wav")" = 4 ] || fail "4-microphone render: $(soxi -c "$out/array.wav") channels, expected 4"
grep -q "4 channels; source at bearing 30 deg, 1.5 m: direct sound at 4.2.*DRR 20.00 dB at the origin" "$out/stderr" \
  || { cat "$out/stderr"; fail "array summary line without the source and room"; }
for c in 1 4; do
  sox "$out/array.wav" "$out/channel$c.wav" remix $c || fail "sox could not take channel $c"
  decodes "$out/channel$c.wav"
done

# Through a measured impulse response (--rir): made here with sox at 44.1 kHz, two channels
# (a direct sound 20 ms late, then a decaying tail about 10 dB below it), so that the render resamples it,
# keeps its delay and names the channel; each channel decodes.
sox -n -r 44100 -c 1 "$out/click.wav" synth 0.0001 square 1 pad 0.02 0.3 || fail "sox could not make a click"
sox -n -r 44100 -c 1 "$out/tail.wav" synth 0.3 whitenoise vol 0.01 fade q 0 0.3 0.3 pad 0.023 0 || fail "sox could not make a tail"
sox -m "$out/click.wav" "$out/tail.wav" "$out/response_mono.wav" || fail "sox could not mix the response"
sox -M "$out/response_mono.wav" "$out/response_mono.wav" "$out/response.wav" || fail "sox could not make a stereo response"
"$tool" --in "$out/clean.wav" --out "$out/measured.wav" --rir "$out/response.wav" --channel 1 --noise white --snr 20 \
  2>"$out/stderr" || { cat "$out/stderr"; fail "render through a measured response failed"; }
grep -q "measured response $out/response.wav channel 1 (.* samples), DRR .* dB in 600-5400 Hz" "$out/stderr" \
  || { cat "$out/stderr"; fail "summary line without the measured response"; }
decodes "$out/measured.wav"
# Its delay is kept: the packets start 20 ms later than in the clean file (0.5 s).
grep -q '"kind": "packet".*"start": 0\.52[01]' "$out/decoded" || { cat "$out/decoded"; fail "the response's 20 ms delay was not kept"; }
# Both profiles time their packets: the first packet's first sample left at 0.5 s, and its direct
# sound (the click, 20 ms late) rises to half its peak a little before 20 ms (nava, timed on two
# tones, to within a millisecond; room, on its chirp, to within a few microseconds).
arrival=$(sed -n 's/.*"kind": "packet".*"start": 0\.52.*"arrival": \([0-9.]*\).*/\1/p' "$out/decoded" | head -n 1)
awk -v a="$arrival" 'BEGIN { exit !(a > 0.519 && a < 0.521) }' || { cat "$out/decoded"; fail "nava arrival '$arrival': expected 0.519 to 0.521 s"; }
"$encode" --profile room --out "$out/room_clean.wav" 01020304 || fail "nava_encode --profile room failed"
"$tool" --in "$out/room_clean.wav" --out "$out/room_measured.wav" --rir "$out/response_mono.wav" --noise white --snr 10 \
  2>"$out/stderr" || { cat "$out/stderr"; fail "room packets through a measured response failed"; }
"$decode" --profile room "$out/room_measured.wav" >"$out/decoded" || fail "nava_decode --profile room failed"
arrival=$(sed -n 's/.*"kind": "packet".*"arrival": \([0-9.]*\).*/\1/p' "$out/decoded" | head -n 1)
awk -v a="$arrival" 'BEGIN { exit !(a > 0.5197 && a < 0.5201) }' || { cat "$out/decoded"; fail "arrival '$arrival': expected 0.5197 to 0.5201 s"; }
# nava_bench --arrival over a folder holding that response: every packet timed, the targets met.
mkdir -p "$out/rooms"
cp "$out/response.wav" "$out/rooms/"
"$bench" --arrival --rir-dir "$out/rooms" --packets 3 >"$out/bench" 2>&1 || { cat "$out/bench"; fail "nava_bench --arrival failed"; }
grep -q "^response.wav:1 .* 3/3 " "$out/bench" || { cat "$out/bench"; fail "nava_bench --arrival did not time every packet"; }
grep -q "target: median <= 100 us and p90 <= 300 us: yes" "$out/bench" || { cat "$out/bench"; fail "nava_bench --arrival missed its target"; }
# nava_bench --rooms over the same folder, each ear also made drier to +30 dB: rows for both.
"$bench" --rooms --rir-dir "$out/rooms" --measured-only --profile nava --rir-packets 2 --minimodem none --drier 30 \
  >"$out/bench" 2>&1 || { cat "$out/bench"; fail "nava_bench --rooms --drier failed"; }
grep -q "^response.wav:1 drier +30 dB  *+30.0 .* white 20 dB" "$out/bench" || { cat "$out/bench"; fail "no row made drier to +30 dB"; }
grep -q "^response.wav:1   .* white 20 dB" "$out/bench" || { cat "$out/bench"; fail "no row as measured"; }
# nava_bench --likeness over the same folder: a line for each ear, measured beside measured-like,
# and the differences over the rooms.
"$bench" --likeness --rir-dir "$out/rooms" --like-rooms 2 >"$out/bench" 2>&1 || { cat "$out/bench"; fail "nava_bench --likeness failed"; }
grep -Eq "^response.wav:1 +[0-9.]+ +[-+][0-9.]+( +-?[0-9.]+){12}$" "$out/bench" || { cat "$out/bench"; fail "nava_bench --likeness: no line for response.wav:1"; }
grep -Eq "^all +2 " "$out/bench" || { cat "$out/bench"; fail "nava_bench --likeness: no summary over both ears"; }
# nava_bench --splice: the two ears are the same response, so each splice at A's energies is A
# again (the same RT60 and DRR as a.wav), and every file is written.
"$bench" --splice --early "$out/response.wav:1" --late "$out/response.wav:0" --at-ms 2.5,10 --out "$out/spliced" \
  >"$out/bench" 2>&1 || { cat "$out/bench"; fail "nava_bench --splice failed"; }
for f in a2.5_b a10_b b2.5_a b10_a; do
  [ -s "$out/spliced/$f.wav" ] || { cat "$out/bench"; fail "nava_bench --splice wrote no $f.wav"; }
done
same=$(awk '$1 == "a.wav" { a = $2 " " $3 } $1 == "a10_b.wav" { b = $2 " " $3 } END { print (a == b && a != "") }' "$out/bench")
[ "$same" = 1 ] || { cat "$out/bench"; fail "nava_bench --splice: a response spliced with itself changed its RT60 or DRR"; }
# nava_bench --direction on a one-cell grid, and the pair judged on a "dummy head" whose two ears
# hear the same response: a sound from its front (head azimuth 0), which no pair can place, and
# the table written.
mkdir -p "$out/heads"
cp "$out/response.wav" "$out/heads/same_headaz+0.wav"
"$bench" --direction --packets 3 --min-decoded 0 --rt60 0.5 --drr 3 --binaural-dir "$out/heads" --threads 1 \
  --errors-out "$out/direction.yaml" >"$out/bench" 2>&1 || { cat "$out/bench"; fail "nava_bench --direction failed"; }
grep -Eq "^ +0\.50 +\+3 \| +3/3 " "$out/bench" || { cat "$out/bench"; fail "nava_bench --direction: no line for the cell"; }
grep -Eq "^same_headaz\+0\.wav +-?0 .* 3/3 +0 +0 +3 " "$out/bench" || { cat "$out/bench"; fail "nava_bench --direction: identical ears gave a direction"; }
grep -q "^  - rt60_s: 0.5" "$out/direction.yaml" || fail "nava_bench --direction: no cell in the table"
tool_was=$tool
tool=$bench
expect_error "--likeness: expected --rir-dir DIR" --likeness
expect_error "--like-rooms: expected a whole number from 1 to 1000, got 0" --likeness --rir-dir "$out/rooms" --like-rooms 0
expect_error "--splice: expected --at-ms T" --splice --early "$out/response.wav:1" --late "$out/response.wav:0" --out "$out/spliced"
expect_error "--at-ms: expected ascending times after the direct sound, ms separated by commas, got 10,2" --splice --early "$out/response.wav:1" --late "$out/response.wav:0" --at-ms 10,2 --out "$out/spliced"
expect_error "--late $out/response.wav:" --splice --early "$out/response.wav:1" --late "$out/response.wav" --at-ms 10 --out "$out/spliced"
expect_error "--early $out/response.wav:99999999999: expected a channel from 0 to 1023" --splice --early "$out/response.wav:99999999999" --late "$out/response.wav:0" --at-ms 10 --out "$out/spliced"
expect_error "--at-ms 900: splice at 900.* no sound in its span" --splice --early "$out/response.wav:1" --late "$out/response.wav:0" --at-ms 900 --out "$out/spliced"
expect_error "--early $out/missing.wav: " --splice --early "$out/missing.wav" --late "$out/response.wav:0" --at-ms 10 --out "$out/spliced"
expect_error "--drier: expected ascending DRRs" --rooms --rir-dir "$out/rooms" --drier 8,4
expect_error "--drier: there are no measured rooms" --rooms --drier 8
expect_error "--curve-rt60: expected ascending reverberation times" --rooms --curve-rt60 1,0.5
expect_error "--curve-drr-min: expected a number from -39" --rooms --curve-drr-min -50
expect_error "--response dry: expected statistical or measured-like" --rooms --response dry
expect_error "--response measured-like: expected --rate above 10800 Hz" --rooms --response measured-like --rate 10000
expect_error "--curve-snr: there is no delivery curve with --measured-only" --rooms --rir-dir "$out/rooms" --measured-only --curve-snr 20
expect_error "--dir /proc/no_such_folder: expected a folder that exists or can be made" --rooms --dir /proc/no_such_folder
expect_error "--arrival: expected --rir-dir DIR" --arrival
mkdir -p "$out/nothing_here"
expect_error "--rir-dir $out/nothing_here: no audio files" --arrival --rir-dir "$out/nothing_here"
expect_error "--rir-dir $out/missing: No such file" --arrival --rir-dir "$out/missing"
expect_error "--direction: expected --rate above 10800 Hz" --direction --rate 8000
expect_error "--drr: expected ascending DRRs" --direction --drr 3,-3
expect_error "--binaural-dir $out/rooms: no two-channel response named" --direction --packets 1 --rt60 0.5 --drr 3 --binaural-dir "$out/rooms"
tool=$tool_was
sox -n -r 48000 -c 1 "$out/silent.wav" trim 0 0.1 || fail "sox could not make silence"
expect_error "--rir $out/response.wav: 2 channels: expected one, or a channel chosen (--channel 0..1)" \
  --in "$out/clean.wav" --out "$out/x.wav" --rir "$out/response.wav"
expect_error "--rir $out/response.wav: channel 2 asked for: expected 0..1" \
  --in "$out/clean.wav" --out "$out/x.wav" --rir "$out/response.wav" --channel 2
expect_error "--rir $out/silent.wav: silent: expected an impulse response with a direct sound" \
  --in "$out/clean.wav" --out "$out/x.wav" --rir "$out/silent.wav"
expect_error "--rir $out/decoded: not a readable audio file" --in "$out/clean.wav" --out "$out/x.wav" --rir "$out/decoded"
expect_error "--rt60: the room is the measured response of --rir" \
  --in "$out/clean.wav" --out "$out/x.wav" --rir "$out/response_mono.wav" --rt60 0.5
expect_error "--channel: there is no response to take a channel of; add --rir FILE.wav" \
  --in "$out/clean.wav" --out "$out/x.wav" --channel 1

# Bad input: a clear message and exit status 1.
in=(--in "$out/clean.wav" --out "$out/x.wav")
expect_error "--rt60: rt60 -1 s: expected 0 (no reverberation) or above 0 and at most 10" "${in[@]}" --rt60 -1
expect_error "--rt60 abc: expected a number" "${in[@]}" --rt60 abc
expect_error "--drr: drr_db 50 dB: expected from -40 to 40" "${in[@]}" --drr 50
expect_error "--tilt: tilt_db 45 dB: expected from -40 to 40" "${in[@]}" --tilt 45
expect_error "--tilt-band: tilt_high_hz 2000 Hz: expected above tilt_low_hz" "${in[@]}" --tilt-band 3000,2000
expect_error "--tilt-band 3000: expected LO,HI" "${in[@]}" --tilt-band 3000
expect_error "--clock: clock_offset 0.07: expected from -0.05 to 0.05" "${in[@]}" --clock 7
expect_error "--noise purple: expected white or pink" "${in[@]}" --noise purple
expect_error "--snr: there is no noise to set; add --noise white|pink" "${in[@]}" --snr 10
expect_error "--snr: snr_db -70 dB: expected from -60 to 100" "${in[@]}" --noise pink --snr -70
expect_error "--sir: there is no interferer to set; add --interferer FILE" "${in[@]}" --sir 3
expect_error "--whine-sir: there is no whine to set" "${in[@]}" --whine-sir 3
expect_error "--whine: whine_hz 30000 Hz: expected 0 (none) or above 0 and below 23762 Hz" "${in[@]}" --whine 30000
expect_error "--seed: expected a whole number" "${in[@]}" --seed -1
expect_error "--in $out/nothing.wav: not a readable audio file" --in "$out/nothing.wav" --out "$out/x.wav"
expect_error "--interferer $out/decoded: not a readable audio file" "${in[@]}" --interferer "$out/decoded"
expect_error "--out is required" --in "$out/clean.wav"
expect_error "unknown option --reverb" "${in[@]}" --reverb 1
expect_error "--mics: microphone positions '0,0,1': 3 numbers; expected an x,y pair per microphone" "${in[@]}" --mics 0,0,1
expect_error "--mics: microphone positions '0,0': 1 microphone; expected at least 2" "${in[@]}" --mics 0,0
expect_error "--mics: microphone positions '0,0,a,1': 'a' is not a number" "${in[@]}" --mics 0,0,a,1
expect_error "--mics: microphone positions '0,0,,1': '' is not a number" "${in[@]}" --mics 0,0,,1
expect_error "--mics: microphone positions '0.1,0,0.1,0': microphones 1 and 2 are both at (0.1, 0); expected distinct positions" "${in[@]}" --mics 0.1,0,0.1,0
expect_error "--bearing: there is no microphone array to place the source around; add --mics" "${in[@]}" --bearing 30
expect_error "--distance: there is no microphone array" "${in[@]}" --distance 3
expect_error "--bearing north: expected a number" "${in[@]}" --mics "$mics" --bearing north
expect_error "--distance: distance 0 m: expected above 0 and at most 100 m" "${in[@]}" --mics "$mics" --distance 0
expect_error "--distance: distance 0.05 m: the source is 0 m from microphone 1" "${in[@]}" --mics "$mics" --distance 0.05
expect_error "--rt60: rt60 -1 s" "${in[@]}" --mics "$mics" --rt60 -1
[ ! -e "$out/x.wav" ] || fail "a failed run wrote its output"
# The room profile through nava_encode, an office-like room and nava_decode, at 16 kHz.
"$encode" --profile room --rate 16000 --out "$out/room_clean.wav" 01020304 a0b0c0d0 || fail "nava_encode --profile room failed"
"$tool" --in "$out/room_clean.wav" --out "$out/office.wav" --rt60 0.6 --drr -6 --noise pink --snr 10 --clock 0.5 \
  --seed 3 2>"$out/stderr" || { cat "$out/stderr"; fail "office room failed"; }
"$decode" --profile room "$out/office.wav" >"$out/decoded" || fail "nava_decode --profile room failed"
for p in 01020304 a0b0c0d0; do
  grep -q "\"kind\": \"packet\".*\"data\": \"$p\"" "$out/decoded" || { cat "$out/decoded"; fail "room profile: packet $p not decoded"; }
done

# Frames of any length on the room profile: a 64-byte frame at each rate through the office room,
# its rate reported; the ladder listed.
long=$(printf '%02x' $(seq 0 63))
for speed in 0 1 2; do
  "$encode" --profile room --rate 16000 --speed "$speed" --out "$out/frame$speed.wav" "$long" 0a || fail "nava_encode --speed $speed failed"
  "$decode" --profile room "$out/frame$speed.wav" >"$out/decoded" || fail "nava_decode of rate $speed failed"
  for p in "$long" 0a; do
    grep -q "\"kind\": \"packet\", \"noise\": \"none\", \"data\": \"$p\", \"rate\": $speed," "$out/decoded" \
      || { cat "$out/decoded"; fail "rate $speed: frame $p not decoded at its rate"; }
  done
done
"$encode" --list-rates --profile room >"$out/rates" || fail "nava_encode --list-rates failed"
[ "$(grep -c '"bit_rate"' "$out/rates")" -eq 3 ] || { cat "$out/rates"; fail "expected a line per rate"; }
grep -q '"name": "robust", "bit_rate": 29.2, "airtime_4": 1.920' "$out/rates" || { cat "$out/rates"; fail "the robust rate's line"; }

# The modem tools' profile errors.
tool=$encode
expect_error "frame 'abc': expected 2 to 510 hex digits (1 to 255 data bytes) on profile room" --profile room --out "$out/x.wav" abc
expect_error "frame '${long}${long}${long}${long}00': expected 2 to 510 hex digits" --profile room --out "$out/x.wav" "$long$long$long$long"00
expect_error "frame '0102030405': expected 8 hex digits (4 data bytes) on profile nava" --out "$out/x.wav" 0102030405
expect_error "--speed: expected a whole number from 0 to 2, got 3" --profile room --speed 3 --out "$out/x.wav" 01
expect_error "--speed: expected a whole number from 0 to 0, got 1" --speed 1 --out "$out/x.wav" 01020304
expect_error "no frames: give one HEX argument" --profile room --out "$out/x.wav"
expect_error "--profile: expected nava or room, got loud" --profile loud --out "$out/x.wav" 01020304
expect_error "--mark sets the nava profile's FSK; the room profile has its own tones" --profile room --mark 2000 --out "$out/x.wav" 01020304
expect_error "profile room: sample rate 8000 Hz cannot carry its band" --profile room --rate 8000 --out "$out/x.wav" 01020304
tool=$decode
expect_error "--profile: expected nava or room, got Room" --profile Room "$out/office.wav"
expect_error "--diagnostics: only the nava profile's receiver keeps diagnostics, not the room profile's" \
  --profile room --diagnostics "$out/x.json" "$out/office.wav"
expect_error "--diagnostics: not with --mics" --mics "$mics" --diagnostics "$out/x.json" "$out/array.wav"
expect_error "--diagnostics: expected a file to write the JSON to" --diagnostics "" "$out/clean.wav"
expect_error "--diagnostics: expected --flag VALUE" "$out/clean.wav" --diagnostics
expect_error "--diagnostics /proc/no_such_folder/x.json: cannot write it" --diagnostics /proc/no_such_folder/x.json "$out/clean.wav"
[ ! -e "$out/x.json" ] || fail "a refused --diagnostics wrote its file"
"$encode" --profile nava --rate 8000 --out "$out/narrow.wav" 01020304 || fail "nava_encode at 8000 Hz failed"
expect_error "$out/narrow.wav: profile room: sample rate 8000 Hz cannot carry its band" --profile room "$out/narrow.wav"
expect_error "--mics: microphone positions '1e9,0,0,0': (1e+09, 0): expected within 10 m" "${in[@]}" --mics 1e9,0,0,0
[ ! -e "$out/x.wav" ] || fail "a failed run wrote its output"
echo "nava_room checks: all passed"
