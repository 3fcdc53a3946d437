#!/usr/bin/env python3
"""Jacobi's elliptic functions at 40 digits, for the tests: an independent reference.

Sol's geodesics are written with Jacobi's elliptic functions of parameter m = k²: sn, cn
and dn, the amplitude am, the zeta function Z(u|m) = E(am u|m) − (E(m)/K(m))·u, the
complete integrals K(m) and E(m), and — for the exits through the horizontal faces — the
incomplete integral of the first kind F(φ|m). The crate computes them by the arithmetic-
geometric mean (src/geometry/elliptic.rs). This script uses none of that: it asks mpmath
(ellipfun, ellipk, ellipe, ellipf, at 50 digits, which evaluates by theta functions and
Carlson's symmetric integrals) for each value, across the parameter from 0 to 1 (both ends
and within 1e-12 of them) and the argument from 0 to several periods, and writes them
rounded to two doubles (the nearest double and the double nearest what it leaves out) to
tests/data/elliptic.json. Every argument (m, u, φ) is a double, so the crate's f64 and
double-double evaluations take exactly the reference's input.

    pip install mpmath     # mpmath 1.3 used
    python3 scripts/elliptic-reference.py

The tests read the stored file; CI does not run this script.
"""

import json
import os

import mpmath as mp

mp.mp.dps = 50

PARAMETERS = [
    "0",
    "1e-12",
    "1e-6",
    "0.01",
    "0.1",
    "0.3",
    "0.5",
    "0.7",
    "0.9",
    "0.99",
    "0.999999",
    "0.999999999999",
]


def pair(x):
    """x as the nearest double and the double nearest the rest, both as repr strings."""
    x = mp.mpf(x)
    hi = float(x)
    lo = float(x - mp.mpf(hi))
    return [repr(hi), repr(lo)]


def zeta(u, m):
    """Jacobi's zeta function Z(u|m) = E(am u | m) − (E/K)·u."""
    if m == 0:
        return mp.mpf(0)
    am = amplitude(u, m)
    return mp.ellipe(am, m) - mp.ellipe(m) / mp.ellipk(m) * u


def amplitude(u, m):
    """am(u|m): the continuous angle whose sine is sn and cosine cn."""
    if m == 1:
        return mp.asin(mp.tanh(u))
    k = mp.ellipk(m)
    # am(u + 2K) = am(u) + π: reduce to |u| ≤ K, where am is the principal angle.
    n = mp.nint(u / (2 * k))
    r = u - 2 * k * n
    sn = mp.ellipfun("sn", r, m=m)
    cn = mp.ellipfun("cn", r, m=m)
    return mp.atan2(sn, cn) + mp.pi * n


def main():
    cases = []
    for text in PARAMETERS:
        # Every argument is a double, exactly: the crate's f64 and double-double evaluations
        # take the same input.
        m = mp.mpf(float(mp.mpf(text)))
        k = mp.ellipk(m)
        e = mp.ellipe(m)
        # Arguments: small, ordinary, the quarter periods and beyond, negative.
        args = [mp.mpf(0), mp.mpf("1e-9"), mp.mpf("0.1"), mp.mpf("0.7"), mp.mpf(-2.1)]
        args += [k / 2, k, 3 * k / 2, 2 * k, 3 * k, 4 * k - mp.mpf("1e-6"), mp.mpf(7.3)]
        args += [mp.mpf(15), -5 * k / 2]
        values = []
        for u in args:
            u = mp.mpf(float(u))
            values.append(
                {
                    "u": pair(u),
                    "sn": pair(mp.ellipfun("sn", u, m=m)),
                    "cn": pair(mp.ellipfun("cn", u, m=m)),
                    "dn": pair(mp.ellipfun("dn", u, m=m)),
                    "am": pair(amplitude(u, m)),
                    "zeta": pair(zeta(u, m)),
                }
            )
        incomplete = []
        for phi in [mp.mpf(0), mp.mpf("0.3"), mp.mpf(1), mp.pi / 2, mp.mpf("2.5"), mp.pi]:
            phi = mp.mpf(float(phi))
            incomplete.append({"phi": pair(phi), "f": pair(mp.ellipf(phi, m))})
        cases.append(
            {
                "m": pair(m),
                "k": pair(k),
                "e": pair(e),
                "values": values,
                "incomplete": incomplete,
            }
        )
    here = os.path.dirname(os.path.abspath(__file__))
    out = os.path.join(here, "..", "tests", "data", "elliptic.json")
    with open(out, "w") as f:
        json.dump(
            {
                "source": "scripts/elliptic-reference.py (mpmath "
                + mp.__version__
                + ", 50 digits)",
                "cases": cases,
            },
            f,
            indent=1,
        )
        f.write("\n")
    print(f"wrote {len(cases)} parameters to {os.path.normpath(out)}")


if __name__ == "__main__":
    main()
