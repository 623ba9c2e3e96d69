#!/usr/bin/env python3
"""make_seeds.py - write the seed corpus of the fuzz targets.

    python3 tests/fuzz/make_seeds.py            # into tests/fuzz/corpus/

Each target reads its input with fuzz_common.h's reader: byte 0 seeds the
PRNG that fills in after the input ends and picks how dirty floats are
(low two bits: 0-1 clean, 2 light, 3 heavy NaN / inf / huge). So a seed of
a few bytes already makes a full-sized call; the seeds below vary byte 0
over the four dirt levels and add a few bytes that steer counts and
choices. Deterministic output, a few KB in all."""
import os
import random

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus")
TARGETS = {"grow": 24, "ropes": 24, "ribbons": 24, "lut": 24, "fur": 24}


def main():
    rng = random.Random(2026)
    total = 0
    for target, n in TARGETS.items():
        d = os.path.join(ROOT, target)
        os.makedirs(d, exist_ok=True)
        for i in range(n):
            length = [1, 4, 16, 64, 256][i % 5]
            data = bytearray(rng.getrandbits(8) for _ in range(length))
            data[0] = (data[0] & ~3) | (i % 4)  # every dirt level
            if i % 6 == 5:  # long runs of one byte: big counts, same floats
                data = bytearray([data[0]]) + bytes([0x22]) * (length + 31)
            path = os.path.join(d, "seed-%02d.bin" % i)
            with open(path, "wb") as f:
                f.write(data)
            total += len(data)
    total += curve_seeds(rng)
    total += obj_seeds()
    print("wrote the seeds (%d bytes) under %s" % (total, ROOT))


def curve_seeds(rng):
    """fuzz_curves reads a file, not the reader: valid small .hair and .tfx
    files (byte 0 even: .hair, odd: .tfx), with and without the optional
    arrays, and a few cut short."""
    import struct
    d = os.path.join(ROOT, "curves")
    os.makedirs(d, exist_ok=True)
    total = 0
    seeds = []
    for flags in (2, 3, 3 | 4, 3 | 16, 3 | 4 | 8 | 16):
        strands = rng.randint(1, 4)
        segs = [rng.randint(1, 5) for _ in range(strands)]
        if not flags & 1:
            segs = [3] * strands
        pts = sum(s + 1 for s in segs)
        head = b"HAIR" + struct.pack("<IIII", strands, pts, flags, 3)
        head += struct.pack("<ff3f", 1.0, 0.0, 1.0, 1.0, 1.0)
        head += b"seed".ljust(88, b"\0")
        body = b""
        if flags & 1:
            body += b"".join(struct.pack("<H", s) for s in segs)
        body += b"".join(struct.pack("<f", rng.uniform(-1, 1)) for _ in range(3 * pts))
        for bit, k in ((4, 1), (8, 1), (16, 3)):
            if flags & bit:
                body += b"".join(struct.pack("<f", rng.random()) for _ in range(k * pts))
        seeds.append(b"\0" + head + body)
    for strands, per in ((1, 2), (2, 4), (3, 16)):
        head = struct.pack("<fII", 4.0, strands, per)
        head += struct.pack("<5I", 160, 0, 0, 0, 0) + bytes(128)
        body = b"".join(struct.pack("<4f", rng.uniform(-1, 1), rng.uniform(-1, 1),
                                    rng.uniform(-1, 1), 1.0)
                        for _ in range(strands * per))
        seeds.append(b"\1" + head + body)
    seeds.append(seeds[1][:-3])   # truncated .hair
    seeds.append(seeds[-2][:100])  # truncated .tfx
    # a .tfx with every array: positions, strand UVs, vertex UVs, strand
    # thickness, vertex colours, one after another
    strands, per = 2, 4
    v = strands * per
    sizes = (16 * v, 8 * strands, 8 * v, 4 * strands, 16 * v)
    offs, at = [], 160
    for n in sizes:
        offs.append(at)
        at += n
    head = struct.pack("<fII", 4.0, strands, per) + struct.pack("<5I", *offs)
    head += bytes(128)
    body = b"".join(struct.pack("<f", rng.uniform(-1, 1)) for _ in range(sum(sizes) // 4))
    seeds.append(b"\1" + head + body)
    for i, data in enumerate(seeds):
        with open(os.path.join(d, "seed-%02d.bin" % i), "wb") as f:
            f.write(data)
        total += len(data)
    return total


def obj_seeds():
    """fuzz_obj reads OBJ text: polylines as `l` lines (whole and as
    segments), with faces and points beside them, negative indices."""
    d = os.path.join(ROOT, "obj")
    os.makedirs(d, exist_ok=True)
    verts = "".join("v %g %g %g\n" % (0.1 * i, 0.02 * i * i, -0.3 * i) for i in range(8))
    seeds = [
        verts + "l 1 2 3 4\nl 5 6 7 8\n",
        verts + "l 1 2\nl 2 3\nl 3 4\nl 6 7\n",
        verts + "o hair\nf 1 2 3\nl 4 5 6\np 7\nf 5 6 7 8\nl 7 8\n",
        verts + "g a\nl -8 -7 -6\ng b\nl -3 -2 -1\n",
        verts + "f 1 2 3\n",
        "v 0 0 0\nv 1 1 1\nl 1 2 3\nl 0 1\n",
    ]
    total = 0
    for i, text in enumerate(seeds):
        with open(os.path.join(d, "seed-%02d.obj" % i), "w") as f:
            f.write(text)
        total += len(text)
    return total


if __name__ == "__main__":
    main()
