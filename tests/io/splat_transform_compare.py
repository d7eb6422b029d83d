#!/usr/bin/env python3
"""The scene and the comparison for tests/io/splat_transform_test.sh, which checks our .splat, .spz,
compressed .ply and .sog writers (and our .spz and .sog readers) against an independent
implementation, PlayCanvas splat-transform.

  splat_transform_compare.py scene OUT.ply [--sh-vectors K]
      writes a float INRIA PLY of 300 Gaussians, SH degree 3, whose values lie where every format
      can hold them (see the ranges below), with unnormalised quaternions of both signs. With
      --sh-vectors, the Gaussians' higher SH are drawn from K vectors only, so that a SOG writer's
      palette (k-means) can hold each exactly, and what is compared is its codebook's rounding.
  splat_transform_compare.py compare CASE ORIGINAL.ply DECODED.ply
      compares what a decoder made of an encoded ORIGINAL, attribute by attribute, Gaussian by
      Gaussian, against CASE's tolerances; prints the largest error of each attribute; exits 1 if
      any exceeds its tolerance. Gaussians are paired in file order, except for the compressed PLY
      and SOG, whose writers reorder them (Morton order): there each decoded Gaussian is paired
      with the original nearest to it, and every original must be paired once.

Plain float PLY is exact both ways, so each comparison measures one encoder and one decoder.
Standard library only.
"""
import math
import random
import struct
import sys

SH_C0 = 0.28209479177387814
SH_REST = 45  # SH degree 3: 15 coefficients x 3 colours

# Per case, the largest error each attribute may have, and why. Colours are compared as f_dc,
# opacities after the sigmoid (the formats store opacity, not its logit), rotations as unit
# quaternions with the sign that makes w (or the first non-zero component) positive.
TOLERANCES = {
    # Ours -> .splat -> splat-transform. 32 bytes a splat: float32 position and linear scale
    # (exact, bar the float rounding of exp then log), colour and opacity as bytes (half a step of
    # 1/255: f_dc 0.5/255/SH_C0 = 0.00696, opacity 0.5/255 = 0.00196), quaternion bytes written as
    # q*128+128 as antimatter15's viewer reads them (half a step: 0.0039) but read back by
    # splat-transform as b/127.5-1, which is up to 0.0078 above b/128-1: 0.0117 a component
    # before normalising, which leaves it about the same. No SH beyond DC.
    "splat": {"position": 1e-6, "log_scale": 2e-6, "f_dc": 0.0070, "opacity": 0.0020, "rotation": 0.0120},
    # Ours -> .spz (version 3 by default, 4 by --format spz-v4: the same values) -> splat-transform
    # (Niantic's own decoder, compiled to WebAssembly).
    # Positions 24-bit fixed point with 12 fractional bits (0.5/4096 = 1.22e-4); log scales as
    # (s+10)*16 in a byte (0.5/16 = 0.03125); colour as f_dc*0.15*255+127.5 in a byte
    # (0.5/(0.15*255) = 0.01307); opacity a byte (0.00196); rotations "smallest three", 9 bits
    # of magnitude each in units of sqrt(1/2)/511 (0.00069), the largest rebuilt as sqrt(1 - the
    # others' squares), which errs by at most (sum of the others / largest) * 0.00069 <= 3 * 0.00069
    # (the largest is at least 1/2); SH as v*128+128 in a byte (0.5/128 = 0.0039).
    "spz": {"position": 1.23e-4, "log_scale": 0.0313, "f_dc": 0.0131, "opacity": 0.0020, "rotation": 0.0021,
            "sh_degree_1": 0.0040, "sh_degree_2_3": 0.0040},
    # splat-transform -> .spz (version 4, its default, or 3) -> our reader. As above, except that splat-transform
    # quantises SH more coarsely (Niantic's defaults): degree 1 to 5 bits (buckets of 8 byte
    # steps: 0.5/128 + 4/128 = 0.0352), degrees 2 and 3 to 4 bits (buckets of 16: 0.5/128 +
    # 8/128 = 0.06641).
    "spz_theirs": {"position": 1.23e-4, "log_scale": 0.0313, "f_dc": 0.0131, "opacity": 0.0020, "rotation": 0.0021,
                   "sh_degree_1": 0.0352, "sh_degree_2_3": 0.0665},
    # Ours -> .compressed.ply -> splat-transform. Each value relative to its chunk of 256's range, the
    # ranges within the scene's: positions (span 16) 11 bits for x and z, 10 for y (16/1023/2 =
    # 0.00782); log scales (span 7) 7/1023/2 = 0.00342; colour 0.5 + SH_C0 * f_dc (span 0.96) in
    # 8 bits: 0.96/255/2/SH_C0 = 0.00667; opacity after the sigmoid 0.5/255 = 0.00196; rotations
    # smallest three in 10 bits, sqrt(2)/1023/2 = 0.00069 each, the largest within 3x that (0.0021);
    # SH a byte over [-4, 4]: half of 8/256 = 0.0157.
    "compressed_ply": {"position": 0.0079, "log_scale": 0.0035, "f_dc": 0.0067, "opacity": 0.0020, "rotation": 0.0021,
                       "sh_degree_1": 0.0157, "sh_degree_2_3": 0.0157},
    # Ours -> .sog -> splat-transform. Positions log-encoded, v = sign(x) ln(|x| + 1), in 16 bits over
    # each axis's range (2 ln 9 = 4.39 for +-8): half a step, 4.39/65535/2 = 3.35e-5 in v, is
    # (|x| + 1) times that in x: 9 * 3.35e-5 = 3.0e-4. Log scales and f_dc: each the nearest entry of
    # a 256-entry codebook (k-means over the scene's 900 values of each), so within half the widest
    # gap between entries, which k-means leaves where values are sparse: measured 0.0263 and 0.0111
    # (entries spread evenly would give 7/255/2 = 0.0137 and 3.4/255/2 = 0.0067). Opacity after the
    # sigmoid a byte (0.00196). Rotations "smallest three" times sqrt(2) in 8 bits: half a step is
    # 2/255/sqrt(2)/2 = 0.0028 for each smaller one, the largest within 3x that (0.0084). Higher SH:
    # 300 Gaussians fit the palette (4096 entries) one entry each, so what is left is the codebook of
    # 256 over the 13,500 values in [-0.95, 0.95]: measured 0.0051 (evenly: 1.9/255/2 = 0.0037).
    "sog": {"position": 3.1e-4, "log_scale": 0.0270, "f_dc": 0.0120, "opacity": 0.0020, "rotation": 0.0084,
            "sh_degree_1": 0.0055, "sh_degree_2_3": 0.0055},
    # splat-transform -> .sog -> ours, the scene's higher SH drawn from 16 vectors (--sh-vectors 16),
    # which its palette of 256 (k-means from random seeds) holds one each. It truncates where we
    # round: a whole step of position (6.0e-4; measured 5.8e-4), opacity (1/255 = 0.0039) and
    # rotation (0.0056, the largest within 3x: 0.0167). Its codebooks (quantize1d, a dynamic
    # programme over a histogram) measured: log scales 0.0134, f_dc 0.0064, SH 0.0030 to 0.0043
    # over runs (its seeds are random, and so its palette's values).
    "sog_theirs": {"position": 6.1e-4, "log_scale": 0.0140, "f_dc": 0.0070, "opacity": 0.0040, "rotation": 0.0167,
                   "sh_degree_1": 0.0060, "sh_degree_2_3": 0.0060},
    # splat-transform -> .glb (KHR_gaussian_splatting, all floats) -> ours (gltf_validator_test.sh).
    # Positions and SH as they are; scales stored linear (exp, then our log, each rounded to
    # float: 1e-6 for log scales within +-8); opacity after the sigmoid, rounded to float (6e-8);
    # its quaternions as the PLY holds them (normalised here before comparing).
    "glb_theirs": {"position": 0.0, "log_scale": 1e-6, "f_dc": 0.0, "opacity": 1e-7, "rotation": 2e-7,
                   "sh_degree_1": 0.0, "sh_degree_2_3": 0.0},
}
# The cases whose writer reorders the Gaussians.
REORDERED = {"compressed_ply", "sog", "sog_theirs"}


