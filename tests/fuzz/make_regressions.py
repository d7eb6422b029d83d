#!/usr/bin/env python3
"""Writes the hostile inputs in tests/fuzz/regressions/<target>/: files built to reach the checks
that keep each reader from crashing, hanging or allocating far beyond the file's size. Each is
named for what it attacks; the comment beside it says which check stops it (or stopped a bug).

usage: make_regressions.py [OUT_DIR]   (default: the regressions folder beside this script)

The committed files are the test's input; this script says how they were made. Inputs found by
libFuzzer (tools/fuzz.sh) are copied into the folder as they are, not generated here.
"""
import gzip
import math
import os
import struct
import sys
import zipfile
from io import BytesIO

from make_seeds import Pickle, SPLIT, colmap_binary, inria_cameras, inria_ply, nerf_transforms, npy, splat

HERE = os.path.dirname(os.path.abspath(__file__))


def write(out, target, name, data):
    folder = os.path.join(out, target)
    os.makedirs(folder, exist_ok=True)
    data = data if isinstance(data, bytes) else data.encode()
    assert len(data) < 64 * 1024, f"{target}/{name} is {len(data)} bytes"
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data)


def with_vertex_count(ply, count):
    return ply.replace(b"element vertex 1\n", f"element vertex {count}\n".encode(), 1)


def ply_inputs(out):
    one = inria_ply(1, 0)
    # 1.2e14 vertices in a 300-byte file: the count is checked against the file before the cloud is allocated.
    write(out, "ply", "vertex_count_beyond_file.ply", with_vertex_count(one, 123456789012345))
    # The same in ASCII, where the bound is the body's length.
    write(out, "ply", "ascii_vertex_count_beyond_body.ply", with_vertex_count(inria_ply(1, 0, "ascii"), 10 ** 12))
    # An element before the vertices whose count times its 4-byte stride wraps past 2^64 to 0.
    header_end = one.index(b"element vertex")
    overflow = one[:header_end] + b"element face 4611686018427387904\nproperty float a\n" + one[header_end:]
    write(out, "ply", "element_size_overflows_64_bits.ply", overflow)
    # A list of 2^32 - 1 floats in a 300-byte file, and a list of length -1 (a double cast to an
    # unsigned count would be undefined behaviour).
    for name, count_type, length in (("list_length_beyond_file.ply", "uint", struct.pack("<I", 0xffffffff)),
                                     ("list_length_negative.ply", "int", struct.pack("<i", -1))):
        header = one[:header_end] + f"element face 1\nproperty list {count_type} float i\n".encode()
        body_start = one.index(b"end_header\n") + len(b"end_header\n")
        write(out, "ply", name, header + one[header_end:body_start] + length + one[body_start:])


def compressed_ply(vertices, chunks, sh_rows=None, vertex_count=None):
    """A PlayCanvas compressed PLY with `vertices` packed rows, `chunks` chunk rows and, when
    sh_rows is given, an sh element of that many rows of 9 bytes (SH degree 1); counts as declared
    may differ (vertex_count)."""
    chunk_fields = ["min_x", "min_y", "min_z", "max_x", "max_y", "max_z", "min_scale_x", "min_scale_y",
                    "min_scale_z", "max_scale_x", "max_scale_y", "max_scale_z"]
    header = "ply\nformat binary_little_endian 1.0\n"
    header += f"element chunk {chunks}\n" + "".join(f"property float {f}\n" for f in chunk_fields)
    header += f"element vertex {vertices if vertex_count is None else vertex_count}\n"
    header += "".join(f"property uint {f}\n" for f in ("packed_position", "packed_rotation", "packed_scale",
                                                       "packed_color"))
    if sh_rows is not None:
        header += f"element sh {sh_rows}\n" + "".join(f"property uchar f_rest_{i}\n" for i in range(9))
    body = struct.pack("<12f", -1, -1, -1, 1, 1, 1, -3, -3, -3, -1, -1, -1) * chunks
    body += struct.pack("<4I", 0x80080200, 0x40100401, 0x80080200, 0xff8040c0) * vertices
    body += bytes(range(9)) * (sh_rows or 0)
    return (header + "end_header\n").encode() + body


