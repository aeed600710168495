#!/usr/bin/env python3
"""An elevation model (a NumPy .npz holding a 2-D int16 or float array "elevation") as a
16-bit grey PNG height map of 2N x 2N: the top-left N x N crop (N the largest power of
two that fits), mirrored in x and y so that it tiles seamlessly, lowest point 0, highest
65535. Pure Python (zipfile, struct, zlib): no NumPy needed.
Usage: scripts/dem-to-png.py DEM.npz OUT.png
Exit 2, one line on stderr and no OUT.png: an argument or DEM.npz it cannot use."""
import ast
import math
import os
import struct
import sys
import zipfile
import zlib


def fail(message):
    print("dem-to-png: " + message, file=sys.stderr)
    sys.exit(2)


def read_npy(data, name):
    """The shape and the values (row-major) of a .npy array."""
    if data[:6] != b"\x93NUMPY" or len(data) < 12:
        fail(f"{name}: not a .npy array")
    size, start = (struct.unpack("<H", data[8:10])[0], 10) if data[6] == 1 else (struct.unpack("<I", data[8:12])[0], 12)
    try:
        header = ast.literal_eval(data[start:start + size].decode("latin1"))
        kinds = {"<i2": "h", "<f4": "f", "<f8": "d", "<i4": "i"}
        ok = header["descr"] in kinds and not header["fortran_order"] and len(header["shape"]) == 2 and \
            all(type(n) is int and n > 0 for n in header["shape"])
    except (ValueError, SyntaxError, MemoryError, RecursionError, KeyError, TypeError):
        fail(f"{name}: its .npy header cannot be read")
    if not ok:
        fail(f"{name}: expected a 2-D C-order array of int16, int32, float32 or float64, got {header}"[:200])
    rows, cols = header["shape"]
    try:
        values = struct.unpack(f"<{rows * cols}{kinds[header['descr']]}", data[start + size:])
    except struct.error:
        fail(f"{name}: holds not {rows} x {cols} values (truncated?)")
    return rows, cols, values


def write_png16(path, size, rows):
    """A 16-bit grey PNG, written whole or not at all."""
    raw = b"".join(b"\0" + struct.pack(f">{size}H", *row) for row in rows)

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)
    tmp = f"{path}.tmp.{os.getpid()}"
    try:
        with open(tmp, "wb") as f:
            f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 16, 0, 0, 0, 0))
                    + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
        os.replace(tmp, path)
    except OSError as e:
        if os.path.exists(tmp):
            os.remove(tmp)
        fail(f"{path}: cannot write it: {e.strerror or e}")


if len(sys.argv) != 3:
    fail("usage: scripts/dem-to-png.py DEM.npz OUT.png")
source, target = sys.argv[1], sys.argv[2]
try:
    with zipfile.ZipFile(source) as z:
        data = z.read("elevation.npy")
except (OSError, zipfile.BadZipFile, KeyError, EOFError) as e:
    fail(f"{source}: no elevation.npy to read in it: {e.strerror if isinstance(e, OSError) else e}")
rows, cols, values = read_npy(data, source)
n = 1
while 2 * n <= min(rows, cols):
    n *= 2
crop = [values[r * cols:r * cols + n] for r in range(n)]
lo, hi = min(min(r) for r in crop), max(max(r) for r in crop)
if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
    fail(f"{source}: its crop is flat or not finite ({lo} to {hi}): no height map in it")
scaled = [[round(65535 * (v - lo) / (hi - lo)) for v in r] for r in crop]
tiled = [r + r[::-1] for r in scaled]
write_png16(target, 2 * n, tiled + tiled[::-1])
print(f"dem-to-png: {source}: {rows} x {cols}, crop {n} x {n} ({lo} to {hi}), mirrored to {target}", file=sys.stderr)
