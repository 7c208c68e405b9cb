#!/usr/bin/env python3
"""contrib/lmgc90/deposit_700.py -- the 700-pentagon deposit of `lmgc90_deposit_case`, built
with LMGC90's pre-processor (pylmgc90.pre), exported as an nscd sample file, and optionally run
with LMGC90's chipy so that both codes can be compared step by step.

The scene (the same settings as examples/deposit/lmgc90_case.cpp):
  700 regular pentagons, circumradius uniform in [12.5, 25] mm (pre.granulo_Random), density
  2700 kg/m3, orientations uniform in [0, 2 pi/5), on a 28 x 25 square lattice of pitch 55 mm
  (pre.squareLattice2D, lower-left corner of the lattice at (0, 25 mm): first row 52.5 mm above
  the floor); box 1.54 m wide, inner faces x = 0, x = 1.54 m, floor y = 0, fixed walls 5 cm
  thick and 1.45 m high; IQS_CLB mu = 0.5; alert 1.25 mm; dt = 2e-4 s, theta = 0.5; NLGS
  Stored_Delassus_Loops, QM/16, tol 1.666e-4, 10 sweeps between checks, at most 100 checks
  (1000 sweeps); 10,000 steps.

Walls: --walls joncs (default) builds them as LMGC90 JONCx (a rectangle with half-disc ends,
half thickness 25 mm), --walls polygons as POLYG rectangles, which is what nscd has. Their inner
faces are the same in both cases and the same as nscd's box (shared/samples.cpp, add_box).

Usage (LMGC90 built in /work/lmgc90/build, so that PYTHONPATH=/work/lmgc90/build):
  python3 deposit_700.py --export tests/data/lmgc90/deposit_700.txt   # the sample file only
  python3 deposit_700.py --run --steps 10000 --workdir /tmp/lmgc90_run  # build, run, measure
Outputs of --run, in --workdir: DATBOX/ (LMGC90's input), steps.csv (one row per step: contacts,
active contacts, sweeps, converged, max overlap from the detection gap, step time) and
summary.txt (the keys of nscd's deposit summary that LMGC90 can give).
"""
import argparse
import math
import os
import sys
import time

import numpy

import chipy_steps

SEED = 700
N, COLUMNS, ROWS, PITCH, Y0 = 700, 28, 25, 0.055, 0.025
RMIN, RMAX = 0.0125, 0.025
WIDTH, HEIGHT, WALL = 1.54, 1.45, 0.05
DENSITY, MU, ALERT = 2700.0, 0.5, 1.25e-3
DT, THETA, TOL, CHECK_EVERY, MAX_CHECKS = 2e-4, 0.5, 1.666e-4, 10, 100