def compressed_ply_inputs(out):
    # 300 vertices need two chunks of 256; with one, the second chunk's row would be read past the table.
    write(out, "compressed_ply", "fewer_chunks_than_vertices.ply", compressed_ply(300, 1))
    # An sh element shorter than the vertex element: rows past its end would be read.
    write(out, "compressed_ply", "sh_rows_fewer_than_vertices.ply", compressed_ply(3, 1, sh_rows=1))
    # 2^62 vertices of 16 bytes: the element's size overflows 64 bits.
    write(out, "compressed_ply", "vertex_size_overflows_64_bits.ply",
          compressed_ply(1, 1, vertex_count=4611686018427387904))
    # A billion chunk rows (72 GB) declared in a small file: checked before the table is allocated.
    write(out, "compressed_ply", "chunk_rows_beyond_file.ply",
          compressed_ply(1, 1).replace(b"element chunk 1\n", b"element chunk 1000000000\n"))


def splat_inputs(out):
    # A record cut short: the size is not a multiple of 32.
    write(out, "splat", "partial_record.splat", splat(2)[:45])
    # An all-zero quaternion (128, 128, 128, 128: normalising would divide by zero) and a scale of -1
    # (whose log is NaN): read, with a note and a value sanitize() drops.
    record = struct.pack("<3f3f", 0, 0, 0, -1.0, 0.0, 1e-45) + bytes([10, 20, 30, 0, 128, 128, 128, 128])
    write(out, "splat", "zero_quaternion_negative_scale.splat", record)


def spz_raw(count, sh_degree=0, fractional_bits=12, version=3, body=None):
    header = struct.pack("<IIIBBBB", 0x5053474e, version, count, sh_degree, fractional_bits, 0, 0)
    rotation = 4 if version >= 3 else 3
    return header + (body if body is not None else bytes((9 + 1 + 3 + 3 + rotation) * count))


