#!/usr/bin/python3
"""plot_settlement.py — the sleeper settlement against the loading cycle, to a PNG.

Reads either
  * one or more cycles.csv of `ballast` runs (or their output directories): one curve each,
    the settlement at the smallest load of every cycle (--column settlement_max_load for the
    largest load), or the blocks CSV `cycle_blocks.py --csv` wrote of such a run: its
    settlement at the last cycle of every block (kept when a run's cycles are not), or
  * a settlement_by_k.csv of `stiffness_study` (or its study directory): for every k factor
    the mean settlement over the samples, with a band of ± one standard deviation
    (the paper's Fig. 11, Saussine et al. 2006).

Examples
  contrib/plots/plot_settlement.py out/ballast/cycles.csv -o settlement.png
  contrib/plots/plot_settlement.py out/stiffness_study/k1_s2006 out/stiffness_study/k1000_s2006
  contrib/plots/plot_settlement.py out/stiffness_study/settlement_by_k.csv -o fig11.png
  contrib/plots/plot_settlement.py out/long_run --break 3000   (and its change of slope after cycle 3000)
  contrib/plots/plot_settlement.py docs/results/long20000_s2006_blocks.csv --break 3000

Needs python3 and matplotlib (Debian: apt-get install python3-matplotlib).
"""
import argparse
import csv
import os
import sys


