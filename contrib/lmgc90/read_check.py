#!/usr/bin/env python3
"""contrib/lmgc90/read_check.py -- does LMGC90 read a DATBOX as written? (issue #39)

Reads the folder with LMGC90's own reader (chipy.ReadDatbox, then ComputeMass) and compares what
LMGC90 holds for every RBDY2 -- mass, inertia, position (x, y, angle), velocity -- with what the
files say: mass Umas pi avrd^2, inertia mass gyrd^2 (BODIES.DAT, BULK_BEHAV.DAT), position coo + X
and velocity V (DOF.INI). Prints the largest relative difference of each and the contactor counts,
and exits with 1 if one passes 1e-6 (the files hold 8 significant digits).

  PYTHONPATH=/work/lmgc90/build python3 contrib/lmgc90/read_check.py out/datbox_disks/DATBOX
"""
import os
import re
import shutil
import sys
import tempfile

NUM = r'([-+]?\d*\.?\d+(?:[EeDd][-+]?\d+)?)'


def num(s):
    return float(s.replace('D', 'E').replace('d', 'e'))


def expected(folder):
    """{body: (mass, inertia, [x, y, a], [vx, vy, w])} from the files."""
    umas = {m.group(1): num(m.group(2)) for m in
            re.finditer(r'^\s(\w+)\s+RIGID\s+Umas=\s*' + NUM, open(os.path.join(folder, 'BULK_BEHAV.DAT')).read(), re.M)}
    out = {}
    for b in open(os.path.join(folder, 'BODIES.DAT')).read().split('$bdyty')[1:]:
        n = int(re.search(r'RBDY2\s+(\d+)', b).group(1))
        m = re.search(r'behav\s+(\w+)\s+avrd=\s*' + NUM + r'\s+gyrd=\s*' + NUM, b)
        coo = [num(c) for c in re.search(r'coo1=\s*' + NUM + r'\s+coo2=\s*' + NUM + r'\s+coo3=\s*' + NUM, b).groups()]
        mass = umas[m.group(1)] * 3.141592653589793 * num(m.group(2)) ** 2
        out[n] = [mass, mass * num(m.group(3)) ** 2, coo, [0.0, 0.0, 0.0]]
    dof = os.path.join(folder, 'DOF.INI')
    if os.path.exists(dof):
        for b in open(dof).read().split('$bdyty')[1:]:
            n = int(re.search(r'RBDY2\s+(\d+)', b).group(1))
            X = [num(re.search(r'X\(%d\)=\s*' % k + NUM, b).group(1)) for k in (1, 2, 3)]
            V = [num(re.search(r'V\(%d\)=\s*' % k + NUM, b).group(1)) for k in (1, 2, 3)]
            out[n][2] = [c + x for c, x in zip(out[n][2], X)]
            out[n][3] = V
    return out


def main():
    if len(sys.argv) != 2 or sys.argv[1] in ('-h', '--help'):
        print(__doc__)
        return 2
    folder = os.path.abspath(sys.argv[1])
    want = expected(folder)
    work = tempfile.mkdtemp(prefix='lmgc90_read_check_')
    shutil.copytree(folder, os.path.join(work, 'DATBOX'))
    os.chdir(work)
    from pylmgc90 import chipy
    chipy.Initialize()
    chipy.checkDirectories()
    chipy.utilities_DisableLogMes()
    chipy.SetDimension(2)
    chipy.TimeEvolution_SetTimeStep(1e-3)
    chipy.Integrator_InitTheta(0.5)
    chipy.ReadDatbox(deformable=False)
    chipy.ComputeMass()
    n = chipy.RBDY2_GetNbRBDY2()
    worst = {'mass': 0.0, 'inertia': 0.0, 'position': 0.0, 'velocity': 0.0}
    scale = max(1.0, max(abs(c) for w in want.values() for c in w[2][:2]))
    kinds = {}
    for i in range(1, n + 1):
        mass, inertia, pos, vel = want[i]
        got_pos = chipy.RBDY2_GetBodyVector('Coorb', i)
        got_vel = chipy.RBDY2_GetBodyVector('Vbeg_', i)
        worst['mass'] = max(worst['mass'], abs(chipy.RBDY2_GetBodyMass(i) - mass) / mass if mass else 0.0)
        worst['inertia'] = max(worst['inertia'], abs(chipy.RBDY2_GetBodyInertia(i) - inertia) / inertia if inertia else 0.0)
        worst['position'] = max(worst['position'], max(abs(g - w) for g, w in zip(got_pos, pos)) / scale)
        vs = max(1.0, max(abs(v) for v in vel))
        worst['velocity'] = max(worst['velocity'], max(abs(g - w) for g, w in zip(got_vel, vel)) / vs)
        t = chipy.RBDY2_GetContactorType(i)  # the body's first contactor
        kinds[t] = kinds.get(t, 0) + 1
    chipy.Finalize()
    shutil.rmtree(work, ignore_errors=True)
    print('LMGC90 read %d RBDY2 (first contactors: %s) from %s' % (n, ', '.join('%d %s' % (v, k) for k, v in sorted(kinds.items())), folder))
    print('largest relative difference to the files: ' + ', '.join('%s %.1e' % kv for kv in worst.items()))
    bad = n != len(want) or max(worst.values()) > 1e-6
    print('FAIL' if bad else 'OK')
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main())
