"""Every private name of Textual the viewer relies on, behind small functions: the rest of
``tuibrdf/app`` uses Textual's public API only (tests/test_textual_internals.py checks both).

Checked against Textual 8.2.8.  tests/test_textual_internals.py fails, naming the internal, when
one of them is missing or its signature changed (:func:`checks`).  At run time the viewer then
does without it where it can: Textual's own compositor (:data:`PARTIAL_PAINT` false), no wait
for a busy writer (:func:`writer_backlog` answers 0), styles read afresh every time
(:func:`styles_key`).

===============================================  ==================================================
internal (Textual 8.2.8)                         what the viewer does with it
===============================================  ==================================================
``textual._compositor.Compositor``               subclassed by ``paint.ViewerCompositor``
``Compositor.render_partial_update()``           which overrides it (the partial repaint)
``Compositor.cuts``                              read by it: each line's widget edges
``Compositor.visible_widgets``                   read by it: each widget's region and clip
``Compositor.size``                              read by it: the screen's size
``Compositor._dirty_regions``                    :func:`take_dirty_regions`: what to repaint
``Compositor._regions_to_spans(regions)``        :func:`regions_to_spans`: those as spans
``ChopsUpdate(chops, spans, chop_ends)``         ``textual._compositor.ChopsUpdate``, made and
                                                 subclassed by ``paint.SpansUpdate``, which
``ChopsUpdate.render_segments(console)``         overrides it (each span from its first cell)
``Screen._compositor``                           :func:`install_compositor`: the viewer's
``Screen._compositor_refresh()``                 :class:`HeldPaints` overrides it (no paint
``Screen._dirty_widgets``                        written before the frame of a new layout),
``Screen._repaint_required``                     and clears these
``Styles._cache_key``                            :func:`styles_key`: changes when a style does
``App._driver``                                  :func:`writer_backlog`: the writes Textual's
``LinuxDriver._writer_thread``                   output thread still has queued
``WriterThread._queue``                          (``app._driver._writer_thread._queue``)
``CommandPalette._action_command_list(action)``  :class:`SafeCommandPalette` overrides it
``Parser.__init__()`` (textual._parser)          :class:`SafeXTermParser` re-runs it to start
                                                 afresh after a malformed sequence
``App._handle_exception(error)``                 :class:`OneLineCrash` overrides it, and
``App._exit_renderables``                        replaces what it prints (a traceback) by one
``App._return_code``                             line; :meth:`OneLineCrash.panic` sets it to 1
``<driver module>.XTermParser``                  :func:`guard_input_parsing` replaces it with
                                                 :class:`SafeXTermParser` in each driver module
                                                 (Linux, inline, web) that reads it there
``LinuxDriver.start_application_mode()``         installs a Python SIGWINCH handler, which
                                                 :func:`coalesce_resize_signals` wraps
===============================================  ==================================================
"""

from __future__ import annotations

import asyncio
import inspect
import io
import time
from collections.abc import Iterable

from textual._compositor import ChopsUpdate, Compositor
from textual._parser import Parser
from textual._xterm_parser import XTermParser
from textual.await_complete import AwaitComplete
from textual.command import CommandPalette
from textual.css.styles import RenderStyles
from textual.geometry import Region
from textual.screen import Screen
from textual.widget import Widget

__all__ = ["ChopsUpdate", "Compositor", "PARTIAL_PAINT", "SafeCommandPalette",
           "OneLineCrash", "SafeXTermParser", "checks", "guard_input_parsing",
           "HOLD_PAINTS", "HeldPaints", "install_compositor", "regions_to_spans",
           "styles_key", "take_dirty_regions", "writer_backlog"]


def _params(owner, name: str) -> list[str] | None:
    """The parameters of ``owner.name``; None when it is not there or not callable."""
    method = getattr(owner, name, None)
    if not callable(method):
        return None
    return list(inspect.signature(method).parameters)


