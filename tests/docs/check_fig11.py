#!/usr/bin/python3
"""check_fig11.py — the table of Fig. 11's first cycles on the paper's 8 samples in
docs/studies.md (§5.9) against the gathered study committed beside it
(docs/results/fig11_10cycles_settlement_by_k.csv, stiffness_study's settlement_by_k.csv): every
mean ± standard deviation of the table, in mm, against the CSV's in metres. Exits 1 on a
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
if checked < 12:
    errors.append(f"only {checked} cells found in the table")
for e in errors:
    print("check_fig11:", e)
print(f"check_fig11: {checked} cells, " + ("passed" if not errors else f"{len(errors)} differ"))
sys.exit(1 if errors else 0)
