#!/usr/bin/env python3
"""Writes deck.stl: the bridge deck of this case as a closed ASCII STL, drawn in millimetres.

A flat slab 200 mm along the flow (x), 25 mm thick, on three girders 25 mm wide and 25 mm deep
(at its front, middle and back), extruded 50 mm across the flume (y). Origin: the front girder's
bottom corner at y = 0; case.toml places it with scale = 0.001 and translate. Run it from this
folder: `python3 deck_stl.py` (standard library only).
"""

WIDTH = 50.0  # across the flume [mm]: the tank's width
SLAB = (200.0, 25.0)  # length along x, thickness [mm]
GIRDER = (25.0, 25.0)  # width along x, depth [mm]
GIRDER_X = (0.0, 87.5, 175.0)  # front faces of the girders [mm]


def section():
    """The cross-section in (x, z), counter-clockwise, from the front girder's bottom."""
    gw, gd = GIRDER
    length, thick = SLAB
    points = []
    for x in GIRDER_X:
        if x > 0.0:
            points += [(x, gd)]
        points += [(x, 0.0), (x + gw, 0.0)]
        if x + gw < length:
            points += [(x + gw, gd)]
    return points + [(length, gd + thick), (0.0, gd + thick)]


def cross(o, a, b):
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def inside(p, a, b, c):
    return cross(a, b, p) > 0 and cross(b, c, p) > 0 and cross(c, a, p) > 0


def ears(poly):
    """Triangles (index triples, counter-clockwise) of a simple counter-clockwise polygon."""
    idx = list(range(len(poly)))
    out = []
    while len(idx) > 3:
        for k in range(len(idx)):
            i, j, m = idx[k - 1], idx[k], idx[(k + 1) % len(idx)]
            a, b, c = poly[i], poly[j], poly[m]
            if cross(a, b, c) <= 0:
                continue
            if any(inside(poly[q], a, b, c) for q in idx if q not in (i, j, m)):
                continue
            out.append((i, j, m))
            idx.pop(k)
            break
        else:
            raise ValueError("no ear: the section is not simple")
    out.append(tuple(idx))
    return out


def triangles():
    poly = section()
    at = lambda p, y: (p[0], y, p[1])  # noqa: E731
    tris = []
    for i, j, m in ears(poly):
        tris.append((at(poly[i], 0.0), at(poly[j], 0.0), at(poly[m], 0.0)))  # normal −y
        tris.append((at(poly[i], WIDTH), at(poly[m], WIDTH), at(poly[j], WIDTH)))  # normal +y
    for k, p in enumerate(poly):
        q = poly[(k + 1) % len(poly)]
        a, b, c, d = at(p, 0.0), at(q, 0.0), at(q, WIDTH), at(p, WIDTH)
        tris += [(a, c, b), (a, d, c)]  # outward: to the right of p → q
    return tris


def normal(t):
    u = [t[1][i] - t[0][i] for i in range(3)]
    v = [t[2][i] - t[0][i] for i in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    s = sum(c * c for c in n) ** 0.5
    return [c / s for c in n]


def main():
    lines = ["solid deck"]
    for t in triangles():
        lines.append("  facet normal %g %g %g" % tuple(normal(t)))
        lines.append("    outer loop")
        lines += ["      vertex %g %g %g" % v for v in t]
        lines.append("    endloop")
        lines.append("  endfacet")
    lines.append("endsolid deck")
    with open("deck.stl", "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
