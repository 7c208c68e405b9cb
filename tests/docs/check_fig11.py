#!/usr/bin/python3
"""check_fig11.py — Fig. 11 in docs/studies.md (§5.9) against the data committed beside it: every
mean ± standard deviation of the table of the first cycles on the paper's 8 samples, in mm,
against the gathered study (docs/results/fig11_10cycles_settlement_by_k.csv, in metres); and
each full-length run's settlement at cycle 3,000 ("seed S at × K, … mm at cycle 3,000") against
the last block of its blocks CSV (docs/results/fig11_3000_k<K>_s<S>_blocks.csv). Exits 1 on a
difference."""
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
for seed, k, mm in re.findall(r"[Ss]eed (\d+) at × (\d+)[,:] ([\d.]+) mm at cycle 3,000", full):
    blocks = list(csv.DictReader(open(os.path.join(
        source, "docs", "results", f"fig11_3000_k{k}_s{seed}_blocks.csv"), encoding="utf-8")))
    runs += 1
    if blocks[-1]["last_cycle"] != "3000" or blocks[-1]["settlement_mm"] != mm:
        errors.append(f"seed {seed} at × {k}: the page says {mm} mm at cycle 3,000, the blocks "
                      f"{blocks[-1]['settlement_mm']} at cycle {blocks[-1]['last_cycle']}")
if runs < 2:
    errors.append(f"only {runs} full-length runs found on the page")
if checked < 12:
    errors.append(f"only {checked} cells found in the table")
for e in errors:
    print("check_fig11:", e)
print(f"check_fig11: {checked} cells, {runs} runs of 3,000 cycles, " + ("passed" if not errors else f"{len(errors)} differ"))
sys.exit(1 if errors else 0)
