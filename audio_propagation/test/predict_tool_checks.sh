#!/usr/bin/env bash
# audio_channel_predict end to end: responses written here with a known RT60 and DRR (a direct
# impulse, then white noise decaying exponentially) read back within their tolerance; the
# shipped tables' prediction rising with the SNR; a recorded noise weighed by where its power
# lies; the measured teaching room's DRR as ../shared/realrooms/README.md gives it (when that
# directory is beside the project); then the tool's answers to bad input.
#   predict_tool_checks.sh AUDIO_CHANNEL_PREDICT [REALROOMS_DIR]
set -uo pipefail
export PATH="/usr/bin:/bin:${PATH}"
tool=$1
realrooms=${2:-}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
source "$(dirname "$0")/../../test/tool_checks.sh"

for case in "0.5 0" "1.2 -6" "0.3 8"; do
  set -- $case
  wav "$out/room.wav" room "$1" "$2"
  line=$("$tool" --profile nava --rir "$out/room.wav" --noise white --snr-db 20) || fail "a response of RT60 $1 s"
  echo "$line"
  near "$(field rt60_s "$line")" "$1" "$(awk -v r="$1" 'BEGIN { print 0.1 * r }')" || fail "RT60 $1 s read as $(field rt60_s "$line")"
  near "$(field drr_db "$line")" "$2" 1.0 || fail "DRR $2 dB read as $(field drr_db "$line")"
done

# The shipped tables: a packet is likelier at 20 dB than at -25, for both profiles.
wav "$out/room.wav" room 0.5 0
for profile in nava room; do
  high=$(field probability "$("$tool" --profile $profile --rir "$out/room.wav" --noise pink --snr-db 20)")
  low=$(field probability "$("$tool" --profile $profile --rir "$out/room.wav" --noise pink --snr-db -25)")
  awk -v h="$high" -v l="$low" 'BEGIN { exit !(h > l && h <= 1 && l >= 0) }' || fail "$profile: $high at 20 dB, $low at -25 dB"
done

# A recorded tone on nava's mark puts all its power where nava listens: read as white noise 16 dB
# louder (600 of 24000 Hz); between the tones, as nothing much.
wav "$out/mark.wav" tone 2300
line=$("$tool" --profile nava --rir "$out/room.wav" --noise "$out/mark.wav" --snr-db 10) || fail "a recorded noise"
echo "$line"
near "$(field table_snr_db "$line")" -6.02 0.2 || fail "a tone on the mark read at $(field table_snr_db "$line") dB, expected -6"
wav "$out/between.wav" tone 3000
line=$("$tool" --profile nava --rir "$out/room.wav" --noise "$out/between.wav" --snr-db 10)
awk -v s="$(field table_snr_db "$line")" 'BEGIN { exit !(s > 30) }' || fail "a tone between nava's tones: $line"

if [ -n "$realrooms" ] && [ -f "$realrooms/brir_sweep_Netzwerkakademie_headaz-80.wav" ]; then
  line=$("$tool" --profile room --rir "$realrooms/brir_sweep_Netzwerkakademie_headaz-80.wav" --channel 0 --noise white --snr-db 0)
  echo "$line"
  near "$(field drr_db "$line")" 0.2 0.1 || fail "the teaching room at -80 degrees: DRR $(field drr_db "$line"), its README says +0.2"
else
  echo "no measured rooms beside the project: the teaching room's check is skipped"
fi

wav "$out/silent.wav" silent
wav "$out/short.wav" short
wav "$out/noise.wav" noise
expect_error "$out/silent.wav: .*silent" --profile nava --rir "$out/silent.wav" --noise white --snr-db 0
expect_error "$out/short.wav: too short" --profile nava --rir "$out/short.wav" --noise white --snr-db 0
expect_error "$out/noise.wav: no direct peak" --profile nava --rir "$out/noise.wav" --noise white --snr-db 0
expect_error "$out/nothing.wav" --profile nava --rir "$out/nothing.wav" --noise white --snr-db 0
expect_error "channel 3 asked for" --profile nava --rir "$out/room.wav" --channel 3 --noise white --snr-db 0
expect_error "$out/silent.wav: .*silent" --profile nava --rir "$out/room.wav" --noise "$out/silent.wav" --snr-db 0
expect_error "whine.*expected white, pink, speech or a recording" --profile nava --rir "$out/room.wav" --noise whine --snr-db 0
expect_error "--snr-db is required" --profile nava --rir "$out/room.wav" --noise white
expect_error "--profile: expected nava or room" --profile fsk --rir "$out/room.wav" --noise white --snr-db 0
echo "predict_tool_checks: all checks passed"
