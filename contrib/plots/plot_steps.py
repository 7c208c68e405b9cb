#!/usr/bin/python3
"""plot_steps.py — what the steps of a ballast run cost and got, against time, to a PNG.

Reads the steps.csv of one or more `ballast` runs (or their output directories) and draws
three panels sharing the time axis:
  1. NLGS sweeps per step (the cost),
  2. mean and largest overlap between grains (the error the solver left; log scale),
  3. the sleeper settlement (and, with --load, the load on the sleeper on a second axis).

Examples
  contrib/plots/plot_steps.py out/ballast/steps.csv -o steps.png
  contrib/plots/plot_steps.py out/stiffness_study/k1_s2006 out/stiffness_study/k1000_s2006 --every 5
  contrib/plots/plot_steps.py out/ballast --load --tmin 1.0 --tmax 1.2      (a few cycles, close up)

Needs python3 and matplotlib (Debian: apt-get install python3-matplotlib).
"""
import argparse
import csv
import os
import sys

NEEDED = ("time", "load", "settlement", "sweeps", "mean_overlap", "max_overlap")


def fail(message):
    print(f"plot_steps.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def resolve(path):
    if os.path.isdir(path):
        candidate = os.path.join(path, "steps.csv")
        if not os.path.isfile(candidate):
            fail(f"directory '{path}' has no steps.csv")
        return candidate
    if not os.path.isfile(path):
        fail(f"no such file: '{path}'")
    return path


def read_steps(path, every, tmin, tmax):
    """The NEEDED columns of a steps.csv as lists of floats, every `every`-th row in [tmin, tmax]."""
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader, None)
        if header is None:
            fail(f"'{path}' is empty")
        header = [h.strip() for h in header]
        missing = [c for c in NEEDED if c not in header]
        if missing:
            fail(f"'{path}' is not a ballast steps.csv: no column {', '.join(missing)}")
        index = {c: header.index(c) for c in NEEDED}
        data = {c: [] for c in NEEDED}
        kept = 0
        for line_no, row in enumerate(reader, start=2):
            if not row:
                continue
            try:
                t = float(row[index["time"]])
                if (tmin is not None and t < tmin) or (tmax is not None and t > tmax):
                    continue
                if kept % every == 0:
                    for c in NEEDED:
                        data[c].append(float(row[index[c]]))
                kept += 1
            except (ValueError, IndexError):
                fail(f"{path}:{line_no}: malformed row")
    if not data["time"]:
        fail(f"'{path}' has no rows" + (" in the --tmin/--tmax window" if tmin is not None or tmax is not None else ""))
    return data


def main():
    p = argparse.ArgumentParser(
        description="Plot a ballast run's steps.csv (sweeps, overlaps, settlement against time) to a PNG.",
        epilog="Directories are accepted for their steps.csv; several runs are overlaid.")
    p.add_argument("inputs", nargs="+", metavar="CSV_OR_DIR", help="steps.csv files or ballast output directories")
    p.add_argument("-o", "--output", default="steps.png", help="PNG file to write (default: %(default)s)")
    p.add_argument("--labels", help="comma-separated legend labels, one per input")
    p.add_argument("--every", type=int, default=1, help="plot every N-th row (long runs; default: %(default)s)")
    p.add_argument("--tmin", type=float, help="first time to plot (s)")
    p.add_argument("--tmax", type=float, help="last time to plot (s)")
    p.add_argument("--load", action="store_true", help="also draw the load on the sleeper (N) in the settlement panel")
    p.add_argument("--title", default=None, help="figure title")
    args = p.parse_args()
    if args.every < 1:
        fail("--every must be >= 1")
    paths = [resolve(i) for i in args.inputs]
    labels = args.labels.split(",") if args.labels else [os.path.basename(os.path.dirname(os.path.abspath(x))) for x in paths]
    if len(labels) != len(paths):
        fail(f"--labels has {len(labels)} names for {len(paths)} inputs")
    runs = [read_steps(x, args.every, args.tmin, args.tmax) for x in paths]

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax_sw, ax_ov, ax_st) = plt.subplots(3, 1, sharex=True, figsize=(9, 8), dpi=120)
    for d, label in zip(runs, labels):
        t = d["time"]
        ax_sw.plot(t, d["sweeps"], linewidth=0.7, label=label)
        line, = ax_ov.plot(t, d["max_overlap"], linewidth=0.7, label=f"{label}: largest")
        # The mean overlap can be 0 (no contact): left out of the log scale.
        tm = [x for x, m in zip(t, d["mean_overlap"]) if m > 0]
        ax_ov.plot(tm, [m for m in d["mean_overlap"] if m > 0], linewidth=0.7, linestyle="--",
                   color=line.get_color(), label=f"{label}: mean")
        ax_st.plot(t, [1e3 * s for s in d["settlement"]], linewidth=0.8, label=label)
    if args.load:
        ax_load = ax_st.twinx()
        for d in runs:
            ax_load.plot(d["time"], d["load"], color="0.6", linewidth=0.5)
        ax_load.set_ylabel("load on the sleeper (N, grey)")
    ax_sw.set_ylabel("NLGS sweeps per step")
    ax_ov.set_ylabel("overlap (m)")
    if any(v > 0 for d in runs for v in d["max_overlap"]):
        ax_ov.set_yscale("log")
    ax_st.set_ylabel("settlement (mm)")
    ax_st.set_xlabel("time (s)")
    for ax in (ax_sw, ax_ov, ax_st):
        ax.grid(True, alpha=0.3)
    ax_sw.legend(fontsize="small")
    ax_ov.legend(fontsize="small", ncol=2)
    fig.suptitle(args.title or "Ballast run, step by step")
    fig.tight_layout()
    try:
        fig.savefig(args.output)
    except OSError as e:
        fail(f"cannot write '{args.output}': {e.strerror}")
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