def spz_inputs(out):
    # 2^32 - 1 splats declared in 40 bytes of gzip: checked against the data before the cloud is allocated.
    write(out, "spz", "count_4294967295_gzip.spz", gzip.compress(spz_raw(0xffffffff, body=bytes(20)), mtime=0))
    # The same without gzip (an uncompressed stream is accepted).
    write(out, "spz", "count_4294967295_uncompressed.spz", spz_raw(0xffffffff, body=bytes(20)))
    # SH degree 255 would index past every per-degree table.
    write(out, "spz", "sh_degree_255.spz", gzip.compress(spz_raw(1, sh_degree=255), mtime=0))
    # 255 fractional bits for 24-bit positions.
    write(out, "spz", "fractional_bits_255.spz", gzip.compress(spz_raw(1, fractional_bits=255), mtime=0))
    # The gzip stream stops halfway.
    whole = gzip.compress(spz_raw(50, version=2), mtime=0)
    write(out, "spz", "gzip_stream_cut_short.spz", whole[:len(whole) // 2])
    # One splat, then 40 MB of zeros in 40 KB: only what the header asks for (and one byte) is inflated.
    write(out, "spz", "one_splat_then_40mb_of_zeros.spz",
          gzip.compress(spz_raw(1) + bytes(40 * 1024 * 1024), compresslevel=9, mtime=0))


def npy_inputs(out):
    valid = npy("<f4", [2], "<2f", [1, 2])
    # Format version 2 with a header length of 4 GiB - 1 in a 70-byte file.
    write(out, "npy", "header_length_4gib.npy", b"\x93NUMPY\x02\x00" + struct.pack("<I", 0xffffffff) + valid[10:])
    # Extents whose product overflows 64 bits, one that does not fit in 64 bits, and 4 TB of
    # float32 declared over 8 bytes of data.
    for name, shape in (("shape_product_overflows.npy", [1 << 62, 8]),
                        ("extent_beyond_64_bits.npy", [10 ** 23]),
                        ("shape_beyond_data.npy", [10 ** 12])):
        write(out, "npy", name, npy("<f4", shape, "<2f", [1, 2]))
    # A descr string that never closes, and a shape that never closes.
    write(out, "npy", "descr_unterminated.npy", valid.replace(b"'<f4'", b"'<f4 "))
    write(out, "npy", "shape_unterminated.npy", valid.replace(b"(2,)", b"(2, "))


def json_inputs(out):
    for target, valid in (("cameras_json", inria_cameras()), ("transforms_json", nerf_transforms())):
        # A number beyond the double range: nlohmann throws out_of_range, not parse_error (a bug,
        # fixed in src/io/json_fields.cpp).
        write(out, target, "number_overflow_1e999.json", valid.replace("50", "1e999", 1).replace("0.69", "1e999"))
        # 20000 nested arrays: the parser and the value's destructor must not recurse on the stack.
        write(out, target, "nested_20000_deep.json", "[" * 20000 + "]" * 20000)
        # Sizes beyond int (casting 1e300 to int is undefined behaviour).
        write(out, target, "size_beyond_int.json", valid.replace('"width": 64', '"width": 1e300')
              .replace('"w": 64', '"w": 1e300'))
    # A NeRF frame without w/h whose image does not exist.
    write(out, "transforms_json", "no_size_and_no_image.json", nerf_transforms().replace('"w": 64, "h": 48, ', ""))


def colmap_inputs(out):
    cameras, images = colmap_binary().split(SPLIT)
    # 2^63 cameras in a file of two: read one by one until the file ends, never reserved.
    write(out, "colmap_binary", "camera_count_2_63.bin", struct.pack("<Q", 1 << 63) + cameras[8:] + SPLIT + images)
    # Model id -5 would index before the table of parameter counts.
    bad_model = cameras[:12] + struct.pack("<i", -5) + cameras[16:]
    write(out, "colmap_binary", "negative_model_id.bin", bad_model + SPLIT + images)
    # A width of 2^40, which int cannot hold.
    wide = cameras[:16] + struct.pack("<Q", 1 << 40) + cameras[24:]
    write(out, "colmap_binary", "width_2_40.bin", wide + SPLIT + images)
    # The first image's 2D point count is 2^62: times 24 bytes it overflows 64 bits.
    count_at = 8 + struct.calcsize("<i4d3di") + len(b"a.png\0")
    points = images[:count_at] + struct.pack("<Q", 1 << 62) + images[count_at + 8:]
    write(out, "colmap_binary", "points2d_size_overflows_64_bits.bin", cameras + SPLIT + points)
    # An image name that runs to the end of the file without its NUL.
    write(out, "colmap_binary", "name_without_nul.bin", cameras + SPLIT + images[:count_at - 3])

    images_txt = "1 1 0 0 0 0.5 -0.2 3 1 a.png\n\n"
    for name, camera_line in (("negative_width.txt", "1 PINHOLE -1 48 50 52 32 24"),  # wraps to 2^64 - 1
                              ("pinhole_with_two_params.txt", "1 PINHOLE 64 48 50 52"),  # params[3] would be read
                              ("param_not_a_number.txt", "1 PINHOLE 64 48 50 nan? 32 24")):
        write(out, "colmap_text", name, (camera_line + "\n").encode() + SPLIT + images_txt.encode())
    write(out, "colmap_text", "image_without_name.txt",
          b"1 PINHOLE 64 48 50 52 32 24\n" + SPLIT + b"1 1 0 0 0 0.5 -0.2 3 1\n\n")


def long1(value):
    """Pickle LONG1: an integer of any size up to 8 bytes, little-endian two's complement."""
    data = value.to_bytes(8, "little", signed=True).rstrip(b"\0") or b"\0"
    if data[-1] & 0x80:
        data += b"\0"
    return b"\x8a" + bytes([len(data)]) + data


def checkpoint(pickle_bytes, storages=(), method=zipfile.ZIP_STORED):
    buffer = BytesIO()
    with zipfile.ZipFile(buffer, "w", method) as archive:
        entries = [("ckpt/data.pkl", pickle_bytes)] + [(f"ckpt/data/{i}", s) for i, s in enumerate(storages)]
        for name, data in entries:
            # A fixed time stamp, so that the files come out the same every time.
            archive.writestr(zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0)), data, compress_type=method)
    return buffer.getvalue()


