#!/usr/bin/env bash
# Continuous English speech for testing the modems against a talking interferer, made at run
# time with espeak-ng (nothing is downloaded): different sentences in two or three voices and
# speeds chosen by SEED, one after another with short pauses, until SECONDS, written as a WAV at
# espeak-ng's own 22050 Hz (nava_room resamples interferers to the modem's rate).
#
#   make_speech.sh OUT.wav [SECONDS] [SEED]        defaults: 30 s, seed 1
set -euo pipefail
export PATH="/usr/bin:/bin:${PATH}"

usage="usage: make_speech.sh OUT.wav [SECONDS] [SEED]"
[ $# -ge 1 ] && [ $# -le 3 ] || { echo "$usage" >&2; exit 1; }
out=$1
seconds=${2:-30}
seed=${3:-1}
[[ "$seconds" =~ ^[0-9]+([.][0-9]+)?$ ]] && awk -v s="$seconds" 'BEGIN { exit !(s > 0 && s <= 3600) }' \
  || { echo "make_speech.sh: SECONDS $seconds: expected a number above 0 and at most 3600" >&2; exit 1; }
[[ "$seed" =~ ^[0-9]+$ ]] || { echo "make_speech.sh: SEED $seed: expected a whole number" >&2; exit 1; }
for program in espeak-ng sox soxi; do
  command -v "$program" >/dev/null || { echo "make_speech.sh: $program not found (scripts/setup.sh installs it)" >&2; exit 1; }
done

sentences=(
  "The robot found the charger near the door and waited for its turn."
  "Please move the red box to the corner of the second room."
  "Battery level is low, returning to the docking station now."
  "I can hear another robot on the far side of the wall."
  "Turn left at the end of the corridor, then go straight ahead for three metres."
  "The meeting starts at half past ten in the small conference room."
  "Could somebody open the window? It is getting rather warm in here."
  "Seven robots shared two chargers for a whole afternoon without a single collision."
  "The coffee machine on the third floor has been broken since Monday."
  "Listen carefully, the next instruction will only be given once."
  "We measured the echo in the hall and it lasted almost a second."
  "Nobody knows where the blue robot went after lunch."
)
voices=(en-us+m3 en-gb+f3 en-us+f2 en-gb-scotland+m1 en-gb-x-rp+f4 en-us+m7)
# The seed fixes everything below (bash's RANDOM is deterministic once seeded).
RANDOM=$seed
count=$((2 + RANDOM % 2))
chosen_voices=()
chosen_speeds=()
for ((i = 0; i < count; ++i)); do
  # Distinct voices: each pick is taken out of the list.
  pick=$((RANDOM % ${#voices[@]}))
  chosen_voices+=("${voices[pick]}")
  voices=("${voices[@]:0:pick}" "${voices[@]:pick+1}")
  chosen_speeds+=($((135 + RANDOM % 50)))  # words per minute
done

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
parts=()
total=0
k=0
first=$((RANDOM % ${#sentences[@]}))
while awk -v t="$total" -v s="$seconds" 'BEGIN { exit !(t < s) }'; do
  sentence=${sentences[(first + k) % ${#sentences[@]}]}
  v=$((k % count))
  part="$work/part_$k.wav"
  espeak-ng -v "${chosen_voices[v]}" -s "${chosen_speeds[v]}" -w "$work/raw.wav" "$sentence"
  # A pause of 0.15-0.45 s after each sentence, as between speakers' turns. RANDOM is drawn
  # here, not inside $(...): bash reseeds it in subshells.
  r=$((RANDOM % 31))
  pause=$(awk -v r="$r" 'BEGIN { printf "%.2f", 0.15 + r / 100 }')
  # -D: no dither (sox's is random per run, and these edits lose nothing to dither away).
  sox -D "$work/raw.wav" "$part" pad 0 "$pause"
  parts+=("$part")
  total=$(awk -v t="$total" -v d="$(soxi -D "$part")" 'BEGIN { print t + d }')
  k=$((k + 1))
done
sox -D "${parts[@]}" "$out" trim 0 "$seconds"
echo "make_speech.sh: $out: $seconds s of speech at 22050 Hz, $k sentences, voices ${chosen_voices[*]} at ${chosen_speeds[*]} wpm" >&2
