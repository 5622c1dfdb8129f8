"""Tilt of the plate in a coupled run of this case (standard library only).

usage: python3 tilt.py OUT_DIR [OUT_DIR ...]
Reads OUT_DIR/floater/body-plate.csv (t,x,y,z,qw,qx,qy,qz,...) and prints, per run, the plate's
pitch (rotation about y; positive = the upstream edge, facing the column, up) and roll at chosen
times, when the plate comes nearest the far wall, and the largest pitch either way.
"""
import csv
import math
import sys

FAR_WALL = 0.6
HALF = 0.07  # half the plate's 14 cm length


def pitch_roll(r):
    qw, qx, qy, qz = (float(r[k]) for k in ("qw", "qx", "qy", "qz"))
    # the plate's own z axis in the tank: R e_z
    zx = 2.0 * (qx * qz + qw * qy)
    zy = 2.0 * (qy * qz - qw * qx)
    zz = 1.0 - 2.0 * (qx * qx + qy * qy)
    return math.degrees(math.atan2(zx, zz)), math.degrees(math.atan2(-zy, zz))


for out in sys.argv[1:]:
    rows = list(csv.DictReader(open(f"{out}/floater/body-plate.csv")))
    print(f"== {out}: {len(rows)} rows to t = {float(rows[-1]['t']):.3f} s")
    for want in (0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0):
        r = min(rows, key=lambda r: abs(float(r["t"]) - want))
        if abs(float(r["t"]) - want) > 0.01:
            continue
        p, q = pitch_roll(r)
        print(f"  t = {float(r['t']):.3f} s: centre x {float(r['x']):.4f} z {float(r['z']):.4f} m, pitch {p:+6.1f}°, roll {q:+6.1f}°")
    near = max(rows, key=lambda r: float(r["x"]))
    p, q = pitch_roll(near)
    print(f"  nearest the far wall at t = {float(near['t']):.3f} s (centre {FAR_WALL - float(near['x']) - HALF:+.4f} m from touching it flat): pitch {p:+.1f}°, roll {q:+.1f}°")
    pitches = [(pitch_roll(r)[0], float(r["t"])) for r in rows]
    hi, lo = max(pitches), min(pitches)
    print(f"  largest pitch: {hi[0]:+.1f}° at {hi[1]:.3f} s (upstream edge up), {lo[0]:+.1f}° at {lo[1]:.3f} s (downstream edge up)")
