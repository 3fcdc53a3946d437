#!/usr/bin/env python3
"""SL̃(2,R)'s geodesics at 40 digits, for the tests: an independent reference.

The crate evaluates the geodesics of the unit tangent bundle UT H² (the SL̃(2,R) geometry)
in closed form, as products of matrix exponentials in SO(2,1) (src/space/sl2r/flow.rs).
This script uses none of that: it writes UT H² in a chart (x, y, θ), with the base point
p = (x, y, √(1 + x² + y²)) on the hyperboloid x² + y² − w² = −1 and the unit vector
e = cos θ E1(p) + sin θ E2(p), where (E1, E2) is the boost of the origin's (∂x, ∂y) to p,
takes the Sasaki metric from its definition,

    ds² = ⟨dp, dp⟩ + ⟨De, De⟩,   De = de + ⟨de, p⟩ p   (the covariant derivative of e on H²)

(⟨,⟩ the Lorentz form x x′ + y y′ − w w′), writes it as ⟨dp, dp⟩ + (dθ + ω)² with ω the
frame field's connection form (checked against the definition at a point), differentiates
it with sympy, and integrates the
geodesic equations of the chart's metric matrix by mpmath's Taylor-series ODE solver at 45
digits. At a few times of each start it writes the point (p, e) and the body velocity
(a, b, c) in the frame X = the horizontal lift of e, Y = that of e turned +90° (counter-
clockwise seen from +w), V = vertical (turning e counter-clockwise at one radian per unit),
rounded to 40 digits, to tests/data/sl2r_geodesics.json, and checks the speed stays 1 to
35 digits.

    pip install mpmath sympy     # mpmath 1.3, sympy 1.14 used
    python3 scripts/sl2r-reference.py

The tests read the stored file; CI does not run this script.
"""

import json
import os
import sys

import mpmath as mp
import sympy as sp

mp.mp.dps = 45

X, Y, T = sp.symbols("x y theta", real=True)
COORDS = (X, Y, T)


def lorentz(u, v):
    return u[0] * v[0] + u[1] * v[1] - u[2] * v[2]


def chart():
    """p, E1, E2, e and e⊥ as sympy vectors of the chart (x, y, θ)."""
    w = sp.sqrt(1 + X**2 + Y**2)
    p = sp.Matrix([X, Y, w])
    # The boost taking the origin (0, 0, 1) to p; its first two columns frame T_p H².
    e1 = sp.Matrix([1 + X**2 / (1 + w), X * Y / (1 + w), X])
    e2 = sp.Matrix([X * Y / (1 + w), 1 + Y**2 / (1 + w), Y])
    e = sp.cos(T) * e1 + sp.sin(T) * e2
    eperp = -sp.sin(T) * e1 + sp.cos(T) * e2
    return p, e, eperp


def metric_matrix():
    """The Sasaki metric from its definition, ⟨dp, dp⟩ + ⟨De, De⟩ (slow to differentiate:
    used once, to check the short form below at a point)."""
    p, e, _ = chart()
    dp = [p.diff(c) for c in COORDS]
    de = [e.diff(c) for c in COORDS]
    # The part of de tangent to the hyperboloid at p (⟨p, p⟩ = −1).
    dcov = [d + lorentz(d, p) * p for d in de]
    return sp.Matrix(3, 3, lambda i, j: lorentz(dp[i], dp[j]) + lorentz(dcov[i], dcov[j]))


def short_metric():
    """The same metric as ⟨dp, dp⟩ + (dθ + ω)², ω = ⟨dE1, E2⟩ the connection form of the
    frame field (De = (dθ + ω) e⊥), each piece simplified: fast to differentiate."""
    w = sp.sqrt(1 + X**2 + Y**2)
    p = sp.Matrix([X, Y, w])
    e1 = sp.Matrix([1 + X**2 / (1 + w), X * Y / (1 + w), X])
    e2 = sp.Matrix([X * Y / (1 + w), 1 + Y**2 / (1 + w), Y])
    h = [[sp.simplify(lorentz(p.diff(a), p.diff(b))) for b in (X, Y)] for a in (X, Y)]
    om = [sp.simplify(lorentz(e1.diff(a), e2)) for a in (X, Y)] + [sp.Integer(1)]
    hh = [[h[0][0], h[0][1], 0], [h[1][0], h[1][1], 0], [0, 0, 0]]
    return sp.Matrix(3, 3, lambda i, j: hh[i][j] + om[i] * om[j])


def build():
    g = short_metric()
    # The short form is the definition (checked at a point, to 40 digits).
    full = metric_matrix()
    at = {X: sp.Rational(3, 10), Y: sp.Rational(-7, 10), T: sp.Rational(11, 10)}
    diff = (g.subs(at) - full.subs(at)).evalf(50)
    if max(abs(v) for v in diff) > sp.Float("1e-40"):
        sys.exit(f"the short metric is not the Sasaki metric: {diff}")
    dg = [g.diff(c) for c in COORDS]
    p, e, eperp = chart()
    dp = [p.diff(c) for c in COORDS]
    de = [e.diff(c) for c in COORDS]
    dcov = [d + lorentz(d, p) * p for d in de]
    # The body velocity (a, b, c) = B · chart velocity.
    b = sp.Matrix(
        3,
        3,
        lambda i, j: [lorentz(dp[j], e), lorentz(dp[j], eperp), lorentz(dcov[j], eperp)][i],
    )
    f = lambda m: sp.lambdify(COORDS, m, modules="mpmath", cse=True)  # noqa: E731
    return f(g), [f(d) for d in dg], f(b), f(p), f(e)


