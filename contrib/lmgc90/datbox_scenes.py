#!/usr/bin/env python3
"""contrib/lmgc90/datbox_scenes.py -- four small LMGC90 2D rigid scenes, built with LMGC90's own
pre-processor (pylmgc90.pre) and written as DATBOX folders, for the side-by-side runs of issue #39
(docs/benchmarks.md section 9, tests/data/datbox/<scene>/).

The scenes follow LMGC90's examples (examples/Pre/prepro_grains/box, box_polyg, drum and
examples/Pre/wall2D/test_rigid_bricks of its source tree), made small so that they run in a test:
  disks_jcbox     disks deposited geometrically (pre.depositInBox2D) in a box of four fixed JONCx
  polygons_jcbox  the same deposit, each disk replaced by a regular polygon of 3, 4 or 5 vertices
  disk_drum       disks deposited in the lower half of an xKSID drum (pre.depositInDrum2D) that
                  turns at a constant speed
  block_wall      a running-bond wall of rigid bricks (pre.brick2D) on a fixed JONCx floor
Radii are drawn with pre.granulo_Random and a fixed seed, so the files are the same every time.

Usage (LMGC90 built in /work/lmgc90/build):
  PYTHONPATH=/work/lmgc90/build python3 contrib/lmgc90/datbox_scenes.py --out tests/data/datbox
  PYTHONPATH=/work/lmgc90/build python3 contrib/lmgc90/datbox_scenes.py --out DIR --scene disk_drum
"""
import argparse
import math
import os
import sys

SEED = 39


def containers(pre):
    """Empty bodies, materials, models, laws and see tables, and the rigid 2D model."""
    c = dict(bodies=pre.avatars(), mats=pre.materials(), mods=pre.models(), tacts=pre.tact_behavs(),
             svs=pre.see_tables())
    c['mod'] = pre.model(name='rigid', physics='MECAx', element='Rxx2D', dimension=2)
    c['mods'].addModel(c['mod'])
    return c


def materials(pre, c, grain_density, wall_density):
    grain = pre.material(name='PLEXx', materialType='RIGID', density=grain_density)
    wall = pre.material(name='TDURx', materialType='RIGID', density=wall_density)
    c['mats'].addMaterial(grain, wall)
    return grain, wall


def see(pre, c, law, cd, cd_color, an, an_color, alert):
    c['svs'] += pre.see_table(CorpsCandidat='RBDY2', candidat=cd, colorCandidat=cd_color, behav=law,
                              CorpsAntagoniste='RBDY2', antagoniste=an, colorAntagoniste=an_color, alert=alert)


def law(pre, c, name, fric):
    t = pre.tact_behav(name=name, law='IQS_CLB', fric=fric)
    c['tacts'] += t
    return t


def jonc_box(pre, c, wall, lx, ly, thick):
    """Four fixed JONCx of half thickness `thick` whose inner faces are x = 0, x = lx, y = 0, y = ly."""
    sides = [([0.5 * lx, -thick], 0.5 * lx + thick, 0.0), ([0.5 * lx, ly + thick], 0.5 * lx + thick, 0.0),
             ([-thick, 0.5 * ly], 0.5 * ly + thick, -0.5 * math.pi), ([lx + thick, 0.5 * ly], 0.5 * ly + thick, 0.5 * math.pi)]
    for centre, half, psi in sides:
        j = pre.rigidJonc(axe1=half, axe2=thick, center=centre, model=c['mod'], material=wall, color='WALLx')
        c['bodies'] += j
        if psi:
            j.rotate(psi=psi, center=j.nodes[1].coor)
        j.imposeDrivenDof(component=[1, 2, 3], dofty='vlocy')


def box_deposit(pre, n, lx, ly, rmin, rmax):
    radii = pre.granulo_Random(n, rmin, rmax, seed=SEED)
    kept, coor, radii = pre.depositInBox2D(radii, lx, ly)
    return kept, coor, radii


def disks_jcbox(pre, n=120, lx=16.0, ly=16.0, rmin=0.4, rmax=0.8):
    c = containers(pre)
    grain, wall = materials(pre, c, 100.0, 1000.0)
    kept, coor, radii = box_deposit(pre, n, lx, ly, rmin, rmax)
    for r, xy in zip(radii, coor):
        c['bodies'] += pre.rigidDisk(r=float(r), center=[float(xy[0]), float(xy[1])], model=c['mod'], material=grain,
                                     color='BLEUx')
    jonc_box(pre, c, wall, lx, ly, rmax)
    see(pre, c, law(pre, c, 'iqsc0', 0.3), 'DISKx', 'BLEUx', 'DISKx', 'BLEUx', 0.1 * rmin)
    see(pre, c, law(pre, c, 'iqsc1', 0.5), 'DISKx', 'BLEUx', 'JONCx', 'WALLx', 0.1 * rmin)
    return c, kept


def polygons_jcbox(pre, n=90, lx=14.0, ly=16.0, rmin=0.4, rmax=0.8):
    c = containers(pre)
    grain, wall = materials(pre, c, 100.0, 1000.0)
    kept, coor, radii = box_deposit(pre, n, lx, ly, rmin, rmax)
    for i, (r, xy) in enumerate(zip(radii, coor)):
        c['bodies'] += pre.rigidPolygon(radius=float(r), center=[float(xy[0]), float(xy[1])], nb_vertices=3 + i % 3,
                                        model=c['mod'], material=grain, color='BLEUx')
    jonc_box(pre, c, wall, lx, ly, rmax)
    see(pre, c, law(pre, c, 'iqsc0', 0.3), 'POLYG', 'BLEUx', 'POLYG', 'BLEUx', 0.1 * rmin)
    see(pre, c, law(pre, c, 'iqsc1', 0.5), 'POLYG', 'BLEUx', 'JONCx', 'WALLx', 0.1 * rmin)
    return c, kept


