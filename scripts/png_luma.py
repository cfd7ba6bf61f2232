#!/usr/bin/env python3
"""Mean luminance of PNG images (8-bit greyscale, RGB or RGBA, with or without alpha, not
interlaced: what glrt's GLRT_DUMP and `glrt replay --out` write), with the standard library only.

    png_luma.py FILE.png...                     one line per image: mean luma (0-255, Rec. 709
                                                weights on the stored sRGB values), size, name
    png_luma.py --shrink N IN.png OUT.png       also writes IN downscaled N times (box filter,
                                                RGB) as OUT
    png_luma.py --regions 'X0,Y0,X1,Y1;...' FILE.png...
                                                mean luma of each region of each image
                                                (pixels x0 <= x < x1, y0 <= y < y1, y from
                                                the top row)
    png_luma.py --diff A.png B.png              how B differs from A (same size): mean luma of
                                                each, mean signed and absolute luma difference,
                                                and the share of pixels whose largest channel
                                                difference exceeds 4, 16 and 64
"""
import struct
import sys
import zlib

CHANNELS = {0: 1, 2: 3, 4: 2, 6: 4}  # colour type -> samples per pixel


def read_png(path):
    """(width, height, channels, rows) with rows as lists of bytes, filters undone."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise SystemExit(f"{path}: not a PNG")
    pos, idat, header = 8, [], None
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in CHANNELS or interlace:
        raise SystemExit(f"{path}: only 8-bit non-interlaced grey/RGB/RGBA PNGs are read")
    bpp = CHANNELS[colour]
    raw = zlib.decompress(b"".join(idat))
    stride = width * bpp
    rows, prev = [], bytearray(stride)
    for y in range(height):
        start = y * (stride + 1)
        kind, line = raw[start], bytearray(raw[start + 1:start + 1 + stride])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return width, height, bpp, rows


def rgb(bpp, line, x):
    if bpp < 3:
        v = line[x * bpp]
        return v, v, v
    return line[x * bpp], line[x * bpp + 1], line[x * bpp + 2]


def mean_luma(width, height, bpp, rows, box=None):
    """Over the whole image, or over box (x0, y0, x1, y1): x0 <= x < x1, y0 <= y < y1, y
    counted from the top row."""
    x0, y0, x1, y1 = box or (0, 0, width, height)
    if not (0 <= x0 < x1 <= width and 0 <= y0 < y1 <= height):
        raise SystemExit(f"region {x0},{y0},{x1},{y1} is not inside the {width}x{height} image")
    total = 0.0
    for line in rows[y0:y1]:
        for x in range(x0, x1):
            r, g, b = rgb(bpp, line, x)
            total += 0.2126 * r + 0.7152 * g + 0.0722 * b
    return total / ((x1 - x0) * (y1 - y0))


def write_png(path, width, height, rows):
    raw = b"".join(b"\x00" + bytes(line) for line in rows)

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def shrink(width, height, bpp, rows, n):
    w, h = width // n, height // n
    out = []
    for y in range(h):
        line = bytearray()
        for x in range(w):
            acc = [0, 0, 0]
            for yy in range(y * n, y * n + n):
                for xx in range(x * n, x * n + n):
                    for k, v in enumerate(rgb(bpp, rows[yy], xx)):
                        acc[k] += v
            line += bytes(round(v / (n * n)) for v in acc)
        out.append(line)
    return w, h, out


def diff(a, b):
    """The --diff line of images a and b, each (width, height, bpp, rows)."""
    (w, h, abpp, arows), (bw, bh, bbpp, brows) = a, b
    if (w, h) != (bw, bh):
        raise SystemExit(f"sizes differ: {w}x{h} and {bw}x{bh}")
    signed = absolute = 0.0
    beyond = {4: 0, 16: 0, 64: 0}
    for y in range(h):
        for x in range(w):
            pa, pb = rgb(abpp, arows[y], x), rgb(bbpp, brows[y], x)
            d = sum(k * (q - p) for k, p, q in zip((0.2126, 0.7152, 0.0722), pa, pb))
            signed += d
            absolute += abs(d)
            largest = max(abs(q - p) for p, q in zip(pa, pb))
            for t in beyond:
                beyond[t] += largest > t
    n = w * h
    shares = ", ".join(f">{t}: {100 * c / n:.2f}%" for t, c in beyond.items())
    return (f"luma {mean_luma(*a):.2f} -> {mean_luma(*b):.2f}; mean difference {signed / n:+.3f}, "
            f"mean |difference| {absolute / n:.3f}; pixels beyond {shares}")


def main(args):
    if args[:1] == ["--diff"] and len(args) == 3:
        print(f"{args[2]} vs {args[1]}: {diff(read_png(args[1]), read_png(args[2]))}")
        return
    if args[:1] == ["--shrink"] and len(args) == 4:
        n, src, dst = int(args[1]), args[2], args[3]
        w, h, bpp, rows = read_png(src)
        sw, sh, small = shrink(w, h, bpp, rows, n)
        write_png(dst, sw, sh, small)
        print(f"{dst}: {sw}x{sh} from {src}")
        return
    if args[:1] == ["--regions"] and len(args) >= 3:
        boxes = [tuple(int(v) for v in box.split(",")) for box in args[1].split(";")]
        for path in args[2:]:
            image = read_png(path)
            print(path + ": " + "  ".join(f"{','.join(map(str, box))} {mean_luma(*image, box):.2f}" for box in boxes))
        return
    if not args:
        raise SystemExit(__doc__)
    for path in args:
        w, h, bpp, rows = read_png(path)
        print(f"{mean_luma(w, h, bpp, rows):7.2f}  {w}x{h}  {path}")


if __name__ == "__main__":
    main(sys.argv[1:])