def _compositor_checks() -> dict[str, bool]:
    probe = Compositor()
    return {
        "Compositor._dirty_regions": isinstance(getattr(probe, "_dirty_regions", None), set),
        "Compositor._regions_to_spans(regions)":
            _params(probe, "_regions_to_spans") == ["regions"],
        "Compositor.render_partial_update()": _params(probe, "render_partial_update") == [],
        "Compositor.cuts": isinstance(getattr(Compositor, "cuts", None), property),
        "Compositor.visible_widgets":
            isinstance(getattr(Compositor, "visible_widgets", None), property),
        "Compositor.size": hasattr(probe, "size"),
        "ChopsUpdate(chops, spans, chop_ends)":
            _params(ChopsUpdate, "__init__") == ["self", "chops", "spans", "chop_ends"],
        "ChopsUpdate.render_segments(console)":
            _params(ChopsUpdate, "render_segments") == ["self", "console"],
    }


def _hold_checks() -> dict[str, bool]:
    screen = Screen()
    return {
        "Screen._compositor_refresh()": _params(Screen, "_compositor_refresh") == ["self"],
        "Screen._dirty_widgets": isinstance(getattr(screen, "_dirty_widgets", None), set),
        "Screen._repaint_required": isinstance(getattr(screen, "_repaint_required", None),
                                               bool),
    }


def _other_checks() -> dict[str, bool]:
    from textual.app import App
    from textual.drivers._writer_thread import WriterThread
    from textual.drivers.linux_driver import LinuxDriver

    async def driver_attributes() -> dict:  # (a driver is made in a running loop)
        return vars(LinuxDriver(app))

    app = App()
    writer = WriterThread(io.StringIO())  # (not started)
    loop = asyncio.new_event_loop()
    try:
        driver = loop.run_until_complete(driver_attributes())
    finally:
        loop.close()
    return {
        "Screen._compositor": isinstance(getattr(Screen(), "_compositor", None), Compositor),
        **_hold_checks(),
        "Styles._cache_key": isinstance(getattr(RenderStyles, "_cache_key", None), property),
        "App._driver": "_driver" in vars(app),
        "LinuxDriver._writer_thread": "_writer_thread" in driver,
        "WriterThread._queue": callable(getattr(getattr(writer, "_queue", None), "qsize", None)),
        "CommandPalette._action_command_list(action)":
            _params(CommandPalette, "_action_command_list") == ["self", "action"],
        "Parser.__init__()": _params(Parser, "__init__") == ["self"],
        "App._handle_exception(error)": _params(App, "_handle_exception") == ["self", "error"],
        "App._exit_renderables": isinstance(vars(app).get("_exit_renderables"), list),
        "App._return_code": "_return_code" in vars(app),
        "LinuxDriver.start_application_mode()": "signal.SIGWINCH" in inspect.getsource(
            LinuxDriver.start_application_mode),
        "<driver module>.XTermParser": all(
            getattr(m, "XTermParser", None) in (XTermParser, SafeXTermParser)
            for m in _driver_modules()) and bool(_driver_modules()),
    }


def coalesce_resize_signals() -> None:
    """Make the SIGWINCH handler that Textual's Linux driver installs not re-entrant.  It reads
    the terminal's size and posts a Resize from inside the signal handler, so a signal arriving
    while it ran ran it again inside itself: a flood of window changes (2,000 in a test) nested
    it 1,000 deep, a RecursionError that ended the viewer.  Wrapped, a signal arriving while it
    runs makes it run once more when it returns, and that run reads the size the terminal has
    then.  A handler already wrapped, or none Python can call (the web driver, a test's
    headless one), is left as it is.  Call from the main thread after the driver has started
    (on mount, and after a resume, which installs Textual's handler again)."""
    import signal

    if not hasattr(signal, "SIGWINCH"):
        return
    inner = signal.getsignal(signal.SIGWINCH)
    if not callable(inner) or getattr(inner, "coalesced", False):
        return
    state = {"busy": False, "again": False}

    def handler(signum, frame) -> None:
        if state["busy"]:  # inside the handler already: once more when it returns
            state["again"] = True
            return
        state["busy"] = True
        try:
            while True:
                state["again"] = False
                inner(signum, frame)
                if not state["again"]:
                    break
        finally:
            state["busy"] = False

    handler.coalesced = True
    signal.signal(signal.SIGWINCH, handler)


