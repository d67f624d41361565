#!/usr/bin/env bash
# decode_table_bench end to end on its quick table: the table is written, does not depend on the
# number of threads, and says how it was made; the model's calibration on two rooms written here
# (a line per case, the bins, the worst bin); then the answers to bad input.
#   table_tool_checks.sh DECODE_TABLE_BENCH [sanitized]
# With "sanitized" (the AddressSanitizer build, several times slower) the table is measured once,
# on two threads, and the calibration without its recorded noise: the thread-count comparison
# and the noise are left to the main suite.
set -uo pipefail
export PATH="/usr/bin:/bin:${PATH}"
tool=$1
sanitized=${2:-}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
source "$(dirname "$0")/../../test/tool_checks.sh"

thread_counts=(1 2)
[ "$sanitized" = sanitized ] && thread_counts=(2)
for threads in "${thread_counts[@]}"; do
  "$tool" --profile nava --quick --packets 2 --threads "$threads" --dir "$out" --out "$out/t$threads.yaml" \
    >"$out/summary$threads" 2>"$out/stderr" || { cat "$out/stderr"; fail "--profile nava --quick failed"; }
done
t=${thread_counts[0]}
grep -q '^profile: nava$' "$out/t$t.yaml" || fail "no profile line"
grep -q "^command: \"decode_table_bench --profile nava --quick --packets 2 --threads $t " "$out/t$t.yaml" || fail "no command line"
grep -q '^snr_db: \[-12, 0, 12\]$' "$out/t$t.yaml" || fail "not the quick SNR axis"
if [ "$sanitized" != sanitized ]; then
  diff <(grep -v '^command:' "$out/t1.yaml") <(grep -v '^command:' "$out/t2.yaml") >/dev/null \
    || fail "the table depends on the number of threads"
fi
grep -q '^packet ' "$out/summary$t" || { cat "$out/summary$t"; fail "summary without the packet kind"; }
grep -q "CPU on $t threads" "$out/summary$t" || { cat "$out/summary$t"; fail "summary without the CPU time"; }
# --rt60 replaces the RT60 axis (and --snr-db the SNR axis), in the table written.
"$tool" --profile nava --quick --packets 1 --snr-db 0 --rt60 0.2,2.5 --dir "$out" --out "$out/axes.yaml" \
  >/dev/null 2>"$out/stderr" || { cat "$out/stderr"; fail "--rt60 0.2,2.5 failed"; }
grep -q '^rt60: \[0.2, 2.5\]$' "$out/axes.yaml" || fail "--rt60 0.2,2.5 is not the table's RT60 axis"
grep -q '^snr_db: \[0\]$' "$out/axes.yaml" || fail "--snr-db 0 is not the table's SNR axis"
# A table over rooms like measured ones: measured, and its command says so.
"$tool" --profile room --quick --packets 1 --snr-db 0 --response measured-like --dir "$out" --out "$out/like.yaml" \
  >/dev/null 2>"$out/stderr" || { cat "$out/stderr"; fail "--response measured-like failed"; }
grep -q '^command: ".*--response measured-like' "$out/like.yaml" || fail "the measured-like table's command does not say so"

# --whine-harm: a copy of the quick table with nava's whine harm curve, its cells kept; a whine on
# the mark is worse than the table's own between the tones.
"$tool" --profile nava --whine-harm --quick --packets 8 --table "$out/t$t.yaml" --out "$out/harm.yaml" \
  >"$out/harm" 2>"$out/stderr" || { cat "$out/stderr"; fail "--whine-harm --quick failed"; }
cat "$out/harm"
grep -q '^  hz: \[1200, 2300, 3000\]$' "$out/harm.yaml" || fail "the quick curve's frequencies are not 1200, 2300 and the table's 3000 Hz"
grep -q '^  db: \[.*, 0\]$' "$out/harm.yaml" || fail "the table's own whine is not at 0 dB in its curve"
diff <(sed -n '/^kinds:/,$p' "$out/t$t.yaml") <(sed -n '/^kinds:/,$p' "$out/harm.yaml") >/dev/null \
  || fail "--whine-harm changed the table's cells"
on_mark=$(sed -n 's/^ *2300 Hz *\([-+][0-9.]*\) dB.*/\1/p' "$out/harm")
awk -v h="$on_mark" 'BEGIN { exit !(h > 3) }' || fail "a whine on the mark read as $on_mark dB against the table's"
expect_error "--whine-harm: measured for nava's tones; expected --profile nava" --profile room --whine-harm
expect_error "--whine-harm and --calibrate: one at a time" --profile nava --whine-harm --calibrate --rir-dir "$out/rooms"
expect_error "--whine-harm keeps the table's cells" --profile nava --whine-harm --dir "$out"

