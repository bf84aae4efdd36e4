"""Dependency direction: core ← render ← app ← cli.  The numpy API never loads textual/rich."""

import subprocess
import sys

import pytest

from tests import ROOT


def loaded_after(statement: str) -> set[str]:
    code = f"{statement}\nimport sys\nprint(' '.join(sorted(sys.modules)))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return {m.split(".")[0] for m in out.stdout.split()}


@pytest.mark.parametrize("statement", ["import tuibrdf", "import tuibrdf.core",
                                       "import tuibrdf.core.registry"])
def test_core_imports_neither_textual_nor_rich(statement):
    mods = loaded_after(statement)
    assert "textual" not in mods
    assert "rich" not in mods


def import_graph() -> dict[str, set[str]]:
    """``tuibrdf`` module → the ``tuibrdf`` modules it imports (anywhere in its code, function
    bodies included), from the source with ``ast``."""
    import ast

    root = ROOT / "tuibrdf"
    names = {}
    for path in root.rglob("*.py"):
        parts = path.relative_to(root.parent).with_suffix("").parts
        names[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    graph: dict[str, set[str]] = {}
    for mod, path in names.items():
        pkg = mod if path.name == "__init__.py" else mod.rsplit(".", 1)[0]
        deps = set()
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            targets = []
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    up = pkg.split(".")[: len(pkg.split(".")) - node.level + 1]
                    base = ".".join(up + ([base] if base else []))
                targets = [base] + [f"{base}.{a.name}" for a in node.names]
            deps |= {t for t in targets if t in names and t != mod}
        graph[mod] = deps
    return graph


def test_no_import_cycle_and_layers_point_down():
    graph = import_graph()
    # layers: core ← render ← state ← app ← cli (a lower layer never imports a higher one)
    rank = {"core": 0, "render": 1, "state": 2, "app": 3, "cli": 4}

    def layer(m: str) -> int:
        parts = m.split(".")
        return rank.get(parts[1], -1) if len(parts) > 1 else -1

    for mod, deps in graph.items():
        for d in deps:
            if layer(mod) >= 0 and layer(d) >= 0:
                assert layer(d) <= layer(mod), f"{mod} imports {d}"
    # no cycle (a package's __init__ importing its own modules is the usual exception)
    state: dict[str, int] = {}

    def visit(m: str, path: list[str]) -> None:
        state[m] = 1
        for d in graph[m]:
            if m.startswith(d + ".") or d.startswith(m + "."):
                continue  # package ↔ its own modules
            if state.get(d) == 1:
                raise AssertionError("import cycle: " + " → ".join(path + [m, d]))
            if d not in state:
                visit(d, path + [m])
        state[m] = 2

    for m in graph:
        if m not in state:
            visit(m, [])


@pytest.mark.parametrize("statement", ["import tuibrdf.core.views.frame",
                                       "import tuibrdf.core.material",
                                       "import tuibrdf.core.sphere.peak",
                                       "import tuibrdf.state.viewer, tuibrdf.state.presets"])
def test_the_frame_computation_is_numpy_only(statement):
    mods = loaded_after(statement)
    assert "textual" not in mods and "rich" not in mods


def test_no_frame_of_a_built_in_model_imports_numpy_ma():
    # numpy imports numpy.ma on first use of a few functions (np.unique without index
    # outputs calls np.ma.is_masked): a one-off 8–30 ms inside the first frame of a model.
    # Every built-in model's whole frame (map, sections, peak, albedo and its curve) must
    # go without it.
    code = """
from tuibrdf.core.material import Material
from tuibrdf.core.registry import MODELS
from tuibrdf.core.views.frame import FrameRequest, compute_frame
for name, m in MODELS.items():
    if any(p.kind == "path" for p in m.params):  # measured data: needs a file
        continue
    req = FrameRequest((Material(name),), 80.0, map_px=(40, 40), curve=True)
    compute_frame(req)
"""
    full = subprocess.run([sys.executable, "-c", code + "\nimport sys\nprint('numpy.ma' in "
                           "sys.modules, 'tuibrdf.core.formats.rgl_bsdf' in sys.modules)"],
                          capture_output=True, text=True, check=True)
    # nor the .bsdf reader (a .bsdf model carries its albedo's kernel: a built-in model's
    # albedo needs nothing of it): 4 ms of the viewer's first frame
    assert full.stdout.split()[-2:] == ["False", "False"], full.stdout


def test_the_viewer_starts_without_plotext_or_tomllib():
    # the viewer's modules import plotext (the albedo plot) and tomllib (presets) when they
    # draw or read one: ≈ 20 ms each of every start-up otherwise (docs/benchmarks.md)
    mods = loaded_after("import tuibrdf.cli.view, tuibrdf.app.app, tuibrdf.render.panes")
    assert "textual" in mods  # the viewer was imported
    assert "plotext" not in mods and "tomllib" not in mods


def test_the_viewer_starts_without_what_its_first_frame_does_not_use():
    # what a key, a click, a figure, another view or compare mode needs is imported when
    # first used: each module below is 1–5 ms of every start-up otherwise (importtime)
    code = ("import tuibrdf.cli, tuibrdf.cli.view, tuibrdf.app.app, tuibrdf.render.panes\n"
            "import sys\nprint(' '.join(sorted(sys.modules)))")
    mods = set(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                              check=True).stdout.split())
    assert "tuibrdf.app.app" in mods and "tuibrdf.core.views.frame" in mods
    later = {"tuibrdf.app.screens", "tuibrdf.app.checks", "tuibrdf.render.pick",
             "tuibrdf.render.export.figure", "tuibrdf.core.sphere.compare",
             "tuibrdf.render.solid", "tuibrdf.render.albedo_plot", "tuibrdf.render.energy_view",
             "tuibrdf.render.lit_view", "textual.drivers.web_driver",
             "textual.drivers.linux_inline_driver"}
    assert not mods & later, sorted(mods & later)


def test_the_core_is_grouped_by_trade():
    # the core's floors, bottom up: base (params, numerics, conventions, display, directions,
    # lru) ←
    # brdf ← formats ← registry, evaluate, material ← sphere ← views, fit.  A trade never
    # imports a trade above it.
    floor = {"params": 0, "numerics": 0, "conventions": 0, "display": 0, "directions": 0,
             "lru": 0, "brdf": 1, "formats": 2, "registry": 3, "evaluate": 3, "material": 3,
             "sphere": 4, "views": 5, "fit": 5}
    graph = import_graph()
    for mod, deps in graph.items():
        parts = mod.split(".")
        if parts[:2] != ["tuibrdf", "core"] or len(parts) < 3:
            continue
        assert parts[2] in floor, f"{mod}: a module of the core outside its trades"
        for d in deps:
            dp = d.split(".")
            if dp[:2] == ["tuibrdf", "core"] and len(dp) > 2:
                # the registry's lazy lookup of user files is the one arrow up (a name that
                # is not registered may be a path)
                if mod == "tuibrdf.core.registry" and d.startswith("tuibrdf.core.formats"):
                    continue
                assert floor[dp[2]] <= floor[parts[2]], f"{mod} imports {d}"


def test_no_module_is_too_long_to_read():

    root = ROOT / "tuibrdf"
    long = {str(p.relative_to(root)): n for p in root.rglob("*.py")
            if (n := len(p.read_text(encoding="utf-8").splitlines())) > 720}
    assert not long, long
