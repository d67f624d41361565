#!/usr/bin/env bash
# scripts/figures.sh's manifest holds (the whole figures run is too long for CI): every figure's
# documented value is found exactly once in its doc, every command is a tool the build made and
# takes each option given. Then that the check can fail (a lost doc figure, an unknown tool, an
# unknown option), and that the runner tells OK, MOVED, TARGET MISSED, FAILED and SKIPPED apart
# on a made-up manifest whose commands are echo.
#   figures_manifest_checks.sh SOURCE_DIR BUILD_DIR
set -uo pipefail
export PATH="/usr/bin:/bin:${PATH}"
src=$1
build=$2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
figures=("/usr/bin/python3" "$src/scripts/figures.py")

"${figures[@]}" --check-manifest --build "$build" >"$out/ok" 2>&1 || { cat "$out/ok"; fail "the manifest does not hold"; }
"${figures[@]}" --list >"$out/list" 2>&1 || { cat "$out/list"; fail "--list failed"; }
grep -q "^\[quick" "$out/list" || fail "--list shows no quick run"

# expect_broken WORDS SED_SCRIPT: the manifest changed by SED_SCRIPT must fail the check, saying WORDS.
expect_broken() {
  sed "$2" "$src/scripts/figures.yaml" >"$out/broken.yaml"
  cmp -s "$src/scripts/figures.yaml" "$out/broken.yaml" && fail "'$2' changed nothing in the manifest"
  if "${figures[@]}" --check-manifest --build "$build" --manifest "$out/broken.yaml" >"$out/err" 2>&1; then
    fail "the check passed a manifest changed by '$2'"
  fi
  grep -q -- "$1" "$out/err" || { cat "$out/err"; fail "the check of '$2' did not say '$1'"; }
}
expect_broken "arrival.room.median: documented pattern found 0 times in docs/audio_link.md" \
  "s/documented: 'error median {num} us, 90th percentile'/documented: 'error median {num} ms, 90th percentile'/"
expect_broken "nava_modem/nava_bench_x: no such tool built" \
  "s|{build}/nava_modem/nava_bench --arrival|{build}/nava_modem/nava_bench_x --arrival|"
expect_broken "--teamz: not among ranging_bench's options" "s|ranging_bench --teams|ranging_bench --teamz|"
expect_broken "documented: expected one group" "s/documented: 'error median {num} us, 90th percentile'/documented: 'error median [0-9.]+ us'/"

# The runner, on a made-up doc and echo for tools.
mkdir -p "$out/root/docs"
cat >"$out/root/docs/made_up.md" <<'DOC'
The widget takes 10.0 ms
(target 12 ms), the gadget 5 ms, the gizmo 7 ms and the doohickey 3 ms.
DOC
cat >"$out/fake.yaml" <<'YAML'
variables: {build: build, rooms: docs}
runs:
  echo_run: {command: "/bin/echo widget 10.4 gadget 8 gizmo 13", quick: true, minutes: 0.1}
  failing_run: {command: "/bin/false", minutes: 0.1}
  needs_run: {command: "/bin/echo doohickey 3", minutes: 0.1, requires: ["docs/absent.wav"]}
figures:
  - {id: widget, doc: docs/made_up.md, documented: 'widget takes {num} ms', run: echo_run, measured: 'widget {num}', tolerance: 5%, target: '<= 12'}
  - {id: gadget, doc: docs/made_up.md, documented: 'gadget {num} ms', run: echo_run, measured: 'gadget {num}', tolerance: 1}
  - {id: gizmo, doc: docs/made_up.md, documented: 'gizmo {num} ms', run: echo_run, measured: 'gizmo {num}', tolerance: 10, target: '<= 12'}
  - {id: gizmo_unprinted, doc: docs/made_up.md, documented: 'gizmo {num} ms', run: echo_run, measured: 'sprocket {num}', tolerance: 1}
  - {id: failing, doc: docs/made_up.md, documented: 'gadget {num} ms', run: failing_run, measured: 'gadget {num}', tolerance: 1}
  - {id: doohickey, doc: docs/made_up.md, documented: 'doohickey {num} ms', run: needs_run, measured: 'doohickey {num}', tolerance: 1}
YAML
run_fake() { "${figures[@]}" --manifest "$out/fake.yaml" --root "$out/root" --logs "$out/logs" "$@" >"$out/run" 2>&1; }
run_fake
status=$?
[ "$status" -eq 1 ] || { cat "$out/run"; fail "a run with moved and failed figures exited with $status, expected 1"; }
line() { grep "^  $1 " "$out/run" || { cat "$out/run"; fail "no line for $1"; }; }
line widget | grep -q " OK$" || { cat "$out/run"; fail "widget (10.4 against 10.0 +-5 %) is not OK"; }
line gadget | grep -q " MOVED$" || { cat "$out/run"; fail "gadget (8 against 5 +-1) did not move"; }
line gizmo | grep -q " TARGET MISSED (target <= 12)$" || { cat "$out/run"; fail "gizmo (13, target <= 12) did not miss its target"; }
line gizmo_unprinted | grep -q "FAILED (measured pattern not found" || { cat "$out/run"; fail "a pattern the output lacks did not fail"; }
line failing | grep -q "FAILED (exit status 1" || { cat "$out/run"; fail "a failing command did not fail its figure"; }
line doohickey | grep -q "SKIPPED (missing docs/absent.wav)" || { cat "$out/run"; fail "a run without its file was not skipped"; }
grep -q "^figures: 6 checked: 1 OK, 1 MOVED, 1 TARGET MISSED, 2 FAILED, 1 SKIPPED$" "$out/run" || { cat "$out/run"; fail "wrong summary"; }
grep -q '^\$ /bin/echo widget 10.4 gadget 8 gizmo 13$' "$out/run" || { cat "$out/run"; fail "the command is not printed"; }
run_fake --only widget,doohickey || { cat "$out/run"; fail "OK and SKIPPED figures alone must exit 0"; }
run_fake --quick || true
grep -q "^  failing " "$out/run" && fail "--quick ran a run not marked quick"
run_fake --only 'nothing*'
[ $? -eq 2 ] || { cat "$out/run"; fail "--only matching no figure must exit 2"; }
grep -q "^figures: --only nothing\*: no figure has such an id" "$out/run" || { cat "$out/run"; fail "--only's error"; }
echo "figures manifest checks passed"
