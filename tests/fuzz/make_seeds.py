#!/usr/bin/env python3
"""Writes the fuzz seed corpora: one small, valid file per reader (a few per format where the
format has variants), so that libFuzzer starts from inputs that reach deep into each reader.

usage: make_seeds.py OUT_DIR [FORMATS_DIR]

Everything is generated here with the Python standard library, except the compressed PLY and
the SPZ seeds, which are cut down (a few splats kept, counts rewritten) from the fixtures in
FORMATS_DIR (../shared/data/formats) so that they carry real quantised data. Without that folder
they are skipped. The COLMAP targets read two files from one input: cameras, then the marker
below, then images (tests/fuzz/fuzz_targets.hpp splits them the same way).
"""
import gzip
import json
import math
import os
import struct
import sys
import zipfile
import zlib

SPLIT = b"\n#VKSPLAT-FUZZ-SPLIT#\n"


def write(out, target, name, data):
    folder = os.path.join(out, target)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def inria_ply(count, rest, fmt="binary_little_endian"):
    names = ["x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"]
    names += [f"f_rest_{i}" for i in range(rest)] + ["opacity", "scale_0", "scale_1", "scale_2"]
    names += ["rot_0", "rot_1", "rot_2", "rot_3"]
    header = f"ply\nformat {fmt} 1.0\nelement vertex {count}\n"
    header += "".join(f"property float {n}\n" for n in names) + "end_header\n"
    rows = [[0.1 * (i + 1) * (j % 5 - 2) for j in range(len(names))] for i in range(count)]
    for row in rows:
        row[-4:] = [1.0, 0.0, 0.0, 0.0]
    if fmt == "ascii":
        return (header + "".join(" ".join(f"{v:g}" for v in r) + "\n" for r in rows)).encode()
    endian = "<" if fmt == "binary_little_endian" else ">"
    return header.encode() + b"".join(struct.pack(endian + "f" * len(r), *r) for r in rows)


def colmap_text():
    cameras = ("# Camera list\n1 PINHOLE 64 48 50 52 32 24\n2 SIMPLE_RADIAL 32 32 30 16 16 0.01\n")
    images = ("# Image list\n"
              "1 1 0 0 0 0.5 -0.2 3 1 a.png\n0.0 0.0 -1\n"
              "2 0.7071068 0.7071068 0 0 0 0 4 2 b.png\n\n")
    return cameras.encode() + SPLIT + images.encode()


def colmap_binary():
    cameras = struct.pack("<Q", 2)
    cameras += struct.pack("<iiQQ", 1, 1, 64, 48) + struct.pack("<4d", 50, 52, 32, 24)
    cameras += struct.pack("<iiQQ", 2, 0, 32, 32) + struct.pack("<3d", 30, 16, 16)
    images = struct.pack("<Q", 2)
    for image_id, q, t, cam, name, points in ((1, (1, 0, 0, 0), (0, 0.5, 3), 1, b"a.png", 1),
                                              (2, (0.7071068, 0.7071068, 0, 0), (0, 0, 4), 2, b"b.png", 0)):
        images += struct.pack("<i4d3di", image_id, *q, *t, cam) + name + b"\0"
        images += struct.pack("<Q", points) + struct.pack("<ddq", 1.0, 2.0, -1) * points
    return cameras + SPLIT + images


def inria_cameras():
    return json.dumps([
        {"id": 0, "img_name": "a", "width": 64, "height": 48, "position": [0, 0, -3],
         "rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "fx": 50, "fy": 50},
        {"id": 1, "img_name": "b", "width": 32, "height": 32, "position": [1, 0, -3],
         "rotation": [[0, -1, 0], [1, 0, 0], [0, 0, 1]], "fx": 30, "fy": 31, "cx": 15, "cy": 16},
    ])


def nerf_transforms():
    frame = lambda name, z: {"file_path": name, "transform_matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, z],
                                                                   [0, 0, 0, 1]]}
    return json.dumps({"camera_angle_x": 0.69, "w": 64, "h": 48, "cx": 31, "cy": 24,
                       "frames": [frame("./train/r_0", 4), frame("./train/r_1", 3)]})


def npy(descr, shape, values_format, values):
    header = "{'descr': '%s', 'fortran_order': False, 'shape': %s, }" % (descr, repr(tuple(shape)))
    header += " " * ((64 - (10 + len(header) + 1) % 64) % 64) + "\n"
    return b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header.encode() + struct.pack(values_format, *values)


def splat(count):
    out = b""
    for i in range(count):
        out += struct.pack("<3f3f", i * 0.5, -i, 2.0, 0.1, 0.2, 0.3)
        out += bytes([200, 100, 50, 255 if i == 0 else 128, 200, 128, 100, 128])
    return out


def spz_from(fixture, count):
    raw = gzip.decompress(open(fixture, "rb").read())
    magic, version, total, sh_degree, fractional_bits, flags, _ = struct.unpack("<IIIBBBB", raw[:16])
    sh_per_splat = {0: 0, 1: 9, 2: 24, 3: 45}[sh_degree] * 1
    rotation_bytes = 4 if version >= 3 else 3
    sizes = [9, 1, 3, 3, rotation_bytes, sh_per_splat]
    body, offset = b"", 16
    for size in sizes:
        body += raw[offset:offset + count * size]
        offset += total * size
    header = struct.pack("<IIIBBBB", magic, version, count, sh_degree, fractional_bits, flags, 0)
    return gzip.compress(header + body, mtime=0)


