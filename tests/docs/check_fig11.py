#!/usr/bin/python3
"""check_fig11.py — Fig. 11 in docs/studies.md (§5.9) against the data committed beside it: every
mean ± standard deviation of the table of the first cycles on the paper's 8 samples, in mm,
against the gathered study (docs/results/fig11_10cycles_settlement_by_k.csv, in metres); and
each row of the full-length runs' table (settlements at cycles 3,000 and 1,000, what the last
two thousands added, the overlaps and the sweeps) against its blocks CSV
(docs/results/fig11_3000_k<K>_s<S>_blocks.csv). Exits 1 on a difference."""
import csv
import os
import re
import sys

source = sys.argv[1]
page = open(os.path.join(source, "docs", "studies.md"), encoding="utf-8").read()
start = page.index("**Fig. 11's first 10 cycles on the paper's 8 samples**")
section = page[start:page.index("**Fig. 11 at the paper's length**", start)]
rows = {int(r["cycle"]): r for r in csv.DictReader(open(
    os.path.join(source, "docs", "results", "fig11_10cycles_settlement_by_k.csv"), encoding="utf-8"))}

lines = [l for l in section.split("\n") if l.startswith("|")]
header = [c.strip() for c in lines[0].strip("|").split("|")]
cycles = [int(m.group(1)) for c in header for m in [re.fullmatch(r"cycle (\d+)", c)] if m]
errors, checked = [], 0
for line in lines[2:]:
    cells = [c.strip() for c in line.strip("|").split("|")]
    k = re.fullmatch(r"× (\d+)", cells[0]).group(1)
    for i, cycle in enumerate(cycles):
        mean, std = (float(v) for v in cells[1 + i].split(" ± "))
        want = (1000 * float(rows[cycle]["mean_k" + k]), 1000 * float(rows[cycle]["std_k" + k]))
        checked += 1
        if abs(mean - want[0]) > 0.005 or abs(std - want[1]) > 0.005:
            errors.append(f"× {k}, cycle {cycle}: the page says {mean} ± {std} mm, the CSV {want[0]:.3f} ± {want[1]:.3f}")
full = page[page.index("**Fig. 11 at the paper's length**"):page.index("**The paper's full plans**")]
runs = 0
for line in full.split("\n"):
    m = re.fullmatch(r"\| (\d+) \| × (\d+) \| ([\d.]+) \| ([\d.]+) \| ([\d.]+) / ([\d.]+) \| ([\d.]+) / ([\d.]+) "
                     r"\| (\d+)–(\d+) \|", line)
    if not m:
        continue
    seed, k = m.group(1), m.group(2)
    page_values = [float(v) for v in m.groups()[2:]]
    blocks = list(csv.DictReader(open(os.path.join(
        source, "docs", "results", f"fig11_3000_k{k}_s{seed}_blocks.csv"), encoding="utf-8")))
    runs += 1
    at = {int(r["last_cycle"]): float(r["settlement_mm"]) for r in blocks}
    sweeps = [float(r["mean_sweeps"]) for r in blocks]
    if blocks[-1]["last_cycle"] != "3000":
        errors.append(f"seed {seed} at × {k}: its blocks end at cycle {blocks[-1]['last_cycle']}, not 3,000")
        continue
    # what each column says, from the blocks, and the rounding the page gives it
    want = [(at[3000], 0.005), (at[1000], 0.005), (at[2000] - at[1000], 0.015), (at[3000] - at[2000], 0.015),
            (sum(float(r["mean_overlap_um"]) for r in blocks) / len(blocks), 0.0005),
            (max(float(r["max_overlap_um"]) for r in blocks), 0.005), (min(sweeps), 0.5), (max(sweeps), 0.5)]
    names = ["at cycle 3,000", "at cycle 1,000", "added in 1,001-2,000", "added in 2,001-3,000",
             "mean overlap", "largest overlap", "fewest sweeps", "most sweeps"]
    for name, said, (value, tol) in zip(names, page_values, want):
        if abs(said - value) > tol:
            errors.append(f"seed {seed} at × {k}, {name}: the page says {said}, the blocks give {value:.4f}")
if runs < 2:
    errors.append(f"only {runs} full-length runs found on the page")
if checked < 12:
    errors.append(f"only {checked} cells found in the table")
for e in errors:
    print("check_fig11:", e)
print(f"check_fig11: {checked} cells, {runs} runs of 3,000 cycles, " + ("passed" if not errors else f"{len(errors)} differ"))
sys.exit(1 if errors else 0)
