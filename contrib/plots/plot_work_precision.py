#!/usr/bin/python3
"""plot_work_precision.py — work against precision of the contact solvers, to a PNG.

Reads the problems.csv of a `solver_comparison` run (or its output directory) and draws one
panel per problem: solve time (s) against the residual reached (natural-map residual / ||q||),
both on log scales. One colour per solver setting (NLGS with each convergence policy,
NEWTON_AC), the points of one setting joined in the order of its tolerances; a filled marker
reached its tolerance (residual_q <= tol), a hollow one did not (stopped by its own criteria,
the time cap or the iteration cap). Down and to the left is better.

Examples
  contrib/plots/plot_work_precision.py out/solver_comparison -o work_precision.png
  contrib/plots/plot_work_precision.py out/solver_comparison/problems.csv --problems siconos_2020,column_1000

Needs python3 and matplotlib (Debian: apt-get install python3-matplotlib).
"""
import argparse
import csv
import math
import os
import sys

NEEDED = ("problem", "contacts", "solver", "policy", "tol", "iterations", "residual_q", "seconds", "reached")


def fail(message):
    print(f"plot_work_precision.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def resolve(path):
    if os.path.isdir(path):
        candidate = os.path.join(path, "problems.csv")
        if not os.path.isfile(candidate):
            fail(f"directory '{path}' has no problems.csv")
        return candidate
    if not os.path.isfile(path):
        fail(f"no such file: '{path}'")
    return path


def read_rows(path):
    """The rows of problems.csv as dicts (numbers converted), in file order."""
    rows = []
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        if reader.fieldnames is None:
            fail(f"'{path}' is empty")
        missing = [c for c in NEEDED if c not in reader.fieldnames]
        if missing:
            fail(f"'{path}' is not a solver_comparison problems.csv: no column {', '.join(missing)}")
        for line_no, row in enumerate(reader, start=2):
            try:
                rows.append({
                    "problem": row["problem"], "contacts": int(row["contacts"]),
                    "setting": row["solver"] if row["solver"] != "NLGS" else f"NLGS {row['policy']}",
                    "tol": float(row["tol"]), "residual": float(row["residual_q"]),
                    "seconds": float(row["seconds"]), "reached": row["reached"].strip() == "1"})
            except (ValueError, KeyError):
                fail(f"{path}:{line_no}: malformed row")
    if not rows:
        fail(f"'{path}' has no rows")
    return rows


def main():
    p = argparse.ArgumentParser(description="Plot a solver_comparison problems.csv (time against residual) to a PNG.")
    p.add_argument("input", metavar="CSV_OR_DIR", help="problems.csv or a solver_comparison output directory")
    p.add_argument("-o", "--output", default="work_precision.png", help="PNG file to write (default: %(default)s)")
    p.add_argument("--problems", help="comma-separated problem names to draw (default: all, in file order)")
    p.add_argument("--title", default=None, help="figure title")
    args = p.parse_args()
    rows = read_rows(resolve(args.input))
    names = []
    for r in rows:
        if r["problem"] not in names:
            names.append(r["problem"])
    if args.problems:
        wanted = args.problems.split(",")
        unknown = [n for n in wanted if n not in names]
        if unknown:
            fail(f"no problem {', '.join(unknown)} in the file (it has {', '.join(names)})")
        names = wanted
    settings = []
    for r in rows:
        if r["setting"] not in settings:
            settings.append(r["setting"])

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cols = min(3, len(names))
    nrows = math.ceil(len(names) / cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(4.2 * cols, 3.4 * nrows), dpi=110, squeeze=False)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    floor = 1e-16  # a zero residual or time still shows, at the bottom / left
    for k, name in enumerate(names):
        ax = axes[k // cols][k % cols]
        contacts = next(r["contacts"] for r in rows if r["problem"] == name)
        for s, setting in enumerate(settings):
            pts = sorted((r for r in rows if r["problem"] == name and r["setting"] == setting), key=lambda r: -r["tol"])
            if not pts:
                continue
            colour = colours[s % len(colours)]
            x = [max(r["seconds"], floor) for r in pts]
            y = [max(r["residual"], floor) for r in pts]
            ax.plot(x, y, color=colour, linewidth=0.8, label=setting)
            for r, xi, yi in zip(pts, x, y):
                ax.plot([xi], [yi], marker="o", markersize=5, color=colour,
                        markerfacecolor=colour if r["reached"] else "none")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(f"{name} ({contacts} contacts)", fontsize="medium")
        ax.set_xlabel("solve time (s)")
        ax.set_ylabel("residual / ||q||")
        ax.grid(True, which="major", alpha=0.3)
    for k in range(len(names), nrows * cols):
        axes[k // cols][k % cols].axis("off")
    axes[0][0].legend(fontsize="small")
    fig.suptitle(args.title or "Work against precision, from r = 0 (filled: tolerance reached)")
    fig.tight_layout()
    try:
        fig.savefig(args.output)
    except OSError as e:
        fail(f"cannot write '{args.output}': {e.strerror}")
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
