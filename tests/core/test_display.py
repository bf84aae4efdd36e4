"""The look's defaults, declared once (``tuibrdf.core.display``): the viewer, ``render_view``,
the panes and the command line start from them, and the viewer's keys and the CLI's options
keep each one in the same range."""

from __future__ import annotations

import inspect
import re

import pytest

from tuibrdf.cli import build_parser
from tuibrdf.core.display import DISPLAY, Setting
from tuibrdf.render.panes import Look
from tuibrdf.render.views import render_view
from tuibrdf.state.viewer import ViewerState


def test_the_chosen_defaults_and_ranges():
    # written out here, not read from the code: the values the docs and the help promise
    assert DISPLAY.azimuth[:3] == (-60.0, -360.0, 360.0)
    assert DISPLAY.elevation[:3] == (25.0, -90.0, 90.0)
    assert DISPLAY.gamma[:3] == (2.2, 1.0, 3.0)  # 1 linear … 3: every display gamma in use
    assert DISPLAY.exposure[:3] == (1.0, 2.0**-12, 2.0**12)
    assert DISPLAY.theta_d[:3] == (30.0, 0.0, 90.0)
    assert DISPLAY.theta_h[:3] == (0.0, 0.0, 90.0)
    assert DISPLAY.phi_d[:3] == (90.0, 0.0, 180.0)
    assert DISPLAY.theta_i[:3] == (30.0, 0.0, 90.0)
    assert DISPLAY.phi_i[:3] == (180.0, -360.0, 360.0)
    assert DISPLAY.section_azimuth[:3] == (90.0, -360.0, 360.0)
    assert (DISPLAY.cmap, DISPLAY.sqrt_h) == ("grey", True)
    from tuibrdf.render import CMAPS

    assert DISPLAY.cmap in CMAPS
    with pytest.raises(AttributeError):
        DISPLAY.gamma = Setting(1.0, 0.0, 2.0)  # frozen


def test_the_module_docstring_lists_every_setting():
    import tuibrdf.core.display as display

    rows = re.findall(r"^``([a-z_]+)``  ", display.__doc__, flags=re.M)
    assert rows == [k for k, v in DISPLAY._asdict().items() if isinstance(v, Setting)]


def test_everything_starts_from_the_defaults():
    s = ViewerState()
    look = Look()
    params = inspect.signature(render_view).parameters
    for name in ("azimuth", "elevation", "exposure", "gamma"):
        assert getattr(s, name) == getattr(look, name) == getattr(DISPLAY, name).default
    for name in ("azimuth", "elevation", "section_azimuth", "phi_i", "theta_d", "theta_h",
                 "phi_d"):
        assert params[f"{name}_deg"].default == getattr(DISPLAY, name).default, name
    for name in ("exposure", "gamma"):
        assert params[name].default == getattr(DISPLAY, name).default
    for name in ("theta_i", "phi_i", "section_azimuth", "theta_d", "theta_h", "phi_d"):
        assert getattr(s, name) == getattr(DISPLAY, name).default, name
    assert s.cmap == look.cmap == params["cmap"].default == DISPLAY.cmap
    assert s.sqrt_h == params["sqrt_h"].default == DISPLAY.sqrt_h
    args = build_parser(["render"]).parse_args(["render", "lambert"])
    for name in ("azimuth", "elevation", "section_azimuth", "exposure", "gamma", "theta_d",
                 "theta_h", "phi_d", "theta_i", "phi_i"):
        assert getattr(args, name) == getattr(DISPLAY, name).default, name
    assert args.cmap == DISPLAY.cmap and args.linear_theta_h is not DISPLAY.sqrt_h
    view = build_parser(["view"]).parse_args(["view"])
    assert (view.theta_i, view.phi_i) == (DISPLAY.theta_i.default, DISPLAY.phi_i.default)


def viewer_ends(name: str) -> tuple[float, float]:
    """The lowest and highest value the viewer's keys reach, from the default, by the key
    steps (many presses each way)."""
    ends = []
    for sign in (-1, 1):
        s = ViewerState(view={"theta_d": "theta-h", "theta_h": "theta-d",
                              "elevation": "solid"}.get(name, "map"))
        for _ in range(200):
            if name == "theta_i":
                s.step_theta(sign * 10)
            elif name == "elevation":
                s.rotate(0, sign * 5)
            elif name == "exposure":
                s.scale_exposure(2.0 if sign > 0 else 0.5)
            elif name == "gamma":
                s.step_gamma(sign * 0.2)
            elif name in ("theta_d", "theta_h"):
                s.step_fixed(sign * 5)
            elif name == "phi_d":
                s.step_phi_d(sign * 15)
        ends.append(getattr(s, name))
    return ends[0], ends[1]


CLAMPED = [("theta_i", "--theta-i"), ("elevation", "--elevation"), ("exposure", "--exposure"),
           ("gamma", "--gamma"), ("theta_d", "--theta-d"), ("theta_h", "--theta-h"),
           ("phi_d", "--phi-d")]


@pytest.mark.parametrize("name, flag", CLAMPED)
def test_the_viewer_and_the_cli_keep_a_setting_in_the_same_range(name, flag, capsys):
    lo, hi = viewer_ends(name)
    setting = getattr(DISPLAY, name)
    assert (lo, hi) == (setting.lo, setting.hi)
    parser = build_parser(["render"])
    for v in (lo, hi):
        assert getattr(parser.parse_args(["render", "lambert", f"{flag}={v!r}"]), name) == v
    for v in (lo - abs(lo) * 1e-6 - 1e-9, hi * (1 + 1e-6)):
        with pytest.raises(SystemExit) as e:
            parser.parse_args(["render", "lambert", f"{flag}={v!r}"])
        assert e.value.code == 2
        assert "out of range" in capsys.readouterr().err


@pytest.mark.parametrize("name", ["azimuth", "phi_i", "section_azimuth"])
def test_angles_that_turn_stay_in_their_range_in_the_viewer(name):
    # the viewer turns these round (keys wrap them); the CLI accepts one turn either way
    s = ViewerState(view="solid")
    for _ in range(100):
        {"azimuth": lambda: s.rotate(35, 0), "phi_i": lambda: s.step_phi_i(35),
         "section_azimuth": lambda: s.step_section(35)}[name]()
        assert getattr(DISPLAY, name).accepts(getattr(s, name))
    assert getattr(DISPLAY, name).turn
