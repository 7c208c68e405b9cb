#!/usr/bin/env python3
"""contrib/lmgc90/compare_steps.py -- the LMGC90 and nscd runs of the 700-pentagon deposit side
by side, step window by step window (issue #8).

Usage:
  python3 compare_steps.py --lmgc90 RUN/steps.csv --nscd OUT/steps.csv [--window 500] [--max-sweeps 1000]
Inputs: the steps.csv of contrib/lmgc90/deposit_700.py --run (step, contacts, active, sweeps,
checks, converged, max_overlap, ...) and of lmgc90_deposit_case (step, contacts, active,
sweeps, converged, max_overlap, ...). Prints a Markdown table: per window, the mean sweeps per
step (LMGC90 as it counts them, i.e. without its check sweeps, and with them), the steps at the
sweep cap, the mean contacts and active contacts, and the largest overlap of each code. When
one run is shorter (a stopped LMGC90 run), both are compared over its steps. LMGC90 counts 10
sweeps for a step without contact (its solver runs one block on an empty list), nscd 0.
Overlaps are not the same quantity: LMGC90's is -gapTT, the gap its detection finds at the
start of the step; nscd's is -g_f, the end-of-step gap g_m + theta h U_N (see docs/benchmarks.md).
"""
import argparse
import csv
import sys


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit('%s: no step' % path)
    return rows


def first(rows, key):
    for r in rows:
        if float(r[key]) > 0:
            return int(float(r['step']))
    return -1


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument('--lmgc90', required=True)
    p.add_argument('--nscd', required=True)
    p.add_argument('--window', type=int, default=500)
    p.add_argument('--max-sweeps', type=int, default=1000)
    a = p.parse_args()
    if a.window < 1:
        p.error('--window must be >= 1')
    L, N = read(a.lmgc90), read(a.nscd)
    n = min(len(L), len(N))
    print('first contact step: LMGC90 %d, nscd %d; first nonzero force: LMGC90 %d, nscd %d' %
          (first(L, 'contacts'), first(N, 'contacts'), first(L, 'active'), first(N, 'active')))
    print()
    print('| steps | sweeps LMGC90 (+checks) | sweeps nscd | capped LMGC90 | capped nscd | contacts L / n | active L / n '
          '| max overlap LMGC90 (m) | max overlap nscd (m) |')
    print('|---|---|---|---|---|---|---|---|---|')
    tot = None
    for lo in list(range(0, n, a.window)) + [None]:
        if lo is None:
            lw, nw, label = L[:n], N[:n], 'all 1-%d' % n
        else:
            hi = min(lo + a.window, n)
            lw, nw = L[lo:hi], N[lo:hi]
            label = '%d-%d' % (lo + 1, lo + len(lw))
        k = len(lw)
        ls = sum(float(r['sweeps']) for r in lw) / k
        lc = sum(float(r['sweeps']) + float(r['checks']) for r in lw) / k
        ns = sum(float(r['sweeps']) for r in nw) / k
        lcap = sum(1 for r in lw if int(float(r['converged'])) == 0)
        ncap = sum(1 for r in nw if int(float(r['converged'])) == 0 and float(r['sweeps']) >= a.max_sweeps)
        lcon = sum(float(r['contacts']) for r in lw) / k
        ncon = sum(float(r['contacts']) for r in nw) / k
        lact = sum(float(r['active']) for r in lw) / k
        nact = sum(float(r['active']) for r in nw) / k
        lov = max(float(r['max_overlap']) for r in lw)
        nov = max(float(r['max_overlap']) for r in nw)
        print('| %s | %.1f (%.1f) | %.1f | %d | %d | %.0f / %.0f | %.0f / %.0f | %.2e | %.2e |' %
              (label, ls, lc, ns, lcap, ncap, lcon, ncon, lact, nact, lov, nov))
    print()
    print('final max overlap: LMGC90 %.2e m, nscd %.2e m' % (float(L[n - 1]['max_overlap']), float(N[n - 1]['max_overlap'])))


if __name__ == '__main__':
    main()
