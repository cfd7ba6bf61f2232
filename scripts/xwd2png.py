#!/usr/bin/env python3
"""Converts an `xwd` screenshot (24 or 32 bits per pixel, TrueColor) to PNG with the standard
library only, optionally cropped: xwd2png.py IN.xwd OUT.png [WIDTHxHEIGHT]."""
import struct
import sys
import zlib


def read_xwd(data):
    fields = struct.unpack(">25I", data[:100])
    header_size, width, height = fields[0], fields[4], fields[5]
    byte_order, bpp, bytes_per_line = fields[7], fields[11], fields[12]
    masks, ncolors = fields[14:17], fields[19]
    if bpp not in (24, 32):
        raise SystemExit(f"xwd2png: {bpp} bits per pixel not supported (need 24 or 32)")
    step = bpp // 8
    pixels = data[header_size + 12 * ncolors:]
    order = "little" if byte_order == 0 else "big"
    shifts = [(m & -m).bit_length() - 1 for m in masks]
    rows = []
    for y in range(height):
        line = pixels[y * bytes_per_line:y * bytes_per_line + step * width]
        values = [int.from_bytes(line[i:i + step], order) for i in range(0, len(line), step)]
        rows.append(bytes(
            (v & m) >> s for v in values for m, s in zip(masks, shifts)))
    return width, height, rows


def write_png(path, width, height, rows):
    def chunk(kind, body):
        return (struct.pack(">I", len(body)) + kind + body
                + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF))
    raw = b"".join(b"\0" + row for row in rows)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(raw, 6)))
        f.write(chunk(b"IEND", b""))


def main():
    if len(sys.argv) not in (3, 4):
        raise SystemExit(__doc__)
    width, height, rows = read_xwd(open(sys.argv[1], "rb").read())
    if len(sys.argv) == 4:
        cw, ch = (int(v) for v in sys.argv[3].lower().split("x"))
        width, height = min(width, cw), min(height, ch)
        rows = [row[:3 * width] for row in rows[:height]]
    write_png(sys.argv[2], width, height, rows)


if __name__ == "__main__":
    main()
