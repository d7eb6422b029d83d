#!/usr/bin/env bash
# Our .splat and .spz writers checked by an independent decoder, and our .spz reader by an
# independent encoder: PlayCanvas splat-transform (npm; tools/bootstrap.sh test installs the pinned
# version in .npm-tools/). There is no compressed-PLY writer of ours to check.
#   splat_transform_test.sh VKSPLAT_BINARY WORK_DIR
# A generated scene (tests/io/splat_transform_compare.py) is written as .splat and .spz by
# `vksplat convert`; splat-transform decodes each to a float PLY, compared with the scene within
# each format's quantisation. Then splat-transform encodes the scene as .spz (version 3, the newest
# we read) and `vksplat convert` decodes it. Exits 77 (skipped) when splat-transform is not there.
set -euo pipefail
vksplat=$(realpath "$1")
work=$2
here=$(cd "$(dirname "$0")" && pwd)
splat_transform=$here/../../.npm-tools/node_modules/.bin/splat-transform
if [ ! -x "$splat_transform" ] || ! command -v node >/dev/null; then
  echo "SKIPPED: no splat-transform at $splat_transform (tools/bootstrap.sh test installs it)" >&2
  exit 77
fi
rm -rf "$work"
mkdir -p "$work"
cd "$work"

# Runs a command quietly; on failure shows what it printed.
run() {
  "$@" >run.log 2>&1 || { cat run.log >&2; echo "FAILED: $*" >&2; exit 1; }
}
compare() { python3 "$here/splat_transform_compare.py" compare "$@"; }

run python3 "$here/splat_transform_compare.py" scene scene.ply
status=0
for format in splat spz; do
  run "$vksplat" convert scene.ply "ours.$format"
  run "$splat_transform" "ours.$format" "theirs_from_ours_$format.ply"
  compare "$format" scene.ply "theirs_from_ours_$format.ply" || status=1
done
run "$splat_transform" scene.ply --spz-version 3 theirs.spz
run "$vksplat" convert theirs.spz ours_from_theirs_spz.ply
compare spz_theirs scene.ply ours_from_theirs_spz.ply || status=1
exit $status
