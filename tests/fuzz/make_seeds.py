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
    print("wrote %d seeds (%d bytes) under %s" % (4 * 24, total, ROOT))


if __name__ == "__main__":
    main()
