#!/usr/bin/python3
"""check_cycle_blocks.py — contrib/plots/cycle_blocks.py against the 3000-cycle table of
docs/studies.md (§5.9): the script, run on the committed docs/results/long3000_cycles.csv by
250 cycles, gives every row's settlement, largest and mean overlap, sweeps and unconverged
steps as the page prints them; and on a made-up run settling 2 mm per 1000 cycles, the last
cycle of each block 1 mm higher, each block's trend is 2 mm per 1000 cycles plus that one
cycle's pull on a least-squares slope; and --break finds a made-up run's change of slope. Exits
1 on a difference."""
import csv
import math
import os
import re
import subprocess
import sys
import tempfile


def write_fake(path, cycles, settlement_mm):
    """A made-up cycles.csv of `cycles` cycles, settlement_mm(c) at cycle c."""
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["cycle", "settlement_min_load", "max_overlap", "mean_overlap", "mean_sweeps",
                    "unconverged_steps", "wall_time"])
        for c in range(1, cycles + 1):
            w.writerow([c, settlement_mm(c) * 1e-3, 1e-7, 1e-8, 100, 0, 1.0])


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

# a made-up run: 1000 cycles, s = 10 mm + 2 mm per 1000 cycles, the last cycle of each block of
# n = 100 cycles 1 mm higher; that cycle, (n − 1) / 2 cycles past the block's mean, moves a
# least-squares slope by 1 mm × ((n − 1) / 2) / (n (n² − 1) / 12) = 6 / (n (n + 1)) mm a cycle,
# 0.59 mm per 1000 cycles
with tempfile.TemporaryDirectory() as tmp:
    fake = os.path.join(tmp, "cycles.csv")
    write_fake(fake, 1000, lambda c: 10 + 2e-3 * c + (1 if c % 100 == 0 else 0))
    out = os.path.join(tmp, "blocks.csv")
    subprocess.run([sys.executable, script, fake, "--every", "100", "--csv", out], check=True)
    with open(out, newline="") as f:
        fake_rows = list(csv.DictReader(f))
    n = 100
    pull = 6 / (n * (n + 1)) * 1e3
    for r in fake_rows:
        want = f"{2 + pull:.2f}"
        if r["trend_mm_per_1000"] != want:
            print(f"check_cycle_blocks: made-up run, cycles {r['first_cycle']}–{r['last_cycle']}: trend is "
                  f"{r['trend_mm_per_1000']}, want {want}")
            bad += 1
    if fake_rows[1]["added_mm"] != "0.20":  # 0.2 mm the block, the 1 mm of both ends cancel
        print(f"check_cycle_blocks: made-up run: the second block added {fake_rows[1]['added_mm']}, want 0.20")
        bad += 1

# --break on a made-up run whose slope changes at cycle 4000, from 3 to 0.5 mm per 1000 cycles,
# with a ripple of ±0.05 mm every 7 cycles: the break and both slopes come back; searched from
# cycle 5000 on, where the run is one straight line, the two lines fit no better than one.
with tempfile.TemporaryDirectory() as tmp:
    fake = os.path.join(tmp, "cycles.csv")
    write_fake(fake, 10000, lambda c: 10 + 3e-3 * min(c, 4000) + 0.5e-3 * max(c - 4000, 0)
               + 0.05 * math.sin(2 * math.pi * c / 7))

    def brk(*extra):
        text = subprocess.run([sys.executable, script, fake, "--break", *extra], check=True, capture_output=True,
                              text=True).stdout
        return [float(v) for v in text.strip().splitlines()[-1].strip("|").replace("–", "|").split("|")]

    first, last, at, before, after, rms2, rms1 = brk()
    if (first, last) != (1, 10000) or abs(at - 4000) > 10 or abs(before - 3) > 0.02 or abs(after - 0.5) > 0.02:
        print(f"check_cycle_blocks: --break found cycle {at:.0f}, slopes {before} and {after}; want 4000, 3 and 0.5")
        bad += 1
    if not (rms2 < 0.05 < rms1):  # the ripple's RMS is 0.035 mm
        print(f"check_cycle_blocks: --break: RMS {rms2} mm of the two lines, {rms1} mm of one; want < 0.05 < it")
        bad += 1
    # the fit's settlement at the break (what plot_settlement.py --break draws from): 22 mm
    sys.path.insert(0, os.path.dirname(script))
    from cycle_blocks import read_cycles, slope_break
    level = slope_break(read_cycles(fake, "settlement_min_load"), "settlement_min_load", 1, 10000)["at_break_mm"]
    if abs(level - 22) > 0.01:
        print(f"check_cycle_blocks: --break: the fit is at {level} mm at the break, want 22")
        bad += 1
    first, last, at, before, after, rms2, rms1 = brk("--from", "5000", "--to", "9000")
    if (first, last) != (5000, 9000) or abs(before - 0.5) > 0.05 or abs(after - 0.5) > 0.05 or rms1 - rms2 > 0.002:
        print(f"check_cycle_blocks: --break on one straight line (cycles {first:.0f}–{last:.0f}): slopes "
              f"{before} and {after}, RMS {rms2} against {rms1}; want 0.5, 0.5 and no better fit than one line")
        bad += 1

print(f"check_cycle_blocks: {len(rows)} blocks, {bad} difference(s)")
sys.exit(1 if bad else 0)
