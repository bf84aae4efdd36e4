"""Time one frame of the 3D solid (tuibrdf/render/solid.py) at the pane sizes of a 160×48 and
a 240×70 terminal (upper bounds: the whole width, two pixel rows per cell).

    PYTHONPATH=$PWD python scripts/bench_solid.py
"""

import timeit

from tuibrdf.core.material import Material
from tuibrdf.core.views.frame import FrameRequest, compute_frame
from tuibrdf.render.solid import solid_image


def main() -> None:
    for m, w, h in [(0.2, 160, 2 * 47), (0.07, 240, 2 * 69)]:
        req = FrameRequest((Material("cook-torrance", {"m": m}),), 45.0, solid=True)
        side = compute_frame(req, slow=False).sides[0]

        def frame(side=side, w=w, h=h):
            return solid_image(side.solid, 45.0, w, h, rmax=side.peak.value)

        n = 20
        best = min(timeit.repeat(frame, number=n, repeat=5)) / n
        print(f"cook-torrance m={m} θi=45°, {w}×{h} px: {best * 1e3:.1f} ms per frame")


if __name__ == "__main__":
    main()
