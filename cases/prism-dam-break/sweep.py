"""S2 §5(1)-(2): the prism dam break for the seven prism widths (unresolved drag coupling) and
the resolved 0.05 m prism, the X force per unit width against time of each, and their plot.

usage: python3 cases/prism-dam-break/sweep.py [--spacing DS] [--end T] [--out DIR]
                                               [--coupler PATH] [--widths W,W,...] [--no-run]
                                               [--method isph] [--gradient NAME]

--spacing: particle size (default 0.005, S2 Table 1); the time steps scale with it (Δt = 2e-4 s
at 5 mm: c Δt/Δs = 0.6) and the water column keeps its size (so 0.01 gives 16 000 particles).
--method isph: the fluid as S2 ran it, ISPH (its default settings) at S2's Δt = 5e-4 s at 5 mm
(Table 1), scaled alike, with the coupling window and the frame's step the same.
--gradient NAME: with --method isph, the case key isph.pressure_gradient ("corrected-difference"
is S2-8's own gradient; default: ISPH's default, "conservative").
Writes into DIR (default out/prism-dam-break): one coupler run per width (w0.0005/, …) and
resolved/, force-per-width.csv (time, F_x/D of each run), force-per-width.png (drawn by
`coupler plot`), and prints each
run's peak and the two widest widths against the resolved force. --no-run only re-reads them.
Only the Python standard library is used (the plot is the coupler's).
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
BASE_STEP_EMPS = 2.0e-4
BASE_STEP_ISPH = 5.0e-4


def scaled(text, spacing, end, method, gradient=None):
    """The case text at particle size `spacing` (time steps scaled alike), end time `end` and
    fluid method `method` ("emps": the case's; "isph": S2's method and Δt, with the pressure
    gradient `gradient` or ISPH's default)."""
    step = {"emps": BASE_STEP_EMPS, "isph": BASE_STEP_ISPH}[method] * spacing / BASE_SPACING
    if method == "isph":
        settings = 'method = "isph"'
        if gradient:
            settings += '\nisph = { pressure_gradient = "%s" }' % gradient
        text = text.replace("sound_speed = 15.0", settings)
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


def png_plot(coupler, csv_path, names, spacing):
    """All series of `csv_path` on one PNG, the resolved run dashed, drawn by `coupler plot`
    (the report's plotting; what was drawn goes beside it as force-per-width.plot.csv)."""
    png = csv_path[:-len(".csv")] + ".png"
    args = [coupler, "plot", csv_path, "--png", png,
            "--title", "prism dam break: X force per unit width, particle size %g m" % spacing,
            "--y-label", "F_x / D [N/m]"]
    args += ["--dashed", "resolved_fx_per_width"] if "resolved" in names else []
    done = subprocess.run(args)
    if done.returncode != 0:
        sys.exit("coupler plot failed on %s (exit %d)" % (csv_path, done.returncode))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--spacing", type=float, default=BASE_SPACING)
    ap.add_argument("--end", type=float, default=None)
    ap.add_argument("--out", default="out/prism-dam-break")
    ap.add_argument("--coupler", default="target/release/coupler")
    ap.add_argument("--widths", default=",".join("%g" % w for w in WIDTHS))
    ap.add_argument("--no-run", action="store_true")
    ap.add_argument("--method", choices=["emps", "isph"], default="emps")
    ap.add_argument("--gradient", choices=["conservative", "corrected-difference", "symmetric"], default=None)
    a = ap.parse_args()
    widths = [float(w) for w in a.widths.split(",")]
    os.makedirs(a.out, exist_ok=True)
    base = scaled(open(os.path.join(HERE, "case.toml")).read(), a.spacing, a.end, a.method, a.gradient)
    resolved = scaled(open(os.path.join(HERE, "resolved.toml")).read(), a.spacing, a.end, a.method, a.gradient)
    # the unresolved cases name resolved.toml as their [reference] case: it must exist first
    with open(os.path.join(a.out, "resolved.toml"), "w") as f:
        f.write(resolved)
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
    png_plot(a.coupler, os.path.join(a.out, "force-per-width.csv"), names, a.spacing)
    print("wrote", os.path.join(a.out, "force-per-width.csv"), "and force-per-width.png")


if __name__ == "__main__":
    main()
