#!/usr/bin/python3
"""plot_biaxial.py — the curves of a `biaxial` run (examples/biaxial) to a PNG.

Reads curves.csv and draws two panels sharing the axial strain axis:
  1. the mobilized friction angle phi = asin((sigma1 - sigma3) / (sigma1 + sigma3)) in degrees,
  2. the volumetric strain (contraction > 0) and the packing fraction.

Example
  contrib/plots/plot_biaxial.py out/biaxial/curves.csv out/biaxial/curves.png

Needs python3 and matplotlib (Debian: apt-get install python3-matplotlib).
"""
import csv
import sys


def main(argv):
    if len(argv) != 3:
        sys.exit("usage: plot_biaxial.py CURVES_CSV OUTPUT_PNG")
    with open(argv[1], newline="") as f:
        rows = list(csv.DictReader(f))
    for need in ("strain", "phi_deg", "volumetric_strain", "packing_fraction"):
        if not rows or need not in rows[0]:
            sys.exit(f"plot_biaxial.py: {argv[1]} has no '{need}' column (is it a biaxial curves.csv?)")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    e = [float(r["strain"]) for r in rows]
    fig, (a1, a2) = plt.subplots(2, 1, sharex=True, figsize=(6.5, 6.5))
    a1.plot(e, [float(r["phi_deg"]) for r in rows], color="tab:red")
    a1.set_ylabel("mobilized friction angle (deg)")
    a1.grid(alpha=0.3)
    a2.plot(e, [float(r["volumetric_strain"]) for r in rows], color="tab:blue", label="volumetric strain")
    a2.set_ylabel("volumetric strain (contraction > 0)")
    a2.set_xlabel("axial strain")
    a2.grid(alpha=0.3)
    b2 = a2.twinx()
    b2.plot(e, [float(r["packing_fraction"]) for r in rows], color="tab:gray", linestyle="--", label="packing fraction")
    b2.set_ylabel("packing fraction")
    fig.suptitle("biaxial compression of disks")
    fig.tight_layout()
    fig.savefig(argv[2], dpi=120)


if __name__ == "__main__":
    main(sys.argv)
