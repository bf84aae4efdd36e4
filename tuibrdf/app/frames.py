"""How a frame reaches the screen: the viewer's state → a
:class:`~tuibrdf.core.views.frame.FrameRequest` → the core's
:func:`~tuibrdf.core.views.frame.compute_frame` → every visible pane, the panels and the status
line, drawn from that one result.

A request computed before is shown at once (the core caches results by request).  A frame of
registered models only (:func:`built_in`: no model file, no measured data) is computed on the
event loop, where the key is handled, unless frames of its kind took :data:`INLINE_S` of CPU
time or more lately.  Every other frame is computed by :meth:`FrameDelivery.compute` in a
daemon thread of its own (:class:`FrameJob`), one at a time: a request made while a job
computes another waits for it (the newest request replaces an older waiting one), and the
running job then skips its slow part and shows its pictures as they are, so a held key shows
a frame every time one is computed, and the latest state's frame always arrives last.  (Two
jobs at once would share the interpreter and each take twice as long; one that cancelled the
other at every key showed nothing while a key was held.)  A job running for :data:`STUCK_S`
or more may be a user's kernel that never returns: a newer request then gets a thread of its
own.  The job posts the fast part (maps, sections, peak) and the slow part (albedo, albedo
curve) in one message when the slow part of its kind was quick lately (:data:`HOLD_S`; each
message is a paint, and a second paint waits for Textual's next 1/60 s tick), else each as
soon as it has it (:class:`FrameComputed`); a frame not there after :data:`PENDING_S` lets
the panels and the status line go ahead of it (counted from the first key it waits for, so
they follow a held key).
So the kernel of a model read from a user's file (``.py``, ``.brdf``, ``.bsdf``) or from
measured data (MERL) never runs on the event loop (in sync mode, for tests, every frame
does).  A user's kernel may never return: a frame still coming after :data:`SLOW_S` says
"model too slow" (the last picture stays), at most :data:`MAX_JOBS` threads run at a time,
and nothing waits for them at exit.

A frame waits while Textual's output thread still has writes queued for the terminal (a slow
link), and each pane is redrawn only when what it shows changed, through
:func:`tuibrdf.render.lines.pane_lines` (rows of segments, not Rich's line splitting).
"""

from __future__ import annotations

import threading
import time
from functools import partial
from time import monotonic  # (tests replace the module time with a clock of their own)

from rich.text import Text
from textual.message import Message
from textual.timer import Timer

from tuibrdf.app.guard import survives
from tuibrdf.app.text import PANES, TERSE_FORMS, legend_text, status_text, visible_panes
from tuibrdf.app.textual_internals import writer_backlog
from tuibrdf.app.widgets import drawn_size
from tuibrdf.core.material import Material
from tuibrdf.core.registry import MODELS
from tuibrdf.core.views import frame as core_frame
from tuibrdf.core.views.frame import FrameRequest, FrameResult
from tuibrdf.render import EXTRA_VIEWS, MIN_HEIGHT, MIN_WIDTH, panes
from tuibrdf.render.views import extra_pixels, map_pixels