def compressed_ply_from(fixture, vertices):
    data = open(fixture, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    lines = data[:end].decode().splitlines()
    sizes = {"float": 4, "uint": 4, "uchar": 1}
    elements = []  # [name, count, stride]
    for line in lines:
        parts = line.split()
        if parts[0] == "element":
            elements.append([parts[1], int(parts[2]), 0])
        elif parts[0] == "property":
            elements[-1][2] += sizes[parts[1]]
    keep = {"chunk": 1, "vertex": vertices, "sh": vertices}
    header, body, offset = [], b"", end
    for line in lines:
        parts = line.split()
        if parts[0] == "element":
            line = f"element {parts[1]} {keep[parts[1]]}"
        header.append(line)
    for name, count, stride in elements:
        body += data[offset:offset + keep[name] * stride]
        offset += count * stride
    return ("\n".join(header) + "\n").encode() + body


class Pickle:
    """The protocol-2 opcodes torch.save writes."""

    def __init__(self):
        self.b = b"\x80\x02"

    def op(self, c):
        self.b += c
        return self

    def text(self, s):
        return self.op(b"X" + struct.pack("<I", len(s)) + s.encode())

    def integer(self, v):
        return self.op(b"K" + bytes([v]) if v < 256 else b"J" + struct.pack("<i", v))

    def glob(self, module, name):
        return self.op(b"c" + f"{module}\n{name}\n".encode())

    def ints(self, values):
        self.op(b"(")
        for v in values:
            self.integer(v)
        return self.op(b"t")

    def ordered_dict(self):
        return self.glob("collections", "OrderedDict").op(b")R")

    def tensor(self, storage, key, numel, sizes, strides, memo):
        self.glob("torch._utils", "_rebuild_tensor_v2").op(b"(")
        self.op(b"(").text("storage").glob("torch", storage).text(key).text("cpu").integer(numel).op(b"t")
        self.op(b"Q" + b"q" + bytes([memo]))
        self.integer(0).ints(sizes).ints(strides).op(b"\x89").ordered_dict().op(b"tR")
        return self


def gsplat_checkpoint(n, k, deflate):
    tensors = [("means", [n, 3]), ("quats", [n, 4]), ("scales", [n, 3]), ("opacities", [n]),
               ("sh0", [n, 1, 3])] + ([("shN", [n, k, 3])] if k else [])
    p = Pickle()
    p.op(b"}q\x00(").text("step").integer(7).text("splats").ordered_dict().op(b"q\x01(")
    storages = []
    for index, (name, sizes) in enumerate(tensors):
        numel = math.prod(sizes)
        strides = [math.prod(sizes[i + 1:]) for i in range(len(sizes))]
        p.text(name).tensor("FloatStorage", str(index), numel, sizes, strides, index + 2)
        values = [1.0, 0.0, 0.0, 0.0] * n if name == "quats" else [0.01 * (i % 17 - 8) for i in range(numel)]
        storages.append(struct.pack(f"<{numel}f", *values))
    p.op(b"u").op(b"u").op(b".")
    out = zipfile.BytesIO() if hasattr(zipfile, "BytesIO") else __import__("io").BytesIO()
    method = zipfile.ZIP_DEFLATED if deflate else zipfile.ZIP_STORED
    with zipfile.ZipFile(out, "w", method) as archive:
        archive.writestr("ckpt/data.pkl", p.b)
        for index, storage in enumerate(storages):
            archive.writestr(f"ckpt/data/{index}", storage)
        archive.writestr("ckpt/version", "3\n")
        archive.writestr("ckpt/byteorder", "little")
    return out.getvalue()


def main():
    out = sys.argv[1]
    formats = sys.argv[2] if len(sys.argv) > 2 else None
    write(out, "ply", "binary_sh1.ply", inria_ply(3, 9))
    write(out, "ply", "ascii_sh0.ply", inria_ply(2, 0, "ascii"))
    write(out, "ply", "big_endian_sh0.ply", inria_ply(2, 0, "binary_big_endian"))
    write(out, "cameras_json", "two.json", inria_cameras())
    write(out, "transforms_json", "two.json", nerf_transforms())
    write(out, "colmap_text", "model.txt", colmap_text())
    write(out, "colmap_binary", "model.bin", colmap_binary())
    write(out, "npy", "f32_2x3.npy", npy("<f4", [2, 3], "<6f", [1, 2, 3, 4, 5, 6]))
    write(out, "npy", "i32_4.npy", npy("<i4", [4], "<4i", [1, -2, 3, -4]))
    write(out, "npy", "u8_scalar.npy", npy("|u1", [], "<B", [7]))
    write(out, "splat", "three.splat", splat(3))
    write(out, "gsplat_pt", "stored_sh1.pt", gsplat_checkpoint(3, 3, False))
    write(out, "gsplat_pt", "deflated_sh0.pt", gsplat_checkpoint(2, 0, True))
    if formats and os.path.isdir(formats):
        write(out, "spz", "snowmiku_3.spz", spz_from(os.path.join(formats, "snowmiku.spz"), 3))
        write(out, "compressed_ply", "snowmiku_3.ply",
              compressed_ply_from(os.path.join(formats, "snowmiku.compressed.ply"), 3))


if __name__ == "__main__":
    main()
