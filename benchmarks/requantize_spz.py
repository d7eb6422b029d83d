#!/usr/bin/env python3
"""Rewrites an SPZ (version 2 or 3, gzip) with its higher SH bytes rounded to fewer bits, as
Niantic's encoder does with sh1Bits / shRestBits: what the README's `--sh-bits` table measured on
bonsai's SPZ (then rendered with `vksplat render --images`). Standard library only.

    requantize_spz.py in.spz out.spz DEGREE1_BITS HIGHER_BITS
"""
import gzip
import struct
import sys


def bucket_table(bits):
    bucket = 1 << (8 - bits)
    return bytes(min(max((b + bucket // 2) // bucket * bucket, 0), 255) for b in range(256))


def main():
    src, dst, degree1_bits, higher_bits = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
    data = bytearray(gzip.open(src).read())
    _, version, n, degree, _, _, _ = struct.unpack('<IIIBBBB', data[:16])
    if version not in (2, 3):
        sys.exit(f'{src}: SPZ version {version}; this reads 2 and 3')
    per = {0: 0, 1: 9, 2: 24, 3: 45}[degree]
    sh = 16 + 9 * n + n + 3 * n + 3 * n + (4 if version == 3 else 3) * n  # positions .. rotations
    first, rest = bucket_table(degree1_bits), bucket_table(higher_bits)
    for i in range(n):
        at = sh + per * i
        data[at:at + min(per, 9)] = data[at:at + min(per, 9)].translate(first)
        if per > 9:
            data[at + 9:at + per] = data[at + 9:at + per].translate(rest)
    with gzip.open(dst, 'wb', compresslevel=9) as out:
        out.write(bytes(data))


if __name__ == '__main__':
    main()
