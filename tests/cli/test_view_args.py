"""``tuibrdf view --view NAME``: the viewer starts in a main view of the ``v`` cycle; a name
outside it is one line and exit 2, before Textual."""

from __future__ import annotations

import pytest

from tuibrdf.cli import build_parser, main
from tuibrdf.cli.view import build_state
from tuibrdf.state.viewer import MAIN_VIEWS


@pytest.mark.parametrize("view", MAIN_VIEWS)
def test_view_starts_in_the_named_view(view):
    args = build_parser().parse_args(["view", "phong", "--view", view])
    assert build_state(args).view == view


def test_view_default_is_the_map():
    assert build_state(build_parser().parse_args(["view", "phong"])).view == "map"


def test_view_wins_over_a_seed_preset():
    args = build_parser().parse_args(["view", "--preset", "specular", "--view", "sphere"])
    state = build_state(args)
    assert state.compare and state.view == "sphere"


@pytest.mark.parametrize("bad,says", [("sphre", "did you mean 'sphere'"),
                                      ("incidence", "always shown beside")])
def test_view_refuses_other_names(bad, says, capsys):
    assert main(["view", "phong", "--view", bad]) == 2
    err = capsys.readouterr().err
    assert says in err and "Traceback" not in err and len(err.strip().splitlines()) == 1
