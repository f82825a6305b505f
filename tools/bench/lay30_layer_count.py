#!/usr/bin/env python3
"""Where the elements of the unloading meshes after a capped loading come from
(doc/benchmarks.md "Stop 64: lay30"), from the stderr of an egw-table built with
tools/bench/lay30_layer_probe.patch (on ff9888a) and run with EGW_LAY_PROBE=1.

MESHC lines: locating flag, elements, then the elements added by a_max's layers, the
rim's layers, the layers inside a, the kept elements halved, the graded family's own
elements, the attempt, the step. LVL lines: each refinement level's estimate/rel_tol.
The probe's knobs EGW_LAY_A (layers inside a, default 5), EGW_LAY_AMAX (8) and
EGW_LAY_RIMW (factor on the rim's last layer width, 1) set the variants measured there.

usage: lay30_layer_count.py STDERR_FILE
"""
import collections
import sys


def number(x):
    try:
        return float(x)
    except ValueError:   # Fortran's three-digit exponents (1.2-212): below any scale
        return 0.0


def main():
    lines = [l.split() for l in open(sys.argv[1])]
    tot = collections.Counter()
    for r in (l for l in lines if l and l[0] == 'MESHC'):
        k = 'loc' if r[1] == 'T' else 'lvl'
        n, na, nr, nA, nh, ng = map(int, r[2:8])
        tot[k + '_meshes'] += 1
        for name, v in (('elem', n), ('amax', na), ('rim', nr), ('a', nA), ('halve', nh),
                        ('graded', ng), ('n2', n * n)):
            tot[k + '_' + name] += v
    for k in ('loc', 'lvl'):
        m = tot[k + '_meshes']
        if not m:
            continue
        print(k, m, 'mean elements %.1f' % (tot[k + '_elem'] / m),
              ' '.join('%s %.2f' % (x, tot[k + '_' + x] / m)
                       for x in ('graded', 'amax', 'rim', 'a', 'halve')),
              'sum of elements^2 %.3g' % tot[k + '_n2'])
    levels = [l for l in lines if l and l[0] == 'LVL']
    print('levels', dict(collections.Counter(r[3] for r in levels)),
          'nodes sum', sum(int(r[4]) for r in levels))
    e1 = sorted(number(r[5]) for r in levels if r[3] == '1')
    if e1:
        n = len(e1)
        print('first refinement level est/rel_tol quantiles 0 .1 .25 .5 .75 .9 .95 .99 1:',
              [round(e1[int(q * (n - 1))], 4) for q in (0, .1, .25, .5, .75, .9, .95, .99, 1)])


if __name__ == '__main__':
    main()
