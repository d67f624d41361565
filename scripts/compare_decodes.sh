#!/usr/bin/env bash
# Whether a change to a receiver changed what it decodes, packet for packet: renders every
# measured room response in DIR with packets of the profile (nava_bench --rooms --measured-only,
# white noise at 20 and 0 dB and speech), decodes each file with the nava_decode of two builds,
# and compares every event (time, kind, noise class, data, level, quality, rate error, arrival).
#
#   scripts/compare_decodes.sh [--rooms DIR] [--profile nava|room] [--keep DIR] OLD_BUILD NEW_BUILD
#
# OLD_BUILD and NEW_BUILD are build folders (say a worktree of the old commit's build/ and this
# one's). The files are rendered once, with NEW_BUILD's nava_bench. Prints "same: N events in K
# files" and exits 0, or the first differences and exits 1. --keep DIR keeps the rendered files
# and both event lists there. DIR defaults to ../shared/realrooms beside the checkout.
set -euo pipefail
export PATH="/usr/bin:/bin:${PATH}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
rooms="$here/../shared/realrooms"
profile=nava
keep=""
usage() {
  sed -n 's/^#   //p' "${BASH_SOURCE[0]}" >&2
  exit 2
}
while [ $# -gt 0 ]; do
  case "$1" in
    --rooms) rooms=${2:?--rooms: expected a folder}; shift 2 ;;
    --profile) profile=${2:?--profile: expected nava or room}; shift 2 ;;
    --keep) keep=${2:?--keep: expected a folder}; shift 2 ;;
    -h|--help) usage ;;
    -*) echo "compare_decodes.sh: unknown option $1" >&2; usage ;;
    *) break ;;
  esac
done
[ $# -eq 2 ] || usage
old=$1
new=$2
case "$profile" in nava|room) ;; *) echo "compare_decodes.sh: --profile $profile: expected nava or room" >&2; exit 2 ;; esac
[ -d "$rooms" ] || { echo "compare_decodes.sh: --rooms $rooms: no such folder (measured impulse responses, WAV)" >&2; exit 2; }
for b in "$old" "$new"; do
  for tool in nava_bench nava_decode; do
    [ -x "$b/nava_modem/$tool" ] || { echo "compare_decodes.sh: $b: no nava_modem/$tool (a built build folder expected)" >&2; exit 2; }
  done
done
if [ -n "$keep" ]; then
  work=$keep
  mkdir -p "$work"
else
  work=$(mktemp -d "${TMPDIR:-/tmp}/compare_decodes.XXXXXX")
  trap 'rm -rf "$work"' EXIT
fi

echo "compare_decodes.sh: rendering $rooms for $profile into $work/rendered"
"$new/nava_modem/nava_bench" --rooms --rir-dir "$rooms" --measured-only --profile "$profile" --plot-packets 0 \
  --dir "$work/rendered" >"$work/render.log" 2>&1 || { tail -n 20 "$work/render.log"; echo "compare_decodes.sh: rendering failed" >&2; exit 1; }
files=("$work"/rendered/measured_*_"$profile".wav)
[ -e "${files[0]}" ] || { echo "compare_decodes.sh: nothing rendered (see $work/render.log)" >&2; exit 1; }

# Every event of every file, each line after its file's name. (The rate step, printed since frames
# of several rates, is left out when it is 0, today's only one, so that builds from before compare.)
decode_all() {
  local build=$1 out=$2 f
  : >"$out"
  for f in "${files[@]}"; do
    echo "== $(basename "$f")" >>"$out"
    "$build/nava_modem/nava_decode" --profile "$profile" "$f" 2>&1 | sed 's/, "rate": 0,/,/' >>"$out"
  done
}
decode_all "$old" "$work/old.txt"
decode_all "$new" "$work/new.txt"
events=$(grep -vc '^== ' "$work/new.txt" || true)
if cmp -s "$work/old.txt" "$work/new.txt"; then
  echo "same: $events events in ${#files[@]} files"
  exit 0
fi
echo "DIFFERENT: the first differences (old <, new >):"
diff "$work/old.txt" "$work/new.txt" | head -n 20
exit 1
