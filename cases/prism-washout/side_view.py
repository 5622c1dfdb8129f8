"""Side view (x–z) of the prism's frame at a few times of a prism-washout run, as one SVG, with
the fractures of the run listed: the figure to hold against S2 Fig. 7 (fractured at about
0.175 s, pieces carried downstream by 0.3 s).

usage: python3 cases/prism-washout/side_view.py [OUT] [--times T,T,...] [--svg PATH]

OUT is the run's output folder (default out/prism-washout): it reads OUT/prism/frame.pvd, the
frame snapshots it lists and OUT/prism/hinge-events.csv, and writes OUT/side-view.svg (or
--svg). Each element is drawn as a bar of the section's width (0.05 m) between its two nodes;
the channel floor (z = 0) and its end wall (x = 1 m) are grey. Standard library only.
"""
import argparse
import csv
import os
import re
import sys

SECTION = 0.05  # the prism's side [m] (case.toml's section)
X_RANGE = (0.55, 1.02)  # m: the prism stands at x = 0.7, the channel ends at 1.0
Z_RANGE = (-0.02, 0.2)
SCALE = 900.0  # px per m
COLUMNS = 3


def snapshots(pvd):
    """(time, file) of every frame snapshot the PVD lists."""
    text = open(pvd).read()
    found = re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', text)
    return [(float(t), os.path.join(os.path.dirname(pvd), f)) for t, f in found]


def frame(vtu):
    """(node positions [(x, z)], elements [(a, b)]) of a frame snapshot (ASCII VTU)."""
    text = open(vtu).read()
    arrays = dict(re.findall(r'<DataArray[^>]*Name="(\w+)"[^>]*>(.*?)</DataArray>', text, re.S))
    points = re.search(r"<Points><DataArray[^>]*>(.*?)</DataArray>", text, re.S)
    if points is None or "connectivity" not in arrays:
        sys.exit("%s: no points or no connectivity" % vtu)
    p = [float(v) for v in points.group(1).split()]
    nodes = [(p[k], p[k + 2]) for k in range(0, len(p), 3)]
    c = [int(v) for v in arrays["connectivity"].split()]
    return nodes, [(c[k], c[k + 1]) for k in range(0, len(c), 2)]


def fractures(path):
    """(time, member, node) of each fracture row of hinge-events.csv."""
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return [(float(r["t"]), r["member"], r["node"]) for r in csv.DictReader(f) if r["event"] == "fracture"]


def panel(t, nodes, elements, left, top):
    """SVG of one snapshot with its top-left corner at (left, top)."""
    w = (X_RANGE[1] - X_RANGE[0]) * SCALE
    h = (Z_RANGE[1] - Z_RANGE[0]) * SCALE

    def xy(x, z):
        return left + (x - X_RANGE[0]) * SCALE, top + (Z_RANGE[1] - z) * SCALE

    out = ['<rect x="%.1f" y="%.1f" width="%.1f" height="%.1f" fill="#f4f8fc" stroke="#999"/>' % (left, top, w, h)]
    fx0, fz = xy(X_RANGE[0], 0.0)
    fx1, _ = xy(X_RANGE[1], 0.0)
    out.append('<line x1="%.1f" y1="%.1f" x2="%.1f" y2="%.1f" stroke="#777" stroke-width="3"/>' % (fx0, fz, fx1, fz))
    ex, ez0 = xy(1.0, 0.0)
    _, ez1 = xy(1.0, Z_RANGE[1])
    out.append('<line x1="%.1f" y1="%.1f" x2="%.1f" y2="%.1f" stroke="#777" stroke-width="3"/>' % (ex, ez0, ex, ez1))
    for a, b in elements:
        (x1, y1), (x2, y2) = xy(*nodes[a]), xy(*nodes[b])
        out.append(
            '<line x1="%.1f" y1="%.1f" x2="%.1f" y2="%.1f" stroke="#b5651d" stroke-opacity="0.85" '
            'stroke-width="%.1f"/>' % (x1, y1, x2, y2, SECTION * SCALE)
        )
        for x, y in ((x1, y1), (x2, y2)):
            out.append('<circle cx="%.1f" cy="%.1f" r="2.5" fill="#222"/>' % (x, y))
    out.append('<text x="%.1f" y="%.1f" font-family="sans-serif" font-size="15">t = %.2f s</text>' % (left + 8, top + 18, t))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out", nargs="?", default="out/prism-washout")
    ap.add_argument("--times", default="0.15,0.2,0.25,0.3,0.4,0.5")
    ap.add_argument("--svg")
    a = ap.parse_args()
    shots = snapshots(os.path.join(a.out, "prism", "frame.pvd"))
    if not shots:
        sys.exit("no frame snapshots in %s/prism/frame.pvd" % a.out)
    wanted = [float(t) for t in a.times.split(",")]
    chosen = [min(shots, key=lambda s: abs(s[0] - t)) for t in wanted]
    w = (X_RANGE[1] - X_RANGE[0]) * SCALE
    h = (Z_RANGE[1] - Z_RANGE[0]) * SCALE
    rows = (len(chosen) + COLUMNS - 1) // COLUMNS
    gap, head = 12.0, 30.0
    width = COLUMNS * (w + gap) + gap
    height = head + rows * (h + gap) + 30.0
    breaks = fractures(os.path.join(a.out, "prism", "hinge-events.csv"))
    body = []
    for k, (t, vtu) in enumerate(chosen):
        nodes, elements = frame(vtu)
        body += panel(t, nodes, elements, gap + (k % COLUMNS) * (w + gap), head + (k // COLUMNS) * (h + gap))
    title = "prism-washout: the frame seen from the side (x %.2f to %.2f m, z up to %.2f m)" % (
        X_RANGE[0], X_RANGE[1], Z_RANGE[1])
    listed = "; ".join("%.4f s (member %s, node %s)" % b for b in breaks) or "none"
    svg = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d">' % (width, height),
           '<rect width="100%" height="100%" fill="white"/>',
           '<text x="%.1f" y="20" font-family="sans-serif" font-size="16">%s</text>' % (gap, title)]
    svg += body
    svg.append('<text x="%.1f" y="%.1f" font-family="sans-serif" font-size="14">fractures: %s</text>'
               % (gap, height - 10, listed))
    svg.append("</svg>")
    path = a.svg or os.path.join(a.out, "side-view.svg")
    with open(path, "w") as f:
        f.write("\n".join(svg) + "\n")
    print("wrote", path, "(%d snapshots, %d fractures)" % (len(chosen), len(breaks)))


if __name__ == "__main__":
    main()
