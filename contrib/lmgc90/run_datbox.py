#!/usr/bin/env python3
"""contrib/lmgc90/run_datbox.py -- runs a DATBOX folder with LMGC90's chipy under the settings
`datbox_run` takes as options, so that the two codes run one scene alike (issue #39,
docs/benchmarks.md section 9).

The NLGS loop is spelled out (as ExSolver does it: CHECK_EVERY sweeps, then a check) so that its
sweeps can be counted (chipy_steps.py, shared with deposit_700.py). At the end it writes LMGC90's OUTBOX/DOF.LAST and OUTBOX/Vloc_Rloc.LAST,
which contrib/lmgc90/compare_datbox.py reads next to nscd's --write-datbox folder.

Usage (LMGC90 built in /work/lmgc90/build):
  PYTHONPATH=/work/lmgc90/build python3 contrib/lmgc90/run_datbox.py --datbox tests/data/datbox/disks_jcbox \
      --workdir /tmp/lmgc90_disks --steps 500 --dt 1e-2
Outputs in --workdir: DATBOX/ (a copy), OUTBOX/, steps.csv (per step: interactions, those with a
non-zero force, sweeps, converged, the largest overlap -gapTT) and summary.txt (cpu_time: the
process CPU time of the time loop without the per-step measurement of the overlap).
"""
import argparse
import os
import shutil
import sys
import time

import chipy_steps


def run(a):
    import numpy
    from pylmgc90 import chipy
    chipy_steps.start(chipy, a.dt, a.theta)
    rows, spent = [], 0.0
    cpu0 = time.process_time()
    for n in range(1, a.steps + 1):
        sweeps, checks, status = chipy_steps.step(chipy, a.norm, a.tol, a.relaxation, a.check_every,
                                                  max(1, a.sweeps // a.check_every))
        m0 = time.process_time()
        nc, active, overlap = chipy_steps.measure(chipy, numpy)
        spent += time.process_time() - m0
        rows.append((n, nc, active, sweeps, checks, 1 if status in (0, -1) else 0, overlap))
    cpu = time.process_time() - cpu0 - spent
    chipy.WriteLastDof()
    chipy.WriteLastVlocRloc()
    chipy.Finalize()
    with open('steps.csv', 'w') as f:
        f.write('step,contacts,active,sweeps,checks,converged,max_overlap\n')
        for r in rows:
            f.write('%d,%d,%d,%d,%d,%d,%.9g\n' % r)
    s = numpy.array(rows, dtype=float)
    with open('summary.txt', 'w') as f:
        f.write('code = LMGC90 (chipy)\nsteps = %d\ncpu_time = %.6g\n' % (a.steps, cpu))
        f.write('mean_sweeps = %.6g\n' % s[:, 3].mean())
        f.write('mean_sweeps_with_checks = %.6g\n' % (s[:, 3] + s[:, 4]).mean())
        f.write('unconverged_steps = %d\n' % int((s[:, 5] == 0).sum()))
        f.write('max_overlap = %.6g\n' % s[:, 6].max())
        f.write('contacts = %d\nactive = %d\n' % (rows[-1][1], rows[-1][2]))
    print(open('summary.txt').read(), end='')


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument('--datbox', required=True, help='the DATBOX folder (copied into WORKDIR/DATBOX)')
    p.add_argument('--workdir', required=True)
    p.add_argument('--steps', type=int, default=1000)
    p.add_argument('--dt', type=float, default=1e-3)
    p.add_argument('--theta', type=float, default=0.5)
    p.add_argument('--tol', type=float, default=1.666e-4)
    p.add_argument('--norm', default='QM/16', help="LMGC90's norm: 'Quad ', 'QM/16', 'Maxm '")
    p.add_argument('--relaxation', type=float, default=1.0)
    p.add_argument('--sweeps', type=int, default=1000, help='at most this many sweeps per step')
    p.add_argument('--check-every', type=int, default=10, help='sweeps between checks')
    a = p.parse_args()
    if a.steps < 1 or a.sweeps < 1 or a.check_every < 1:
        p.error('--steps, --sweeps and --check-every must be >= 1')
    a.norm = (a.norm + '     ')[:5]  # LMGC90 compares 5 characters
    src = os.path.abspath(a.datbox)
    os.makedirs(a.workdir, exist_ok=True)
    os.chdir(a.workdir)
    shutil.rmtree('DATBOX', ignore_errors=True)
    shutil.rmtree('OUTBOX', ignore_errors=True)
    shutil.copytree(src, 'DATBOX')
    run(a)


if __name__ == '__main__':
    sys.exit(main())
