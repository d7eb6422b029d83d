#!/usr/bin/env python3
"""Writes the Gaussians of a binary little-endian INRIA PLY that a keep mask selects, for GPU hosts
where the vksplat CLI (it links OpenCV) cannot run: `vksplat prune` chooses on this machine, the
mask travels (a few hundred KB instead of a PLY per model), and vksplat_bench times the models there.
The mask is a .npy of N uint8 (non-zero: keep), N the PLY's vertex count; rows keep their order,
as GaussianCloud::subset keeps them.
usage: subset_ply.py IN.ply MASK.npy OUT.ply"""
import sys

import numpy as np


def main(src, mask_path, out):
    with open(src, "rb") as f:
        header = b""
        while not header.endswith(b"end_header\n"):
            line = f.readline()
            if not line:
                sys.exit(f"{src}: no end_header")
            header += line
        lines = header.decode("ascii").splitlines()
        if "format binary_little_endian 1.0" not in lines:
            sys.exit(f"{src}: only binary little-endian PLY files")
        count = next(int(l.split()[2]) for l in lines if l.startswith("element vertex"))
        if any(l.startswith("property") and l.split()[1] != "float" for l in lines):
            sys.exit(f"{src}: only float properties")
        fields = sum(1 for l in lines if l.startswith("property"))
        rows = np.fromfile(f, dtype="<f4", count=count * fields)
    if rows.size != count * fields:
        sys.exit(f"{src}: truncated ({rows.size} of {count * fields} floats)")
    keep = np.load(mask_path).astype(bool)
    if keep.shape != (count,):
        sys.exit(f"{mask_path}: shape {keep.shape}, the PLY has {count} Gaussians")
    kept = rows.reshape(count, fields)[keep]
    new_header = header.replace(f"element vertex {count}\n".encode(), f"element vertex {len(kept)}\n".encode())
    with open(out, "xb") as f:  # never overwrites
        f.write(new_header)
        kept.astype("<f4").tofile(f)
    print(f"{out}: {len(kept)} of {count} Gaussians")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
