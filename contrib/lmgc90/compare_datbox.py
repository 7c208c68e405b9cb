#!/usr/bin/env python3
"""contrib/lmgc90/compare_datbox.py -- the end state of one DATBOX scene run by both codes, measured
the same way from the files each code writes (issue #39, docs/benchmarks.md section 9).

  python3 contrib/lmgc90/compare_datbox.py --lmgc90 /tmp/lmgc90_disks --nscd /tmp/nscd_disks

--lmgc90 is run_datbox.py's workdir (DATBOX/BODIES.DAT, OUTBOX/DOF.LAST, OUTBOX/Vloc_Rloc.LAST,
summary.txt); --nscd is datbox_run's --output, run with --write-datbox OUTPUT/DATBOX (BODIES.DAT,
DOF.INI, Vloc_Rloc.INI, and summary.txt, steps.csv beside). Per code: the contacts (Vloc_Rloc
records), those with a non-zero normal force, the coordination (2 x grain pairs in contact with
a force / grains), the mean height of the grain centres (the packing), the mean and largest
overlap (-gapTT over the records with gapTT < 0), the mean sweeps per step and the CPU time.
Grains are the bodies with a DISKx or POLYG.
"""
import argparse
import csv
import os
import re
import sys

NUM = r'([-+]?\d*\.?\d+(?:[EeDd][-+]?\d+)?)'


def num(s):
    return float(s.replace('D', 'E').replace('d', 'e'))


def blocks(path, head):
    """The text of each block that starts with the line `head` ($bdyty, $icdan ...)."""
    text = open(path).read()
    parts = re.split(r'^\%s' % head, text, flags=re.M)
    return parts[1:]


def bodies(path):
    """{body: (x0, y0, is_grain)} from BODIES.DAT."""
    out = {}
    for b in blocks(path, '$bdyty'):
        n = int(re.search(r'RBDY2\s+(\d+)', b).group(1))
        m = re.search(r'coo1=\s*' + NUM + r'\s+coo2=\s*' + NUM, b)
        grain = re.search(r'^\s*(DISKx|POLYG)\s', b, flags=re.M) is not None
        out[n] = (num(m.group(1)), num(m.group(2)), grain)
    return out


def dofs(path):
    """{body: (X1, X2)} from DOF.INI / DOF.LAST."""
    out = {}
    for b in blocks(path, '$bdyty'):
        n = int(re.search(r'RBDY2\s+(\d+)', b).group(1))
        m = re.search(r'X\(1\)=\s*' + NUM + r'\s+X\(2\)=\s*' + NUM, b)
        out[n] = (num(m.group(1)), num(m.group(2)))
    return out


def contacts(path):
    """[(cd body, an body, rln, gap)] from Vloc_Rloc.INI / Vloc_Rloc.LAST."""
    out = []
    for b in blocks(path, '$icdan'):
        cd, an = re.findall(r'RBDY2\s+(\d+)', b)[:2]
        rln = num(re.search(r'rln/H\s*' + NUM, b).group(1))
        gap = num(re.search(r'gapTT\s*' + NUM, b).group(1))
        out.append((int(cd), int(an), rln, gap))
    return out


def summary(path):
    d = {}
    if os.path.exists(path):
        for line in open(path):
            if '=' in line:
                k, v = line.split('=', 1)
                d[k.strip()] = v.strip()
    return d


def measure(bodies_dat, dof, vloc, summ, steps_csv=None):
    b, x, c = bodies(bodies_dat), dofs(dof), contacts(vloc)
    grains = [n for n, v in b.items() if v[2]]
    heights = [b[n][1] + x.get(n, (0.0, 0.0))[1] for n in grains]
    pairs = {(min(i, j), max(i, j)) for i, j, rln, _ in c if rln != 0.0 and b[i][2] and b[j][2]}
    over = [-g for _, _, _, g in c if g < 0.0]
    s = summary(summ)
    sweeps = s.get('mean_sweeps')
    if sweeps is None and steps_csv and os.path.exists(steps_csv):
        rows = list(csv.DictReader(open(steps_csv)))
        sweeps = sum(float(r['sweeps']) for r in rows) / max(1, len(rows))
    return {'grains': len(grains), 'contacts': len(c), 'active': sum(1 for r in c if r[2] != 0.0),
            'coordination': 2.0 * len(pairs) / max(1, len(grains)), 'mean_height': sum(heights) / max(1, len(heights)),
            'mean_overlap': sum(over) / len(over) if over else 0.0, 'max_overlap': max(over) if over else 0.0,
            'sweeps': float(sweeps) if sweeps is not None else float('nan'),
            'cpu': float(s['cpu_time']) if 'cpu_time' in s else float('nan')}


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument('--lmgc90', required=True, help="run_datbox.py's workdir")
    p.add_argument('--nscd', required=True, help="datbox_run's --output (with --write-datbox OUTPUT/DATBOX)")
    p.add_argument('--nscd-cpu', type=float, help='CPU time of the nscd run (s), from /usr/bin/time')
    p.add_argument('--lmgc90-cpu', type=float, help='CPU time of the LMGC90 run (s), instead of its summary')
    a = p.parse_args()
    L, N = a.lmgc90, a.nscd
    lm = measure(os.path.join(L, 'DATBOX', 'BODIES.DAT'), os.path.join(L, 'OUTBOX', 'DOF.LAST'),
                 os.path.join(L, 'OUTBOX', 'Vloc_Rloc.LAST'), os.path.join(L, 'summary.txt'))
    ns = measure(os.path.join(N, 'DATBOX', 'BODIES.DAT'), os.path.join(N, 'DATBOX', 'DOF.INI'),
                 os.path.join(N, 'DATBOX', 'Vloc_Rloc.INI'), os.path.join(N, 'no-summary'), os.path.join(N, 'steps.csv'))
    if a.nscd_cpu is not None:
        ns['cpu'] = a.nscd_cpu
    if a.lmgc90_cpu is not None:
        lm['cpu'] = a.lmgc90_cpu
    print('%-14s %14s %14s %10s' % ('', 'LMGC90', 'nscd', 'nscd/LMGC90'))
    for k in ('grains', 'contacts', 'active', 'coordination', 'mean_height', 'mean_overlap', 'max_overlap', 'sweeps', 'cpu'):
        r = ns[k] / lm[k] if lm[k] else float('nan')
        print('%-14s %14.6g %14.6g %10.4f' % (k, lm[k], ns[k], r))


if __name__ == '__main__':
    sys.exit(main())
