#!/usr/bin/python3
"""cycle_blocks.py — a long ballast run's cycles.csv as a table of blocks of cycles.

For each block of --every cycles (the last one may be shorter): the settlement at the
block's last cycle, what the block added, its trend (the least-squares slope of the
settlement over the block's cycles, in mm per 1000 cycles: steadier than what the block
added, which one fluctuating cycle at either end moves), the largest and the mean
overlap, the mean sweeps a step, the unconverged steps and the wall time a cycle. The overlaps' means are
of the cycles' means (every cycle has as many steps). Prints a Markdown table, or writes a
CSV with --csv; a run still going can be read at any time (its last block is partial).

Examples
  contrib/plots/cycle_blocks.py out/long_run --every 1000
  contrib/plots/cycle_blocks.py out/long_run/cycles.csv --every 250 --csv blocks.csv
  contrib/plots/cycle_blocks.py out/long_run --column settlement_max_load

Needs python3 only.
"""
import argparse
import csv
import os
import sys

NEEDED = ("cycle", "max_overlap", "mean_overlap", "mean_sweeps", "unconverged_steps", "wall_time")


def fail(message):
    print(f"cycle_blocks.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_cycles(path, column):
    """The rows of a cycles.csv (or of the cycles.csv in a directory), checked."""
    if os.path.isdir(path):
        path = os.path.join(path, "cycles.csv")
    if not os.path.isfile(path):
        fail(f"no such file: '{path}' (give a run's cycles.csv or its output directory)")
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        fail(f"'{path}' has no cycles yet")
    missing = [c for c in NEEDED + (column,) if c not in rows[0]]
    if missing:
        fail(f"'{path}' is not a ballast cycles.csv: no column {', '.join(missing)}")
    try:
        return [{k: float(r[k]) for k in NEEDED + (column,)} for r in rows]
    except (TypeError, ValueError) as e:
        fail(f"'{path}': a value is not a number ({e})")


def trend(b, column):
    """The least-squares slope of the settlement (mm) against the cycle over rows b, per
    1000 cycles; 0 for a block of one cycle."""
    n = len(b)
    if n < 2:
        return 0.0
    mx = sum(r["cycle"] for r in b) / n
    my = sum(r[column] for r in b) / n
    sxx = sum((r["cycle"] - mx) ** 2 for r in b)
    sxy = sum((r["cycle"] - mx) * (r[column] - my) for r in b)
    return sxy / sxx * 1e3 * 1e3 if sxx > 0 else 0.0


def blocks(rows, every, column):
    """One dict a block of `every` cycles, in order."""
    out, before = [], 0.0
    for i in range(0, len(rows), every):
        b = rows[i:i + every]
        last = b[-1][column] * 1e3
        out.append({
            "first_cycle": int(b[0]["cycle"]),
            "last_cycle": int(b[-1]["cycle"]),
            "settlement_mm": last,
            "added_mm": last - before,
            "trend_mm_per_1000": trend(b, column),
            "max_overlap_um": max(r["max_overlap"] for r in b) * 1e6,
            "mean_overlap_um": sum(r["mean_overlap"] for r in b) / len(b) * 1e6,
            "mean_sweeps": sum(r["mean_sweeps"] for r in b) / len(b),
            "unconverged_steps": int(sum(r["unconverged_steps"] for r in b)),
            "wall_s_per_cycle": sum(r["wall_time"] for r in b) / len(b),
        })
        before = last
    return out


FORMATS = {"settlement_mm": "{:.2f}", "added_mm": "{:.2f}", "trend_mm_per_1000": "{:.2f}", "max_overlap_um": "{:.3f}",
           "mean_overlap_um": "{:.4f}", "mean_sweeps": "{:.1f}", "wall_s_per_cycle": "{:.3f}"}


def cell(key, value):
    return FORMATS.get(key, "{}").format(value)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[1],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("run", help="a ballast run's cycles.csv, or its output directory")
    p.add_argument("--every", type=int, default=1000, help="cycles a block (default 1000)")
    p.add_argument("--column", default="settlement_min_load",
                   help="the settlement column (default settlement_min_load; or settlement_max_load)")
    p.add_argument("--csv", metavar="FILE", help="write the table as CSV to FILE instead of printing Markdown")
    a = p.parse_args()
    if a.every < 1:
        fail(f"--every must be at least 1, got {a.every}")
    table = blocks(read_cycles(a.run, a.column), a.every, a.column)
    keys = list(table[0].keys())
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(keys)
            for r in table:
                w.writerow([cell(k, r[k]) for k in keys])
        return
    print("| cycles | settlement at the last (mm) | added (mm) | trend (mm / 1000 cycles) | largest overlap (µm) "
          "| mean overlap (µm) | sweeps/step | unconverged steps | wall s/cycle |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in table:
        print(f"| {r['first_cycle']}–{r['last_cycle']} | " + " | ".join(cell(k, r[k]) for k in keys[2:]) + " |")


if __name__ == "__main__":
    main()