def checks() -> dict[str, bool]:
    """Each internal listed above → whether it is there as in Textual 8.2.8 (the attribute,
    its kind, the parameters of a method)."""
    return {**_compositor_checks(), **_other_checks()}


#: the viewer's compositor can replace the screen's (paint.py); else Textual's paints
PARTIAL_PAINT = all(_compositor_checks().values())

_STYLES_KEY = isinstance(getattr(RenderStyles, "_cache_key", None), property)

#: the viewer's screen can hold its paints until its first frame (paint.ViewerScreen); else
#: it paints as Textual does
HOLD_PAINTS = PARTIAL_PAINT and all(_hold_checks().values())


class HeldPaints(Screen):
    """A screen that writes no paint while :attr:`held`: what those paints would have written
    (their regions) is kept, and written by the first paint after :meth:`release`
    (``paint.ViewerScreen``: no paint before the frame of a new layout)."""

    held = False

    def release(self) -> None:
        """Paint from now on: the next paint, due now, writes every region the held ones did
        not."""
        if self.held:
            self.held = False
            compositor = self._compositor
            if self._repaint_required:  # a repaint of the whole screen asked for meanwhile:
                self._repaint_required = False  # the next paint makes it (a layout and a
                compositor._dirty_regions.add(Region(0, 0, *compositor.size))  # repaint
            if compositor._dirty_regions:  # due together would paint twice); the screen
                self._dirty_widgets.add(self)  # marked as dirty, with no region of its
                self.check_idle()  # own: the next update paints the kept regions, once

    def _compositor_refresh(self) -> None:  # Textual's paint
        if self.held:  # its regions stay marked; its widgets are marked by them
            self._dirty_widgets.clear()
            return
        super()._compositor_refresh()


def take_dirty_regions(compositor: Compositor) -> set[Region]:
    """The regions marked for repaint since the last paint; none are marked afterwards (as
    Textual's ``render_partial_update`` takes them)."""
    regions = compositor._dirty_regions.copy()
    compositor._dirty_regions.clear()
    return regions


def regions_to_spans(compositor: Compositor,
                     regions: Iterable[Region]) -> Iterable[tuple[int, int, int]]:
    """``regions`` as non-overlapping horizontal spans ``(y, x1, x2)``, Textual's way."""
    return compositor._regions_to_spans(regions)


def install_compositor(screen: Screen, compositor: Compositor) -> bool:
    """``compositor`` paints ``screen`` (before it is mounted); whether it could."""
    if not (PARTIAL_PAINT and isinstance(getattr(screen, "_compositor", None), Compositor)):
        return False
    screen._compositor = compositor
    return True


def styles_key(widget: Widget) -> tuple:
    """A key that changes when a style of ``widget`` or of an ancestor changes (a new object
    every call without Textual's ``_cache_key``: nothing derived from styles is then kept)."""
    if not _STYLES_KEY:
        return (object(),)
    return tuple(node.styles._cache_key for node in widget.ancestors_with_self)


def writer_backlog(app) -> int:
    """How many writes Textual's output thread still has queued for the terminal (0 when not
    known: no driver yet, a headless one, or another Textual)."""
    try:
        return app._driver._writer_thread._queue.qsize()
    except AttributeError:
        return 0


class SafeCommandPalette(CommandPalette):
    """Textual 8.2's palette, made safe against key bursts.  It raises ``KeyError`` when
    PageUp/PageDown (or Home/End) reach its option list before the list has been laid out
    (ctrl+p then PageUp in one burst): its line index is still empty.  Such a key is
    dropped; once laid out, the list works as usual.  It closes only while on top
    (:meth:`dismiss`)."""

    def dismiss(self, result=None):
        """Only while on top: a second Enter queued behind the first (ctrl+p Enter Enter)
        asked it to close again after it had gone, and Textual's ``dismiss`` then popped the
        viewer's own screen (``ScreenStackError``)."""
        stack = self.app.screen_stack
        if not stack or stack[-1] is not self:
            return AwaitComplete.nothing()
        return super().dismiss(result)

    def _action_command_list(self, action: str) -> None:
        try:
            super()._action_command_list(action)
        except (KeyError, IndexError):
            pass


