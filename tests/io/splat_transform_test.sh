#!/usr/bin/env bash
# Our .splat, .spz (versions 4 and 3), compressed .ply and .sog writers checked by an independent
# decoder, and our .spz and .sog readers by an independent encoder: PlayCanvas splat-transform (npm;
# tools/bootstrap.sh test installs the pinned version in .npm-tools/).
#   splat_transform_test.sh VKSPLAT_BINARY WORK_DIR
# A generated scene (tests/io/splat_transform_compare.py) is written as .splat, .spz (3, our
# default, and 4) and .compressed.ply by `vksplat convert`; splat-transform decodes each to a float
# PLY, compared with the scene within each format's quantisation. Then splat-transform encodes the
# scene as .spz, version 4 (its default) and 3, and `vksplat convert` decodes each. Last SOG: ours
# as a .sog zip and as a folder (meta.json) decoded by splat-transform, and its .sog of a scene
# whose higher SH come from 16 vectors (which its palette holds exactly) decoded by us. Exits 77
# (skipped) when splat-transform is not there.
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
# starts_with FILE BYTES: the file is of the version the test means (SPZ 4 "NGSP", SPZ 3 gzip).
starts_with() {
  [ "$(head -c ${#2} "$1")" = "$2" ] || { echo "FAILED: $1 does not start with '$2'" >&2; status=1; }
}
for format in splat spz compressed.ply; do
  case=${format/./_}
  run "$vksplat" convert scene.ply "ours.$format"
  run "$splat_transform" "ours.$format" "theirs_from_ours_$case.ply"
  compare "$case" scene.ply "theirs_from_ours_$case.ply" || status=1
done
starts_with ours.spz $'\x1f'
head -c 2000 ours.compressed.ply | grep -qax "element chunk 2" ||
  { echo "FAILED: ours.compressed.ply has no chunk element: not a compressed PLY" >&2; status=1; }
run "$vksplat" convert scene.ply ours_v4.spz --format spz-v4
starts_with ours_v4.spz NGSP
run "$splat_transform" ours_v4.spz theirs_from_ours_spz_v4.ply
compare spz scene.ply theirs_from_ours_spz_v4.ply || status=1
for version in 4 3; do
  run "$splat_transform" scene.ply --spz-version $version "theirs_v$version.spz"
  run "$vksplat" convert "theirs_v$version.spz" "ours_from_theirs_spz_v$version.ply"
  compare spz_theirs scene.ply "ours_from_theirs_spz_v$version.ply" || status=1
done
starts_with theirs_v4.spz NGSP

run "$vksplat" convert scene.ply ours.sog
starts_with ours.sog PK
run "$splat_transform" ours.sog theirs_from_ours_sog.ply
compare sog scene.ply theirs_from_ours_sog.ply || status=1
mkdir ours_sog_folder
run "$vksplat" convert scene.ply ours_sog_folder/meta.json
run "$splat_transform" ours_sog_folder/meta.json theirs_from_ours_sog_folder.ply
compare sog scene.ply theirs_from_ours_sog_folder.ply || status=1
run python3 "$here/splat_transform_compare.py" scene scene_sh16.ply --sh-vectors 16
# -g cpu: its SH palette's k-means would ask for a WebGPU device, which a test machine may lack.
run "$splat_transform" -g cpu scene_sh16.ply theirs.sog
starts_with theirs.sog PK
run "$vksplat" convert theirs.sog ours_from_theirs_sog.ply
compare sog_theirs scene_sh16.ply ours_from_theirs_sog.ply || status=1
exit $status