RETRY_S = 0.02  # re-check a busy writer after this long
#: a frame not computed by then: the panels and status line go ahead of it (a key's new value
#: shows at once on a slow model; a fast frame brings them itself, in the same paint)
PENDING_S = 0.05
#: what a pane or a worker shows as a message instead of stopping the viewer: bad data
#: (ValueError, OSError) and a floating-point exception from a kernel (the kernels raise on
#: one, core/numerics.py; a picture is not worth losing the session over)
DRAW_ERRORS = (ValueError, OSError, ArithmeticError)
#: a frame of registered models is computed on the event loop, not in the worker (handing it
#: to a thread and back costs two hand-offs, each a wake-up the scheduler of a busy machine
#: may delay), unless frames of its kind (:meth:`FrameDelivery._kind`) took this much CPU
#: time or more lately: such a frame still leaves the loop free between two keys of a key held
#: at 30 a second; a slower one (a sharp lobe's albedo, a large solid) keeps the worker, which
#: shows the pictures before the albedo and which a newer key cancels.  CPU time, not wall
#: time: what a frame costs, not how busy the machine is
INLINE_S = 0.012
#: the computing times kept per kind of frame (the largest decides)
INLINE_KEEP = 3
#: a frame still computing after this long (wall time): the status line says "model too
#: slow" (and again every SLOW_S); the last picture computed stays on screen
SLOW_S = 2.0
#: at most this many frame threads at a time: a kernel that never returns keeps its thread
#: (a thread cannot be stopped); beyond this, the newest request waits for one to end
MAX_JOBS = 3
#: a job computing for this long (wall time) may never end (a user's kernel in a loop): a
#: newer request no longer waits for it but gets a thread of its own (up to MAX_JOBS)
STUCK_S = 0.25
#: the slow part of a frame (the albedo) is posted with the fast part, in one paint, when the
#: slow part of frames of its kind took less CPU time than this lately (a 60 Hz frame):
#: waiting for it costs less than a second paint, which Textual holds until its next 1/60 s
#: tick after the first
HOLD_S = 0.016
#: how long a held job's pictures wait for it to end (wall time, from its start): a slow
#: part far slower than its kind's lately (a user's kernel, a new region of a table) lets
#: them go; its usual jitter on a busy machine (the event loop drawing meanwhile) stays in
#: one paint
HOLD_WAIT_S = 0.1


def built_in(material: Material) -> bool:
    """Whether ``material`` is a registered model that reads no data file: its kernel is the
    package's own, never a user's file's code or measured data (those frames go to the
    worker)."""
    return material.name in MODELS and not any(p.kind == "path" for p in material.model.params)


class FrameJob:
    """One frame computed in a daemon thread of its own (:meth:`FrameDelivery.compute`), not
    in Textual's thread workers: Textual waits for those when the app closes, and a user's
    kernel that never returns would keep the process alive after q.  A daemon thread is
    abandoned at exit (the CLI exits without waiting for it, cli/view.py)."""

    def __init__(self, request: FrameRequest) -> None:
        self.request = request
        self.started = monotonic()
        self.done = False  # the thread has ended
        self._cancelled = threading.Event()
        #: a newer request waits for this job: its pictures are still shown, its slow part is
        #: not computed
        self.superseded = threading.Event()
        #: its slow part is posted with its fast part (:data:`HOLD_S`)
        self.hold = False
        #: a held job's fast part, once computed: the loop shows it if the slow part is late
        #: (:data:`HOLD_WAIT_S`)
        self.pictures: FrameResult | None = None

    def cancel(self) -> None:
        """A newer request wants the screen: this job's results are dropped."""
        self._cancelled.set()

    def stuck(self) -> bool:
        """Computing for :data:`STUCK_S` or more: a newer request does not wait for it."""
        return not self.done and monotonic() - self.started >= STUCK_S

    @property
    def is_cancelled(self) -> bool:
        return self._cancelled.is_set()

    @property
    def is_running(self) -> bool:
        return not self.done


class FrameComputed(Message):
    """What a frame's thread reports to the event loop: a ``result`` (``seconds``: the CPU
    time computing it took, when none of it was cached, else None; ``slow_seconds``: that of
    its slow part alone), an ``error``, or that the job has ended (``last``)."""

    def __init__(self, job: FrameJob, result: FrameResult | None = None,
                 seconds: float | None = None, error: Exception | None = None,
                 last: bool = False, slow_seconds: float | None = None) -> None:
        super().__init__()
        self.job, self.result, self.seconds, self.error, self.last = (job, result, seconds,
                                                                       error, last)
        self.slow_seconds = slow_seconds


