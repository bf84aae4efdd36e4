"""How a frame reaches the screen: the viewer's state → a
:class:`~tuibrdf.core.views.frame.FrameRequest`
→ the core's :func:`~tuibrdf.core.views.frame.compute_frame` (in a thread worker) → every visible
pane,
the panels and the status line, drawn from that one result.

A request computed before is shown at once (the core caches results by request); otherwise
:meth:`FrameDelivery.compute` runs in an exclusive thread worker
(``@work(exclusive=True, thread=True)``): the newest request cancels the older ones, and a
result that is no longer the current request is dropped, so the latest state always wins and
its frame always arrives.  The worker posts the fast part (maps, sections, peak) at once and
the slow part (albedo, albedo curve) when done; the fast part waits up to :data:`HOLD_S` for
the slow one, so a fast model's key costs one paint: every pane, the panels and the status
line together (a slow frame lets the panels and status go ahead after :data:`PENDING_S`).
Once a frame is on the terminal the garbage of its key is collected (:data:`GC_YOUNG`), not in
the middle of the next one; after a key pressed again and again (:data:`PREDICTED`) the frames
the latest keys show next are computed and drawn while the viewer is idle (:meth:`prefetch`), and
the pictures a frame replaces are kept for the key back.  A
frame waits while Textual's output writer still has frames queued (a slow terminal), and each
pane is redrawn only when what it shows changed, through
:func:`tuibrdf.render.lines.pane_lines` (rows of segments, not Rich's line splitting).
"""

from __future__ import annotations

import asyncio
import contextvars
import gc
import time
from functools import partial

from rich.console import RenderableType
from rich.text import Text
from textual import work
from textual.worker import get_current_worker

from tuibrdf.app.text import PANES, TERSE_FORMS, legend_text, side_files, status_text, visible_panes
from tuibrdf.core.registry import MODELS
from tuibrdf.core.views import frame as scene
from tuibrdf.core.views.frame import FrameRequest, FrameResult
from tuibrdf.render import EXTRA_VIEWS, MIN_HEIGHT, MIN_WIDTH, panes
from tuibrdf.render.lines import pane_lines
from tuibrdf.render.views import extra_pixels, map_pixels
from tuibrdf.state.viewer import ViewerState

RETRY_S = 0.02  # re-check a busy writer after this long
#: a frame not computed by then: the panels and status line go ahead of it (a key's new value
#: shows at once on a slow model; a fast frame brings them itself, in the same paint)
PENDING_S = 0.05
#: how long maps and sections wait for their albedo (a fast model's albedo takes 1–2 ms:
#: both then go out in one paint; a slow one does not hold the picture up)
HOLD_S = 0.006
#: what a pane or a worker shows as a message instead of stopping the viewer: bad data
#: (ValueError, OSError) and a floating-point exception from a kernel (the kernels raise on
#: one, core/numerics.py; a picture is not worth losing the session over)
DRAW_ERRORS = (ValueError, OSError, ArithmeticError)
#: the automatic collector's young-generation threshold once start-up is over (Python's is
#: 700): a key leaves ≈ 1,000 objects in reference cycles (Textual's strips cache themselves),
#: so at 700 a collection fell inside one key in two, and a middle-generation one (≈ 3 ms) in
#: one in four.  The young objects are collected after each frame instead
#: (:meth:`FrameDelivery._collect_young`); this threshold only catches what no frame collects
#: (a burst of keys, a file read).  docs/benchmarks.md has the numbers.
GC_YOUNG = 10_000
#: a frame whose kind (:meth:`FrameDelivery._kind`) took less than this to compute lately is
#: computed on the event loop, not in the worker: handing it to a thread and back cost ≈ 2 ms
#: of a key's ≈ 14 (the thread's start, the loop and the thread taking turns with the
#: interpreter lock; docs/benchmarks.md).  With the drawing, such a frame still leaves the loop
#: free between two keys of a key held at 30 a second; a slower one (measured data, a
#: file's model, an albedo curve) keeps the worker, which a newer key cancels
INLINE_S = 0.012
#: the computing times kept per kind of frame (the largest decides)
INLINE_KEEP = 3
#: after a frame is shown, when its paint is on the terminal: Textual paints it ≈ 2–15 ms
#: later and its writer thread, which needs the interpreter lock a collection holds, sends it
#: ≈ 1 ms after that (a collection run right after the paint delayed the last byte by ≈ 2 ms)
GC_AFTER_S = 0.03
GC_IDLE_S = 1.0  #: a full collection once no frame has come for this long
#: after the frame of a key in :data:`PREDICTED` is complete on the screen, the frame the
#: same key (then the key before it, :data:`PREDICT_KEEP`) shows next is computed in the
#: worker this long after (its paint and collection done, :data:`GC_AFTER_S`), and its
#: pictures drawn while idle: stepping θi, a parameter or the model then costs a key the last
#: drawing steps and the paint (docs/benchmarks.md).  Any key cancels it, and the key it was for
#: waits for it rather than starting again
PREFETCH_S = 0.04
#: the transitions prepared ahead: the keys a user presses again and again (θi ←/→, the
#: light's azimuth </>, a parameter's +/−, the model m/M); a model only when registered, with
#: no data file to read
PREDICTED = frozenset({"step_theta", "step_phi_i", "step_param", "cycle_model"})
#: how many of the latest different transitions are prepared ahead, the latest first: a user
#: who goes from one key to another and back (θi, then a parameter, then θi again) finds
#: both ready (docs/benchmarks.md); after a key pressed twice in a row, only that key's
PREDICT_KEEP = 2
#: a θi or parameter key is prepared ahead only when the frames of its kind took less than
#: this lately (the registered models' frames take 2–25 ms at 160×48): measured data, a
#: model file's slow kernel or a curve would keep the worker, and the interpreter lock,
#: from the next key for longer than preparing it could save
PREFETCH_MAX_S = 0.03