def fail(message):
    print(f"plot_settlement.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def resolve(path):
    """A CSV file, or the cycles.csv / settlement_by_k.csv of a directory."""
    if os.path.isdir(path):
        for name in ("settlement_by_k.csv", "cycles.csv"):
            candidate = os.path.join(path, name)
            if os.path.isfile(candidate):
                return candidate
        fail(f"directory '{path}' has neither settlement_by_k.csv nor cycles.csv")
    if not os.path.isfile(path):
        fail(f"no such file: '{path}'")
    return path


def read_columns(path):
    """Header → list of floats per column (empty cells become None)."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        fail(f"'{path}' is empty")
    header = [h.strip() for h in rows[0]]
    columns = {h: [] for h in header}
    for line_no, row in enumerate(rows[1:], start=2):
        if not row:
            continue
        if len(row) < len(header):
            fail(f"{path}:{line_no}: {len(row)} cells, the header has {len(header)}")
        for h, cell in zip(header, row):
            cell = cell.strip()
            try:
                columns[h].append(float(cell) if cell else None)
            except ValueError:
                fail(f"{path}:{line_no}: '{cell}' in column '{h}' is not a number")
    return header, columns


def label_of(path):
    """k100_s2006 for out/study/k100_s2006/cycles.csv; the path otherwise."""
    parent = os.path.basename(os.path.dirname(os.path.abspath(path)))
    return parent or path


BLOCK_COLUMNS = ("first_cycle", "last_cycle", "settlement_mm")


def curve(path, column):
    """A run's (cycle, settlement in m) points: every cycle of a cycles.csv, or the last cycle of
    every block of a cycle_blocks.py CSV (whose settlement is in mm, at the smallest load)."""
    _, cols = read_columns(path)
    if all(h in cols for h in BLOCK_COLUMNS):
        if column != "settlement_min_load":
            fail(f"'{path}' is a blocks CSV: it holds the settlement at the smallest load only, not '{column}'")
        cycles, values = cols["last_cycle"], [None if s is None else 1e-3 * s for s in cols["settlement_mm"]]
    else:
        for needed in ("cycle", column):
            if needed not in cols:
                fail(f"'{path}' has no column '{needed}' (a ballast cycles.csv has: cycle, settlement_min_load, ...;"
                     f" a blocks CSV: {', '.join(BLOCK_COLUMNS)}, ...)")
        cycles, values = cols["cycle"], cols[column]
    points = [(c, s) for c, s in zip(cycles, values) if c is not None and s is not None]
    if not points:
        fail(f"'{path}' has no rows")
    return points


def plot_runs(ax, paths, column, labels, scale):
    for i, path in enumerate(paths):
        points = curve(path, column)
        ax.plot([c for c, _ in points], [scale * s for _, s in points], marker="." if len(points) < 60 else None,
                label=labels[i] if labels else label_of(path))


def plot_breaks(ax, paths, column, scale, first):
    """Each run's best single change of slope from cycle `first` on (cycle_blocks.py --break),
    dashed over its curve, in the curve's colour; a blocks CSV's is fitted to its blocks' points."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from cycle_blocks import slope_break
    for path, line in zip(paths, ax.get_lines()):
        rows = [{"cycle": c, column: s} for c, s in curve(path, column)]
        b = slope_break(rows, column, first, int(rows[-1]["cycle"]))
        if b is None:
            fail(f"'{path}': too few points from cycle {first} on for two slopes (at least 21)")
        c0, at = b["break_cycle"], b["at_break_mm"]
        xs = [b["first_cycle"], c0, b["last_cycle"]]
        ys = [at + b["slope_before"] * (xs[0] - c0) * 1e-3, at, at + b["slope_after"] * (xs[2] - c0) * 1e-3]
        ax.plot(xs, [scale * 1e-3 * y for y in ys], linestyle="--", color=line.get_color(), linewidth=1.2,
                label=f"two slopes: {b['slope_before']:.2f} / {b['slope_after']:.2f} mm per 1000 cycles, break at {c0}")


def plot_by_k(ax, path, scale):
    header, cols = read_columns(path)
    ks = [h[len("mean_k"):] for h in header if h.startswith("mean_k")]
    if "cycle" not in cols or not ks:
        fail(f"'{path}' is not a settlement_by_k.csv (expected columns cycle, mean_k<F>, std_k<F>, ...)")
    for k in ks:
        if f"std_k{k}" not in cols:
            fail(f"'{path}' has mean_k{k} but no std_k{k}")
        rows = [(c, m, s) for c, m, s in zip(cols["cycle"], cols[f"mean_k{k}"], cols[f"std_k{k}"])
                if c is not None and m is not None and s is not None]
        if not rows:
            continue
        cycle = [r[0] for r in rows]
        mean = [scale * r[1] for r in rows]
        std = [scale * r[2] for r in rows]
        line, = ax.plot(cycle, mean, label=f"k$_N$ × {k}")
        ax.fill_between(cycle, [m - s for m, s in zip(mean, std)], [m + s for m, s in zip(mean, std)],
                        color=line.get_color(), alpha=0.2, linewidth=0)


def main():
    p = argparse.ArgumentParser(
        description="Plot the ballast settlement against the loading cycle (cycles.csv files, or the "
                    "settlement_by_k.csv of a stiffness study with mean ± std bands) to a PNG.",
        epilog="Directories are accepted for their cycles.csv or settlement_by_k.csv.")
    p.add_argument("inputs", nargs="+", metavar="CSV_OR_DIR",
                   help="cycles.csv or blocks CSVs (one curve each) or one settlement_by_k.csv")
    p.add_argument("-o", "--output", default="settlement.png", help="PNG file to write (default: %(default)s)")
    p.add_argument("--column", default="settlement_min_load",
                   help="cycles.csv column to plot (default: %(default)s; or settlement_max_load, lateral_displacement, ...)")
    p.add_argument("--labels", help="comma-separated legend labels for the cycles.csv curves")
    p.add_argument("--title", default=None, help="plot title")
    p.add_argument("--metres", action="store_true", help="plot in m instead of mm")
    p.add_argument("--logx", action="store_true", help="logarithmic cycle axis")
    p.add_argument("--break", dest="break_from", type=int, metavar="FROM",
                   help="draw each run's best single change of slope from cycle FROM on (cycle_blocks.py --break)")
    args = p.parse_args()

    paths = [resolve(i) for i in args.inputs]
    by_k = [x for x in paths if os.path.basename(x) == "settlement_by_k.csv" or _is_by_k(x)]
    if by_k and len(paths) > 1:
        fail("give one settlement_by_k.csv alone, or cycles.csv and blocks CSVs only")
    labels = args.labels.split(",") if args.labels else None
    if labels and len(labels) != len(paths):
        fail(f"--labels has {len(labels)} names for {len(paths)} inputs")
    if by_k and args.break_from is not None:
        fail("--break draws a run's change of slope: give cycles.csv files, not a settlement_by_k.csv")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    scale, unit = (1.0, "m") if args.metres else (1e3, "mm")
    fig, ax = plt.subplots(figsize=(8, 5), dpi=120)
    if by_k:
        plot_by_k(ax, paths[0], scale)
        ax.set_ylabel(f"mean settlement at the smallest load ({unit}), ± 1 std")
        ax.set_title(args.title or "Settlement by sublayer stiffness (mean over samples)")
    else:
        plot_runs(ax, paths, args.column, labels, scale)
        if args.break_from is not None:
            plot_breaks(ax, paths, args.column, scale, args.break_from)
        what = "settlement" if args.column.startswith("settlement") else args.column.replace("_", " ")
        load = {"settlement_min_load": " at the smallest load", "settlement_max_load": " at the largest load"}.get(args.column, "")
        ax.set_ylabel(f"{what}{load} ({unit})")
        ax.set_title(args.title or "Sleeper settlement")
    ax.set_xlabel("loading cycle")
    if args.logx:
        ax.set_xscale("log")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    try:
        fig.savefig(args.output)
    except OSError as e:
        fail(f"cannot write '{args.output}': {e.strerror}")
    print(f"wrote {args.output}")


def _is_by_k(path):
    with open(path, newline="") as f:
        first = f.readline()
    return "mean_k" in first and "settlement_min_load" not in first


if __name__ == "__main__":
    main()