class FrameDelivery:
    """The frame half of :class:`~tuibrdf.app.app.BrdfApp` (a mixin: it uses the app's
    ``state``, ``look``, ``one``, ``sync``, ``frame``, ``request`` and ``message``)."""

    #: the timer of the frame on its way: its panels going ahead (:data:`PENDING_S`)
    _pending_timer: Timer | None = None
    _slow_timer: Timer | None = None  # says "model too slow" (:data:`SLOW_S`)
    _worker: FrameJob | None = None  # the frame job started last, and its request
    _worker_for: FrameRequest | None = None
    #: the request waiting for the running job to end (or for one of MAX_JOBS stuck ones)
    _queued: FrameRequest | None = None
    #: (the app's ``_jobs``: the frame jobs whose thread has not reported its end)

    _asked_at = 0.0  # when the current request was made (time.monotonic)

    def stuck_jobs(self) -> int:
        """How many frame threads are still computing (the CLI does not wait for them)."""
        return sum(1 for j in self._jobs if not j.done)

    def _panels(self) -> None:
        for i in range(len(self.state.sides)):
            self.one(f"panel-{'ab'[i]}").show(self.state, i)

    @survives
    def _pending(self) -> None:
        """The current request's frame is slow to come: show the panels and the status line
        (its numbers "…") now rather than with it."""
        self._pending_timer = None
        if self.frame is None or self.frame.request != self.request:
            self._panels()
            self._status()

    def _stop_pending(self) -> None:
        if self._pending_timer is not None:
            self._pending_timer.stop()
            self._pending_timer = None

    @survives
    def request_rebuild(self) -> None:
        """A pane was resized: the request (pane sizes) changed."""
        self._changed(self.message)

    def _pane_size(self, pane: str) -> tuple[int, int]:
        """The size ``pane``'s picture is drawn at (at most ``widgets.MAX_PANE``)."""
        size = self.one(pane).size
        return drawn_size(size.width, size.height)

    def frame_request(self) -> FrameRequest:
        """What the visible panes show, from the state and the pane sizes."""
        s = self.state
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
                            sqrt_h=s.sqrt_h, probe=s.probe, phi_i=s.phi_i,
                            energy_param=s.row.param.name if extra == "energy" else None)

    def refresh_frame(self) -> None:
        """Show the current state's frame: at once when computed before or quick to compute
        here, else when the worker has computed it."""
        # too small for the panes, or before the first layout: the panels now (their height
        # shapes the panes), the frame when the panes' own resize asks again, sized
        if self.screen.has_class("small") or not any(
                self.one(p).size.area for p in visible_panes(self.state)):
            self._panels()
            self._status()
            if self.screen.has_class("small"):  # what it says is the screen
                self.release_screen()
            return
        if not self._files_ready():  # measured data still loading: its panes say so
            for pane in visible_panes(self.state):
                self.one(pane).show(
                    Text("loading measured data …", justify="center"), None)
            self._panels()
            self._status()
            self.release_screen()
            return
        req = self.frame_request()
        if req != self.request:
            self._asked_at = monotonic()
        self.request = req
        self._queued = None  # a request waiting for a job: this one replaces it
        if self.sync:
            try:
                self.show_frame(core_frame.compute_frame(req))
            except DRAW_ERRORS as e:
                self._failed(req, e)
            return
        done = core_frame.cached_frame(req)
        if done is not None and done.complete:
            self.show_frame(done)
            return
        busy = self._worker is not None and self._worker.is_running
        on_its_way = busy and self._worker_for == req
        if not on_its_way and self._quick(req):
            if busy:
                self._worker.cancel()  # an older request's: its result would be dropped
            self._compute_here(req, fresh=done is None)
            return
        if done is not None:  # its fast part: shown now, the rest from the worker
            self.show_frame(done)
        elif self._pending_timer is None:  # (a key held meanwhile does not put it off: the
            # panels and status line then follow the keys every PENDING_S)
            self._pending_timer = self.set_timer(PENDING_S, self._pending)
        if not on_its_way:
            if busy and not self._worker.stuck():  # wait for it: its pictures still show
                self._worker.superseded.set()
                self._queued = req
                return
            if busy:
                self._worker.cancel()  # an older request's: its results would be dropped
            self._worker, self._worker_for = self.compute(req), req

    @staticmethod
    def _kind(req: FrameRequest) -> tuple:
        """What a frame's computing time depends on, but for the angles and parameter values
        (the models, the panes and their sizes)."""
        return (tuple(m.name for m in req.materials), req.map_px, req.solid, req.curve,
                req.extra, req.extra_px)

    def _took(self, req: FrameRequest, seconds: float, costs: dict | None = None) -> None:
        """Note the CPU time a frame of ``req``'s kind took to compute, none of it cached (in
        ``costs``: the app's ``_costs``, or ``_slow_costs`` for its slow part alone)."""
        kept = (self._costs if costs is None else costs).setdefault(self._kind(req), [])
        kept.append(seconds)
        del kept[:-INLINE_KEEP]

    def _quick(self, req: FrameRequest) -> bool:
        """Whether ``req``'s frame is computed on the event loop: registered models only
        (:func:`built_in`), no new albedo curve, and no frame of its kind took
        :data:`INLINE_S` or more lately."""
        if core_frame.needs_curve(req) or not all(built_in(m) for m in req.materials):
            return False
        return max(self._costs.get(self._kind(req), ()), default=0.0) < INLINE_S

    def _compute_here(self, req: FrameRequest, fresh: bool) -> None:
        """Compute and show ``req``'s frame now, on the event loop (``fresh``: none of it is
        cached, its time is then noted)."""
        start = time.thread_time()
        try:
            res = core_frame.compute_frame(req)
        except DRAW_ERRORS as e:
            self._failed(req, e)
            return
        if fresh:
            self._took(req, time.thread_time() - start)
        self.show_frame(res)

    def compute(self, req: FrameRequest) -> FrameJob:
        """Start computing the frame of ``req`` in a daemon thread (:class:`FrameJob`): the
        fast part, then the albedo (and the albedo curve), each posted
        (:class:`FrameComputed`) unless a newer request cancelled the job.  While
        :data:`MAX_JOBS` jobs still run (kernels that do not return) the request waits
        for one of them to end."""
        alive = [j for j in self._jobs if not j.done]
        if len(alive) >= MAX_JOBS:
            self._queued = req
            return alive[-1]
        job = FrameJob(req)
        job.hold = max(self._slow_costs.get(self._kind(req), (1.0,))) < HOLD_S
        if job.hold:
            self.set_timer(HOLD_WAIT_S, partial(self._held_too_long, job))
        self._jobs.append(job)
        self._queued = None
        threading.Thread(target=self._run_job, args=(job,), name="tuibrdf-frame",
                         daemon=True).start()
        if self._slow_timer is None:
            self._slow_timer = self.set_interval(SLOW_S, self._too_slow)
        return job

    def _run_job(self, job: FrameJob) -> None:
        """The body of a frame's thread (never on the event loop): results, an error and
        the job's end reach the loop as messages (``post_message`` is thread-safe and never
        waits for the loop, which may be closing)."""
        req = job.request

        def post(**kw) -> None:
            if not job.is_cancelled or kw.get("last"):
                try:
                    self.post_message(FrameComputed(job, **kw))
                except RuntimeError:  # the app (and its loop) has closed meanwhile
                    pass

        try:
            if job.is_cancelled:
                return
            fresh = core_frame.cached_frame(req) is None
            start = time.thread_time()
            first = core_frame.compute_frame(req, slow=False)
            if first.complete or not job.hold or job.superseded.is_set():
                post(result=first,
                     seconds=time.thread_time() - start if first.complete and fresh else None)
                if first.complete or job.superseded.is_set():
                    return
            fast = time.thread_time()
            job.pictures = first  # held: they wait for the slow part HOLD_WAIT_S at most
            res = core_frame.compute_frame(
                req, check=lambda: not (job.is_cancelled or job.superseded.is_set()))
            if res is not None:
                now = time.thread_time()
                post(result=res, seconds=now - start if fresh else None,
                     slow_seconds=now - fast if fresh else None)
            elif job.hold:  # superseded meanwhile: its pictures
                post(result=first)
        except Exception as e:  # bad data, a user's kernel raising anything: a message
            post(error=e)
        finally:
            job.done = True
            post(last=True)

    @survives
    def on_frame_computed(self, message: FrameComputed) -> None:
        job = message.job
        if message.last:
            self._job_ended(job)
        elif message.error is not None:
            self._failed(job.request, message.error)
        else:
            if message.seconds is not None:
                self._took(message.result.request, message.seconds)
            if message.slow_seconds is not None:
                self._took(message.result.request, message.slow_seconds, self._slow_costs)
            # a superseded job's pictures: shown as the last state computed until the newer
            # request's frame comes (its status line says "…" for the numbers meanwhile)
            self.show_frame(message.result, passed=job is self._worker and self._queued is not None)

    def _job_ended(self, job: FrameJob) -> None:
        """A frame's thread has ended: the request that waited for it starts now."""
        if job in self._jobs:
            self._jobs.remove(job)
        if self._queued is not None and self._queued == self.request:
            self._worker, self._worker_for = self.compute(self._queued), self._queued

    @survives
    def _held_too_long(self, job: FrameJob) -> None:
        """A held job still computing its slow part :data:`HOLD_WAIT_S` after it started: its
        pictures now (``show_frame`` keeps a whole frame shown already, and drops them once
        the request has moved on)."""
        if not job.done and not job.is_cancelled and job.pictures is not None:
            self.show_frame(job.pictures)

    def _stop_slow_timer(self) -> None:
        if self._slow_timer is not None:
            self._slow_timer.stop()
            self._slow_timer = None

    @survives
    def _too_slow(self) -> None:
        """Every :data:`SLOW_S` while the current request's frame is still computing: say
        so (the last picture computed stays on screen; q still quits)."""
        shown = self.frame is not None and self.frame.request == self.request
        if shown or self.request is None:
            self._stop_slow_timer()
            return
        took = monotonic() - self._asked_at
        if took < SLOW_S:
            return
        self.message = (f"model too slow: {took:.0f} s so far for this frame; the last "
                        "picture stays (q quits)")
        self._panels()
        self._status()

    @survives
    def _failed(self, req: FrameRequest, error: Exception) -> None:
        if req == self.request:
            self._failed_request = req  # the status line says its numbers will not come
            self._stop_slow_timer()
            for pane in visible_panes(self.state):
                self.one(pane).show(Text(f"cannot draw: {error}"), None)
            self.message = f"cannot compute this frame: {error}"
            self._panels()
            self._status()
            self.release_screen()

    @survives
    def show_frame(self, res: FrameResult, passed: bool = False) -> None:
        """Draw ``res`` if it is still the current request (and not the fast part of a frame
        shown complete already), or ``passed``: a state the keys went through, whose frame
        stands until the current one comes; every visible pane, the panels and the status
        line in one go (one paint; each pane redrawn only if what it shows changed)."""
        if (res.request != self.request and not passed) or not self.is_running:
            return  # a newer request is on its way, or the app is closing
        shown = self.frame
        if not res.complete and shown is not None and shown.request == res.request \
                and shown.complete:
            return
        if writer_backlog(self):  # trailing edge: try again when the terminal has caught up
            self.set_timer(RETRY_S, partial(self.show_frame, res, passed))
            return
        self._stop_pending()  # this request's frame is shown: its panels and status with it
        if self.message.startswith("model too slow"):  # it came after all
            self.message = ""
        self.frame = res
        self.frames += 1
        for pane in visible_panes(self.state):
            self._draw(pane, res)
        if self.state.compare and self.state.view == "map":
            self.one("legend").update(legend_text(self.state))
        self._panels()
        self._status()
        self.release_screen()  # the first paint: this frame's (paint.ViewerScreen)

    def _pane_key(self, pane: str, res: FrameResult) -> tuple[tuple, int, int] | None:
        """What ``pane`` shows of ``res``: its size and what it is drawn from (a picture is
        drawn again only when this changes), and the size to draw it at; None when the pane is
        too small for it."""
        pic = self.one(pane)
        w, h = drawn_size(pic.size.width, pic.size.height)
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
                                   look.channel, look.zoom))
        return key, w, h

    def _draw(self, pane: str, res: FrameResult) -> None:
        """Show ``pane``'s picture of ``res`` unless it shows it already (:meth:`_pane_key`)."""
        pic = self.one(pane)
        got = self._pane_key(pane, res)
        if got is None:
            pic.show(Text(f"{pic.size.width}×{pic.size.height}: too small for this pane"), None)
            return
        key, w, h = got
        if pic.shown_for == key:
            return
        view, k = PANES[pane]
        try:
            pic.show(panes.pane(view, res, k, w, h, self.look), key)
        except DRAW_ERRORS as e:
            pic.show(Text(f"cannot draw {pane}: {e}"), None)

    def _status(self) -> None:
        self.one("status").show_forms(
            partial(status_text, self.state, self.frame, self.look, self._loading, self.message,
                    failed=self._failed_request is not None
                    and self._failed_request == self.request),
            TERSE_FORMS)
