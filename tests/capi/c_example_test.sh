#!/usr/bin/env bash
# examples/c_api, the C program: its picture of the scene it builds must show something (many
# colours, not only the background), and a scene path that does not exist must fail with the file
# named. usage: c_example_test.sh C_API_EXAMPLE WORK_DIR [SCENE]
# With SCENE, that scene is rendered too (the install test passes `vksplat demo`'s).
set -euo pipefail
example=$1
work=$2
rm -rf "$work" && mkdir -p "$work"

# A P6 PPM of the size the example renders, and how many distinct colours and non-black pixels it holds.
check_picture() {
  python3 - "$1" <<'PY'
import sys
data = open(sys.argv[1], 'rb').read()
header = b'P6\n160 120\n255\n'
assert data.startswith(header), f'{sys.argv[1]}: not a 160 x 120 P6 PPM: {data[:20]!r}'
pixels = data[len(header):]
assert len(pixels) == 160 * 120 * 3, f'{sys.argv[1]}: {len(pixels)} bytes of pixels'
colours = {pixels[i:i + 3] for i in range(0, len(pixels), 3)}
lit = sum(1 for i in range(0, len(pixels), 3) if pixels[i:i + 3] != b'\0\0\0')
print(f'{sys.argv[1]}: {len(colours)} colours, {lit} lit pixels')
assert len(colours) > 100 and lit > 500, 'the picture shows (almost) nothing'
PY
}

"$example" "$work/ring.ppm" >"$work/ring.log"
cat "$work/ring.log"
grep -q '^mean colour: ' "$work/ring.log" || { echo "FAILED: no mean colour printed"; exit 1; }
check_picture "$work/ring.ppm"

if [ $# -ge 3 ]; then
  "$example" "$work/scene.ppm" "$3" >"$work/scene.log"
  cat "$work/scene.log"
  check_picture "$work/scene.ppm"
fi

missing=$work/no_such_scene.ply
if "$example" "$work/missing.ppm" "$missing" >"$work/missing.log" 2>&1; then
  echo "FAILED: a missing scene exited 0"; exit 1
fi
cat "$work/missing.log"
grep -qF "$missing" "$work/missing.log" || { echo "FAILED: the message does not name $missing"; exit 1; }
[ ! -e "$work/missing.ppm" ] || { echo "FAILED: a picture was written for a missing scene"; exit 1; }
echo "c_api example: renders, and names a missing scene"
