#!/usr/bin/python3
"""plot_accuracy.py — the PNGs of an `accuracy_study` folder (issue #10; paper §3.2–3.3).

Reads DIR/table.csv, DIR/trade.csv and DIR/runs.csv (each row's ballast folder, whose
cycles.csv holds the overlaps cycle by cycle) and draws, by study:
  criterion  overlap_vs_time.png  mean, largest and cumulated (summed) overlap against the cycle,
                                  one line per convergence setting (the paper's Fig. 2)
  step       step_overlap.png     mean and largest overlap against time, one line per step
                                  length, vertical and 5° inclined load (Figs. 3–4)
  trade      trade.png            processor time per cycle against the error: mean overlap, and
                                  settlement difference from the tightest setting of the family;
                                  NLGS circles, NEWTON_AC squares, the sample spread as a line
Every study also draws trade.png from its own rows.

Example
  contrib/plots/plot_accuracy.py out/accuracy/trade --study trade

Needs python3 and matplotlib (Debian: apt-get install python3-matplotlib).
"""
import argparse
import csv
import math
import os
import sys


def fail(message):
    print(f"plot_accuracy.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_csv(path):
    if not os.path.isfile(path):
        fail(f"no such file: '{path}'")
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def number(text):
    try:
        v = float(text)
    except (TypeError, ValueError):
        return math.nan
    return v


def cycles_of(run):
    path = os.path.join(run, "cycles.csv")
    if not os.path.isfile(path):
        return None
    rows = read_csv(path)
    cols = {k: [number(r.get(k)) for r in rows] for k in ("cycle", "time", "mean_overlap", "max_overlap", "total_overlap")}
    return cols


def overlap_vs_time(plt, directory, runs):
    fig, axes = plt.subplots(1, 3, figsize=(16, 5))
    for r in runs:
        if r["role"] == "spread":
            continue
        c = cycles_of(r["run"])
        if not c:
            continue
        style = "--" if r["setting"].startswith("NEWTON") else "-"
        for ax, key in zip(axes, ("mean_overlap", "max_overlap", "total_overlap")):
            ax.plot(c["cycle"], [1e6 * v for v in c[key]], style, label=r["setting"])
    for ax, title in zip(axes, ("mean overlap (µm)", "largest overlap (µm)", "cumulated overlap: sum over contacts (µm)")):
        ax.set_xlabel("cycle")
        ax.set_title(title)
        ax.set_yscale("log")
        ax.grid(True, alpha=0.3)
    axes[2].legend(fontsize=7, loc="best")
    fig.tight_layout()
    out = os.path.join(directory, "overlap_vs_time.png")
    fig.savefig(out, dpi=80)
    print(f"plot_accuracy.py: wrote {out}")


def step_overlap(plt, directory, runs):
    fig, axes = plt.subplots(2, 2, figsize=(13, 9), sharex=True)
    cmap = plt.get_cmap("viridis")
    # a step row is labelled "dt <dt> vertical|inclined 5"; the reference run is dt 2e-4 vertical
    def where(r):
        if r["role"] == "reference":
            return 2e-4, 0
        return float(r["setting"].split()[1]), 0 if "vertical" in r["setting"] else 1
    steps = [r for r in runs if r["role"] == "reference" or (r["role"] == "step" and r["setting"].startswith("dt "))]
    if not any(r["role"] == "step" for r in steps):
        return
    dts = sorted({where(r)[0] for r in steps})
    for r in steps:
        c = cycles_of(r["run"])
        if not c:
            continue
        dt, col = where(r)
        colour = cmap(dts.index(dt) / max(1, len(dts) - 1))
        for row, key in enumerate(("mean_overlap", "max_overlap")):
            axes[row][col].plot(c["time"], [1e6 * v for v in c[key]], color=colour, label=f"dt {dt:g}")
    for col, load in enumerate(("vertical load", "load inclined 5°")):
        axes[0][col].set_title(f"mean overlap (µm), {load}")
        axes[1][col].set_title(f"largest overlap (µm), {load}")
        axes[1][col].set_xlabel("time (s)")
        for row in range(2):
            axes[row][col].set_yscale("log")
            axes[row][col].grid(True, alpha=0.3)
    axes[0][1].legend(fontsize=7)
    fig.tight_layout()
    out = os.path.join(directory, "step_overlap.png")
    fig.savefig(out, dpi=80)
    print(f"plot_accuracy.py: wrote {out}")


def trade(plt, directory, rows, spread):
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.5))
    for r in rows:
        x = number(r["cpu_per_cycle"])
        if r["family"] == "spread" or not math.isfinite(x) or x <= 0:
            continue
        marker = "s" if r["solver"] == "NEWTON_AC" else ("^" if r["family"] == "step" else "o")
        colour = "tab:red" if r["solver"] == "NEWTON_AC" else ("tab:green" if r["family"] == "step" else "tab:blue")
        for ax, key, scale in ((axes[0], "mean_overlap", 1e6), (axes[1], "settlement_error", 1e3)):
            y = number(r[key]) * scale
            if not math.isfinite(y):
                continue
            shown = max(y, 1e-4) if key == "settlement_error" else y
            ax.scatter([x], [shown], marker=marker, color=colour, s=40)
            ax.annotate(r["setting"].replace(" (reference)", " (ref)"), (x, shown), fontsize=6, xytext=(3, 2),
                        textcoords="offset points")
    if spread is not None and spread > 0:
        axes[1].axhline(1e3 * spread, color="grey", linestyle="--", label="spread between samples")
        axes[1].legend(fontsize=8, loc="lower right")
    axes[0].set_ylabel("mean overlap (µm)")
    axes[1].set_ylabel("|settlement − tightest| (mm; 0 drawn at 1e-4)")
    for ax in axes:
        ax.set_xlabel("processor time per cycle (s)")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_title("cost against overlap (NLGS ● criterion, ▲ step; NEWTON_AC ■)", fontsize=10)
    axes[1].set_title("cost against settlement error", fontsize=10)
    fig.tight_layout()
    out = os.path.join(directory, "trade.png")
    fig.savefig(out, dpi=80)
    print(f"plot_accuracy.py: wrote {out}")


def main():
    p = argparse.ArgumentParser(description="PNGs of an accuracy_study folder")
    p.add_argument("directory")
    p.add_argument("--study", choices=("criterion", "step", "trade"), default="trade")
    a = p.parse_args()
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        fail("matplotlib is not installed (Debian: apt-get install python3-matplotlib)")
    runs = read_csv(os.path.join(a.directory, "runs.csv"))
    trade_rows = read_csv(os.path.join(a.directory, "trade.csv"))
    table = read_csv(os.path.join(a.directory, "table.csv"))
    settle = [number(t["settlement"]) for t, r in zip(table, runs) if r["role"] in ("reference", "spread")]
    settle = [v for v in settle if math.isfinite(v)]
    spread = (max(settle) - min(settle)) if len(settle) > 1 else None
    if a.study in ("criterion", "trade"):
        overlap_vs_time(plt, a.directory, [r for r in runs if not r["setting"].startswith("dt ")])
    if a.study in ("step", "trade"):
        step_overlap(plt, a.directory, runs)
    trade(plt, a.directory, trade_rows, spread)


if __name__ == "__main__":
    main()
