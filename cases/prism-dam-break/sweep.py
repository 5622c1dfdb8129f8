"""S2 §5(1)-(2): the prism dam break for the seven prism widths (unresolved drag coupling) and
the resolved 0.05 m prism, the X force per unit width against time of each, and their plot.

usage: python3 cases/prism-dam-break/sweep.py [--spacing DS] [--end T] [--out DIR]
                                               [--coupler PATH] [--widths W,W,...] [--no-run]

--spacing: particle size (default 0.005, S2 Table 1); the time steps scale with it (Δt = 2e-4 s
at 5 mm: c Δt/Δs = 0.6) and the water column keeps its size (so 0.01 gives 16 000 particles).
Writes into DIR (default out/prism-dam-break): one coupler run per width (w0.0005/, …) and
resolved/, force-per-width.csv (time, F_x/D of each run), force-per-width.svg, and prints each
run's peak and the two widest widths against the resolved force. --no-run only re-reads them.
Only the Python standard library is used.
"""
import argparse
import csv
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
WIDTHS = [0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05]
RESOLVED_WIDTH = 0.05
BASE_SPACING = 0.005
BASE_STEP = "2.0e-4"


def scaled(text, spacing, end):
    """The case text at particle size `spacing` (time steps scaled alike) and end time `end`."""
    step = 2.0e-4 * spacing / BASE_SPACING
    text = text.replace("spacing = 0.005", "spacing = %g" % spacing)
    text = text.replace(BASE_STEP, "%.6g" % step)
    if end is not None:
        text = text.replace("end_time = 0.5", "end_time = %g" % end)
    return text


def with_width(text, width):
    """The unresolved case with drag width `width` (only the [[coupling.drag]] table changes)."""
    head, link = text.rsplit("[[coupling.drag]]", 1)
    link = link.replace("width = 0.05", "width = %g" % width)
    head = head.replace('name = "prism-dam-break"', 'name = "prism-dam-break-w%g"' % width)
    return head + "[[coupling.drag]]" + link


def run(coupler, case_text, case_path, out):
    with open(case_path, "w") as f:
        f.write(case_text)
    print("running", case_path, "->", out, flush=True)
    done = subprocess.run([coupler, "run", case_path, "--out", out, "--overwrite"])
    if done.returncode != 0:
        sys.exit("coupler failed on %s (exit %d)" % (case_path, done.returncode))


def force_x(out):
    """(time, F_x on the prism) per window from the run's ledger."""
    with open(os.path.join(out, "ledger.csv")) as f:
        rows = list(csv.reader(f))
    col = rows[0].index("prism_fx")
    return [(float(r[1]), float(r[col])) for r in rows[1:]]