def splats_checkpoint(n, numel, storages, zero_strides=False):
    """A checkpoint whose five required tensors (N = n) are views of one FloatStorage of `numel`
    elements (one entry: the storage is memoised once and shared), contiguous or with all strides 0."""
    p = Pickle()
    p.op(b"}(").text("splats").op(b"}(")
    for index, (name, shape) in enumerate((("means", [3]), ("quats", [4]), ("scales", [3]), ("opacities", []),
                                           ("sh0", [1, 3]))):
        sizes = [n] + shape
        strides = [0 if zero_strides else math.prod(sizes[d + 1:]) for d in range(len(sizes))]
        p.text(name).glob("torch._utils", "_rebuild_tensor_v2").op(b"(")
        if index == 0:
            p.op(b"(").text("storage").glob("torch", "FloatStorage").text("0").text("cpu").op(long1(numel))
            p.op(b"tQq\x00")
        else:
            p.op(b"h\x00")
        p.integer(0).op(b"(" + b"".join(long1(s) for s in sizes) + b"t")
        p.op(b"(" + b"".join(long1(s) for s in strides) + b"t").op(b"\x89").ordered_dict().op(b"tR")
    p.op(b"uu.")
    return checkpoint(p.b, storages)


def gsplat_inputs(out):
    # LONG_BINPUT to memo slot 2^28 in a 20-byte pickle: the memo was a vector grown to the index,
    # 4 GiB of empty slots (a bug, fixed in src/io/gsplat_checkpoint.cpp).
    write(out, "gsplat_pt", "memo_index_2_28.pt", checkpoint(b"\x80\x02}r" + struct.pack("<I", 1 << 28) + b"."))
    # Tensors of 2^40 Gaussians that repeat 4 floats through zero strides: the cloud and the gathered
    # values were allocated for 2^40 Gaussians (a bug, fixed in src/io/gsplat_checkpoint.cpp).
    write(out, "gsplat_pt", "zero_strides_2_40_gaussians.pt",
          splats_checkpoint(1 << 40, 4, [struct.pack("<4f", 1, 0, 0, 0)], zero_strides=True))

    valid = checkpoint(Pickle().op(b"}.").b, [bytes(16)])
    eocd = valid.rindex(b"PK\x05\x06")
    # The end record claims 65535 entries in a directory of two.
    write(out, "gsplat_pt", "directory_claims_65535_entries.pt",
          valid[:eocd + 8] + struct.pack("<HH", 0xffff, 0xffff) + valid[eocd + 12:])
    # The directory lies beyond the end of the file.
    write(out, "gsplat_pt", "directory_beyond_file.pt", valid[:eocd + 16] + struct.pack("<I", 0x7fffffff) +
          valid[eocd + 20:])
    # A zip64 locator whose record lies beyond the file (the 0xffffffff offset asks for zip64).
    locator = b"PK\x06\x07" + struct.pack("<IQI", 0, 1 << 60, 1)
    write(out, "gsplat_pt", "zip64_record_beyond_file.pt",
          valid[:eocd] + locator + valid[eocd:eocd + 16] + struct.pack("<I", 0xffffffff) + valid[eocd + 20:])
    # The pickle's entry claims a 4 GiB deflated size: inflated as it comes, it ends after 5 bytes.
    deflated = checkpoint(Pickle().op(b"}.").b, method=zipfile.ZIP_DEFLATED)
    directory = deflated.rindex(b"PK\x01\x02")
    write(out, "gsplat_pt", "deflated_size_claims_4gib.pt",
          deflated[:directory + 24] + struct.pack("<I", 0xfffffffe) + deflated[directory + 28:])
    # A storage of 2^40 floats whose entry holds 16 bytes.
    write(out, "gsplat_pt", "storage_numel_beyond_entry.pt", splats_checkpoint(1, 1 << 40, [bytes(16)]))
    # LONG1 of 255 bytes, and a BINUNICODE8 whose length runs past the pickle.
    write(out, "gsplat_pt", "long1_of_255_bytes.pt", checkpoint(b"\x80\x02\x8a\xff" + bytes(255) + b"."))
    write(out, "gsplat_pt", "unicode8_length_beyond_pickle.pt",
          checkpoint(b"\x80\x02\x8d" + struct.pack("<Q", 1 << 62) + b"abc."))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "regressions")
    ply_inputs(out)
    compressed_ply_inputs(out)
    splat_inputs(out)
    spz_inputs(out)
    npy_inputs(out)
    json_inputs(out)
    colmap_inputs(out)
    gsplat_inputs(out)


if __name__ == "__main__":
    main()
