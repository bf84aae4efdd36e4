"""Where the peak finder falls short on rough Cook-Torrance's V-cavity creases.

    PYTHONPATH=. python scripts/scan_peak_creases.py

Compares :func:`tuibrdf.core.peak.find_peaks` with the largest value in the plane of
incidence (a 20,000-point scan and golden section, the check of tests/test_peak.py) for
cook-torrance with kd = 0 over m = 0.300…1 (step 0.025) × θi = 3…40° (step 1°), f and
f·cos θr, and prints the cases more than 1e-10 below it.  Not a test: about a minute and a
half; the numbers are in docs/app.md.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
from test_peak import peak, plane_max  # noqa: E402


def main() -> int:
    short = {}
    for m in np.arange(0.30, 1.0001, 0.025):
        for th in np.arange(3.0, 40.01, 1.0):
            for cos in (False, True):
                p = {"kd": 0.0, "m": min(float(m), 1.0)}
                got = peak("cook-torrance", p, float(th), cos)[0].value
                ref = plane_max("cook-torrance", p, float(th), 0.0, cos)
                if got < ref * (1.0 - 1e-10):
                    short[(round(float(m), 3), float(th), cos)] = 1.0 - got / ref
    print(f"{len(short)} cases more than 1e-10 below the plane's maximum")
    for (m, th, cos), s in sorted(short.items(), key=lambda kv: -kv[1]):
        print(f"m={m:.3f} θi={th:4.1f}° {'f·cos θr' if cos else 'f':8s} {s:.2e}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