def scene(path, count=300, seed=7, sh_vectors=0):
    """Values inside every format's range: positions within +-8 (12 fractional bits of SPZ's 24),
    log scales in [-6, 1] (SPZ holds [-10, 5.9]), colours 0.5 + SH_C0 * f_dc in [0.02, 0.98]
    (a .splat byte holds [0, 1]), opacity logits in [-4.5, 4.5] (away from bytes 0 and 255, which
    splat-transform and we map to different finite logits), SH in [-0.95, 0.95] (SPZ holds [-1, 1)),
    from `sh_vectors` vectors when that is not 0."""
    rng = random.Random(seed)
    palette = [[rng.uniform(-0.95, 0.95) for _ in range(SH_REST)] for _ in range(sh_vectors)]
    names = ["x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"]
    names += [f"f_rest_{i}" for i in range(SH_REST)]
    names += ["opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"]
    rows = []
    for _ in range(count):
        row = [rng.uniform(-8, 8) for _ in range(3)] + [0.0, 0.0, 0.0]
        row += [rng.uniform(-0.48, 0.48) / SH_C0 for _ in range(3)]
        row += rng.choice(palette) if palette else [rng.uniform(-0.95, 0.95) for _ in range(SH_REST)]
        row += [rng.uniform(-4.5, 4.5)] + [rng.uniform(-6, 1) for _ in range(3)]
        quaternion = [rng.gauss(0, 1) for _ in range(4)]
        length = rng.uniform(0.5, 2) / math.sqrt(sum(q * q for q in quaternion))
        row += [q * length for q in quaternion]
        rows.append(row)
    header = f"ply\nformat binary_little_endian 1.0\nelement vertex {count}\n"
    header += "".join(f"property float {name}\n" for name in names) + "end_header\n"
    with open(path, "wb") as out:
        out.write(header.encode())
        for row in rows:
            out.write(struct.pack(f"<{len(row)}f", *row))