def build(pre, walls):
    """Bodies, materials, models, laws and visibility tables of the deposit (pylmgc90.pre)."""
    bodies = pre.avatars()
    mats = pre.materials()
    mods = pre.models()
    tacts = pre.tact_behavs()
    svs = pre.see_tables()
    grain = pre.material(name='PDURx', materialType='RIGID', density=DENSITY)
    wallm = pre.material(name='TDURx', materialType='RIGID', density=DENSITY)
    mats.addMaterial(grain, wallm)
    mod = pre.model(name='rigid', physics='MECAx', element='Rxx2D', dimension=2)
    mods.addModel(mod)

    radii = pre.granulo_Random(N, RMIN, RMAX, seed=SEED)   # seeds numpy.random
    thetas = numpy.random.uniform(0.0, 2.0 * math.pi / 5.0, N)  # same stream, after the radii
    coor = pre.squareLattice2D(COLUMNS, ROWS, PITCH, x0=0.0, y0=Y0)
    grains = []
    for i in range(N):
        b = pre.rigidPolygon(model=mod, material=grain, center=coor[i], theta=float(thetas[i]),
                             color='BLUEx', generation_type='regular', nb_vertices=5, radius=float(radii[i]))
        bodies += b
        grains.append((float(coor[i, 0]), float(coor[i, 1]), float(radii[i]), float(thetas[i]), b))

    t = WALL
    # inner faces: floor y = 0 (x from -t to WIDTH + t), walls x = 0 and x = WIDTH (y from -t to HEIGHT)
    boxes = [((0.5 * WIDTH, -0.5 * t), WIDTH + 2 * t, t, 0.0),
             ((-0.5 * t, 0.5 * (HEIGHT - t)), HEIGHT + t, t, 0.5 * math.pi),
             ((WIDTH + 0.5 * t, 0.5 * (HEIGHT - t)), HEIGHT + t, t, 0.5 * math.pi)]
    for centre, length, thick, angle in boxes:
        if walls == 'joncs':
            w = pre.rigidJonc(axe1=0.5 * length, axe2=0.5 * thick, center=list(centre), model=mod, material=wallm,
                              color='WALLx')
            if angle:
                w.rotate(psi=angle, center=w.nodes[1].coor)
        else:
            hl, ht = 0.5 * length, 0.5 * thick
            if angle:
                hl, ht = ht, hl
            v = numpy.array([[-hl, -ht], [hl, -ht], [hl, ht], [-hl, ht]])
            w = pre.rigidPolygon(model=mod, material=wallm, center=list(centre), color='WALLx',
                                 generation_type='full', vertices=v)
        w.imposeDrivenDof(component=[1, 2, 3], dofty='vlocy')
        bodies += w

    law = pre.tact_behav(name='iqsc0', law='IQS_CLB', fric=MU)
    tacts += law
    svs += pre.see_table(CorpsCandidat='RBDY2', candidat='POLYG', colorCandidat='BLUEx', behav=law,
                         CorpsAntagoniste='RBDY2', antagoniste='POLYG', colorAntagoniste='BLUEx', alert=ALERT)
    svs += pre.see_table(CorpsCandidat='RBDY2', candidat='POLYG', colorCandidat='BLUEx', behav=law,
                         CorpsAntagoniste='RBDY2', antagoniste='JONCx' if walls == 'joncs' else 'POLYG',
                         colorAntagoniste='WALLx', alert=ALERT)
    return bodies, mats, mods, tacts, svs, grains


def export(grains, path, walls):
    """One line per grain: index, centre x y, circumradius, orientation, the 5 vertices (m, rad)."""
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, 'w') as f:
        f.write('# nscd sample file: the 700 pentagons of the LMGC90 comparison deposit\n')
        f.write('# made by contrib/lmgc90/deposit_700.py --export (LMGC90 3.0.0.rc1 pylmgc90.pre: granulo_Random(700, '
                '0.0125, 0.025, seed=%d), then numpy.random.uniform(0, 2pi/5, 700) orientations, squareLattice2D(28, 25, '
                '0.055, x0=0, y0=0.025), rigidPolygon(generation_type=regular, nb_vertices=5, radius, theta))\n' % SEED)
        f.write('# vertex k of grain i is (x, y) + r (cos(theta + 2 pi k/5), sin(theta + 2 pi k/5)), counter-clockwise\n')
        f.write('# box of the LMGC90 run: inner faces x = 0, x = 1.54, floor y = 0 (walls: %s)\n' % walls)
        f.write('# LMGC90 itself reads these values back from its DATBOX files, written with 8 significant digits: '
                'its grains differ from these by up to ~1e-10 m\n')
        f.write('# columns: index x y radius theta x0 y0 x1 y1 x2 y2 x3 y3 x4 y4 (SI units)\n')
        for i, (x, y, r, th, b) in enumerate(grains):
            local = numpy.asarray(b.contactors[0].vertices)
            c, s = math.cos(th), math.sin(th)
            verts = [(x + c * vx - s * vy, y + s * vx + c * vy) for vx, vy in local[:, :2]]
            f.write('%d %.17g %.17g %.17g %.17g %s\n' % (i, x, y, r, th, ' '.join('%.17g %.17g' % v for v in verts)))


