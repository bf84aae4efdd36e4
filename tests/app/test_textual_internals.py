"""The private names of Textual the viewer relies on are all in tuibrdf/app/textual_internals.py
and still there as in the Textual they were checked against; no other module of tuibrdf/app
reaches one."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest
from textual.app import App
from textual.command import CommandPalette
from textual.dom import DOMNode
from textual.message_pump import MessagePump
from textual.screen import Screen
from textual.widget import Widget
from textual.widgets import Static

from tests import ROOT
from tuibrdf.app import textual_internals

APP = ROOT / "tuibrdf" / "app"
CHECKS = textual_internals.checks()


@pytest.mark.parametrize("internal", list(CHECKS))
def test_each_textual_internal_the_viewer_uses_is_there(internal):
    assert CHECKS[internal], (
        f"Textual's {internal} is missing or changed (tuibrdf/app/textual_internals.py relies "
        "on it): check what the viewer does with it there, against this Textual")


def test_every_internal_checked_is_listed_in_the_modules_docstring():
    doc = textual_internals.__doc__
    for internal in CHECKS:
        assert f"``{internal}``" in doc, internal
    assert "Textual 8.2.8" in doc


def _textual_private_names() -> set[str]:
    names: set[str] = set()
    for cls in (App, Screen, Widget, Static, DOMNode, MessagePump, CommandPalette):
        names |= set(dir(cls))
    for obj in (App(), Screen(), Widget(), Static()):
        names |= set(vars(obj))
    return {n for n in names if n.startswith("_") and not n.startswith("__")}


def _private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def _defined_and_used(path: Path) -> tuple[set[str], dict[str, int]]:
    """The private names a module defines (methods, ``self._x = …``, class attributes) and
    the private attributes it reads or writes (``x._name``, ``getattr(x, "_name")``), each
    with a line number."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    defined: set[str] = set()
    used: dict[str, int] = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.ClassDef):
            for item in node.body:
                if isinstance(item, (ast.FunctionDef, ast.AsyncFunctionDef)):
                    defined.add(item.name)
                elif isinstance(item, ast.AnnAssign) and isinstance(item.target, ast.Name):
                    defined.add(item.target.id)
                elif isinstance(item, ast.Assign):
                    defined |= {t.id for t in item.targets if isinstance(t, ast.Name)}
        elif isinstance(node, (ast.Assign, ast.AnnAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            for t in targets:
                for sub in ast.walk(t):
                    if isinstance(sub, ast.Attribute) and isinstance(sub.value, ast.Name) \
                            and sub.value.id == "self":
                        defined.add(sub.attr)
        if isinstance(node, ast.Attribute) and _private(node.attr):
            used.setdefault(node.attr, node.lineno)
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and \
                node.func.id in ("getattr", "hasattr", "setattr") and len(node.args) >= 2 and \
                isinstance(node.args[1], ast.Constant) and isinstance(node.args[1].value, str) \
                and _private(node.args[1].value):
            used.setdefault(node.args[1].value, node.lineno)
    return {n for n in defined if _private(n)}, used


def test_no_other_module_of_the_viewer_reaches_a_private_name_of_textual():
    # every private attribute a module of tuibrdf/app (but textual_internals.py) reads or
    # writes is one the viewer's own code defines, and none of those shadows one of Textual's
    # (a method or attribute of App, Screen, Widget, … of the same name would be replaced)
    modules = [p for p in sorted(APP.glob("*.py")) if p.name != "textual_internals.py"]
    defined: set[str] = set()
    used: dict[str, str] = {}
    for path in modules:
        d, u = _defined_and_used(path)
        defined |= d
        for name, line in u.items():
            used.setdefault(name, f"{path.name}:{line}")
    textual = _textual_private_names()
    foreign = {name: where for name, where in used.items() if name not in defined}
    assert not foreign, f"private names not of the viewer's own, outside " \
                        f"textual_internals.py: {foreign}"
    shadowing = sorted(defined & textual)
    assert not shadowing, f"the viewer's own private names shadow Textual's: {shadowing}"


def test_a_resize_signal_inside_the_handler_runs_it_again_after_not_inside():
    # Textual's SIGWINCH handler does its work inside the signal handler; a signal arriving
    # while it runs (simulated: the handler calls the installed one again, as Python does
    # between two bytecodes of it) must not nest it, but run it once more after it returns
    import signal

    from tuibrdf.app.textual_internals import coalesce_resize_signals

    depth, most, calls = [0], [0], [0]

    def textual_like(signum, frame):
        depth[0] += 1
        most[0] = max(most[0], depth[0])
        calls[0] += 1
        if calls[0] <= 3:  # three signals arrive while it runs
            signal.getsignal(signal.SIGWINCH)(signum, frame)
            signal.getsignal(signal.SIGWINCH)(signum, frame)
        depth[0] -= 1

    before = signal.signal(signal.SIGWINCH, textual_like)
    try:
        coalesce_resize_signals()
        coalesce_resize_signals()  # wrapped once only
        wrapped = signal.getsignal(signal.SIGWINCH)
        assert wrapped is not textual_like
        wrapped(signal.SIGWINCH, None)
        assert most[0] == 1  # never inside itself
        assert calls[0] == 4  # each run that saw signals ran once more; the last saw none
    finally:
        signal.signal(signal.SIGWINCH, before)