def read_ply(path):
    """The vertex element of a binary little-endian PLY of float properties, as {name: [values]}."""
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    count, names = 0, []
    for line in data[:end].decode().splitlines():
        words = line.split()
        if words[:2] == ["format", "ascii"] or words[:2] == ["format", "binary_big_endian"]:
            sys.exit(f"{path}: only binary little-endian PLY is compared")
        if words[:1] == ["element"]:
            if names:
                break  # elements after the vertices are not needed
            if words[1] != "vertex":
                sys.exit(f"{path}: the vertices must come first")
            count = int(words[2])
        elif words[:1] == ["property"]:
            if words[1] != "float":
                sys.exit(f"{path}: property {words[-1]} is {words[1]}, only float is compared")
            names.append(words[2])
    values = struct.unpack_from(f"<{count * len(names)}f", data, end)
    return {name: values[i::len(names)] for i, name in enumerate(names)}, count


def unit_quaternion(q):
    length = math.sqrt(sum(v * v for v in q))
    q = [v / length for v in q]
    first = next((v for v in q if abs(v) > 1e-6), 1.0)
    return [-v for v in q] if first < 0 else q


def sigmoid(x):
    return 1 / (1 + math.exp(-x))


def nearest_original(original, decoded, count):
    """For each decoded Gaussian the index of the original nearest to it by position; exits unless
    that pairs them one to one."""
    pairs = []
    for i in range(count):
        p = [decoded[axis][i] for axis in "xyz"]
        pairs.append(min(range(count), key=lambda j: sum((original[axis][j] - p[a]) ** 2 for a, axis in enumerate("xyz"))))
    if len(set(pairs)) != count:
        sys.exit(f"the decoded Gaussians pair with only {len(set(pairs))} of the {count} originals")
    return pairs


def compare(case, original_path, decoded_path):
    limits = TOLERANCES[case]
    original, count = read_ply(original_path)
    decoded, decoded_count = read_ply(decoded_path)
    if decoded_count != count:
        sys.exit(f"{case}: {decoded_path} holds {decoded_count} Gaussians, {original_path} {count}")
    if case in REORDERED:
        pairs = nearest_original(original, decoded, count)
        reordered = {}
        for name, values in decoded.items():
            column = [0.0] * count
            for i, j in enumerate(pairs):
                column[j] = values[i]
            reordered[name] = column
        decoded = reordered
    rest = sum(1 for name in decoded if name.startswith("f_rest_"))
    expected_rest = SH_REST if "sh_degree_1" in limits else 0
    if rest != expected_rest:
        sys.exit(f"{case}: {decoded_path} has {rest} f_rest_* properties, expected {expected_rest}")

    worst = {attribute: (0.0, 0, "") for attribute in limits}  # error, Gaussian, property

    def note(attribute, error, gaussian, name):
        if not error <= worst[attribute][0]:  # NaN counts as worse
            worst[attribute] = (error, gaussian, name)

    for i in range(count):
        for a, axis in enumerate("xyz"):
            note("position", abs(decoded[axis][i] - original[axis][i]), i, axis)
            for name, attribute in ((f"scale_{a}", "log_scale"), (f"f_dc_{a}", "f_dc")):
                note(attribute, abs(decoded[name][i] - original[name][i]), i, name)
        note("opacity", abs(sigmoid(decoded["opacity"][i]) - sigmoid(original["opacity"][i])), i, "opacity")
        q_original = unit_quaternion([original[f"rot_{k}"][i] for k in range(4)])
        q_decoded = unit_quaternion([decoded[f"rot_{k}"][i] for k in range(4)])
        for k in range(4):
            note("rotation", abs(q_decoded[k] - q_original[k]), i, f"rot_{k}")
        for r in range(rest):
            # f_rest_* is colour-major: coefficients 1..3 of each colour are degree 1.
            attribute = "sh_degree_1" if r % 15 < 3 else "sh_degree_2_3"
            name = f"f_rest_{r}"
            note(attribute, abs(decoded[name][i] - original[name][i]), i, name)

    failed = False
    for attribute, (error, gaussian, name) in worst.items():
        ok = error <= limits[attribute]
        failed |= not ok
        where = f" (Gaussian {gaussian}, {name})" if error else ""
        print(f"{case:10s} {attribute:13s} max error {error:.6g}{where}, tolerance {limits[attribute]}"
              f"{'' if ok else '  <-- FAILS'}")
    return 1 if failed else 0


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "scene":
        scene(sys.argv[2])
        return 0
    if len(sys.argv) == 5 and sys.argv[1] == "scene" and sys.argv[3] == "--sh-vectors":
        scene(sys.argv[2], sh_vectors=int(sys.argv[4]))
        return 0
    if len(sys.argv) == 5 and sys.argv[1] == "compare" and sys.argv[2] in TOLERANCES:
        return compare(*sys.argv[2:])
    sys.exit(__doc__)


if __name__ == "__main__":
    sys.exit(main())
