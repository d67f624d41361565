# Shell helpers for the command-line tools' end-to-end tests; source it after setting `tool`
# (the program under test) and `out` (a scratch directory).

fail() { echo "FAIL: $*" >&2; exit 1; }

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
