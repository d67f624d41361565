#!/usr/bin/env bash
# Reruns the headline figures README.md and docs/*.md state, each with the command the docs give
# beside it, and prints documented against measured; exits 1 if any moved past its noise, missed
# its target or failed. The manifest is scripts/figures.yaml; scripts/figures.py does the work.
#
#   scripts/figures.sh [--quick] [--only ID[,ID...]] [--list] [--rooms DIR] [--build DIR] [--logs DIR]
#
#   --quick      only the runs under about 2 minutes on two cores (about 15 minutes in all)
#   --only       these figures (patterns too: --only 'ranging.*,survey.*')
#   --list       the manifest and each documented value, without running anything
#   --rooms DIR  the measured rooms (default ../shared/realrooms)
# The whole run takes over two hours on two cores: run it before resolving an issue that could
# move a figure, not in CI (test/figures_manifest_checks.sh checks the manifest in ctest).
# Needs the built tools (scripts/setup.sh builds them into build/); runs them from the repository
# root, one at a time (run it under nice on a shared machine).
set -euo pipefail
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:${PATH}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# No ROS environment needed: the tools are ROS-free and find the package's data (tables, speech)
# from where they are (package_data/), so build/devel/setup.bash is not sourced.
exec /usr/bin/python3 "$here/scripts/figures.py" "$@"