G, DG, B, P, E = build()


def accel(pos, vel):
    """ẍ^k = −Γ^k_ij ẋ^i ẋ^j from the Euler–Lagrange equations of ½ g(ẋ, ẋ):
    g ẍ = ½ ∂_k g(ẋ, ẋ) − (∂_i g ẋ^i) ẋ."""
    g = mp.matrix(G(*pos))
    dg = [mp.matrix(d(*pos)) for d in DG]
    rhs = []
    for k in range(3):
        half = sum(dg[k][i, j] * vel[i] * vel[j] for i in range(3) for j in range(3)) / 2
        mixed = sum(dg[i][k, j] * vel[i] * vel[j] for i in range(3) for j in range(3))
        rhs.append(half - mixed)
    return mp.lu_solve(g, mp.matrix(rhs))


def body(pos, vel):
    return list(mp.matrix(B(*pos)) * mp.matrix(vel))


def pair(x):
    """A number as a double-double: the nearest f64 and the nearest f64 to what is left,
    each as the shortest decimal that reads back as it."""
    hi = float(x)
    return [repr(hi), repr(float(x - mp.mpf(hi)))]


def model(pos):
    return [c for c in mp.matrix(P(*pos))] + [c for c in mp.matrix(E(*pos))]


def strings(v):
    return [mp.nstr(c, 40) for c in v]


def geodesic(start, u, times):
    u = [mp.mpf(c) for c in u]
    norm = mp.sqrt(sum(c * c for c in u))
    u = [c / norm for c in u]
    start = [mp.mpf(c) for c in start]
    v0 = list(mp.lu_solve(mp.matrix(B(*start)), mp.matrix(u)))

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
        m = model(pos)
        out.append(
            {
                "t": str(t),
                # The chart's θ integrated with the rest: the lifted fibre angle (no wrap).
                "theta": mp.nstr(pos[2], 40),
                "model": strings(m),
                "velocity": strings(b),
                "model_dd": [pair(c) for c in m],
                "velocity_dd": [pair(c) for c in b],
            }
        )
    return u, out


H = mp.sqrt(mp.mpf(1) / 2)
# (name, chart start (x, y, θ), body velocity before normalising, times). ω² = a² + b² − c²
# picks the shadow's kind: a hypercycle (> 0), a horocycle (= 0), a circle (< 0).
CASES = [
    ("horizontal", [0, 0, 0], [mp.cos(0.3), mp.sin(0.3), 0], [0.5, 2, 5]),
    ("fibre", [0.1, -0.2, 0.4], [0, 0, 1], [0.5, 3, 7]),
    ("hypercycle", [0.3, -0.2, 1.0], [0.8 * mp.cos(1.1), 0.8 * mp.sin(1.1), 0.6], [0.25, 1, 4]),
    ("circle", [-0.4, 0.45, -2.0], [0.6 * mp.cos(-2), 0.6 * mp.sin(-2), -0.8], [0.5, 2, 8]),
    ("horocycle", [0, 0, 0], [H, 0, H], [1, 4]),
    ("just hyperbolic", [0.2, 0.1, 0.5], [H, 0, H * (1 - mp.mpf("1e-7"))], [1, 5]),
    ("just elliptic", [0.2, 0.1, 0.5], [0, H, -H * (1 + mp.mpf("1e-7"))], [1, 5]),
    ("far start", [1.5, -0.7, 2.0], [0.3, -0.9, 0.3], [1, 3]),
]


def main():
    out = {
        "about": "SL~(2,R) geodesics: UT H² with the Sasaki metric in the chart (x, y, θ) "
        "(p = (x, y, sqrt(1 + x² + y²)), e = cos θ E1 + sin θ E2, (E1, E2) the boost of the "
        "origin's frame), integrated by mpmath's Taylor ODE solver at 45 digits from the "
        "Christoffel symbols of the metric sympy derived from ⟨dp, dp⟩ + ⟨De, De⟩; points as "
        "model = [px, py, pw, ex, ey, ew], velocities in the frame (X, Y, V), theta the chart's "
        "angle as integrated (the lifted fibre angle, not wrapped), 40 digits. "
        "Written by scripts/sl2r-reference.py (mpmath " + mp.__version__ + ").",
        "cases": [],
    }
    for name, start, u, times in CASES:
        unit, samples = geodesic(start, u, times)
        m = model([mp.mpf(c) for c in start])
        out["cases"].append(
            {
                "name": name,
                "theta": mp.nstr(mp.mpf(start[2]), 40),
                "model": strings(m),
                "model_dd": [pair(c) for c in m],
                "velocity": strings(unit),
                "velocity_dd": [pair(c) for c in unit],
                "samples": samples,
            }
        )
        print(f"{name}: {len(samples)} samples", flush=True)
    path = os.path.join(os.path.dirname(__file__), "..", "tests", "data", "sl2r_geodesics.json")
    with open(path, "w") as f:
        json.dump(out, f, indent=1, ensure_ascii=False)
        f.write("\n")
    print(f"wrote {os.path.normpath(path)}")


if __name__ == "__main__":
    main()
