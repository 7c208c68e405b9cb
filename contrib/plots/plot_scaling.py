#!/usr/bin/python3
"""plot_scaling.py — settled step cost against the number of grains, log-log, with fitted slopes.

Reads the CSV written by `scaling --csv` (one row per run; several runs per size are reduced to
their median) and draws two panels:
  1. the CPU time per step and its parts (detection, NLGS solve, the rest) against N, log-log,
     each with its least-squares slope d log(cost) / d log(N) in the legend (1 = linear);
  2. the NLGS sweeps per step and the solve cost per grain per sweep against N.
It prints the per-size medians and the slopes, and exits with status 1 when --max-slope is given
and the step's slope exceeds it (status 2 on bad input).

Examples
  contrib/plots/plot_scaling.py tests/bench/results/2core-shared-vm/scaling.csv -o scaling.png
  contrib/plots/plot_scaling.py out/scaling.csv --label tiled700 --max-slope 1.1

Needs python3 and matplotlib (Debian: apt-get install python3-matplotlib; use /usr/bin/python3).
"""
import argparse
import csv
import math
import statistics
import sys

PARTS = (("step_ms", "step"), ("detect_ms", "detection"), ("solve_ms", "NLGS solve"), ("rest_ms", "the rest"))


def fail(message):
    print(f"plot_scaling.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def slope(xs, ys):
    """Least-squares slope of log(y) against log(x); None with fewer than two sizes or y <= 0."""
    pts = [(math.log(x), math.log(y)) for x, y in zip(xs, ys) if x > 0 and y > 0]
    if len(pts) < 2:
        return None
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    return sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx if sxx > 0 else None


def load(path, label):
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        fail(f"cannot read {path}: {e.strerror}")
    needed = ["grains", "label"] + [p[0] for p in PARTS] + ["median_sweeps", "solve_ns_per_grain_sweep", "contacts_per_grain"]
    if not rows:
        fail(f"{path} has no data row")
    missing = [k for k in needed if k not in rows[0]]
    if missing:
        fail(f"{path} lacks the column(s) {', '.join(missing)} (is it a `scaling --csv` file?)")
    if label is not None:
        rows = [r for r in rows if r["label"] == label]
        if not rows:
            fail(f"{path} has no row with label '{label}'")
    by_n = {}
    for r in rows:
        try:
            by_n.setdefault(int(r["grains"]), []).append({k: float(r[k]) for k in needed if k != "label"})
        except ValueError:
            fail(f"{path}: a row has a non-numeric value: {r}")
    sizes = sorted(by_n)
    med = {k: [statistics.median(x[k] for x in by_n[n]) for n in sizes] for k in needed if k not in ("label", "grains")}
    return sizes, med, {n: len(by_n[n]) for n in sizes}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("csv", help="CSV written by `scaling --csv`")
    ap.add_argument("-o", "--output", default="scaling.png", help="PNG to write (default scaling.png)")
    ap.add_argument("--label", help="only the rows with this label")
    ap.add_argument("--title", default="", help="title prefix (e.g. the machine)")
    ap.add_argument("--max-slope", type=float, help="exit 1 when the step's slope exceeds this")
    ap.add_argument("--no-plot", action="store_true", help="print the table and the slopes only")
    a = ap.parse_args()
    sizes, med, runs = load(a.csv, a.label)

    print(f"{'grains':>8} {'runs':>4} {'contacts/gr':>11} {'sweeps':>6} {'step ms':>9} {'detect ms':>9} {'solve ms':>9} "
          f"{'rest ms':>9} {'us/step/gr':>10} {'ns/gr/sweep':>11}")
    for i, n in enumerate(sizes):
        print(f"{n:>8} {runs[n]:>4} {med['contacts_per_grain'][i]:>11.3f} {med['median_sweeps'][i]:>6.0f} "
              f"{med['step_ms'][i]:>9.3f} {med['detect_ms'][i]:>9.3f} {med['solve_ms'][i]:>9.3f} {med['rest_ms'][i]:>9.3f} "
              f"{1e3 * med['step_ms'][i] / n:>10.4f} {med['solve_ns_per_grain_sweep'][i]:>11.3f}")
    slopes = {key: slope(sizes, med[key]) for key, _ in PARTS}
    slopes["sweeps"] = slope(sizes, med["median_sweeps"])
    slopes["per_sweep"] = slope(sizes, med["solve_ns_per_grain_sweep"])
    fmt = lambda s: "n/a" if s is None else f"{s:.3f}"
    print("slopes d log(cost) / d log(N): " + ", ".join(f"{name} {fmt(slopes[key])}" for key, name in PARTS) +
          f"; sweeps per step {fmt(slopes['sweeps'])}; NLGS cost per grain per sweep {fmt(slopes['per_sweep'])}")

    if not a.no_plot:
        try:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError:
            fail("matplotlib is missing (Debian: apt-get install python3-matplotlib; run with /usr/bin/python3)")
        fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
        for (key, name), marker in zip(PARTS, "osD^"):
            ax1.loglog(sizes, med[key], marker=marker, label=f"{name} (slope {fmt(slopes[key])})")
        ref = med["step_ms"][0]
        ax1.loglog(sizes, [ref * n / sizes[0] for n in sizes], "k:", label="slope 1")
        ax1.set_xlabel("grains N")
        ax1.set_ylabel("CPU time per settled step (ms)")
        ax1.set_title(f"{a.title} step cost".strip())
        ax1.grid(True, which="both", alpha=0.3)
        ax1.legend(fontsize=8)
        ax2.semilogx(sizes, med["median_sweeps"], "o-", label=f"sweeps per step (slope {fmt(slopes['sweeps'])})")
        ax2.set_xlabel("grains N")
        ax2.set_ylabel("NLGS sweeps per step")
        ax2.grid(True, which="both", alpha=0.3)
        ax3 = ax2.twinx()
        ax3.semilogx(sizes, med["solve_ns_per_grain_sweep"], "s--", color="C3",
                     label=f"ns per grain per sweep (slope {fmt(slopes['per_sweep'])})")
        ax3.set_ylabel("NLGS ns per grain per sweep")
        ax3.set_ylim(bottom=0)
        ax2.set_ylim(bottom=0)
        h1, l1 = ax2.get_legend_handles_labels()
        h2, l2 = ax3.get_legend_handles_labels()
        ax2.legend(h1 + h2, l1 + l2, fontsize=8, loc="lower right")
        ax2.set_title("NLGS: sweeps and cost per sweep")
        fig.tight_layout()
        fig.savefig(a.output, dpi=110)
        print(f"wrote {a.output}")
    if a.max_slope is not None and slopes["step_ms"] is not None and slopes["step_ms"] > a.max_slope:
        print(f"step cost slope {slopes['step_ms']:.3f} > {a.max_slope}", file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
