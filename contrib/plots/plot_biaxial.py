#!/usr/bin/python3
"""plot_biaxial.py — the curves of a `biaxial` run (examples/biaxial) to a PNG.

Reads curves.csv and draws two panels sharing the axial strain axis:
  1. the mobilized friction angle phi = asin((sigma1 - sigma3) / (sigma1 + sigma3)) in degrees:
     from the wall stresses averaged over each row's steps (phi_deg), from the grains' internal
     stress (phi_internal_deg) and, faint, from the last step of each row alone
     (phi_last_step_deg), when the file has those columns,
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
    if "phi_last_step_deg" in rows[0]:
        a1.plot(e, [float(r["phi_last_step_deg"]) for r in rows], color="tab:gray", alpha=0.35, linewidth=0.7,
                label="walls, last step of a row")
    a1.plot(e, [float(r["phi_deg"]) for r in rows], color="tab:red", label="walls, row average")
    if "phi_internal_deg" in rows[0]:
        a1.plot(e, [float(r["phi_internal_deg"]) for r in rows], color="tab:green", linewidth=0.8,
                label="internal stress, row average")
        a1.legend(fontsize=8, loc="lower right")
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
