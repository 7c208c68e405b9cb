#!/usr/bin/env python3
"""Tile an LMGC90 DATBOX scene: K copies of it side by side along x, each body of copy c moved
by c x DX and renumbered after the copies before it, so that a scene of LMGC90's pre-processor
can be run K times larger without LMGC90 (docs/user-guide.md section 8, "On threads").

    tools/datbox_tile.py --datbox tests/data/datbox/polygons_jcbox --copies 4 --dx 17 --out /tmp/poly4

BODIES.DAT, DRV_DOF.DAT and DOF.INI are tiled; BULK_BEHAV.DAT, TACT_BEHAV.DAT and POSTPRO.DAT
are copied as they are. The contacts of Vloc_Rloc.INI are left out (its header is kept): the
tiled scene starts cold. Only a body's node moves (the $nodty line's coo1): LMGC90 gives the
contactors' points relative to it. Give a DX wider than the scene, its walls included, so that
the copies do not touch (polygons_jcbox: 17 m; disks_jcbox: 19 m).
Columns are kept as LMGC90 writes them, since its readers (and nscd's) read fixed columns.
"""
import argparse
import os
import re
import shutil
import sys

BODY = re.compile(r"^( RBDY2)( +)(\d+)(.*)$")
COO1 = re.compile(r"coo1=([ +-][0-9.]+E[+-]\d\d)")


def renumber(line, offset):
    """The RBDY2 line with its number moved by offset, right-aligned in the same columns."""
    m = BODY.match(line)
    if not m:
        return line
    width = len(m.group(2)) + len(m.group(3))
    number = str(int(m.group(3)) + offset)
    if len(number) > width:
        sys.exit(f"datbox_tile: body number {number} does not fit LMGC90's columns")
    return m.group(1) + number.rjust(width) + m.group(4)


def blocks(lines):
    """The lines before the first $bdyty, then each body's block ($bdyty … $$$$$$ and what follows)."""
    head, out, cur = [], [], None
    for line in lines:
        if line.startswith("$bdyty"):
            cur = [line]
            out.append(cur)
        elif cur is None:
            head.append(line)
        else:
            cur.append(line)
    return head, out


def count_bodies(lines):
    return sum(1 for line in lines if BODY.match(line))


def tile_file(path, copies, bodies, dx=None):
    with open(path) as f:
        lines = f.read().split("\n")
    head, body_blocks = blocks(lines)
    out = list(head)
    for c in range(copies):
        for block in body_blocks:
            in_node = False
            for line in block:
                line = renumber(line, c * bodies)
                if line.startswith("$nodty"):
                    in_node = True
                elif line.startswith("$"):
                    in_node = False
                elif in_node and dx is not None and "coo1=" in line:
                    x = float(COO1.search(line).group(1)) + c * dx
                    line = COO1.sub(lambda m: "coo1=" + f"{x:14.7E}", line, count=1)
                out.append(line)
    return "\n".join(out)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--datbox", required=True, help="the DATBOX folder to tile")
    p.add_argument("--copies", type=int, required=True, help="copies side by side, >= 1")
    p.add_argument("--dx", type=float, required=True, help="x distance between two copies (m), > 0")
    p.add_argument("--out", required=True, help="the new DATBOX folder (must not exist, unless --overwrite)")
    p.add_argument("--overwrite", action="store_true", help="replace the DATBOX files of an existing --out")
    a = p.parse_args()
    if a.copies < 1 or not a.dx > 0:
        sys.exit("datbox_tile: --copies must be >= 1 and --dx > 0")
    if os.path.exists(a.out) and not a.overwrite:
        sys.exit(f"datbox_tile: {a.out} exists; give a new folder, or --overwrite")
    src = lambda name: os.path.join(a.datbox, name)
    if not os.path.isfile(src("BODIES.DAT")):
        sys.exit(f"datbox_tile: no BODIES.DAT in {a.datbox}")
    with open(src("BODIES.DAT")) as f:
        bodies = count_bodies(f.read().split("\n"))
    os.makedirs(a.out, exist_ok=True)
    for name in sorted(os.listdir(a.datbox)):
        if name == "README" or not os.path.isfile(src(name)):
            continue
        dst = os.path.join(a.out, name)
        if name in ("BODIES.DAT", "DRV_DOF.DAT", "DOF.INI"):
            text = tile_file(src(name), a.copies, bodies, a.dx if name == "BODIES.DAT" else None)
            with open(dst, "w") as f:
                f.write(text)
        elif name == "Vloc_Rloc.INI":
            with open(src(name)) as f:
                lines = f.read().split("\n")
            keep = next((i for i, line in enumerate(lines) if line.startswith("$icdan")), len(lines))
            with open(dst, "w") as f:
                f.write("\n".join(lines[:keep]).rstrip("\n") + "\n")
        else:
            shutil.copyfile(src(name), dst)
    print(f"datbox_tile: {a.copies} x {bodies} bodies in {a.out}")


if __name__ == "__main__":
    main()