def run(chipy, steps, workdir, walls, relax=1.0):
    """Runs the deposit with chipy, the NLGS loop spelled out so that its sweeps can be counted."""
    chipy_steps.start(chipy, DT, THETA)
    rows = []
    # steps.csv is written as the run goes (flushed every 100 steps): a stopped run keeps its rows
    out = open(os.path.join(workdir, 'steps.csv'), 'w')
    out.write('step,contacts,active,sweeps,checks,converged,max_overlap,step_s\n')
    t0, cpu0 = time.perf_counter(), time.process_time()
    measure_s = 0.0
    for n in range(1, steps + 1):
        ts = time.perf_counter()
        # ExSolver('Stored_Delassus_Loops', 'QM/16', TOL, RELAX, 10, 100), its loop spelled out
        sweeps, checks, status = chipy_steps.step(chipy, 'QM/16', TOL, relax, CHECK_EVERY, MAX_CHECKS)
        tm = time.perf_counter()
        nc, active, overlap = chipy_steps.measure(chipy, numpy)
        te = time.perf_counter()
        measure_s += te - tm
        rows.append((n, nc, active, sweeps, checks, 1 if status == 0 else 0, overlap, te - ts))
        out.write('%d,%d,%d,%d,%d,%d,%.9g,%.6g\n' % rows[-1])
        if n % 100 == 0:
            out.flush()
            print('step %d  contacts %d  sweeps %d  max overlap %.2e m  elapsed %.0f s' % (n, nc, sweeps, overlap,
                                                                                          time.perf_counter() - t0), flush=True)
    wall, cpu = time.perf_counter() - t0, time.process_time() - cpu0
    chipy.Finalize()
    out.close()
    a = numpy.array([r[:7] for r in rows], dtype=float)
    first = lambda col: int(a[numpy.argmax(a[:, col] > 0), 0]) if (a[:, col] > 0).any() else -1
    with open(os.path.join(workdir, 'summary.txt'), 'w') as f:
        f.write('code = LMGC90 (chipy), walls %s\n' % walls)
        f.write('steps = %d\n' % steps)
        f.write('relax = %g\n' % relax)
        f.write('wall_time = %.6g\n' % wall)
        f.write('cpu_time = %.6g\n' % cpu)
        f.write('measure_time = %.6g\n' % measure_s)
        f.write('mean_sweeps = %.6g\n' % a[:, 3].mean())
        f.write('mean_sweeps_with_checks = %.6g\n' % (a[:, 3] + a[:, 4]).mean())
        f.write('capped_steps = %d\n' % int((a[:, 5] == 0).sum()))
        f.write('first_contact_step = %d\n' % first(1))
        f.write('first_active_contact_step = %d\n' % first(2))
        f.write('max_overlap = %.6g\n' % a[:, 6].max())
        f.write('final_max_overlap = %.6g\n' % a[-1, 6])
        f.write('final_contacts = %d\n' % int(a[-1, 1]))
    print(open(os.path.join(workdir, 'summary.txt')).read(), end='')


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument('--export', metavar='FILE', help='write the nscd sample file')
    p.add_argument('--run', action='store_true', help='run the deposit with chipy in --workdir')
    p.add_argument('--steps', type=int, default=10000)
    p.add_argument('--workdir', default='lmgc90_deposit_700')
    p.add_argument('--walls', choices=['joncs', 'polygons'], default='joncs')
    p.add_argument('--relax', type=float, default=1.0,
                   help="NLGS relaxation RELAX of nlgs_SetCheckType (nscd's --relaxation; default 1)")
    a = p.parse_args()
    if not a.export and not a.run:
        p.error('nothing to do: give --export FILE and/or --run')
    if a.steps < 1:
        p.error('--steps must be >= 1')
    from pylmgc90 import pre
    bodies, mats, mods, tacts, svs, grains = build(pre, a.walls)
    if a.export:
        export(grains, a.export, a.walls)
    if a.run:
        os.makedirs(a.workdir, exist_ok=True)
        os.chdir(a.workdir)
        pre.writeDatbox(2, mats, mods, bodies, tacts, svs, datbox_path='DATBOX', gravy=[0.0, -9.81, 0.0])
        from pylmgc90 import chipy
        run(chipy, a.steps, '.', a.walls, a.relax)


if __name__ == '__main__':
    sys.exit(main())
