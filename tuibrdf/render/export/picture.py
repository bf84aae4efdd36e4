"""``tuibrdf.picture(model, params, theta_i, view=…)``: one view for a notebook or a script.

    >>> import tuibrdf
    >>> p = tuibrdf.picture("phong", {"n": 50}, theta_i=30)   # doctest: +SKIP
    >>> p                                   # Jupyter: the PNG (``_repr_png_``)
    >>> rich.print(p)                       # a terminal: the half-block picture
    >>> p.save("phong.png"); p.save("phong.npz"); p.save("phong.svg")

``save`` picks the format by the suffix: ``.png`` (image views), ``.svg``, ``.html``,
``.txt``, ``.ansi`` (the terminal picture, ``width × height`` cells), ``.npz`` (map, slice),
``.csv``, ``.json`` (sections, albedo, θh, θd), ``.pdf`` (matplotlib, the ``[plot]`` extra):
the files of ``tuibrdf render --format``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from tuibrdf.render.export.figure import DEFAULT_SIZE, IMAGE_VIEWS

SUFFIXES = {".png": "png", ".svg": "svg", ".html": "html", ".htm": "html", ".txt": "text",
            ".ansi": "ansi", ".npz": "npz", ".csv": "csv", ".json": "json", ".pdf": "pdf"}
#: render_view's look keywords that the numbers depend on too
_TABLE_KEYS = {"section_azimuth_deg": "section_azimuth", "theta_d_deg": "theta_d",
               "theta_h_deg": "theta_h", "phi_d_deg": "phi_d", "sqrt_h": "sqrt_h",
               "cosine": "cosine"}


class Picture:
    """A view of a material; drawn when shown or saved (see the module docstring)."""

    def __init__(self, model: Any, params: dict[str, Any] | None = None, theta_i: float = 30.0,
                 view: str = "map", *, phi_i: float = 180.0, size: int = DEFAULT_SIZE,
                 width: int = 80, height: int = 24, **look: Any) -> None:
        from tuibrdf.core.material import Material
        from tuibrdf.render import VIEWS

        if view not in VIEWS:
            raise ValueError(f"unknown view {view!r}: expected one of {', '.join(VIEWS)}")
        m = Material(model, params)  # validated now: a bad parameter fails here, not on show
        self.model, self.values = m.model, dict(m.items)
        self.theta_i, self.phi_i, self.view = float(theta_i), float(phi_i), view
        self.size, self.width, self.height = int(size), int(width), int(height)
        self.look = dict(look)

    def __repr__(self) -> str:
        return (f"<tuibrdf.Picture {self.view} of {self.model.name} at θi={self.theta_i:g}°; "
                ".save(path) writes it>")

    def renderable(self, color: str = "truecolor"):
        from tuibrdf.render.views import render_view

        return render_view(self.view, self.model, self.values, self.theta_i, self.width,
                           self.height, color=color, phi_i_deg=self.phi_i, **self.look)

    def __rich__(self):
        return self.renderable()

    def png(self) -> bytes:
        """The PNG of an image view (:data:`IMAGE_VIEWS`); ``ValueError`` for a line view."""
        from tuibrdf.render.export.figure import figure

        return figure(self.view, self.model, self.values, self.theta_i, self.size,
                      phi_i_deg=self.phi_i, **self.look).png()

    def _repr_png_(self) -> bytes | None:
        # None: Jupyter shows the next representation (a line view has no pixel picture)
        return self.png() if self.view in IMAGE_VIEWS else None

    def table(self):
        """The numbers (:func:`tuibrdf.core.views.tables.for_view`)."""
        from tuibrdf.core.views.tables import for_view

        kw = {_TABLE_KEYS[k]: v for k, v in self.look.items() if k in _TABLE_KEYS}
        return for_view(self.view, self.model, self.values, self.theta_i, self.phi_i,
                        size=self.size, **kw)

    def data(self, fmt: str) -> bytes | str:
        """The file's contents in ``fmt`` (a value of :data:`SUFFIXES`)."""
        if fmt == "png":
            return self.png()
        if fmt in ("svg", "html", "text", "ansi"):
            from tuibrdf.render.export.terminal import export

            color = "none" if fmt == "text" else "truecolor"
            return export([self.renderable(color)], self.width, fmt,
                          f"tuibrdf {self.view} of {self.model.name}")
        if fmt == "pdf":  # the [plot] extra (matplotlib)
            from tuibrdf.render.export.plot import pdf

            return pdf(self.table(), cmap=self.look.get("cmap", "grey"),
                       log=bool(self.look.get("log", False)))
        from tuibrdf.render.export import numbers

        return {"npz": numbers.to_npz, "csv": numbers.to_csv,
                "json": numbers.to_json}[fmt](self.table())

    def save(self, path: str | Path) -> Path:
        """Write the picture or its numbers to ``path``, the format by its suffix."""
        path = Path(path)
        fmt = SUFFIXES.get(path.suffix.lower())
        if fmt is None:
            raise ValueError(f"{path}: unknown suffix; expected one of "
                             f"{', '.join(sorted(SUFFIXES))}")
        data = self.data(fmt)
        if isinstance(data, bytes):
            path.write_bytes(data)
        else:
            path.write_text(data, encoding="utf-8", newline="")
        return path


def picture(model: Any, params: dict[str, Any] | None = None, theta_i: float = 30.0,
            view: str = "map", **kwargs: Any) -> Picture:
    """A :class:`Picture` of ``view`` (``map``, ``incidence``, ``perpendicular``, ``solid``,
    ``albedo``, ``sphere``, ``plane``, ``slice``, ``theta-h``, ``theta-d``); ``kwargs``:
    ``phi_i``, ``size`` (PNG pixels), ``width``/``height`` (terminal cells) and the look of
    :func:`tuibrdf.render.views.render_view` (``cmap``, ``log``, ``cosine``, …)."""
    return Picture(model, params, theta_i, view, **kwargs)
