#!/usr/bin/env python3
"""Recompresses 8-bit RGB PNGs in place with zlib level 9 and a per-row filter choice (minimum sum
of absolute differences), using only the Python standard library. Used for the pictures in
docs/figures, which `myoshell head --render` writes with a simple fixed-Huffman encoder.

usage: scripts/png_recompress.py FILE.png...
"""
import struct
import sys
import zlib


def chunks(data):
    i = 8
    while i < len(data):
        (n,) = struct.unpack(">I", data[i:i + 4])
        yield data[i + 4:i + 8], data[i + 8:i + 8 + n]
        i += 12 + n


def unfilter(raw, w, h, bpp=3):
    stride = w * bpp
    rows, prev, i = [], bytearray(stride), 0
    for _ in range(h):
        f, line = raw[i], bytearray(raw[i + 1:i + 1 + stride])
        i += 1 + stride
        for x in range(stride):
            a = line[x - bpp] if x >= bpp else 0
            b = prev[x]
            c = prev[x - bpp] if x >= bpp else 0
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pr = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[x] = (line[x] + pr) & 255
        rows.append(line)
        prev = line
    return rows


def refilter(rows, bpp=3):
    out, prev = bytearray(), bytearray(len(rows[0]))
    for line in rows:
        best = None
        for f in range(5):
            enc = bytearray(len(line))
            for x in range(len(line)):
                a = line[x - bpp] if x >= bpp else 0
                b = prev[x]
                c = prev[x - bpp] if x >= bpp else 0
                if f == 0:
                    p = 0
                elif f == 1:
                    p = a
                elif f == 2:
                    p = b
                elif f == 3:
                    p = (a + b) // 2
                else:
                    q = a + b - c
                    pa, pb, pc = abs(q - a), abs(q - b), abs(q - c)
                    p = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                enc[x] = (line[x] - p) & 255
            score = sum(v if v < 128 else 256 - v for v in enc)
            if best is None or score < best[0]:
                best = (score, f, enc)
        out.append(best[1])
        out += best[2]
        prev = line
    return bytes(out)


def chunk(kind, body):
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))


def main(paths):
    for path in paths:
        data = open(path, "rb").read()
        ihdr, idat = None, b""
        for kind, body in chunks(data):
            if kind == b"IHDR":
                ihdr = body
            elif kind == b"IDAT":
                idat += body
        w, h, depth, ctype = struct.unpack(">IIBB", ihdr[:10])
        if depth != 8 or ctype != 2:
            sys.exit(f"{path}: only 8-bit RGB PNGs are supported")
        rows = unfilter(zlib.decompress(idat), w, h)
        body = zlib.compress(refilter(rows), 9)
        png = data[:8] + chunk(b"IHDR", ihdr) + chunk(b"IDAT", body) + chunk(b"IEND", b"")
        open(path, "wb").write(png)
        print(f"{path}: {len(data)} -> {len(png)} bytes")


if __name__ == "__main__":
    main(sys.argv[1:])
