"""Box history and surge front of a coupled run of this case.

usage: python3 plot_history.py OUT_DIR [PNG]
OUT_DIR is the coupler's --out folder; it reads OUT_DIR/floater/body-box.csv (t,x,y,z,qw,qx,qy,qz,…)
and the fluid's frames OUT_DIR/tank/tank_*.vtu, prints the surge front per frame and a summary of
the box's motion, and plots the box's height and tilt against time into PNG.
"""
import glob
import math
import re
import struct
import sys

import numpy as np

SPACING = 0.01
FAR_WALL = 0.6


def read_vtu(path):
    """Positions and kinds of a fluid-solver VTU frame (raw appended data, UInt64 headers)."""
    raw = open(path, "rb").read()
    head = raw[:4096].decode("latin1")
    data = head.index("_", head.index('<AppendedData encoding="raw">')) + 1

    def array(name, dtype):
        at = data + int(re.search(r'Name="%s"[^>]*offset="(\d+)"' % name, head).group(1))
        n = struct.unpack("<Q", raw[at:at + 8])[0]
        return np.frombuffer(raw[at + 8:at + 8 + n], dtype=dtype)

    return array("position", "<f8").reshape(-1, 3), array("kind", "u1")


def surge_front_and_run_up(pos, kind):
    """Largest x of the water, and the highest water within 5 cm of the far wall, spray left
    out: a Δs cell counts when its 3 × 3 × 3 block of cells holds at least 9 fluid particles (a
    third of a full lattice)."""
    cells = np.floor(pos[kind == 0] / SPACING).astype(np.int64)
    keys, counts = np.unique(cells, axis=0, return_counts=True)
    count = {tuple(k): c for k, c in zip(keys, counts)}
    front, run_up = 0.0, 0.0
    for k in keys:
        near = sum(count.get((k[0] + a, k[1] + b, k[2] + c), 0)
                   for a in (-1, 0, 1) for b in (-1, 0, 1) for c in (-1, 0, 1))
        if near >= 9:
            x = (k[0] + 0.5) * SPACING
            front = max(front, x)
            if x >= FAR_WALL - 0.05:
                run_up = max(run_up, (k[2] + 1) * SPACING)
    return front, run_up


def main():
    out = sys.argv[1]
    png = sys.argv[2] if len(sys.argv) > 2 else "box-history.png"
    frames = sorted(glob.glob(out + "/tank/tank_*.vtu"))
    times = []
    for line in open(out + "/tank/tank.pvd"):
        m = re.search(r'timestep="([^"]+)"', line)
        if m:
            times.append(float(m.group(1)))
    arrival = None
    peak = (0.0, 0.0)
    print("t [s]   surge front x [m]   water height at the far wall [m]")
    for t, f in zip(times, frames):
        x, h = surge_front_and_run_up(*read_vtu(f))
        print(f"{t:5.2f}   {x:.3f}               {h:.3f}")
        if arrival is None and x >= FAR_WALL - 2 * SPACING:
            arrival = t
        if t <= 1.0 and h > peak[1]:
            peak = (t, h)
    print(f"surge at the far wall (front within 2 Δs of x = {FAR_WALL} m): first frame t = {arrival} s")
    print(f"highest run-up at the far wall before 1 s: {peak[1]:.2f} m at t = {peak[0]} s")

    lines = open(out + "/floater/body-box.csv").read().splitlines()[1:]
    rows = np.array([[float(v) for v in l.split(",")] for l in lines if l.count(",") == 14])
    t, z = rows[:, 0], rows[:, 3]
    qw, qx, qy, qz = rows[:, 4], rows[:, 5], rows[:, 6], rows[:, 7]
    # Tilt: angle between the box's own z axis (its 4 cm thickness) and the vertical.
    tilt = np.degrees(np.arccos(np.clip(1.0 - 2.0 * (qx * qx + qy * qy), -1.0, 1.0)))
    turn = np.degrees(2.0 * np.arccos(np.clip(np.abs(qw), 0.0, 1.0)))
    for s in (0.25, 0.5, 0.75, 0.9, 1.0, 1.25, 1.5, 2.0, 2.5, 3.0, 3.5):
        k = np.argmin(abs(t - s))
        print(f"t = {t[k]:.2f} s: centre ({rows[k, 1]:.3f}, {rows[k, 2]:.3f}, {z[k]:.3f}) m, tilt {tilt[k]:5.1f}°, total rotation {turn[k]:5.1f}°")
    first = t[np.argmax(tilt > 20.0)] if (tilt > 20.0).any() else None
    print(f"first tilt above 20°: t = {first} s; largest tilt {tilt.max():.1f}° at t = {t[np.argmax(tilt)]:.2f} s")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(2, 1, figsize=(6, 4), sharex=True, dpi=90)
    ax[0].plot(t, z, lw=1)
    ax[0].set_ylabel("box centre z [m]")
    ax[1].plot(t, tilt, lw=1, label="tilt of the box's z axis")
    ax[1].plot(t, turn, lw=1, ls="--", label="total rotation")
    ax[1].set_ylabel("angle [°]")
    ax[1].set_xlabel("t [s]")
    ax[1].legend(fontsize=7)
    for a in ax:
        a.grid(alpha=0.3)
        if arrival is not None:
            a.axvline(arrival, color="grey", lw=0.8, ls=":")
    ax[0].set_title("dam break with a floating box (Δs = 1 cm); dotted: surge at the far wall", fontsize=9)
    fig.tight_layout()
    fig.savefig(png)


if __name__ == "__main__":
    main()