def svg_plot(path, series, title):
    """A line plot of `series` [(label, [(t, y)])] as SVG (no plotting library needed)."""
    w, h, left, bottom, top, right = 720, 440, 70, 50, 30, 170
    t_max = max(t for _, s in series for t, _ in s)
    y_max = max(max(y for _, y in s) for _, s in series)
    y_min = min(0.0, min(min(y for _, y in s) for _, s in series))
    sx = lambda t: left + (w - left - right) * t / t_max
    sy = lambda y: h - bottom - (h - bottom - top) * (y - y_min) / (y_max - y_min)
    colours = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#000000"]
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif" font-size="12">' % (w, h),
           '<rect width="100%" height="100%" fill="white"/>',
           '<text x="%d" y="18">%s</text>' % (left, title)]
    out.append('<line x1="%g" y1="%g" x2="%g" y2="%g" stroke="black"/>' % (left, sy(y_min), left, sy(y_max)))
    out.append('<line x1="%g" y1="%g" x2="%g" y2="%g" stroke="black"/>' % (left, sy(0), sx(t_max), sy(0)))
    for k in range(6):
        t = t_max * k / 5
        out.append('<text x="%g" y="%g" text-anchor="middle">%.2f</text>' % (sx(t), h - bottom + 18, t))
        y = y_min + (y_max - y_min) * k / 5
        out.append('<text x="%g" y="%g" text-anchor="end">%.3g</text>' % (left - 6, sy(y) + 4, y))
    out.append('<text x="%g" y="%g" text-anchor="middle">t [s]</text>' % ((left + w - right) / 2, h - 10))
    out.append('<text x="14" y="%g" transform="rotate(-90 14 %g)" text-anchor="middle">F_x / D [N/m]</text>' % (h / 2, h / 2))
    for i, (label, s) in enumerate(series):
        c = colours[i % len(colours)]
        dash = ' stroke-dasharray="6 3"' if label.startswith("resolved") else ""
        pts = " ".join("%.1f,%.1f" % (sx(t), sy(y)) for t, y in s)
        out.append('<polyline fill="none" stroke="%s" stroke-width="1.3"%s points="%s"/>' % (c, dash, pts))
        ly = top + 16 * i + 10
        out.append('<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="%s" stroke-width="2"%s/>' % (w - right + 10, ly, w - right + 35, ly, c, dash))
        out.append('<text x="%d" y="%d">%s</text>' % (w - right + 40, ly + 4, label))
    out.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(out))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--spacing", type=float, default=BASE_SPACING)
    ap.add_argument("--end", type=float, default=None)
    ap.add_argument("--out", default="out/prism-dam-break")
    ap.add_argument("--coupler", default="target/release/coupler")
    ap.add_argument("--widths", default=",".join("%g" % w for w in WIDTHS))
    ap.add_argument("--no-run", action="store_true")
    a = ap.parse_args()
    widths = [float(w) for w in a.widths.split(",")]
    os.makedirs(a.out, exist_ok=True)
    base = scaled(open(os.path.join(HERE, "case.toml")).read(), a.spacing, a.end)
    resolved = scaled(open(os.path.join(HERE, "resolved.toml")).read(), a.spacing, a.end)
    runs = [("w%g" % w, w, with_width(base, w)) for w in widths]
    runs.append(("resolved", RESOLVED_WIDTH, resolved))
    series = {}
    for name, width, text in runs:
        out = os.path.join(a.out, name)
        if not a.no_run:
            run(a.coupler, text, os.path.join(a.out, name + ".toml"), out)
        series[name] = [(t, f / width) for t, f in force_x(out)]

    names = [n for n, _, _ in runs]
    times = [t for t, _ in series[names[0]]]
    with open(os.path.join(a.out, "force-per-width.csv"), "w") as f:
        f.write("time," + ",".join("%s_fx_per_width" % n for n in names) + "\n")
        for k, t in enumerate(times):
            f.write("%.6g," % t + ",".join("%.6g" % series[n][k][1] if k < len(series[n]) else "" for n in names) + "\n")
    print("\nX force per unit width F_x/D [N/m], Δs = %g m:" % a.spacing)
    print("%10s %12s %10s %14s" % ("run", "peak F_x/D", "at t [s]", "impulse/D [N s/m]"))
    for n in names:
        s = series[n]
        tp, fp = max(s, key=lambda p: p[1])
        impulse = sum(0.5 * (s[k][1] + s[k - 1][1]) * (s[k][0] - s[k - 1][0]) for k in range(1, len(s)))
        print("%10s %12.4g %10.4f %14.4g" % (n, fp, tp, impulse))
    ref = series["resolved"]
    ref_peak = max(y for _, y in ref)
    for n in ["w%g" % w for w in widths if w >= 0.025]:
        s = series[n]
        m = min(len(s), len(ref))
        rms = math.sqrt(sum((s[k][1] - ref[k][1]) ** 2 for k in range(m)) / m)
        print("%s against resolved: peak ratio %.3f, RMS difference %.3g N/m = %.1f %% of the resolved peak"
              % (n, max(y for _, y in s) / ref_peak, rms, 100 * rms / ref_peak))
    svg_plot(os.path.join(a.out, "force-per-width.svg"),
             [("D = %s m" % n[1:], series[n]) for n in names if n != "resolved"]
             + [("resolved D = 0.05 m", series["resolved"])],
             "prism dam break: X force per unit width, particle size %g m" % a.spacing)
    print("wrote", os.path.join(a.out, "force-per-width.csv"), "and force-per-width.svg")


if __name__ == "__main__":
    main()
