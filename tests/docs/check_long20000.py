#!/usr/bin/python3
"""check_long20000.py — the tables of the paper's 20,000-cycle runs in docs/studies.md (§5.9)
against the data committed beside them: every 500-cycle row of each seed against that seed's
250-cycle blocks (docs/results/long20000_s<seed>_blocks.csv); for a seed whose cycles are
committed (docs/results/long20000_s<seed>/cycles.*.csv.gz), its blocks CSV, its column of the
1000-cycle trend table and its rows of the change-of-slope table against what
contrib/plots/cycle_blocks.py computes from those cycles; and the change of slope that
contrib/plots/plot_settlement.py draws from a blocks CSV within a block of the table's, which was
fitted to every cycle. Exits 1 on a difference."""
import csv
import glob
import gzip
import os
import re
import subprocess
import sys
import tempfile

source = sys.argv[1]
results = os.path.join(source, "docs", "results")
plots = os.path.join(source, "contrib", "plots")
sys.path.insert(0, plots)
from cycle_blocks import slope_break  # noqa: E402
from plot_settlement import curve  # noqa: E402

page = open(os.path.join(source, "docs", "studies.md"), encoding="utf-8").read()
section = page[page.index("**The paper's 20,000-cycle run (Fig. 12)**"):page.index("**Fig. 11's first 10 cycles on the paper's 8 samples**")]
errors = []


def check(ok, message):
    if not ok:
        errors.append(message)


def table(header_start):
    """The header cells and the body rows (lists of cells) of the section's table whose header
    begins with header_start."""
    lines = section[section.index(header_start):].split("\n")
    rows = []
    for line in lines[2:]:
        if not line.startswith("|"):
            break
        rows.append([c.strip() for c in line.strip("|").split("|")])
    return [c.strip() for c in lines[0].strip("|").split("|")], rows


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def number(cell):
    return float(cell.replace(",", "").replace("−", "-"))


# 1. The 500-cycle table: three cells a seed (settlement, "largest / mean" overlap, sweeps), each
# from the seed's two 250-cycle blocks (the mean of two rounded means may differ in its last digit).
header, rows = table("| cycles | seed 2006: settlement")
seeds = [re.match(r"seed (\d+): settlement", h).group(1) for h in header if re.match(r"seed \d+: settlement", h)]
check(len(rows) == 40, f"the 500-cycle table has {len(rows)} rows, not 40")
for i, seed in enumerate(seeds):
    blocks = {int(b["last_cycle"]): b for b in read_csv(os.path.join(results, f"long20000_s{seed}_blocks.csv"))}
    for row in rows:
        last = int(row[0].split("–")[1])
        a, b = blocks.get(last - 250), blocks.get(last)
        if a is None or b is None:
            errors.append(f"seed {seed}: no 250-cycle blocks ending at {last - 250} and {last}")
            continue
        settlement, overlaps, sweeps = row[1 + 3 * i:4 + 3 * i]
        largest, mean = (number(x) for x in overlaps.split("/"))
        where = f"seed {seed}, cycles {row[0]}"
        check(number(settlement) == float(b["settlement_mm"]), f"{where}: settlement {settlement}, blocks {b['settlement_mm']}")
        check(largest == max(float(a["max_overlap_um"]), float(b["max_overlap_um"])), f"{where}: largest overlap {largest}")
        check(abs(mean - (float(a["mean_overlap_um"]) + float(b["mean_overlap_um"])) / 2) <= 1.01e-4, f"{where}: mean overlap {mean}")
        check(abs(number(sweeps) - (float(a["mean_sweeps"]) + float(b["mean_sweeps"])) / 2) <= 0.101, f"{where}: sweeps {sweeps}")


def joined_cycles(seed, folder):
    """The seed's committed cycles, gunzipped and joined into folder/cycles.csv; None if none."""
    parts = sorted(glob.glob(os.path.join(results, f"long20000_s{seed}", "cycles.*.csv.gz")))
    if not parts:
        return None
    path = os.path.join(folder, "cycles.csv")
    with open(path, "wb") as out:
        for part in parts:
            with gzip.open(part, "rb") as f:
                out.write(f.read())
    return path


def run_blocks(*args):
    return subprocess.run([sys.executable, os.path.join(plots, "cycle_blocks.py"), *args], check=True,
                          capture_output=True, text=True).stdout


