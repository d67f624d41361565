#!/usr/bin/env bash
# nava_decode --mics on microphone-array recordings made here: one modem WAV delayed per channel by
# what a far-field sender at a known bearing gives each microphone (whole samples, with sox), then
# the direction on every line, the output without --mics unchanged, and the errors.
#   doa_tool_checks.sh NAVA_ENCODE NAVA_DECODE
set -uo pipefail
export PATH="/usr/bin:/bin:${PATH}"
encode=$1
decode=$2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
source "$(dirname "$0")/../../test/tool_checks.sh"

# array NAME SOURCE DELAY...: NAME.wav, channel i the source delayed by DELAY_i samples.
array() {
  local name=$1 source=$2
  shift 2
  local inputs=()
  local i=0
  for d in "$@"; do
    sox "$source" "$out/$name.$i.wav" pad "${d}s" 0 || fail "sox pad failed"
    inputs+=("$out/$name.$i.wav")
    i=$((i + 1))
  done
  sox -M "${inputs[@]}" "$out/$name.wav" || fail "sox -M failed"
}

# expect_directions FILE WANT TOLERANCE: both packets decoded, every line's direction within
# TOLERANCE rad of WANT (the bearing compared modulo 2 pi), confidence above 0.5.
expect_directions() {
  local file=$1 want=$2 tolerance=$3
  [ "$(grep -c '"kind": "packet"' "$file")" -eq 2 ] || { cat "$file"; fail "$file: expected 2 packets"; }
  awk -v want="$want" -v tol="$tolerance" '
    { if (!match($0, /"direction": -?[0-9.]+, "direction_confidence": [0-9.]+}$/)) { print "no direction: " $0; bad = 1; next }
      split(substr($0, RSTART, RLENGTH), f, /[:,}]/); d = f[2] + 0; c = f[4] + 0
      e = d - want; pi = atan2(0, -1); while (e > pi) e -= 2 * pi; while (e < -pi) e += 2 * pi
      if (e < -tol || e > tol || c <= 0.5) { print "off: " $0; bad = 1 } }
    END { exit bad }' "$file" || fail "$file: directions not near $want"
}

square=0.1,0,0,0.1,-0.1,0,0,-0.1
"$encode" --out "$out/nava.wav" 01020304 a0b0c0d0 || fail "nava_encode failed"
# 0.1 m is 14.0 samples at 48 kHz: a sender ahead (bearing 0) reaches mic 0 first, mic 2 last.
array ahead "$out/nava.wav" 6 20 34 20
"$decode" --mics "$square" "$out/ahead.wav" >"$out/ahead.json" || fail "nava_decode --mics failed"
expect_directions "$out/ahead.json" 0 0.05
# To the left (bearing pi/2): mic 1 first.
array left "$out/nava.wav" 20 6 20 34
"$decode" --mics "$square" "$out/left.wav" >"$out/left.json" || fail "nava_decode --mics failed"
expect_directions "$out/left.json" 1.5708 0.05
# Without --mics: the channels are mixed as before, no direction.
"$decode" "$out/left.wav" >"$out/mixed.json" || fail "nava_decode without --mics failed"
grep -q direction "$out/mixed.json" && fail "a direction without --mics"
[ "$(grep -c '"kind": "packet"' "$out/mixed.json")" -eq 2 ] || { cat "$out/mixed.json"; fail "without --mics: expected 2 packets"; }

# The room profile at 16 kHz, a pair on the x axis, the sender behind: pi (0.2 m is 9.3 samples).
"$encode" --profile room --rate 16000 --out "$out/room.wav" 01020304 a0b0c0d0 || fail "nava_encode --profile room failed"
array behind "$out/room.wav" 14 5
"$decode" --profile room --mics 0.1,0,-0.1,0 "$out/behind.wav" >"$out/behind.json" || fail "nava_decode --profile room --mics failed"
expect_directions "$out/behind.json" 3.1416 0.001
# Broadside to the pair: no direction, null in the JSON.
array beside "$out/room.wav" 10 10
"$decode" --profile room --mics 0.1,0,-0.1,0 "$out/beside.wav" >"$out/beside.json" || fail "nava_decode --profile room --mics failed"
[ "$(grep -c '"direction": null, "direction_confidence": 0.00}$' "$out/beside.json")" -eq 2 ] \
  || { cat "$out/beside.json"; fail "broadside: expected null directions"; }

tool=$decode
expect_error "^nava_decode: $out/ahead.wav has 4 channels, but --mics gives 2 microphones$" --mics 0.1,0,-0.1,0 "$out/ahead.wav"
[ "$(grep -c . "$out/err")" -eq 1 ] || { cat "$out/err"; fail "the channel count error is not one line"; }
expect_error "--mics: microphone positions '0.1,0,-0.1': 3 numbers; expected an x,y pair per microphone" --mics 0.1,0,-0.1 "$out/ahead.wav"
expect_error "--mics: microphone positions '0.1,0,0.1,0': microphones 1 and 2 are both at (0.1, 0)" --mics 0.1,0,0.1,0 "$out/ahead.wav"
expect_error "--mics: microphone positions '1,x': 'x' is not a number" --mics 1,x "$out/ahead.wav"
expect_error "$out/nothing.wav: not a readable audio file" --mics "$square" "$out/nothing.wav"
echo "nava_decode --mics checks: all passed"
