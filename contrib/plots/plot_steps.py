#!/usr/bin/python3
"""plot_steps.py — what the steps of a run cost and got, against time, to a PNG.

Reads the steps.csv of one or more `ballast` or `deposit` runs (or their output directories)
and draws three panels sharing the time axis:
  1. NLGS sweeps per step (the cost),
  2. mean and largest overlap between grains (the error the solver left; log scale),
  3. ballast runs: the sleeper settlement (and, with --load, the load on the sleeper on a
     second axis); deposit runs (no sleeper): the rms grain speed (log scale).
The panel 3 quantity must be the same for every input: ballast and deposit runs are not
overlaid in one figure.

Examples
  contrib/plots/plot_steps.py out/ballast/steps.csv -o steps.png
  contrib/plots/plot_steps.py out/stiffness_study/k1_s2006 out/stiffness_study/k1000_s2006 --every 5
  contrib/plots/plot_steps.py out/ballast --load --tmin 1.0 --tmax 1.2      (a few cycles, close up)
  contrib/plots/plot_steps.py out/deposit -o deposit_steps.png              (a deposit: rms speed)

Needs python3 and matplotlib (Debian: apt-get install python3-matplotlib).
"""
import argparse
import csv
import os
import sys

NEEDED = ("time", "sweeps", "mean_overlap", "max_overlap")  # in ballast's and deposit's steps.csv
OPTIONAL = ("load", "settlement", "rms_speed")  # ballast: load, settlement (and rms_speed); deposit: rms_speed


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
    """The NEEDED and present OPTIONAL columns of a steps.csv as lists of floats, every
    `every`-th row in [tmin, tmax]."""
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader, None)
        if header is None:
            fail(f"'{path}' is empty")
        header = [h.strip() for h in header]
        missing = [c for c in NEEDED if c not in header]
        if missing:
            fail(f"'{path}' is not a ballast or deposit steps.csv: no column {', '.join(missing)}")
        columns = NEEDED + tuple(c for c in OPTIONAL if c in header)
        index = {c: header.index(c) for c in columns}
        data = {c: [] for c in columns}
        kept = 0
        for line_no, row in enumerate(reader, start=2):
            if not row:
                continue
            try:
                t = float(row[index["time"]])
                if (tmin is not None and t < tmin) or (tmax is not None and t > tmax):
                    continue
                if kept % every == 0:
                    for c in columns:
                        data[c].append(float(row[index[c]]))
                kept += 1
            except (ValueError, IndexError):
                fail(f"{path}:{line_no}: malformed row")
    if not data["time"]:
        fail(f"'{path}' has no rows" + (" in the --tmin/--tmax window" if tmin is not None or tmax is not None else ""))
    return data


def main():
    p = argparse.ArgumentParser(
        description="Plot a ballast or deposit run's steps.csv (sweeps, overlaps, and settlement or rms speed, "
                    "against time) to a PNG.",
        epilog="Directories are accepted for their steps.csv; several runs are overlaid.")
    p.add_argument("inputs", nargs="+", metavar="CSV_OR_DIR", help="steps.csv files or ballast / deposit output directories")
    p.add_argument("-o", "--output", default="steps.png", help="PNG file to write (default: %(default)s)")
    p.add_argument("--labels", help="comma-separated legend labels, one per input")
    p.add_argument("--every", type=int, default=1, help="plot every N-th row (long runs; default: %(default)s)")
    p.add_argument("--tmin", type=float, help="first time to plot (s)")
    p.add_argument("--tmax", type=float, help="last time to plot (s)")
    p.add_argument("--load", action="store_true", help="also draw the load on the sleeper (N/m) in the settlement panel (ballast runs)")
    p.add_argument("--title", default=None, help="figure title")
    args = p.parse_args()
    if args.every < 1:
        fail("--every must be >= 1")
    paths = [resolve(i) for i in args.inputs]
    labels = args.labels.split(",") if args.labels else [os.path.basename(os.path.dirname(os.path.abspath(x))) for x in paths]
    if len(labels) != len(paths):
        fail(f"--labels has {len(labels)} names for {len(paths)} inputs")
    runs = [read_steps(x, args.every, args.tmin, args.tmax) for x in paths]
    if all("settlement" in d for d in runs):
        third = "settlement"
    elif not any("settlement" in d for d in runs) and all("rms_speed" in d for d in runs):
        third = "rms_speed"
    else:
        fail("the inputs mix ballast runs (settlement) and deposit runs (no settlement): plot them separately")
    if args.load and not all("load" in d for d in runs):
        fail("--load needs a load column (ballast runs); a deposit's steps.csv has none")

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
        if third == "settlement":
            ax_st.plot(t, [1e3 * s for s in d["settlement"]], linewidth=0.8, label=label)
        else:
            ax_st.plot(t, d["rms_speed"], linewidth=0.8, label=label)
    if args.load:
        ax_load = ax_st.twinx()
        for d in runs:
            ax_load.plot(d["time"], d["load"], color="0.6", linewidth=0.5)
        ax_load.set_ylabel("load on the sleeper (N/m, grey)")
    ax_sw.set_ylabel("NLGS sweeps per step")
    ax_ov.set_ylabel("overlap (m)")
    if any(v > 0 for d in runs for v in d["max_overlap"]):
        ax_ov.set_yscale("log")
    if third == "settlement":
        ax_st.set_ylabel("settlement (mm)")
    else:
        ax_st.set_ylabel("rms grain speed (m/s)")
        if any(v > 0 for d in runs for v in d["rms_speed"]):
            ax_st.set_yscale("log")
    ax_st.set_xlabel("time (s)")
    for ax in (ax_sw, ax_ov, ax_st):
        ax.grid(True, alpha=0.3)
    ax_sw.legend(fontsize="small")
    ax_ov.legend(fontsize="small", ncol=2)
    fig.suptitle(args.title or ("Ballast run, step by step" if third == "settlement" else "Deposit, step by step"))
    fig.tight_layout()
    try:
        fig.savefig(args.output)
    except OSError as e:
        fail(f"cannot write '{args.output}': {e.strerror}")
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