def _driver_modules() -> list:
    """The modules of Textual's drivers that make an ``XTermParser`` (those importable here)."""
    import importlib

    found = []
    for name in ("linux_driver", "linux_inline_driver", "web_driver"):
        try:
            found.append(importlib.import_module(f"textual.drivers.{name}"))
        except ImportError:  # (another platform's driver)
            continue
    return found


class SafeXTermParser(XTermParser):
    """Textual's terminal input parser, but a sequence it cannot parse is dropped, not fatal:
    Textual 8.2 raises out of its input thread on, e.g., a kitty key ``ESC [ 1114112 u``
    (``chr`` of a code point beyond U+10FFFF), which ends the app.  Input is fed one
    character at a time; when the parser raises, it starts afresh with the next character
    (what it had buffered of the bad sequence is dropped).  A bracketed paste whose end never
    comes is dropped after :data:`PASTE_S` (the driver ticks the parser every 0.1 s)."""

    #: a bracketed paste not ended this long after it began is dropped (a terminal sends a
    #: paste in one go; without its end every later key would be read as pasted text)
    PASTE_S = 2.0
    _recent = ""  # the last characters fed (to see a paste begin and end)
    _paste_since: float | None = None

    def feed(self, data: str):
        if not data:  # end of input
            try:
                yield from super().feed(data)
            except Exception:
                pass
            return
        for ch in data:
            self._recent = (self._recent + ch)[-6:]
            if self._recent == "\x1b[200~":
                self._paste_since = time.monotonic()
            elif self._recent == "\x1b[201~":
                self._paste_since = None
            try:
                yield from super().feed(ch)
            except Exception:
                Parser.__init__(self)  # a fresh parse generator, no tokens, no timeout

    def tick(self):
        if self._paste_since is not None and time.monotonic() - self._paste_since > self.PASTE_S:
            self._paste_since = None
            Parser.__init__(self)  # the unended paste is dropped: keys are keys again
            return
        try:
            yield from super().tick()
        except Exception:
            Parser.__init__(self)


def guard_input_parsing(driver_class: type) -> bool:
    """The Textual driver ``driver_class`` (the app's: a terminal's, or the web's under
    ``tuibrdf serve``) parses terminal input with :class:`SafeXTermParser`; whether it could
    be installed (Textual's drivers name ``XTermParser`` in their module).  Only that
    driver's module is touched: the others are not imported at every start-up."""
    import sys

    module = sys.modules.get(driver_class.__module__)
    if getattr(module, "XTermParser", None) not in (XTermParser, SafeXTermParser):
        return False
    module.XTermParser = SafeXTermParser
    return True


def _one_line(renderable, limit: int = 300) -> str:
    """The last non-blank line of what ``renderable`` prints (a traceback's: the error)."""
    from rich.console import Console

    out = io.StringIO()
    Console(file=out, width=200, color_system=None).print(renderable)
    lines = [ln.strip(" │╰╯─") for ln in out.getvalue().splitlines()]
    last = next((ln for ln in reversed(lines) if ln), "unknown error")
    return last if len(last) <= limit else last[:limit - 1] + "…"


class OneLineCrash:
    """A mixin of the app: an error that still reaches Textual (the viewer's own handlers
    report theirs on the status line, :mod:`.guard`) ends the viewer as Textual does (the
    terminal restored, exit status 1) but prints one line, not a 300-line traceback; and a
    ``panic`` (Textual's input thread calls it when it fails) sets exit status 1 too."""

    def _handle_exception(self, error: Exception) -> None:
        super()._handle_exception(error)
        from rich.text import Text

        text = " ".join(f"{type(error).__name__}: {error}".split())[:300]
        self._exit_renderables[:] = [Text(f"tuibrdf view: internal error, the viewer "
                                          f"stopped: {text}")]

    def panic(self, *renderables) -> None:
        from rich.text import Text

        line = _one_line(renderables[0]) if renderables else "unknown error"
        super().panic(Text(f"tuibrdf view: the viewer stopped: {line}"))
        if self._return_code is None:
            self._return_code = 1
