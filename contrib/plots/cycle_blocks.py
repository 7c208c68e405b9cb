#!/usr/bin/python3
"""cycle_blocks.py — a long ballast run's cycles.csv as a table of blocks of cycles.

For each block of --every cycles (the last one may be shorter): the settlement at the
block's last cycle, what the block added, its trend (the least-squares slope of the
settlement over the block's cycles, in mm per 1000 cycles: steadier than what the block
added, which one fluctuating cycle at either end moves), the largest and the mean
overlap, the mean sweeps a step, the unconverged steps and the wall time a cycle. The overlaps' means are
of the cycles' means (every cycle has as many steps). Prints a Markdown table, or writes a
CSV with --csv; a run still going can be read at any time (its last block is partial).

With --break, the settlement's best single change of slope instead (the paper's "brake of
slope", Saussine et al. 2006 §4.3): the continuous two-segment line of least squares over
cycles --from … --to, its break and both slopes, and how much closer it fits than one line.

Examples
  contrib/plots/cycle_blocks.py out/long_run --every 1000
  contrib/plots/cycle_blocks.py out/long_run/cycles.csv --every 250 --csv blocks.csv
  contrib/plots/cycle_blocks.py out/long_run --column settlement_max_load
  contrib/plots/cycle_blocks.py out/long_run --break --from 3000

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


def slope_break(rows, column, first, last):
    """The best single change of slope of the settlement over cycles first … last: the
    continuous two-segment line s = a + b1 (c − c0) for c ≤ c0, a + b2 (c − c0) beyond, fitted
    by least squares for every break c0 that leaves each side a twentieth of the cycles (at
    least 10), and the c0 of the least squared error. Returns the break, both slopes (mm per
    1000 cycles), the fit's settlement at the break (mm), and the RMS of the fit and of one
    straight line (mm); None if too few cycles."""
    pts = [(r["cycle"], r[column] * 1e3) for r in rows if first <= r["cycle"] <= last]
    n = len(pts)
    side = max(10, n // 20)
    if n < 2 * side + 1:
        return None
    mc = sum(c for c, _ in pts) / n
    my = sum(y for _, y in pts) / n
    xs = [(c - mc) * 1e-3 for c, _ in pts]  # thousands of cycles from the mean: well scaled
    ys = [y - my for _, y in pts]
    # prefix sums of 1, x, x², y, xy: each side's sums about any break in O(1)
    pre = [[0.0] * 5]
    for x, y in zip(xs, ys):
        q = pre[-1]
        pre.append([q[0] + 1, q[1] + x, q[2] + x * x, q[3] + y, q[4] + x * y])
    tot, syy = pre[-1], sum(y * y for y in ys)
    best = None
    for k in range(side, n - side):  # the break at point k - 1: the left side is points 0 … k − 1
        x0 = xs[k - 1]
        left = pre[k]
        right = [t - l for t, l in zip(tot, left)]
        # about the break: Σ(x − x0), Σ(x − x0)², Σ(x − x0) y on each side
        sl, sr = left[1] - left[0] * x0, right[1] - right[0] * x0
        sll = left[2] - 2 * x0 * left[1] + left[0] * x0 * x0
        srr = right[2] - 2 * x0 * right[1] + right[0] * x0 * x0
        syl, syr = left[4] - x0 * left[3], right[4] - x0 * right[3]
        # the normal equations of (a, b1, b2): [n sl sr; sl sll 0; sr 0 srr] θ = [Σy syl syr]
        theta = solve3([[n, sl, sr], [sl, sll, 0.0], [sr, 0.0, srr]], [tot[3], syl, syr])
        if theta is None:
            continue
        sse = syy - (theta[0] * tot[3] + theta[1] * syl + theta[2] * syr)
        if best is None or sse < best[0]:
            best = (sse, pts[k - 1][0], theta[1], theta[2], theta[0] + my)
    if best is None:
        return None
    sxx = tot[2] - tot[1] ** 2 / n
    line_sse = syy - (tot[4] ** 2 / sxx if sxx > 0 else 0.0)
    return {"first_cycle": int(pts[0][0]), "last_cycle": int(pts[-1][0]), "break_cycle": int(best[1]),
            "slope_before": best[2], "slope_after": best[3], "at_break_mm": best[4],
            "rms_two_lines_mm": max(best[0], 0.0) ** 0.5 / n ** 0.5,
            "rms_one_line_mm": max(line_sse, 0.0) ** 0.5 / n ** 0.5}


def solve3(m, r):
    """The solution of the 3 × 3 system m θ = r (Cramer's rule); None if m is singular."""
    def det(a):
        return (a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
                + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]))
    d = det(m)
    if abs(d) < 1e-300:
        return None
    return [det([[r[i] if j == col else m[i][j] for j in range(3)] for i in range(3)]) / d for col in range(3)]


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
    p.add_argument("--break", dest="slope_break", action="store_true",
                   help="print the settlement's best single change of slope (a continuous two-segment "
                        "least-squares line) instead of the blocks")
    p.add_argument("--from", dest="first", type=int, default=1,
                   help="with --break: the first cycle searched (default 1)")
    p.add_argument("--to", dest="last", type=int, default=0,
                   help="with --break: the last cycle searched (default: the run's last)")
    a = p.parse_args()
    if a.every < 1:
        fail(f"--every must be at least 1, got {a.every}")
    if not a.slope_break and (a.first != 1 or a.last != 0):
        fail("--from and --to choose the cycles --break searches: give --break too")
    if a.slope_break and a.csv:
        fail("--break prints the change of slope; --csv writes the blocks: give one of them")
    rows = read_cycles(a.run, a.column)
    if a.slope_break:
        return print_break(rows, a)
    table = blocks(rows, a.every, a.column)
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


def print_break(rows, a):
    last = a.last if a.last > 0 else int(rows[-1]["cycle"])
    b = slope_break(rows, a.column, a.first, last)
    if b is None:
        fail(f"cycles {a.first}–{last}: too few cycles for two slopes (at least 21)")
    print("| cycles searched | break at cycle | slope before (mm / 1000 cycles) | slope after | RMS of the two "
          "lines (mm) | RMS of one line (mm) |")
    print("|---|---|---|---|---|---|")
    print(f"| {b['first_cycle']}–{b['last_cycle']} | {b['break_cycle']} | {b['slope_before']:.2f} | "
          f"{b['slope_after']:.2f} | {b['rms_two_lines_mm']:.3f} | {b['rms_one_line_mm']:.3f} |")


if __name__ == "__main__":
    main()
