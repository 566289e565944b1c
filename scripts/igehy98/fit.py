#!/usr/bin/env python3
"""Fit the calibrated costs of models/origin2000.yaml on the calibration
cells of seed 002's Argus table (configs/papers/igehy98/setup.yaml, role
calibration) and nothing else:

  Uniprocessor row (Nurbs 1.65 Hz, March 0.90 Hz) -> rast_pixel (Nurbs's
                   z-tested fragments), rast_blend (March's blended ones)
  Serial API row   (Nurbs 8.8 Hz,  March 6.3 Hz)  -> nurbs_vertex, march_voxel

Every other cost keeps its assumption.  The uniprocessor frame time is
exactly linear in the costs (one processor does all the work), so its two
costs come from one 2x2 solve on the counted vertices and pixels; the
serial rate is fitted by secant steps on each application's own cost.
The two fits alternate until they agree.  Prints the values to write into
models/origin2000.yaml (in microseconds).

    python3 scripts/igehy98/fit.py [build/pgsim]
"""
import json
import subprocess
import sys

PGSIM = sys.argv[1] if len(sys.argv) > 1 else "build/pgsim"
CFG = {"nurbs": "configs/argus-nurbs.yaml", "march": "configs/argus-march.yaml"}
UNI = {"nurbs": 1.65, "march": 0.90}
SERIAL = {"nurbs": 8.8, "march": 6.3}
APP_COST = {"nurbs": "nurbs_vertex", "march": "march_voxel"}
ROWS = {
    "uni": ["workload.uniprocessor=true", "workload.fill_rate=finite"],
    "serial": ["workload.contexts=1", "workload.fill_rate=finite"],
}


def run(app, row, costs):
    cmd = [PGSIM, "run", CFG[app], "-q", "--format", "json",
           "--set", "workload.check_image=false"]
    for s in ROWS[row]:
        cmd += ["--set", s]
    for k, v in costs.items():
        cmd += ["--set", "machine.nodes.cpu.costs.%s=%.6fus" % (k, v)]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True)
    doc = json.loads(out.stdout)
    m = {x["name"]: x["value"] for x in doc["metrics"]}
    return {k: m[k] for k in ("frame_ms", "vertices_issued", "pixels")}


FILL = {"nurbs": "rast_pixel", "march": "rast_blend"}


def fit_uni(costs, app):
    """T = T0 + (f - f0) X: the fill cost that hits the uniprocessor rate."""
    r = run(app, "uni", costs)
    key = FILL[app]
    return costs[key] + (1e6 / UNI[app] - r["frame_ms"] * 1e3) / r["pixels"]


def fit_serial(costs, app):
    """Secant on the application's cost to hit the serial rate."""
    key = APP_COST[app]
    target = 1e3 / SERIAL[app]  # ms
    x0 = costs[key]
    y0 = run(app, "serial", costs)["frame_ms"] - target
    x1 = x0 * 1.2
    for _ in range(6):
        c = dict(costs)
        c[key] = x1
        y1 = run(app, "serial", c)["frame_ms"] - target
        if abs(y1) < 1e-4 * target or y1 == y0:
            break
        x0, y0, x1 = x1, y1, x1 - y1 * (x1 - x0) / (y1 - y0)
        x1 = max(x1, 1e-6)
    return x1


def main():
    costs = {"rast_pixel": 0.1, "rast_blend": 0.3,
             "nurbs_vertex": 0.5, "march_voxel": 0.1}
    for it in range(3):
        for app in ("nurbs", "march"):
            costs[APP_COST[app]] = fit_serial(costs, app)
        for app in ("nurbs", "march"):
            costs[FILL[app]] = fit_uni(costs, app)
        print("iteration %d: %s" % (it, ", ".join(
            "%s %.4f us" % kv for kv in sorted(costs.items()))))
    for app in ("nurbs", "march"):
        for row, pub in (("uni", UNI[app]), ("serial", SERIAL[app])):
            hz = 1e3 / run(app, row, costs)["frame_ms"]
            print("%s %-6s published %.3f Hz, fitted model %.3f Hz (%+.1f%%)"
                  % (app, row, pub, hz, 100 * (hz - pub) / pub))


if __name__ == "__main__":
    main()
