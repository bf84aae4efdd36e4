"""Write the golden outputs of ``tuibrdf render`` that ``tests/cli/test_render.py`` compares
byte for byte.

Usage: ``python scripts/update_goldens.py`` (then look at every file it wrote: a golden is only
worth what the eye checked; the test file says what each one must show).
"""

from __future__ import annotations

import contextlib
import io
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from tuibrdf.cli import main  # noqa: E402

#: file name → argv of ``tuibrdf``
GOLDENS = {
    "lambert-map-24x12.txt": ["render", "lambert", "--view", "map", "--width", "24",
                              "--height", "12", "--color", "none"],
    "phong-map-32x14.txt": ["render", "phong", "-p", "kd=0", "-p", "ks=1", "-p", "n=200",
                            "--theta-i", "45", "--view", "map", "--width", "32", "--height",
                            "14", "--color", "none"],
    "cook-torrance-incidence-48x16.txt": ["render", "cook-torrance", "-p", "kd=0", "-p",
                                          "f0=0.04", "-p", "m=0.07", "--theta-i", "60",
                                          "--view", "incidence", "--width", "48", "--height",
                                          "16", "--color", "none"],
    "phong-map-16x8-truecolor.txt": ["render", "phong", "-p", "kd=0", "-p", "ks=1", "-p",
                                     "n=50", "--theta-i", "30", "--view", "map", "--width",
                                     "16", "--height", "8", "--color", "truecolor"],
    # issue 13's views
    "cook-torrance-perpendicular-48x16.txt": ["render", "cook-torrance", "-p", "kd=0", "-p",
                                              "f0=0.04", "-p", "m=0.07", "--theta-i", "60",
                                              "--view", "perpendicular", "--width", "48",
                                              "--height", "16", "--color", "none"],
    "phong-plane-40x14.txt": ["render", "phong", "-p", "kd=0", "-p", "ks=0.08", "-p", "n=70",
                              "--theta-i", "75", "--view", "plane", "--width", "40",
                              "--height", "14", "--exposure", "0.5", "--color", "none"],
    "cook-torrance-plane-40x14.txt": ["render", "cook-torrance", "-p", "kd=0", "-p", "f0=0.04",
                                      "-p", "m=0.07", "--theta-i", "75", "--view", "plane",
                                      "--width", "40", "--height", "14", "--exposure", "0.5",
                                      "--color", "none"],
    "cook-torrance-sphere-32x14.txt": ["render", "cook-torrance", "-p", "kd=0.5", "-p",
                                       "m=0.2", "--theta-i", "45", "--view", "sphere",
                                       "--width", "32", "--height", "14", "--color", "none"],
    "blinn-phong-slice-48x16.txt": ["render", "blinn-phong", "-p", "kd=0.1", "-p", "ks=0.6",
                                    "-p", "n=50", "--view", "slice", "--width", "48",
                                    "--height", "16", "--color", "none"],
    "blinn-phong-theta-h-48x12.txt": ["render", "blinn-phong", "-p", "kd=0.1", "-p", "ks=0.6",
                                      "-p", "n=50", "--view", "theta-h", "--theta-d", "30",
                                      "--width", "48", "--height", "12", "--color", "none"],
    "cook-torrance-theta-d-48x12.txt": ["render", "cook-torrance", "--view", "theta-d",
                                        "--theta-h", "5", "--log", "--width", "48",
                                        "--height", "12", "--color", "none"],
    "phong-sphere-24x10-truecolor.txt": ["render", "phong", "--theta-i", "30", "--view",
                                         "sphere", "--width", "24", "--height", "10",
                                         "--color", "truecolor"],
}


def output(argv: list[str]) -> str:
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        rc = main(argv)
    if rc != 0:
        raise SystemExit(f"tuibrdf {' '.join(argv)} exited {rc}")
    return buf.getvalue()


if __name__ == "__main__":
    for name, argv in GOLDENS.items():
        path = ROOT / "tests" / "golden" / name
        path.write_text(output(argv), encoding="utf-8")
        print(f"wrote {path.relative_to(ROOT)}")
