"""Key ``w`` and the command palette's "Screenshot": figures out of the viewer.

Written into :attr:`FigureWriter.output_dir` (the current directory, or ``tuibrdf view
--output-dir DIR``, made when missing), never into ``~/Downloads`` (Textual's default, absent
on most lab servers):

- ``tuibrdf-N-screen.svg``: the whole screen (Textual's ``export_screenshot``);
- ``tuibrdf-N-<view>.png``: the main view as pixels (:mod:`tuibrdf.render.export.figure`; the
  map, the slice, the lit sphere and plane, the solid);
- its numbers: ``tuibrdf-N-map.npz`` for the map (and the solid, sphere and plane: the BRDF
  at that θi), ``…-slice.npz``, ``…-albedo.csv``, ``…-theta-h.csv``, ``…-theta-d.csv``
  (:mod:`tuibrdf.core.views.tables`);

``N`` is the first number that overwrites nothing.  In compare mode side B's files end in
``-b``.  The pictures and numbers are computed off the event loop (a thread); the status line
says where they went, or why not.  Under a web driver (``tuibrdf serve``) the files are
delivered to the browser instead (Textual's ``deliver_text`` / ``deliver_binary``).
"""

from __future__ import annotations

import io
import os
from pathlib import Path
from types import SimpleNamespace

from tuibrdf.app.guard import survives

#: the numbers written with each main view: (table view, suffix)
NUMBERS = {"map": ("map", "npz"), "solid": ("map", "npz"), "sphere": ("map", "npz"),
           "plane": ("map", "npz"), "slice": ("slice", "npz"), "albedo": ("albedo", "csv"),
           "theta-h": ("theta-h", "csv"), "theta-d": ("theta-d", "csv")}


def _files(state) -> list[tuple[str, bytes | str]]:
    """``(name suffix, contents)`` of the main view of every side, the PNG and the map's
    numbers ``DEFAULT_SIZE`` pixels across (numpy and zlib: runs in a thread; the figure's
    modules are imported at the first figure, not at start-up)."""
    from tuibrdf.core.views.tables import for_view
    from tuibrdf.render.export import numbers
    from tuibrdf.render.export.figure import DEFAULT_SIZE, IMAGE_VIEWS, figure

    s, out = state, []
    for k, material in enumerate(s.materials):
        tag = "-b" if k else ""
        m, values = material.model, material.values
        look = dict(cmap=s.cmap, log=s.log, cosine=s.cosine and s.view != "albedo",
                    azimuth_deg=s.azimuth, elevation_deg=s.elevation,
                    section_azimuth_deg=s.section_azimuth, exposure=s.exposure, gamma=s.gamma,
                    theta_d_deg=s.theta_d, theta_h_deg=s.theta_h, phi_d_deg=s.phi_d,
                    sqrt_h=s.sqrt_h, phi_i_deg=s.phi_i)
        if s.view in IMAGE_VIEWS:
            out.append((f"{s.view}{tag}.png",
                        figure(s.view, m, values, s.theta_i, DEFAULT_SIZE, **look).png()))
        tview, suffix = NUMBERS.get(s.view, ("map", "npz"))
        tab = for_view(tview, m, values, s.theta_i, s.phi_i, size=DEFAULT_SIZE,
                       section_azimuth=s.section_azimuth, theta_d=s.theta_d,
                       theta_h=s.theta_h, phi_d=s.phi_d, sqrt_h=s.sqrt_h, cosine=s.cosine)
        data = numbers.to_npz(tab) if suffix == "npz" else numbers.to_csv(tab)
        out.append((f"{tview}{tag}.{suffix}", data))
    return out


def snapshot(state) -> SimpleNamespace:
    """What :func:`_files` reads of the viewer's state, as it is now (later keys change the
    state while a thread writes; a :class:`~tuibrdf.core.material.Material` is immutable)."""
    names = ("view", "theta_i", "phi_i", "cmap", "log", "cosine", "azimuth", "elevation",
             "section_azimuth", "exposure", "gamma", "theta_d", "theta_h", "phi_d", "sqrt_h")
    return SimpleNamespace(materials=[side.material for side in state.sides],
                           **{n: getattr(state, n) for n in names})


def first_free(directory: Path, names: list[str]) -> int:
    """The smallest ``N ≥ 1`` for which no ``tuibrdf-N-<name>`` exists yet."""
    n = 1
    while any((directory / f"tuibrdf-{n}-{name}").exists() for name in names):
        n += 1
    return n


class FigureWriter:
    """The ``w`` half of :class:`~tuibrdf.app.app.BrdfApp` (a mixin: it uses the app's
    ``state``, ``background`` and ``_changed``)."""

    #: where ``w`` writes (None: the current directory at the time of the key)
    output_dir: Path | None = None

    @survives
    def action_write_figures(self) -> None:
        self.write_figures()

    def deliver_screenshot(self, filename: str | None = None, path: str | None = None,
                           time_format: str | None = None) -> str | None:
        """The palette's Screenshot (and ``action_screenshot``): in a terminal, what ``w``
        writes (into the output directory, made when missing); in a browser, Textual's own
        delivery of the SVG."""
        if self.is_web:
            return super().deliver_screenshot(filename, path, time_format)
        self.write_figures(Path(path) if path else None)
        return None

    def write_figures(self, directory: Path | None = None) -> None:
        """Write the screen's SVG now (it is the screen of this moment) and the main view's
        PNG and numbers from a thread; the status line says where."""
        svg = self.export_screenshot()
        state = snapshot(self.state)  # the thread works on this moment's state
        if self.is_web:
            self._changed("preparing the figures for the browser …")
            self.background(lambda: self._compute(state), self._deliver)
            self.deliver_text(io.StringIO(svg), save_filename="tuibrdf-screen.svg",
                              mime_type="image/svg+xml", name="screenshot")
            return
        where = Path(directory or self.output_dir or os.getcwd())
        self._changed(f"writing the figures to {where} …")
        self.background(lambda: self._write(where, svg, state), self._changed)

    def _compute(self, state) -> list[tuple[str, bytes | str]] | str:
        try:
            return _files(state)
        except (ValueError, OSError, ArithmeticError, MemoryError) as e:
            return f"figures not written: {e}"

    def _deliver(self, files) -> None:
        if isinstance(files, str):
            self._changed(files)
            return
        for name, data in files:
            blob = data if isinstance(data, bytes) else data.encode("utf-8")
            self.deliver_binary(io.BytesIO(blob), save_filename=f"tuibrdf-{name}")
        self._changed(f"sent {len(files) + 1} files to the browser")

    def _write(self, where: Path, svg: str, state) -> str:
        """Every file into ``where``; the status line's message."""
        try:
            files = [("screen.svg", svg), *_files(state)]
            where.mkdir(parents=True, exist_ok=True)
            n = first_free(where, [name for name, _ in files])
            for name, data in files:
                path = where / f"tuibrdf-{n}-{name}"
                if isinstance(data, bytes):
                    path.write_bytes(data)
                else:
                    path.write_text(data, encoding="utf-8", newline="")
        except (ValueError, OSError, ArithmeticError, MemoryError) as e:
            return f"figures not written: {e}"
        names = ",".join(name for name, _ in files)
        return f"wrote tuibrdf-{n}-{{{names}}} in {where}"
