#!/usr/bin/python3
"""plot_drum.py — the angles of a `drum` run (examples/drum) to a PNG.

Reads DIR/angles.csv and DIR/series.csv and draws two panels:
  1. the dynamic angle of repose against the Froude number (log scale): the centre-of-mass
     measure with its standard deviation over the window, and the top-grain fit;
  2. the angle's history against time, one colour per Froude number, the measured windows dark.

Example
  contrib/plots/plot_drum.py out/drum out/drum/angles.png

Needs python3 and matplotlib (Debian: apt-get install python3-matplotlib).
"""
import csv
import os
import sys


def read(path, need):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for column in need:
        if not rows or column not in rows[0]:
            sys.exit(f"plot_drum.py: {path} has no '{column}' column (is it a drum run's file?)")
    return rows


def main(argv):
    if len(argv) != 3:
        sys.exit("usage: plot_drum.py RUN_DIR OUTPUT_PNG")
    angles = read(os.path.join(argv[1], "angles.csv"), ("froude", "angle_deg", "angle_std_deg", "fit_angle_deg"))
    series = read(os.path.join(argv[1], "series.csv"), ("time", "froude", "angle_deg", "measured"))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    fr = [float(r["froude"]) for r in angles]
    a1.errorbar(fr, [float(r["angle_deg"]) for r in angles], yerr=[float(r["angle_std_deg"]) for r in angles],
                marker="o", capsize=3, label="centre of mass")
    a1.plot(fr, [float(r["fit_angle_deg"]) for r in angles], "s--", color="tab:gray", label="top-grain fit")
    a1.set_xscale("log")
    a1.set_xlabel("Froude number  $\\omega^2 R / g$")
    a1.set_ylabel("dynamic angle of repose (deg)")
    a1.grid(alpha=0.3, which="both")
    a1.legend()
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for k, f in enumerate(sorted({r["froude"] for r in series}, key=float)):
        c = colours[k % len(colours)]
        for measured, alpha in (("0", 0.35), ("1", 1.0)):
            pts = [r for r in series if r["froude"] == f and float(r["measured"]) == float(measured)]
            a2.plot([float(r["time"]) for r in pts], [float(r["angle_deg"]) for r in pts], ".", ms=2, color=c, alpha=alpha,
                    label=f"Fr {float(f):g}" if measured == "1" else None)
    a2.set_xlabel("time (s)")
    a2.set_ylabel("angle (deg), pale: transient")
    a2.grid(alpha=0.3)
    a2.legend(markerscale=4)
    fig.suptitle("rotating drum of disks")
    fig.tight_layout()
    fig.savefig(argv[2], dpi=100)


if __name__ == "__main__":
    main(sys.argv)
