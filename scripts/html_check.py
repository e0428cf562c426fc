#!/usr/bin/env python3
"""Pixel check of the HTML views' screenshots (used by scripts/html-check.sh).

Usage: html_check.py SHOT.png visuals|skeleton [SHOT.png visuals|skeleton ...]
       html_check.py --differ A.png B.png   (at least 2 % of the pixels differ)

Counts pixels by colour class and fails (exit 1) unless the screenshot is not blank and
holds enough pixels of the arm (the seed's blue and orange links, or the grey stick
figure) and of the surface (teal, semi-transparent over white or over the arm).
Standard library only: a minimal PNG decoder (8-bit RGB/RGBA, not interlaced).
"""
import struct
import sys
import zlib

# Minimum pixel counts for a 1000x800 screenshot (the seed arm covers about 10 times more).
MIN = {"blue": 1500, "orange": 400, "skeleton": 800, "surface": 3000}


def decode_png(path):
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise SystemExit(f"{path}: not a PNG")
    pos, idat, ihdr = 8, b"", None
    while pos < len(data):
        (n,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    w, h, depth, ctype, _, _, interlace = ihdr
    if depth != 8 or ctype not in (2, 6) or interlace:
        raise SystemExit(f"{path}: unsupported PNG (depth {depth}, type {ctype})")
    bpp = 3 if ctype == 2 else 4
    raw, stride = zlib.decompress(idat), w * bpp
    out, prev = bytearray(), bytearray(stride)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        out += line
        prev = line
    return w, h, [tuple(out[i:i + 3]) for i in range(0, len(out), bpp)]


def classify(px):
    counts = {"blue": 0, "orange": 0, "skeleton": 0, "surface": 0, "non_white": 0}
    for r, g, b in px:
        if (r, g, b) != (255, 255, 255):
            counts["non_white"] += 1
        if b >= 80 and b > 2 * r + 30 and b > 2 * g + 30:
            counts["blue"] += 1
        elif r >= 120 and 0.3 * r <= g <= 0.7 * r and b < 0.25 * r:
            counts["orange"] += 1
        elif g > r + 40 and b > r + 40 and abs(g - b) < 60:
            counts["surface"] += 1
        elif 50 <= r <= 90 and abs(r - g) < 8 and 0 <= b - r < 16:
            counts["skeleton"] += 1
    return counts


def differ(a, b):
    wa, ha, pa = decode_png(a)
    wb, hb, pb = decode_png(b)
    if (wa, ha) != (wb, hb):
        return 0
    n = sum(1 for x, y in zip(pa, pb) if max(abs(i - j) for i, j in zip(x, y)) > 30)
    print(f"{a} vs {b}: {n} pixels differ")
    return 0 if n >= 0.02 * wa * ha else 1


def main(args):
    if args and args[0] == "--differ":
        return differ(args[1], args[2])
    ok = True
    for path, kind in zip(args[0::2], args[1::2]):
        w, h, px = decode_png(path)
        c = classify(px)
        need = ["surface"] + (["blue", "orange"] if kind == "visuals" else ["skeleton"])
        bad = [k for k in need if c[k] < MIN[k] * w * h / 800000]
        if c["non_white"] < 0.02 * w * h:
            bad.append("non_white")
        print(f"{path}: {w}x{h} {c}" + (f" too few: {bad}" if bad else ""))
        ok &= not bad
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