def disk_drum(pre, n=120, rext=8.0, rmin=0.4, rmax=0.8, speed=math.pi / 30.0):
    c = containers(pre)
    grain, wall = materials(pre, c, 100.0, 100.0)
    radii = pre.granulo_Random(n, rmin, rmax, seed=SEED)
    kept, coor, radii = pre.depositInDrum2D(radii, rext)
    for r, xy in zip(radii, coor):
        c['bodies'] += pre.rigidDisk(r=float(r), center=[float(xy[0]), float(xy[1])], model=c['mod'], material=grain,
                                     color='BLEUx')
    drum = pre.rigidDisk(r=rext, center=[rext, rext], model=c['mod'], material=wall, color='WALLx', is_Hollow=True)
    c['bodies'] += drum
    drum.imposeDrivenDof(component=[1, 2], dofty='vlocy')
    drum.imposeDrivenDof(component=3, dofty='vlocy', ct=speed, rampi=1.0)
    see(pre, c, law(pre, c, 'iqsc0', 0.3), 'DISKx', 'BLEUx', 'DISKx', 'BLEUx', 0.1 * rmin)
    see(pre, c, law(pre, c, 'iqsc1', 0.5), 'DISKx', 'BLEUx', 'xKSID', 'WALLx', 0.1 * rmin)
    return c, kept


def block_wall(pre, courses=8, bricks=5, lx=0.1, ly=0.05):
    """A running-bond wall: odd courses start and end with a half brick; colours alternate per course."""
    c = containers(pre)
    grain, wall = materials(pre, c, 2000.0, 2500.0)
    full, half = pre.brick2D('brick', lx, ly), pre.brick2D('half', 0.5 * lx, ly)
    count = 0
    for k in range(courses):
        row = [full] * bricks if k % 2 == 0 else [half] + [full] * (bricks - 1) + [half]
        x, y = 0.0, (k + 0.5) * ly
        for b in row:
            c['bodies'] += b.rigidBrick(center=[x + 0.5 * b.lx, y], model=c['mod'], material=grain,
                                        color='BLEUx' if k % 2 == 0 else 'REDxx')
            x += b.lx
            count += 1
    floor = pre.rigidJonc(axe1=0.5 * bricks * lx + ly, axe2=0.5 * ly, center=[0.5 * bricks * lx, -0.5 * ly],
                          model=c['mod'], material=wall, color='WALLx')
    c['bodies'] += floor
    floor.imposeDrivenDof(component=[1, 2, 3], dofty='vlocy')
    brick_law = law(pre, c, 'iqsc0', 0.3)
    for a, b in (('BLEUx', 'BLEUx'), ('REDxx', 'REDxx'), ('BLEUx', 'REDxx')):
        see(pre, c, brick_law, 'POLYG', a, 'POLYG', b, 5e-3)
    floor_law = law(pre, c, 'iqsc1', 0.5)
    for a in ('BLEUx', 'REDxx'):
        see(pre, c, floor_law, 'POLYG', a, 'JONCx', 'WALLx', 5e-3)
    return c, count


def scaled(pre, name, k):
    """A scene with k times the grains, its lengths times sqrt(k)."""
    f = math.sqrt(k)
    if name == 'disk_drum':
        return disk_drum(pre, n=int(round(120 * k)), rext=8.0 * f)
    lx = 16.0 if name == 'disks_jcbox' else 14.0
    n = 120 if name == 'disks_jcbox' else 90
    return SCENES[name](pre, n=int(round(n * k)), lx=lx * f, ly=16.0 * f)


SCENES = {'disks_jcbox': disks_jcbox, 'polygons_jcbox': polygons_jcbox, 'disk_drum': disk_drum,
          'block_wall': block_wall}


def write_readme(path, name, grains):
    with open(os.path.join(path, 'README'), 'w') as f:
        f.write('%s: %d grains; made with LMGC90 3.0.0.rc1 pylmgc90.pre by contrib/lmgc90/datbox_scenes.py '
                '--scene %s (seed %d); run side by side with contrib/lmgc90/run_datbox.py '
                '(docs/benchmarks.md section 9)\n' % (name, grains, name, SEED))


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument('--out', required=True, help='parent folder: each scene goes to OUT/<scene>')
    p.add_argument('--scene', choices=sorted(SCENES), action='append', help='only these scenes (default: all)')
    p.add_argument('--scale', type=float, default=1.0,
                   help='disks_jcbox, polygons_jcbox, disk_drum: SCALE times the grains, the box or drum in proportion '
                        '(a larger case for timings; default 1: the files of tests/data/datbox)')
    a = p.parse_args()
    if not a.scale > 0:
        p.error('--scale must be > 0')
    from pylmgc90 import pre
    for name in a.scene or sorted(SCENES):
        c, grains = SCENES[name](pre) if name == 'block_wall' or a.scale == 1.0 else scaled(pre, name, a.scale)
        path = os.path.join(a.out, name)
        os.makedirs(path, exist_ok=True)
        pre.writeDatbox(2, c['mats'], c['mods'], c['bodies'], c['tacts'], c['svs'], datbox_path=path,
                        gravy=[0.0, -9.81, 0.0])
        write_readme(path, name, grains)
        print('%s: %d grains in %s' % (name, grains, path))


if __name__ == '__main__':
    sys.exit(main())
