#!/usr/bin/env python3
"""Fits the four CM-200 dpscan costs (models/cm200.yaml, section dpscan)
to the visible cells of seed 004 (Tables 1 and 2, time_s), by
non-negative least squares on relative error.

    PGSIM_DP_COEF=/tmp/coef.csv build/pgsim reproduce ortega93 >/dev/null
    python3 scripts/fit-ortega93.py /tmp/coef.csv configs/papers/ortega93.yaml

The frame time of a SIMD cell is linear in the costs (dp_cost.h):
time = op * op_slices + step * steps + send_setup * sends
     + send_slice * slices; the coefficients come from the simulator.
"""
import sys
import itertools
import yaml


def published(path):
    d = yaml.safe_load(open(path))
    out = {}
    for t in ("1", "2"):
        for row, cols in d["tables"][t]["rows"].items():
            v = cols["time_s"]
            out[(t, row)] = v["value"] if isinstance(v, dict) else v
    return out


def solve(a, b):
    """Least squares by normal equations (4 unknowns), Gaussian elim."""
    n = len(a[0])
    m = [[sum(r[i] * r[j] for r in a) for j in range(n)] +
         [sum(r[i] * y for r, y in zip(a, b))] for i in range(n)]
    for i in range(n):
        p = max(range(i, n), key=lambda k: abs(m[k][i]))
        m[i], m[p] = m[p], m[i]
        for k in range(n):
            if k != i and m[i][i] != 0:
                f = m[k][i] / m[i][i]
                m[k] = [x - f * y for x, y in zip(m[k], m[i])]
    return [m[i][n] / m[i][i] if m[i][i] else 0.0 for i in range(n)]


def main():
    pub = published(sys.argv[2])
    rows = []
    for line in open(sys.argv[1]):
        t, row, *k = line.strip().split(",")
        if (t, row) in pub:
            rows.append(([float(x) for x in k], pub[(t, row)]))
    names = ["op", "step", "send_setup", "send_slice"]
    best = None
    # Non-negative: try every subset of free parameters, keep the best
    # feasible one.
    for r in range(1, 5):
        for free in itertools.combinations(range(4), r):
            a = [[k[i] / y for i in free] for k, y in rows]
            x = solve(a, [1.0] * len(rows))
            if min(x) < 0:
                continue
            full = [0.0] * 4
            for i, v in zip(free, x):
                full[i] = v
            err = sum((sum(c * v for c, v in zip(k, full)) / y - 1) ** 2
                      for k, y in rows)
            if best is None or err < best[0]:
                best = (err, full)
    err, full = best
    for n, v in zip(names, full):
        print(f"{n}: {v * 1e6:.4g} us")
    for k, y in rows:
        s = sum(c * v for c, v in zip(k, full))
        print(f"  {y:8.3f} -> {s:8.3f} ({(s - y) / y * 100:+.1f} %)")
    print(f"rms relative error {(err / len(rows)) ** 0.5 * 100:.1f} %")


main()