# Calibration: the room profile through a dry and a reverberant room, at -25 and +20 dB, in white
# noise and in a recorded tone; a tone on nava's mark for nava.
mkdir -p "$out/rooms"
wav "$out/rooms/dry.wav" room 0.3 6
wav "$out/rooms/hall.wav" room 1.2 -6
wav "$out/tone.wav" tone 2300
noise=(--noise-file "$out/tone.wav")
cases=8
[ "$sanitized" = sanitized ] && noise=() && cases=4
"$tool" --profile room --calibrate --rir-dir "$out/rooms" "${noise[@]}" --packets 2 --snr-db -25,20 \
  --dir "$out" >"$out/calibration" 2>"$out/stderr" || { cat "$out/stderr"; fail "--calibrate failed"; }
cat "$out/calibration"
[ "$(grep -c '^dry.wav \|^hall.wav ' "$out/calibration")" -eq "$cases" ] || fail "expected 2 rooms x $((cases / 4)) noises x 2 SNRs"
grep -Eq '^dry.wav +\+[0-9.]+ +0\.[23][0-9] +white +\+20 +[0-9]+% +100%$' "$out/calibration" \
  || fail "the room profile should decode every packet through a dry room at +20 dB"
grep -Eq '^calibration: worst bin [0-9.]+ points apart' "$out/calibration" || fail "no calibration line"
# A table over the measured rooms written here, moved to each cell's RT60 and DRR: it says so, and
# names the rooms of each RT60.
"$tool" --profile room --quick --packets 1 --snr-db 0 --rt60 0.25,1 --response measured --rir-dir "$out/rooms" \
  --dir "$out" --out "$out/measured.yaml" >/dev/null 2>"$out/stderr" || { cat "$out/stderr"; fail "--response measured failed"; }
grep -q '^rooms: measured$' "$out/measured.yaml" || fail "the table over measured rooms does not say so"
grep -q '^rooms moved to RT60 1 s (1 places in 1 rooms): hall.wav' "$out/stderr" || { cat "$out/stderr"; fail "the rooms moved to RT60 1 s are not named"; }
expect_error "--response measured: expected --rir-dir DIR" --profile room --quick --response measured
expect_error "--rir-dir $out/none: " --profile room --quick --response measured --rir-dir "$out/rooms,$out/none"
expect_error "no room decays as slowly as an RT60 of 5" --profile room --quick --response measured --rir-dir "$out/rooms" --rt60 5
expect_error "--calibrate: expected --rir-dir DIR" --profile room --calibrate
expect_error "--rir-dir, --noise-file and --table go with --calibrate" --profile room --rir-dir "$out/rooms"
expect_error "--calibrate measures no table: drop --quick and --out" --profile room --calibrate --rir-dir "$out/rooms" --quick
expect_error "--noise-file $out/none.wav" --profile room --calibrate --rir-dir "$out/rooms" --noise-file "$out/none.wav"
wav "$out/rooms/noise.wav" noise
expect_error "noise.wav: no direct peak" --profile room --calibrate --rir-dir "$out/rooms"

expect_error "--profile: expected nava or room, got fsk" --profile fsk --quick
expect_error "--profile is required" --quick
expect_error "--snr-db: expected ascending numbers" --profile nava --quick --snr-db 0,-3
expect_error "--rt60: expected ascending reverberation times from 0.001 to 10 (s) separated by commas, got 0,1" \
  --profile nava --quick --rt60 0,1
expect_error "--rt60: expected ascending reverberation times" --profile nava --quick --rt60 1,0.5
expect_error "--rt60: expected ascending reverberation times" --profile nava --quick --rt60 12
expect_error "--rt60 is a table's axis: it does not go with --calibrate" --profile room --calibrate --rir-dir "$out/rooms" --rt60 1
expect_error "--response odd: expected statistical, measured-like or measured" --profile nava --quick --response odd
expect_error "--response: the calibration's rooms are the measured ones of --rir-dir" --profile room --calibrate \
  --rir-dir "$out/rooms" --response measured-like
expect_error "--threads: expected a whole number from 1" --profile nava --quick --threads 0
expect_error "--out: no folder $out/no/such" --profile nava --quick --out "$out/no/such/t.yaml"
echo "table tool checks passed"
