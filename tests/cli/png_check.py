#!/usr/bin/env python3
"""Checks that every PNG given is a readable 8-bit RGB/RGBA/grey image that is not one colour (standard library
only: zlib). Prints one line per bad file and exits 1 if there is any. Used by tests/cli/analyze_smoke.cmake."""
import struct
import sys
import zlib


def pixels(path):
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG signature")
    pos, idat, ihdr = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            break
        pos += 12 + length
    w, h, depth, ctype, _, _, interlace = ihdr
    if depth != 8 or interlace != 0 or ctype not in (0, 2, 6):
        raise ValueError("unsupported PNG kind (depth %d, colour type %d, interlace %d)" % (depth, ctype, interlace))
    bpp = {0: 1, 2: 3, 6: 4}[ctype]
    raw = zlib.decompress(idat)
    stride = w * bpp
    prev = bytearray(stride)
    rows = []
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + pred) & 255
        rows.append(bytes(line))
        prev = line
    return w, h, bpp, rows


bad = 0
for path in sys.argv[1:]:
    try:
        w, h, bpp, rows = pixels(path)
        colours = {row[i:i + bpp] for row in rows for i in range(0, len(row), bpp)}
        if w == 0 or h == 0 or len(colours) < 2:
            print("blank PNG (one colour): %s" % path)
            bad += 1
    except Exception as e:  # noqa: BLE001 - report any decoding problem by file
        print("unreadable PNG %s: %s" % (path, e))
        bad += 1
print("png_check: %d of %d PNG files are readable and not blank" % (len(sys.argv) - 1 - bad, len(sys.argv) - 1))
sys.exit(1 if bad else 0)
