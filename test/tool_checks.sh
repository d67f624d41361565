# Shell helpers for the command-line tools' end-to-end tests; source it after setting `tool`
# (the program under test) and `out` (a scratch directory).

fail() { echo "FAIL: $*" >&2; exit 1; }

# wav OUT KIND [ARGS]: test responses and noises (test/make_wav.py says which).
wav() { /usr/bin/python3 "$(dirname "${BASH_SOURCE[0]}")/make_wav.py" "$@" || fail "could not write $1"; }
# field NAME LINE: the number after "NAME": in a JSON line.
field() { echo "$2" | sed -n "s/.*\"$1\": \\([-0-9.enull]*\\).*/\\1/p"; }
# near A B TOLERANCE: whether |A - B| <= TOLERANCE.
near() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= t) }'; }

# expect_error WORDS ARGS...: the tool run with ARGS must exit with status 1 and say WORDS
# (a grep pattern) on stderr.
expect_error() {
  local words=$1
  shift
  local status=0
  "$tool" "$@" >"$out/err.out" 2>"$out/err" || status=$?
  [ "$status" -ne 0 ] || fail "$* succeeded"
  [ "$status" -eq 1 ] || fail "$* exited with $status, expected 1"
  grep -q -- "$words" "$out/err" || { cat "$out/err"; fail "$* did not say '$words'"; }
}

# check_shards ARGS...: the tool run with ARGS (a small run) whole, as shards 1/2 and 2/2 and as
# the merge of the two shards must give one report: the merge prints the whole run's stdout and
# writes its files, to the byte. Shards get --out DIR of their own; the whole run and the merge
# get the words of the array `report_args` (if set), with @OUT@ replaced by a directory of their
# own. Then the answers to bad shards and bad --shard values.
check_shards() {
  local s=$out/shards
  rm -rf "$s"
  mkdir -p "$s"
  local whole=("${report_args[@]/@OUT@/$s/whole}") merged=("${report_args[@]/@OUT@/$s/merged}")
  "$tool" "$@" "${whole[@]}" >"$s/whole.out" 2>"$s/err" || { cat "$s/err"; fail "the whole run of $* failed"; }
  [ -s "$s/whole.out" ] || fail "the whole run of $* printed nothing"
  "$tool" "$@" --shard 1/2 --out "$s/1" >"$s/shard.out" 2>"$s/err" || { cat "$s/err"; fail "shard 1/2 failed"; }
  grep -q "^shard 1/2: " "$s/shard.out" || fail "shard 1/2 did not say what it wrote"
  "$tool" "$@" --shard 2/2 --out "$s/2" >/dev/null 2>"$s/err" || { cat "$s/err"; fail "shard 2/2 failed"; }
  "$tool" --merge "$s/2" "$s/1" "${merged[@]}" >"$s/merged.out" 2>"$s/err" || { cat "$s/err"; fail "--merge failed"; }
  cmp "$s/whole.out" "$s/merged.out" || { diff "$s/whole.out" "$s/merged.out"; fail "the merge printed another report than the whole run"; }
  if [ -d "$s/whole" ]; then
    diff -r "$s/whole" "$s/merged" || fail "the merge wrote other files than the whole run"
  fi

  # A changed value in a record must change the report (word 2 of every tool's record is reported).
  cp -r "$s/1" "$s/changed"
  awk 'NR == 1 { $3 = $3 + 1 } { print }' "$s/1/shard_trials.txt" >"$s/changed/shard_trials.txt"
  rm -rf "$s/merged"
  if "$tool" --merge "$s/changed" "$s/2" "${merged[@]}" >"$s/merged.out" 2>/dev/null &&
     cmp -s "$s/whole.out" "$s/merged.out" && { [ ! -d "$s/whole" ] || diff -rq "$s/whole" "$s/merged" >/dev/null; }; then
    fail "a changed record left the merged report as it was: the comparison cannot see a wrong merge"
  fi

  expect_error "--shard: expected K/N with whole numbers 1 <= K <= N, got '0/2'" "$@" --shard 0/2 --out "$s/x"
  expect_error "--shard: expected K/N with whole numbers 1 <= K <= N, got '3/2'" "$@" --shard 3/2 --out "$s/x"
  expect_error "--shard: expected K/N with whole numbers 1 <= K <= N, got 'a/b'" "$@" --shard a/b --out "$s/x"
  expect_error "--shard and --merge: give one of them" --merge "$s/1" "$s/2" --shard 1/2
  expect_error "--merge: expected the shard directories after it" --merge
  expect_error "--merge takes the options from the shards' manifests: drop --seed" --merge "$s/1" "$s/2" --seed 5
  expect_error "$s: expected a shard directory with shard.txt" --merge "$s/1" "$s"
  expect_error "--merge: shard 2/2 missing" --merge "$s/1"
  expect_error "$s/2: shard 2/2 again ($s/2 is shard 2/2 too)" --merge "$s/1" "$s/2" "$s/2"
  # A dropped trial: shard 1/2 holds trials 0, 2, 4, ...
  cp -r "$s/1" "$s/dropped"
  sed -i 2d "$s/dropped/shard_trials.txt"
  expect_error "$s/dropped/shard_trials.txt: expected the [0-9]* trials of shard 1/2, found [0-9]* (trial 2 missing)" \
    --merge "$s/dropped" "$s/2"
  # A shard of another run (another seed).
  "$tool" "$@" --seed 99 --shard 2/2 --out "$s/other" >/dev/null 2>"$s/err" || { cat "$s/err"; fail "shard 2/2 with --seed 99 failed"; }
  expect_error "$s/other: run with --seed 99, but $s/1 with" --merge "$s/1" "$s/other"
}