class FrameDelivery:
    """The frame half of :class:`~tuibrdf.app.app.BrdfApp` (a mixin: it uses the app's
    ``state``, ``look``, ``one``, ``sync``, ``frame``, ``request`` and ``message``)."""

    #: the timers of the frame on its way (:meth:`_after`): its panels going ahead
    #: (:data:`PENDING_S`), its pictures no longer waiting for the albedo (:data:`HOLD_S`)
    _pending_at: asyncio.TimerHandle | None = None
    _hold_at: asyncio.TimerHandle | None = None

    def _after(self, delay: float, callback, *args) -> asyncio.TimerHandle | None:
        """``callback(*args)`` on the event loop in ``delay`` s, as a timer of the loop itself
        (a Textual timer is a task of its own: creating, waking and ending it cost the loop
        ≈ 0.2 ms on every key, docs/benchmarks.md); a bug in it ends the app as in a Textual timer.
        Before the loop is known (tests in sync mode), a Textual timer."""
        if self._event_loop is None:
            self.set_timer(delay, partial(callback, *args))
            return None
        return self._event_loop.call_later(delay, self._guarded, callback, args,
                                           context=self._loop_context)

    def _guarded(self, callback, args: tuple) -> None:
        try:
            callback(*args)
        except Exception as error:  # a bug: the viewer stops with status 1, as Textual does
            self._handle_exception(error)

    def _cancel_timers(self) -> None:
        for handle in (self._pending_at, self._hold_at):
            if handle is not None:
                handle.cancel()
        self._pending_at = self._hold_at = None

    def _panels(self) -> None:
        for i in range(len(self.state.sides)):
            self.one(f"panel-{'ab'[i]}").show(self.state, i)

    def _pending(self, req: FrameRequest) -> None:
        """The frame of ``req`` is slow to come: show the panels and the status line (its
        numbers "…") now rather than with it."""
        if req == self.request and (self.frame is None or self.frame.request != req):
            self._panels()
            self._status()

    def request_rebuild(self) -> None:
        """A pane was resized: the request (pane sizes) changed."""
        self._changed(self.message)

    def _pane_size(self, pane: str) -> tuple[int, int]:
        size = self.one(pane).size
        return size.width, size.height

    def frame_request(self, state: ViewerState | None = None) -> FrameRequest:
        """What the visible panes show, from the state (``state``: another one, at the
        present pane sizes) and the pane sizes."""
        s = self.state if state is None else state
        map_px = None
        if s.view == "map":
            sizes = [self._pane_size(p) for p in visible_panes(s) if PANES[p][0] in
                     ("map", "diff")]
            if all(w >= MIN_WIDTH and h >= MIN_HEIGHT for w, h in sizes):
                map_px = map_pixels(min(w for w, _ in sizes), min(h for _, h in sizes))
        extra = s.view if s.view in EXTRA_VIEWS else None
        extra_px = None
        if extra is not None:
            sizes = [self._pane_size(p) for p in visible_panes(s) if
                     PANES[p][0] == "extra"]
            w, h = min(w for w, _ in sizes), min(h for _, h in sizes)
            if w >= MIN_WIDTH and h >= MIN_HEIGHT:
                extra_px = extra_pixels(extra, w, h)
            elif extra in ("sphere", "plane", "slice"):
                extra = None  # too small: the pane says so
        return FrameRequest(tuple(x.material for x in s.sides), s.theta_i, cosine=s.cosine,
                            map_px=map_px, solid=s.view == "solid", curve=s.view == "albedo",
                            section_azimuth=s.section_azimuth, extra=extra, extra_px=extra_px,
                            theta_d=s.theta_d, theta_h=s.theta_h, phi_d=s.phi_d,
                            sqrt_h=s.sqrt_h, probe=s.probe, phi_i=s.phi_i)

    def refresh_frame(self) -> None:
        """Show the current state's frame: at once when computed before, else when the worker
        has computed it."""
        if self.screen.has_class("small"):
            self._panels()
            self._status()
            return
        if not self._files_ready():  # measured data still loading: its panes say so
            for pane in visible_panes(self.state):
                self.one(pane).show(
                    Text("loading measured data …", justify="center"), None)
            self._panels()
            self._status()
            return
        req = self.request = self.frame_request()
        if self.sync:
            try:
                self.show_frame(scene.compute_frame(req))
            except DRAW_ERRORS as e:
                self._failed(req, e)
            return
        done = scene.cached_frame(req)
        if (done is None or not done.complete) and self._compute_here(req, done is None):
            return
        if done is not None:
            self.frame_ready(done)
        else:
            if self._pending_at is not None:
                self._pending_at.cancel()
            self._pending_at = self._after(PENDING_S, self._pending, req)
        busy = self._worker is not None and self._worker.is_running
        if (done is None or not done.complete) and not (busy and self._worker_for == req):
            self._worker, self._worker_for = self.compute(req), req

    @staticmethod
    def _kind(req: FrameRequest) -> tuple:
        """What a frame's computing time depends on, but for the angles and parameter values
        (the models, the panes and their sizes)."""
        return (tuple(m.name for m in req.materials), req.map_px, req.solid, req.curve,
                req.extra, req.extra_px)

    def _took(self, req: FrameRequest, seconds: float) -> None:
        """Note the time a frame of ``req``'s kind took to compute, none of it cached."""
        kept = self._costs.setdefault(self._kind(req), [])
        kept.append(seconds)
        del kept[:-INLINE_KEEP]

    def _compute_here(self, req: FrameRequest, fresh: bool) -> bool:
        """Compute and show ``req``'s frame now, on the event loop, when frames of its kind
        took less than :data:`INLINE_S` lately (none yet: the worker, which times them) and it
        needs no new albedo curve; returns whether it did.  ``fresh``: none of it is cached
        (its time is then noted)."""
        kept = self._costs.get(self._kind(req))
        if not kept or max(kept) >= INLINE_S or scene.needs_curve(req):
            return False
        if self._worker is not None and self._worker.is_running:
            if self._worker_for == req:  # prefetched (:meth:`prefetch`): on its way
                return False
            self._worker.cancel()  # an older request's: its result would be dropped
        start = time.perf_counter()
        try:
            res = scene.compute_frame(req)
        except DRAW_ERRORS as e:
            self._failed(req, e)
            return True
        if fresh:
            self._took(req, time.perf_counter() - start)
        self.show_frame(res)
        return True

    @work(exclusive=True, thread=True, group="frame", description="frame")  # (Textual would
    # otherwise describe the worker by the repr of its request on every key: ≈ 0.1 ms)
    def compute(self, req: FrameRequest) -> None:
        """The frame of ``req`` off the event loop: the fast part, then the albedo (and the
        albedo curve); each posted unless a newer request cancelled this worker."""
        worker = get_current_worker()

        def post(callback, *args) -> None:
            if not worker.is_cancelled:
                try:
                    self.call_from_thread(callback, *args)
                except RuntimeError:  # the app has closed meanwhile
                    pass

        def hand(callback, *args) -> None:
            """``post`` without waiting for the loop to run it: the albedo starts at once
            (≈ 0.4 ms sooner a key: the loop first has to wake up, docs/benchmarks.md)."""
            if self._event_loop is None:
                post(callback, *args)
            elif not worker.is_cancelled:
                try:
                    self._event_loop.call_soon_threadsafe(self._guarded, callback, args,
                                                          context=self._loop_context)
                except RuntimeError:  # the app (and its loop) has closed meanwhile
                    pass

        if worker.is_cancelled:
            return
        fresh = scene.cached_frame(req) is None
        start = time.perf_counter()
        try:
            res = scene.compute_frame(req, slow=False)
            if res.complete and fresh:  # its time, kept by the loop (:meth:`_took`)
                hand(self._took, req, time.perf_counter() - start)
            hand(self.frame_ready, res)
            if not res.complete and not worker.is_cancelled:
                res = scene.compute_frame(req, check=lambda: not worker.is_cancelled)
                if res is not None:
                    if fresh:
                        hand(self._took, req, time.perf_counter() - start)
                    hand(self.show_frame, res)
        except DRAW_ERRORS as e:  # a data file that vanished or changed on disk
            post(self._failed, req, e)

    def _failed(self, req: FrameRequest, error: Exception) -> None:
        if req == self.request:
            for pane in visible_panes(self.state):
                self.one(pane).show(Text(f"cannot draw: {error}"), None)
            self.message = f"cannot compute this frame: {error}"
            self._panels()
            self._status()

    def _writer_busy(self) -> bool:
        """Frames still queued for the terminal (Textual's private writer; guarded)."""
        try:
            return self._driver._writer_thread._queue.qsize() > 0  # type: ignore[union-attr]
        except AttributeError:
            return False

    def frame_ready(self, res: FrameResult) -> None:
        """A result for the screen: a complete one at once; one still waiting for its albedo
        waits up to :data:`HOLD_S` for it, so that a fast model's key costs one paint."""
        if res.complete or res.request != self.request:
            self.show_frame(res)
        else:
            if self._hold_at is not None:
                self._hold_at.cancel()
            self._hold_at = self._after(HOLD_S, self._show_partial, res)

    def _show_partial(self, res: FrameResult) -> None:
        if self.frame is None or self.frame.request != res.request:
            self.show_frame(res)

    def show_frame(self, res: FrameResult) -> None:
        """Draw ``res`` if it is still the current request: every visible pane, the panels and
        the status line in one go (one paint; each pane redrawn only if what it shows
        changed)."""
        if res.request != self.request or not self.is_running:
            if res.complete and res.request == self._ahead and self.is_running:
                self._after(0.0, self._draw_ahead, res, visible_panes(self.state))
            return  # a newer request is on its way, or the app is closing
        if self._writer_busy():  # trailing edge: try again when the terminal has caught up
            self._after(RETRY_S, self.show_frame, res)
            return
        self._cancel_timers()  # this request's frame is shown: its panels and pictures with it
        self.frame = res
        self.frames += 1
        before, self._drawn_before = self._drawn_before, {}
        for pane in visible_panes(self.state):
            self._draw(pane, res, before)
        self._drawn_ahead.clear()  # (pictures of another frame)
        if self.state.compare and self.state.view == "map":
            self.one("legend").update(legend_text(self.state))
        self._panels()
        self._status()
        paint_now = getattr(self.screen, "paint_now", None)  # the viewer's screen (paint.py)
        if paint_now is not None:
            paint_now()  # to the terminal now, not after a round of idle events
        if self._event_loop is not None:  # not in sync mode (tests)
            self._event_loop.call_later(GC_AFTER_S, self._collect_young,
                                        context=self._loop_context)
            # a key pressed again: that key only (m, m, m: not the θi key before them)
            todo = tuple(t for t in self._repeats[:1 if self._again else None]
                         if t[0] in PREDICTED)
            if todo and res.complete:
                self._after(PREFETCH_S, self.prefetch, res.request, todo)

    def prefetch(self, shown: FrameRequest, todo: tuple[tuple[str, tuple], ...]) -> None:
        """Compute, in the worker, the frame the key of the first transition of ``todo``
        (method, args) would show next, when nothing changed since ``shown`` was drawn and
        the worker is idle (:data:`PREFETCH_S`); then draw its pictures while idle
        (:meth:`_draw_ahead`), then the next transition's.  A transition is tried on a copy
        of the state (:meth:`ViewerState.fork`); the result goes to the core's cache, where
        the key finds it."""
        if shown != self.request or self._computing():
            return
        for i, (method, args) in enumerate(todo):
            req = self._predicted(shown, method, args)
            if req is None:
                continue
            self._ahead, self._ahead_then = req, (shown, todo[i + 1:])
            done = scene.cached_frame(req)
            if done is None or not done.complete:
                self._worker, self._worker_for = self.compute(req), req
            else:
                self._draw_ahead(done, visible_panes(self.state))
            return

    def _computing(self) -> bool:
        """Whether the worker is computing a frame: running, and its frame not complete in
        the cache (a thread worker reads as running a moment after handing over its last
        result, until the event loop learns it has ended)."""
        if self._worker is None or not self._worker.is_running:
            return False
        done = scene.cached_frame(self._worker_for)
        return done is None or not done.complete

    def _predicted(self, shown: FrameRequest, method: str, args: tuple) -> FrameRequest | None:
        """The request the transition ``method(*args)`` would make from the state shown as
        ``shown``; None when it is not prepared ahead (refused, measured data or a model
        file to read, a kind of frame slow lately, nothing new)."""
        if method == "cycle_model":
            if self.state.model_after(*args) not in MODELS:  # a model file: reading it is I/O
                return None
        else:  # the same kind of frame as this one: only when its frames are quick
            kept = self._costs.get(self._kind(shown))
            if not kept or max(kept) >= PREFETCH_MAX_S:
                return None
        ahead = self.state.fork()
        if getattr(ahead, method)(*args) is not None:  # refused (a bound): nothing next
            return None
        if any(side_files(side) for side in ahead.sides):  # measured data: read when asked
            return None
        req = self.frame_request(ahead)
        return None if req == shown else req

    def _draw_ahead(self, res: FrameResult, todo: list[str]) -> None:
        """The pictures of the frame computed ahead (:meth:`prefetch`), drawn while the viewer
        is idle, one pane a call (a key waits for one at most); :meth:`_draw` shows them when
        the key comes, as long as they are what it would draw (the same key).  A picture
        the screen showed just before (:meth:`_draw`) is not drawn again."""
        if res.request != self._ahead or res.request == self.request or not todo:
            return
        pane = todo[0]
        got = self._pane_key(pane, res)
        pic = self.one(pane)
        if got is not None and pic.shown_for != got[0] and got[0] not in self._drawn_before:
            key, w, h = got
            try:
                part = self._picture(pane, res, w, h)
                lines = pane_lines(part, self.console, pic.size.width, pic.size.height)
            except DRAW_ERRORS:
                pass  # drawn, and the error shown, if the key comes
            else:
                self._drawn_ahead[key] = part, lines, pic.size
        if todo[1:]:
            self._after(0.0, self._draw_ahead, res, todo[1:])
        else:  # its garbage now, not in the middle of the next key (GC_YOUNG)
            self._collect_young()
            shown, then = self._ahead_then
            if then:  # then the frame of the next transition
                self._after(0.0, self.prefetch, shown, then)

    def capture_loop(self) -> None:
        """Note the event loop and the app's context (on mount) for the collections."""
        self._loop_context = contextvars.copy_context()
        self._event_loop = asyncio.get_running_loop()

    def _collect_young(self) -> None:
        """:data:`GC_AFTER_S` after a frame is shown, the garbage of its key (:data:`GC_YOUNG`):
        ≈ 0.7 ms between two keys rather than inside one.  Not while the next frame is on its
        way (it collects after it), unless that garbage has grown to half the threshold (a
        held key); once no frame has come for :data:`GC_IDLE_S`, a full collection
        (:meth:`collect_idle`)."""
        busy = self.frame is None or self.frame.request != self.request
        if busy and gc.get_count()[0] < GC_YOUNG // 2:
            return
        gc.collect(1)
        self._collected_at = time.monotonic()

    def collect_idle(self) -> None:
        """A full collection when frames have stopped coming (called on an interval)."""
        last = self._collected_at
        if last is not None and time.monotonic() - last >= GC_IDLE_S:
            self._collected_at = None
            gc.collect()

    def _pane_key(self, pane: str, res: FrameResult) -> tuple[tuple, int, int] | None:
        """What ``pane`` shows of ``res``: its size and what it is drawn from (a picture is
        drawn again only when this changes), and the size to draw it at; None when the pane is
        too small for it."""
        pic = self.one(pane)
        w, h = pic.size.width, pic.size.height
        view, k = PANES[pane]
        look, req = self.look, res.request
        if w < MIN_WIDTH or h < MIN_HEIGHT or (view in ("map", "diff") and not req.map_px) or (
                view == "extra" and req.extra is None):
            return None
        if view in ("map", "diff"):  # every map of a compare grid on the same pixel grid
            w, h = req.map_px[0], req.map_px[1] // 2 + 3
        what = (req.materials, req.theta_i, req.cosine, req.phi_i)
        key = {"map": (what, req.map_px, req.probe, look),
               "diff": (what, req.map_px, look.color),
               "solid": (what, look), "albedo": (req.materials, req.theta_i, req.phi_i,
                                                 look.color, res.complete, look.channel),
               "extra": (req.materials, req.extra_key, look)}.get(view)
        key = (pane, w, h, key or (what, req.section_azimuth, look.color, look.log,
                                   look.channel))
        return key, w, h

    def _picture(self, pane: str, res: FrameResult, w: int, h: int) -> RenderableType:
        """``pane``'s renderable of ``res`` at ``w`` × ``h`` (:meth:`_pane_key`'s size)."""
        view, k = PANES[pane]
        return panes.pane(view, res, k, w, h, self.look)

    def _draw(self, pane: str, res: FrameResult, before: dict[tuple, tuple]) -> None:
        """Show ``pane``'s picture of ``res``: drawn ahead (:meth:`_draw_ahead`), shown just
        before (``before``: a key and the key back, → then ←), or drawn now.  The picture it
        replaces is kept in :attr:`_drawn_before` until the next frame."""
        pic = self.one(pane)
        got = self._pane_key(pane, res)
        shown = pic.drawn()
        if got is not None and shown is not None and shown[0] == got[0]:
            return
        if shown is not None:
            self._drawn_before[shown[0]] = shown[1:]
        if got is None:
            pic.show(Text(f"{pic.size.width}×{pic.size.height}: too small for this pane"), None)
            return
        key, w, h = got
        ready = self._drawn_ahead.pop(key, None) or before.get(key)
        if ready is not None and ready[2] == pic.size:  # drawn already, for this size (a
            pic.show(ready[0], key, ready[1])  # map's key has its pixel grid's, not this)
            return
        try:
            pic.show(self._picture(pane, res, w, h), key)
        except DRAW_ERRORS as e:
            pic.show(Text(f"cannot draw {pane}: {e}"), None)

    def _status(self) -> None:
        self.one("status").show_forms(
            partial(status_text, self.state, self.frame, self.look, self._loading, self.message),
            TERSE_FORMS)