# 2. A seed with committed cycles: its blocks, its trends and its changes of slope, recomputed.
trend_header, trend_rows = table("| cycles | seed 2006: trend")
_, fit_rows = table("| run | cycles searched | break at cycle")


def check_recomputed(seed, cycles, tmp):
    """The seed's blocks CSV, trend column and change-of-slope rows against cycle_blocks.py on its cycles."""
    last_cycle = int(read_csv(cycles)[-1]["cycle"])
    run_blocks(cycles, "--every", "250", "--csv", os.path.join(tmp, "b250.csv"))
    committed = os.path.join(results, f"long20000_s{seed}_blocks.csv")
    check(os.path.isfile(committed) and open(committed).read() == open(os.path.join(tmp, "b250.csv")).read(),
          f"seed {seed}: {committed} is not what cycle_blocks.py --every 250 --csv makes of its cycles")
    run_blocks(cycles, "--every", "1000", "--csv", os.path.join(tmp, "b1000.csv"))
    trends = {int(b["first_cycle"]): b["trend_mm_per_1000"] for b in read_csv(os.path.join(tmp, "b1000.csv"))}
    column = next(j for j, h in enumerate(trend_header) if h.startswith(f"seed {seed}:"))
    for row in trend_rows:
        first, last = (int(x) for x in row[0].split("–"))
        if last > last_cycle:
            check(row[column] == "—", f"seed {seed}: a trend for cycles {row[0]}, past its last cycle {last_cycle}")
        else:
            check(number(row[column]) == float(trends[first]),
                  f"seed {seed}, cycles {row[0]}: trend {row[column]}, cycle_blocks.py {trends[first]}")
    for row in (r for r in fit_rows if r[0] == f"seed {seed}"):
        first = int(number(row[1].split("–")[0]))
        out = run_blocks(cycles, "--break", "--from", str(first)).strip().split("\n")[-1]
        got = [c.strip() for c in out.strip("|").split("|")]
        want = [row[2], row[3], row[4], *(x.strip() for x in row[5].split("/"))]
        check([number(x) for x in want] == [number(x) for x in got[1:]],
              f"seed {seed} from cycle {first}: the table says {want}, cycle_blocks.py --break {got[1:]}")


trend_seeds = [re.match(r"seed (\d+):", h).group(1) for h in trend_header if re.match(r"seed \d+:", h)]
checked = 0
for seed in trend_seeds:
    with tempfile.TemporaryDirectory() as tmp:
        cycles = joined_cycles(seed, tmp)
        if cycles is not None:
            check_recomputed(seed, cycles, tmp)
            checked += 1
check(checked > 0, "no seed's cycles are committed")

# 3. plot_settlement.py's curve of a blocks CSV is its blocks' last cycles (settlement in m), and
# the change of slope fitted to those points lies within a block of the table's fit of every cycle.
for seed in seeds:
    path = os.path.join(results, f"long20000_s{seed}_blocks.csv")
    points = curve(path, "settlement_min_load")
    blocks = read_csv(path)
    check(points == [(float(b["last_cycle"]), 1e-3 * float(b["settlement_mm"])) for b in blocks],
          f"seed {seed}: plot_settlement.py's points are not the blocks' last cycles")
    row = next((r for r in fit_rows if r[0] == f"seed {seed}" and r[1].startswith("3000")), None)
    if row is None:
        continue
    fit = slope_break([{"cycle": c, "s": s} for c, s in points], "s", 3000, int(points[-1][0]))
    check(abs(fit["break_cycle"] - number(row[2])) <= 250, f"seed {seed}: the blocks' break {fit['break_cycle']}, the table's {row[2]}")
    check(abs(fit["slope_before"] - number(row[3])) <= 0.1 and abs(fit["slope_after"] - number(row[4])) <= 0.1,
          f"seed {seed}: the blocks' slopes {fit['slope_before']:.2f} / {fit['slope_after']:.2f}, the table's {row[3]} / {row[4]}")

for e in errors:
    print("check_long20000:", e)
print(f"check_long20000: {len(seeds)} seeds, {len(rows)} rows of 500 cycles, {checked} seed(s) recomputed from "
      f"its cycles: {'FAILED' if errors else 'passed'}")
sys.exit(1 if errors else 0)
