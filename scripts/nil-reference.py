#!/usr/bin/env python3
"""Nil's geodesics at 40 digits, for the tests: an independent reference.

The crate evaluates Nil's geodesics in closed form (src/space/nil/flow.rs). This script
does not use that form: it integrates the geodesic equations of the metric

    ds² = dx² + dy² + (dz − ½(x dy − y dx))²

in the chart, with Christoffel symbols taken from the metric matrix and its derivatives,
by mpmath's Taylor-series ODE solver at 45 significant digits, and writes the chart point
and the body velocity (in the frame E1 = ∂x − (y/2)∂z, E2 = ∂y + (x/2)∂z, E3 = ∂z) at a
few times for a set of starts, rounded to 40 digits, to tests/data/nil_geodesics.json.
It also checks that the speed stays 1 to 35 digits along each.

    pip install mpmath     # 1.3 used
    python3 scripts/nil-reference.py

The tests read the stored file; CI does not run this script.
"""

import json
import os
import sys

import mpmath as mp

mp.mp.dps = 45


def metric(x, y):
    """The metric matrix g and its x and y derivatives (g does not depend on z)."""
    w = [y / 2, -x / 2, mp.mpf(1)]
    g = [[(1 if i == j and i < 2 else 0) + w[i] * w[j] for j in range(3)] for i in range(3)]
    dwx = [0, -mp.mpf(1) / 2, 0]
    dwy = [mp.mpf(1) / 2, 0, 0]
    dgx = [[dwx[i] * w[j] + w[i] * dwx[j] for j in range(3)] for i in range(3)]
    dgy = [[dwy[i] * w[j] + w[i] * dwy[j] for j in range(3)] for i in range(3)]
    return g, [dgx, dgy, [[0] * 3 for _ in range(3)]]


def accel(pos, vel):
    """ẍ^k = −Γ^k_ij ẋ^i ẋ^j from the Euler–Lagrange equations of ½ g(ẋ, ẋ):
    g ẍ = ½ ∂_k g(ẋ, ẋ) − (∂_i g ẋ^i) ẋ."""
    x, y, _ = pos
    g, dg = metric(x, y)
    rhs = []
    for k in range(3):
        half = sum(dg[k][i][j] * vel[i] * vel[j] for i in range(3) for j in range(3)) / 2
        mixed = sum(dg[i][k][j] * vel[i] * vel[j] for i in range(3) for j in range(3))
        rhs.append(half - mixed)
    return mp.lu_solve(mp.matrix(g), mp.matrix(rhs))


def body(pos, vel):
    """Chart velocity to body velocity in E1, E2, E3."""
    x, y, _ = pos
    return [vel[0], vel[1], vel[2] - (x * vel[1] - y * vel[0]) / 2]


def chart_velocity(pos, u):
    x, y, _ = pos
    return [u[0], u[1], u[2] + (x * u[1] - y * u[0]) / 2]


def pair(x):
    """A number as a double-double: the nearest f64 and the nearest f64 to what is left,
    each as the shortest decimal that reads back as it (strings: a JSON reader need not
    round numbers correctly, Rust's `str::parse` does)."""
    hi = float(x)
    return [repr(hi), repr(float(x - mp.mpf(hi)))]


def geodesic(start, u, times):
    u = [mp.mpf(c) for c in u]
    norm = mp.sqrt(sum(c * c for c in u))
    u = [c / norm for c in u]
    start = [mp.mpf(c) for c in start]
    v0 = chart_velocity(start, u)

    def f(t, s):
        a = accel(s[0:3], s[3:6])
        return [s[3], s[4], s[5], a[0], a[1], a[2]]

    sol = mp.odefun(f, 0, start + v0, tol=mp.mpf(10) ** -42, degree=30)
    out = []
    for t in times:
        s = sol(mp.mpf(t))
        pos, vel = s[0:3], s[3:6]
        b = body(pos, vel)
        speed = mp.sqrt(sum(c * c for c in b))
        if abs(speed - 1) > mp.mpf(10) ** -35:
            sys.exit(f"speed drifted to {speed} at t = {t}")
        out.append(
            {
                "t": str(t),
                "point": [mp.nstr(c, 40) for c in pos],
                "velocity": [mp.nstr(c, 40) for c in b],
                "point_dd": [pair(c) for c in pos],
                "velocity_dd": [pair(c) for c in b],
            }
        )
    return [mp.nstr(c, 40) for c in u], [pair(c) for c in u], out


# (name, chart start, body velocity before normalising, times)
CASES = [
    ("horizontal", [0, 0, 0], [mp.cos(0.3), mp.sin(0.3), 0], [0.5, 2, 7]),
    ("vertical up", [0.1, -0.2, 0.05], [0, 0, 1], [0.5, 3]),
    ("vertical down", [0, 0, 0], [0, 0, -1], [1.5]),
    ("tiny c", [0, 0, 0], [1, 0, mp.mpf("1e-9")], [0.75, 4]),
    ("small c", [0.2, 0.1, -0.1], [0.6, -0.8, mp.mpf("1e-3")], [1, 5]),
    ("generic", [0.3, -0.2, 0.1], [0.8 * mp.cos(1.1), 0.8 * mp.sin(1.1), 0.6], [0.25, 1, 4, 10]),
    ("generic down", [-0.4, 0.45, -0.3], [0.6 * mp.cos(-2), 0.6 * mp.sin(-2), -0.8], [0.5, 2, 8]),
    ("near vertical", [0, 0, 0], [mp.mpf("0.01"), 0, 1], [1, 6]),
    ("steep", [0.5, 0.5, 0.5], [0.3, 0.2, 0.9], [2, 20]),
    ("shallow long", [0, 0, 0], [0.95, 0.1, 0.3], [3, 30]),
]


def main():
    out = {
        "about": "Nil geodesics (metric dx² + dy² + (dz − ½(x dy − y dx))²) integrated by "
        "mpmath's Taylor ODE solver at 45 digits from the Christoffel symbols; points in "
        "the chart, velocities in the frame E1 = ∂x − (y/2)∂z, E2 = ∂y + (x/2)∂z, E3 = ∂z, "
        "40 digits. Written by scripts/nil-reference.py (mpmath " + mp.__version__ + ").",
        "cases": [],
    }
    for name, start, u, times in CASES:
        unit, unit_dd, samples = geodesic(start, u, times)
        out["cases"].append(
            {
                "name": name,
                "start": [mp.nstr(mp.mpf(c), 40) for c in start],
                "start_dd": [pair(mp.mpf(c)) for c in start],
                "velocity": unit,
                "velocity_dd": unit_dd,
                "samples": samples,
            }
        )
        print(f"{name}: {len(samples)} samples", flush=True)
    path = os.path.join(os.path.dirname(__file__), "..", "tests", "data", "nil_geodesics.json")
    with open(path, "w") as f:
        json.dump(out, f, indent=1, ensure_ascii=False)
        f.write("\n")
    print(f"wrote {os.path.normpath(path)}")


if __name__ == "__main__":
    main()
