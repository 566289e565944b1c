#!/usr/bin/env python3
"""Fits the CM-200 dpscan costs (models/cm200.yaml, section dpscan) to the
visible cells of seed 004 (Tables 1 and 2, time_s), by non-negative least
squares on relative error.  Nothing else is fitted; Tables 3-4 (CM-5) are
never read.

    PGSIM_DP_COEF=/tmp/coef.csv build/pgsim reproduce ortega93 >/dev/null
    python3 scripts/fit-ortega93.py /tmp/coef.csv \
        configs/papers/ortega93/published.yaml --fix=op=2.3 --fix=step=10

The frame time of a SIMD cell is linear in the costs (dp_cost.h):
time = op * op_slices + step * steps + scan_slice * scan_slices
     + send_setup * sends + send_slice * slices + send_vp * vp_slices
     + news_slice * news_slices + send_msg * msg_slices;
the coefficients come from the simulator (one CSV line per cell:
table,row, the eight sums in NAMES order, then scan_iters, pixel_iters,
flushes, which the fit ignores).  With --fix NAME=us a cost is held at a
value (e.g. one taken from the literature) and the others are fitted.
Prints the in-sample errors and the leave-one-out errors (each cell
predicted by a fit on the other 17).
"""
import itertools
import sys

import yaml

NAMES = ["op", "step", "scan_slice", "send_setup", "send_slice", "send_vp",
         "news_slice", "send_msg"]


def published(path):
    d = yaml.safe_load(open(path))
    out = {}
    for t in ("1", "2"):
        for row, cols in d["tables"][t]["rows"].items():
            v = cols["time_s"]
            out[(t, row)] = v["value"] if isinstance(v, dict) else v
    return out


def solve(a, b):
    """Least squares by normal equations, Gaussian elimination."""
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


def fit(rows, fixed):
    """Best non-negative fit over every subset of the free costs."""
    free_all = [i for i in range(len(NAMES)) if NAMES[i] not in fixed]
    best = None
    for r in range(1, len(free_all) + 1):
        for free in itertools.combinations(free_all, r):
            a, b = [], []
            for k, y in rows:
                rest = sum(k[i] * fixed[NAMES[i]] for i in range(len(NAMES))
                           if NAMES[i] in fixed)
                a.append([k[i] / y for i in free])
                b.append(1.0 - rest / y)
            x = solve(a, b)
            if min(x) < 0:
                continue
            full = [fixed.get(n, 0.0) for n in NAMES]
            for i, v in zip(free, x):
                full[i] = v
            err = sum((sum(c * v for c, v in zip(k, full)) / y - 1) ** 2
                      for k, y in rows)
            if best is None or err < best[0]:
                best = (err, full)
    return best


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--fix")]
    fixed = {}
    for a in sys.argv[1:]:
        if a.startswith("--fix"):
            n, v = a.split("=", 1)[1].split(":") if ":" in a else \
                a[len("--fix="):].split("=")
            fixed[n] = float(v) * 1e-6
    pub = published(args[1])
    rows, names = [], []
    for line in open(args[0]):
        t, row, *k = line.strip().split(",")
        if (t, row) in pub:
            rows.append(([float(x) for x in k], pub[(t, row)]))
            names.append(f"{t} {row}")
    err, full = fit(rows, fixed)
    for n, v in zip(NAMES, full):
        print(f"{n}: {v * 1e6:.4g} us")
    errs = []
    for (k, y), n in zip(rows, names):
        s = sum(c * v for c, v in zip(k, full))
        errs.append((s - y) / y)
        print(f"  {n:18s} {y:8.3f} -> {s:8.3f} ({errs[-1] * 100:+.1f} %)")
    print(f"rms relative error {(err / len(rows)) ** 0.5 * 100:.1f} %, "
          f"mean |error| {sum(map(abs, errs)) / len(errs) * 100:.1f} %, "
          f"worst {max(map(abs, errs)) * 100:.1f} %")
    loo = []
    for i, (k, y) in enumerate(rows):
        _, f = fit(rows[:i] + rows[i + 1:], fixed)
        loo.append((sum(c * v for c, v in zip(k, f)) - y) / y)
    print(f"leave-one-out: mean |error| "
          f"{sum(map(abs, loo)) / len(loo) * 100:.1f} %, "
          f"worst {max(map(abs, loo)) * 100:.1f} % "
          f"({names[max(range(len(loo)), key=lambda j: abs(loo[j]))]})")


main()
