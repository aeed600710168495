#!/usr/bin/env python3
"""An elevation model (a NumPy .npz holding a 2-D int16 or float array "elevation") as a
16-bit grey PNG height map of 2N x 2N: the top-left N x N crop (N the largest power of
two that fits), mirrored in x and y so that it tiles seamlessly, lowest point 0, highest
65535. Pure Python (zipfile, struct, zlib): no NumPy needed.
Usage: scripts/dem-to-png.py DEM.npz OUT.png"""
import ast
import os
import struct
import sys
import zipfile
import zlib


def read_npy(data, name):
    """The shape and the values (row-major) of a .npy array."""
    if data[:6] != b"\x93NUMPY":
        sys.exit(f"dem-to-png: {name}: not a .npy array")
    size, start = (struct.unpack("<H", data[8:10])[0], 10) if data[6] == 1 else (struct.unpack("<I", data[8:12])[0], 12)
    header = ast.literal_eval(data[start:start + size].decode("latin1"))
    kinds = {"<i2": "h", "<f4": "f", "<f8": "d", "<i4": "i"}
    if header["descr"] not in kinds or header["fortran_order"] or len(header["shape"]) != 2:
        sys.exit(f"dem-to-png: {name}: expected a 2-D C-order array, got {header}")
    rows, cols = header["shape"]
    values = struct.unpack(f"<{rows * cols}{kinds[header['descr']]}", data[start + size:])
    return rows, cols, values


def write_png16(path, size, rows):
    """A 16-bit grey PNG, written whole or not at all."""
    raw = b"".join(b"\0" + struct.pack(f">{size}H", *row) for row in rows)

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)
    tmp = f"{path}.tmp.{os.getpid()}"
    with open(tmp, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 16, 0, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    os.replace(tmp, path)


source, target = sys.argv[1], sys.argv[2]
with zipfile.ZipFile(source) as z:
    rows, cols, values = read_npy(z.read("elevation.npy"), source)
n = 1
while 2 * n <= min(rows, cols):
    n *= 2
crop = [values[r * cols:r * cols + n] for r in range(n)]
lo, hi = min(min(r) for r in crop), max(max(r) for r in crop)
scaled = [[round(65535 * (v - lo) / (hi - lo)) for v in r] for r in crop]
tiled = [r + r[::-1] for r in scaled]
write_png16(target, 2 * n, tiled + tiled[::-1])
print(f"dem-to-png: {source}: {rows} x {cols}, crop {n} x {n} ({lo} to {hi}), mirrored to {target}", file=sys.stderr)
