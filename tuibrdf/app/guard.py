"""The viewer goes on after an error in its own code: each place where Textual calls the
viewer (an action, a timer, a callback from a thread, a message, a closed dialog) is
decorated with :func:`survives`, which turns an exception into a message on the status line
(``BrdfApp.report_error``) instead of ending the app.

Textual has no public hook for this: an exception that reaches it ends the app (and where it
reaches a message loop, that loop stops, so overriding its private handler would only hang
the app: Textual issue #2818).  What still escapes (in Textual itself) ends the viewer with
one line and exit status 1 (``textual_internals.OneLineCrash``).
"""

from __future__ import annotations

import inspect
from functools import wraps

from textual.actions import SkipAction


def _report(owner, error: Exception, where: str) -> None:
    app = owner if hasattr(owner, "report_error") else owner.app
    app.report_error(error, where)


def survives(method):
    """``method`` (sync or async, of the app or of one of its screens) with any
    ``Exception`` it raises reported on the status line; it then returns None."""
    where = method.__name__.lstrip("_").removeprefix("action_").removeprefix("on_")
    if inspect.iscoroutinefunction(method):
        @wraps(method)
        async def guarded_async(self, *args, **kw):
            try:
                return await method(self, *args, **kw)
            except SkipAction:  # Textual's own signal: the key goes to the next binding
                raise
            except Exception as e:
                _report(self, e, where)
                return None

        guarded_async.__survives__ = True
        return guarded_async

    @wraps(method)
    def guarded(self, *args, **kw):
        try:
            return method(self, *args, **kw)
        except SkipAction:
            raise
        except Exception as e:
            _report(self, e, where)
            return None

    guarded.__survives__ = True
    return guarded


def error_text(error: BaseException, limit: int = 200) -> str:
    """``TypeName: message`` on one line of at most ``limit`` characters."""
    text = " ".join(f"{type(error).__name__}: {error}".split())
    return text if len(text) <= limit else text[:limit - 1] + "…"
