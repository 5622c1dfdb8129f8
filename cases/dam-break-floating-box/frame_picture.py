"""Picture of a fluid frame of a run, as a PNG: the particles seen from above and in front, water
coloured by speed, the box's particles orange, the tank's walls left out but for a thin outline.
It is the front page's picture (docs/img/dam-break-floating-box.png).

usage: python3 cases/dam-break-floating-box/frame_picture.py [OUT] [--times 0.5,0.9] [--png PATH]

OUT is the run's output folder (default out/dam-break-floating-box): it reads the fluid's PVD
(OUT/tank/tank.pvd), takes the frame nearest each asked time, and writes one panel per time side
by side to --png (default OUT/frames.png). Standard library only: the VTU's raw appended arrays
are read as the fluid solver writes them ([u64 length][little-endian values] per array).
"""
import argparse
import math
import os
import re
import struct
import sys
import zlib

PANEL = (620, 440)  # px per panel
SCALE = 700.0  # px per m
KIND_FLUID, KIND_BODY = 0, 3  # the `kind` array's codes read from the frame (see KINDS below)
SPEED_TOP = 2.5  # m/s at the top of the colour scale


def frames(pvd):
    """(time, file) of every frame the PVD lists."""
    text = open(pvd).read()
    found = re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', text)
    return [(float(t), os.path.join(os.path.dirname(pvd), f)) for t, f in found]


def read_vtu(path):
    """The named arrays of a raw-appended VTU, as lists of tuples (components per item)."""
    data = open(path, "rb").read()
    start = data.index(b"<AppendedData")
    start = data.index(b"_", start) + 1
    header = data[:start].decode("ascii", "replace")
    arrays = {}
    for tag in re.findall(r"<DataArray[^>]*>", header):
        name = re.search(r'Name="([^"]+)"', tag).group(1)
        ty = re.search(r'type="([^"]+)"', tag).group(1)
        comps = int((re.search(r'NumberOfComponents="(\d+)"', tag) or [0, "1"])[1])
        offset = int(re.search(r'offset="(\d+)"', tag).group(1))
        (length,) = struct.unpack_from("<Q", data, start + offset)
        fmt = {"Float64": "d", "Float32": "f", "Int64": "q", "UInt8": "B", "Int32": "i", "UInt32": "I",
               "UInt64": "Q", "Int8": "b"}[ty]
        count = length // struct.calcsize(fmt)
        values = struct.unpack_from("<%d%s" % (count, fmt), data, start + offset + 8)
        arrays[name] = [values[i:i + comps] for i in range(0, count, comps)]
    return arrays


def project(p):
    """Screen position of a point: an oblique view from the front (−y), 30° above."""
    x, y, z = p
    u = x + 0.45 * y
    v = z * math.cos(math.radians(30)) + 0.35 * y
    return u, v


def speed_colour(s):
    """Blue (still) to white (fast), a sequential ramp."""
    t = max(0.0, min(1.0, s / SPEED_TOP))
    return (int(20 + 215 * t), int(70 + 175 * t), int(160 + 95 * t))


def panel(arrays, label):
    """One panel's pixels (rows of RGB tuples)."""
    w, h = PANEL
    img = [[(255, 255, 255)] * w for _ in range(h)]
    depth = [[-1e9] * w for _ in range(h)]
    pos, kind, vel = arrays["position"], arrays["kind"], arrays["velocity"]
    origin = (40, h - 40)
    for p, k, v in zip(pos, kind, vel):
        k = k[0]
        if k not in (KIND_FLUID, KIND_BODY):
            continue
        u, vv = project(p)
        cx, cy = origin[0] + u * SCALE, origin[1] - vv * SCALE
        colour = (240, 140, 30) if k == KIND_BODY else speed_colour(math.sqrt(sum(c * c for c in v)))
        d = -p[1]  # nearer the viewer (smaller y) is drawn over
        r = 2
        for py in range(int(cy) - r, int(cy) + r + 1):
            for px in range(int(cx) - r, int(cx) + r + 1):
                if 0 <= px < w and 0 <= py < h and (px - cx) ** 2 + (py - cy) ** 2 <= r * r + 1:
                    if d >= depth[py][px]:
                        depth[py][px] = d
                        shade = 0.82 + 0.18 * min(1.0, (p[2] + 0.05) / 0.5)
                        img[py][px] = tuple(int(c * shade) for c in colour)
    outline(img, origin)
    text(img, 12, 12, label)
    return img


def outline(img, origin):
    """The tank's edges (0.6 × 0.45 × 0.3 m of water-height walls drawn to 0.3 m) in grey."""
    corners = [(x, y, z) for x in (0.0, 0.6) for y in (0.0, 0.45) for z in (0.0, 0.3)]
    for a in corners:
        for b in corners:
            if sum(1 for i in range(3) if a[i] != b[i]) == 1 and a < b:
                line(img, origin, a, b)


def line(img, origin, a, b):
    h, w = len(img), len(img[0])
    for i in range(201):
        t = i / 200
        p = tuple(a[j] + t * (b[j] - a[j]) for j in range(3))
        u, v = project(p)
        px, py = int(origin[0] + u * SCALE), int(origin[1] - v * SCALE)
        if 0 <= px < w and 0 <= py < h and img[py][px] == (255, 255, 255):
            img[py][px] = (150, 150, 150)


# A 3×5 pixel font for the panel labels (digits, 't', '=', '.', 's', ' ').
FONT = {
    "0": "111101101101111", "1": "010110010010111", "2": "111001111100111", "3": "111001111001111",
    "4": "101101111001001", "5": "111100111001111", "6": "111100111101111", "7": "111001001001001",
    "8": "111101111101111", "9": "111101111001111", ".": "000000000000010", "=": "000111000111000",
    "t": "010111010010011", "s": "000011100001110", " ": "000000000000000",
}


def text(img, x, y, s, size=3):
    for ch in s:
        bits = FONT.get(ch, FONT[" "])
        for i, bit in enumerate(bits):
            if bit == "1":
                r, c = divmod(i, 3)
                for dy in range(size):
                    for dx in range(size):
                        img[y + r * size + dy][x + c * size + dx] = (40, 40, 40)
        x += 4 * size


def write_png(path, rows):
    h, w = len(rows), len(rows[0])
    raw = b"".join(b"\x00" + bytes(c for px in row for c in px) for row in rows)

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    open(path, "wb").write(png)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out", nargs="?", default="out/dam-break-floating-box")
    ap.add_argument("--times", default="0.5,0.9")
    ap.add_argument("--png")
    args = ap.parse_args()
    pvd = os.path.join(args.out, "tank", "tank.pvd")
    if not os.path.exists(pvd):
        sys.exit(f"{pvd} not found: run `coupler run cases/dam-break-floating-box/case.toml` first")
    listed = frames(pvd)
    panels = []
    for t in (float(s) for s in args.times.split(",")):
        time, path = min(listed, key=lambda f: abs(f[0] - t))
        panels.append(panel(read_vtu(path), f"t = {time:.2f} s"))
    rows = [sum((p[r] for p in panels), []) for r in range(PANEL[1])]
    png = args.png or os.path.join(args.out, "frames.png")
    write_png(png, rows)
    print(f"wrote {png}")


if __name__ == "__main__":
    main()
