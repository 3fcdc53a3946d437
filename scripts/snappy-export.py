#!/usr/bin/env python3
"""Export closed hyperbolic manifolds from SnapPy as Curved Spaces generator files (.gen).

Each manifold's Dirichlet domain is computed by SnapPy in high precision; its face pairings
(O(3,1) matrices, time coordinate first) are reordered to put w last and transposed to act
on row vectors, as the .gen format wants. Beside each NAME.gen goes NAME.json with SnapPy's
numbers: volume, homology, in- and out-radius of the domain and the length spectrum, which
the crate's tests compare with its own computations. SnapPy is needed only here:

    pip install snappy
    python3 scripts/snappy-export.py --smallest 10 --out assets/spaces/census
    python3 scripts/snappy-export.py 'm004(1,2)' --out my-spaces

Then `curved-spaces info my-spaces/m004_1_2.gen` (or walk, render, ...) uses the file.
"""

import argparse
import json
import os
import re
import sys

try:
    import snappy
except ImportError:
    sys.exit("this script needs SnapPy: pip install snappy")

# How far the stored length spectrum reaches.
SPECTRUM_CUTOFF = 3.0


def file_stem(name):
    """m003(-3,1) -> m003_-3_1"""
    return re.sub(r"[(),]+", "_", name).strip("_")


def gen_text(name, matrices, volume, rank=None):
    lines = [f"#\t{name}" + (f": closed orientable hyperbolic census manifold no. {rank}" if rank else "")]
    lines.append(f"#\tvolume {volume}")
    lines.append("#\tFace pairings of SnapPy's Dirichlet domain, exported by scripts/snappy-export.py:")
    lines.append("#\t4x4 matrices acting on row vectors (v' = v M), w last, basepoint (0, 0, 0, 1).")
    perm = [1, 2, 3, 0]  # our x, y, z, w are SnapPy's x1, x2, x3, x0
    for m in matrices:
        lines.append("")
        a = [[m[perm[i], perm[j]] for j in range(4)] for i in range(4)]
        # A .gen matrix is the transpose of the column-vector matrix.
        for i in range(4):
            lines.append(" ".join(f"{float(a[j][i]):> .20f}"[:24].rjust(24) for j in range(4)))
    return "\n".join(lines) + "\n"


def export(manifold, out, rank=None):
    name = str(manifold)
    hp = snappy.ManifoldHP(manifold)
    domain = hp.dirichlet_domain()
    matrices = domain.pairing_matrices()
    volume = hp.volume()
    spectrum = manifold.length_spectrum(SPECTRUM_CUTOFF)
    stem = file_stem(name)
    with open(os.path.join(out, stem + ".gen"), "w") as f:
        f.write(gen_text(name, matrices, volume, rank))
    record = {
        "name": name,
        "census_rank": rank,
        "snappy_version": snappy.__version__,
        "volume": float(volume),
        "volume_digits": str(volume),
        "homology": str(manifold.homology()),
        "faces": domain.num_faces(),
        "inradius": float(domain.in_radius()),
        "outradius": float(domain.out_radius()),
        "length_spectrum_cutoff": SPECTRUM_CUTOFF,
        "length_spectrum": [
            {
                "length": float(g.length.real()),
                "torsion": float(g.length.imag()),
                "multiplicity": int(g.multiplicity),
            }
            for g in spectrum
        ],
    }
    with open(os.path.join(out, stem + ".json"), "w") as f:
        json.dump(record, f, indent=1)
        f.write("\n")
    print(f"{stem}.gen: {name}, volume {float(volume):.10f}, {domain.num_faces()} faces", flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("names", nargs="*", help="SnapPy manifold names, e.g. 'm003(-3,1)'")
    parser.add_argument("--smallest", type=int, default=0, help="the N smallest closed orientable census manifolds")
    parser.add_argument("--out", default=".", help="output directory")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    if not args.names and not args.smallest:
        parser.error("name a manifold or give --smallest N")
    for i in range(args.smallest):
        export(snappy.OrientableClosedCensus[i], args.out, rank=i + 1)
    for n in args.names:
        try:
            m = snappy.Manifold(n)
        except Exception as e:  # SnapPy raises several kinds for a bad name
            sys.exit(f"SnapPy does not know the manifold {n!r}: {e}")
        if m.cusp_info() and not all(c.get("filling", (0, 0)) != (0, 0) for c in m.cusp_info()):
            sys.exit(f"{n} has unfilled cusps: give Dehn fillings, e.g. 'm004(1,2)'")
        export(m, args.out)


if __name__ == "__main__":
    main()
