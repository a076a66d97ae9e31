#!/usr/bin/env python3
"""rgb565_to_png.py RAW WIDTH HEIGHT OUT.png - views a raw panel frame.

The firmware dumps frames in the panel format (RGB565 little-endian, rows
top to bottom) over semihosting; this turns one into a PNG with nothing
but the standard library, for looking at a frame or a failed comparison.
"""
import struct, sys, zlib

def main():
    raw, w, h, out = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
    data = open(raw, "rb").read()
    if len(data) != 2 * w * h:
        sys.exit("%s: %d bytes, expected %d for %dx%d" % (raw, len(data), 2 * w * h, w, h))
    rows = bytearray()
    for y in range(h):
        rows.append(0)
        for x in range(w):
            v = data[2 * (y * w + x)] | data[2 * (y * w + x) + 1] << 8
            r, g, b = v >> 11, (v >> 5) & 63, v & 31
            rows += bytes(((r * 255 + 15) // 31, (g * 255 + 31) // 63, (b * 255 + 15) // 31))
    def chunk(t, d):
        return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d))
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(bytes(rows), 9)) + chunk(b"IEND", b"")
    open(out, "wb").write(png)

if __name__ == "__main__":
    main()
