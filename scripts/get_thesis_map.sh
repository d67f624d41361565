#!/usr/bin/env bash
# Puts the thesis's floor plan (the hospital section of the Stage simulator's worlds) at
# maps/thesis/hospital_section.{png,yaml}, where the commands in README.md and docs/, maps/hospital_world.yaml
# and the experiment tools look for it. The image is GPL-2.0 data of the Stage project and is
# not committed here (maps/thesis/ is git-ignored).
#
#   scripts/get_thesis_map.sh [IMAGE.png]
#
# The image comes from IMAGE.png when given, else from ../shared/maps/ beside the project when
# that exists, else from Stage's public repository (tag v4.3.0; the same image at every tag
# since v4.0.0). Whatever its source, its SHA-256 must be the thesis map's, or it is refused.
set -euo pipefail
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$here/maps/thesis"
expected=1ea2abd40f0d639500f2f5cfab7a07e2bdc716c60859d3e87e77988efe561a84
url=https://raw.githubusercontent.com/rtv/Stage/v4.3.0/worlds/bitmaps/hospital_section.png

mkdir -p "$out"
tmp="$(mktemp "$out/.download.XXXXXX")"
trap 'rm -f "$tmp"' EXIT

if [ $# -gt 1 ]; then
  echo "usage: scripts/get_thesis_map.sh [IMAGE.png]" >&2
  exit 1
elif [ $# -eq 1 ]; then
  source="$1"
  [ -f "$source" ] || { echo "get_thesis_map.sh: $source: no such file" >&2; exit 1; }
  cp "$source" "$tmp"
elif [ -f "$here/../shared/maps/hospital_section.png" ]; then
  source="$here/../shared/maps/hospital_section.png"
  cp "$source" "$tmp"
else
  source="$url"
  if command -v curl >/dev/null; then
    curl -fsSL "$url" -o "$tmp" || { echo "get_thesis_map.sh: cannot download $url" >&2; exit 1; }
  elif command -v wget >/dev/null; then
    wget -q "$url" -O "$tmp" || { echo "get_thesis_map.sh: cannot download $url" >&2; exit 1; }
  else
    echo "get_thesis_map.sh: neither curl nor wget to download $url; give the image's path instead" >&2
    exit 1
  fi
fi

actual="$(sha256sum "$tmp" | cut -d' ' -f1)"
if [ "$actual" != "$expected" ]; then
  echo "get_thesis_map.sh: $source is not the thesis's map: SHA-256 $actual, expected $expected" >&2
  exit 1
fi
mv "$tmp" "$out/hospital_section.png"
# map_server's format: 1086 x 443 cells of 3.13 cm, the thesis's 34 x 13.9 m hospital section.
cat > "$out/hospital_section.yaml" <<YAML
image: hospital_section.png
resolution: 0.0313
origin: [0.0, 0.0, 0.0]
negate: 0
occupied_thresh: 0.65
free_thresh: 0.196
YAML
echo "get_thesis_map.sh: maps/thesis/hospital_section.{png,yaml} from $source"
