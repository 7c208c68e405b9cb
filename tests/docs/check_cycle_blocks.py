#!/usr/bin/python3
"""check_cycle_blocks.py — contrib/plots/cycle_blocks.py against the 3000-cycle table of
docs/studies.md (§5.9): the script, run on the committed docs/results/long3000_cycles.csv by
250 cycles, gives every row's settlement, largest and mean overlap, sweeps and unconverged
steps as the page prints them. Exits 1 on a difference."""
import csv
import os
import re
import subprocess
import sys
import tempfile

source = sys.argv[1]
script = os.path.join(source, "contrib", "plots", "cycle_blocks.py")
data = os.path.join(source, "docs", "results", "long3000_cycles.csv")
with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "blocks.csv")
    subprocess.run([sys.executable, script, data, "--every", "250", "--csv", out], check=True)
    with open(out, newline="") as f:
        got = list(csv.DictReader(f))

# the page's rows: | 1–250 | 39.00 | 0.821 | 0.0307 | 209.9 | 992 |
page = open(os.path.join(source, "docs", "studies.md"), encoding="utf-8").read()
rows = re.findall(r"^\| (\d+)–(\d+) \| ([\d.]+) \| ([\d.]+) \| ([\d.]+) \| ([\d.]+) \| (\d+) \|$", page, re.M)
if len(rows) != 12:
    sys.exit(f"check_cycle_blocks: expected the 12 rows of the 3000-cycle table in docs/studies.md, found {len(rows)}")
bad = 0
for r, g in zip(rows, got):
    want = dict(zip(("first_cycle", "last_cycle", "settlement_mm", "max_overlap_um", "mean_overlap_um",
                     "mean_sweeps", "unconverged_steps"), r))
    for key, value in want.items():
        if g[key] != value:
            print(f"check_cycle_blocks: cycles {r[0]}–{r[1]}: {key} is {g[key]}, the page says {value}")
            bad += 1
if len(got) != len(rows):
    print(f"check_cycle_blocks: {len(got)} blocks, the page has {len(rows)}")
    bad += 1
print(f"check_cycle_blocks: {len(rows)} blocks, {bad} difference(s)")
sys.exit(1 if bad else 0)
