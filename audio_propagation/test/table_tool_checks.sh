#!/usr/bin/env bash
# decode_table_bench end to end on its quick table: the table is written, does not depend on the
# number of threads, and says how it was made; then the answers to bad input.
#   table_tool_checks.sh DECODE_TABLE_BENCH
set -uo pipefail
export PATH="/usr/bin:/bin:${PATH}"
tool=$1
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
source "$(dirname "$0")/../../test/tool_checks.sh"

for threads in 1 2; do
  "$tool" --profile nava --quick --packets 2 --threads "$threads" --dir "$out" --out "$out/t$threads.yaml" \
    >"$out/summary$threads" 2>"$out/stderr" || { cat "$out/stderr"; fail "--profile nava --quick failed"; }
done
grep -q '^profile: nava$' "$out/t1.yaml" || fail "no profile line"
grep -q '^command: "decode_table_bench --profile nava --quick --packets 2 --threads 1 ' "$out/t1.yaml" || fail "no command line"
grep -q '^snr_db: \[-12, 0, 12\]$' "$out/t1.yaml" || fail "not the quick SNR axis"
diff <(grep -v '^command:' "$out/t1.yaml") <(grep -v '^command:' "$out/t2.yaml") >/dev/null \
  || fail "the table depends on the number of threads"
grep -q '^packet ' "$out/summary1" || { cat "$out/summary1"; fail "summary without the packet kind"; }
grep -q 'CPU on 1 threads' "$out/summary1" || { cat "$out/summary1"; fail "summary without the CPU time"; }

expect_error "--profile: expected nava or room, got fsk" --profile fsk --quick
expect_error "--profile is required" --quick
expect_error "--snr-db: expected ascending numbers" --profile nava --quick --snr-db 0,-3
expect_error "--threads: expected a whole number from 1" --profile nava --quick --threads 0
expect_error "--out: no folder $out/no/such" --profile nava --quick --out "$out/no/such/t.yaml"
echo "table tool checks passed"
