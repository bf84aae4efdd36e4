"""The viewer's state transitions and presets, without Textual.

Expected values come from the parameter declarations (steps, ranges, constraints as written in
the model modules and SPEC §2) and from the seed's comparison presets (BRDF Viewer doc §8).
"""

import pytest

from tests import DATA_DIR
from tuibrdf.core.registry import MODELS
from tuibrdf.state import presets
from tuibrdf.state.viewer import COMPARE_PRESETS, MAIN_VIEWS, Side, ViewerState, panel_rows


def phong_state(**params):
    return ViewerState(sides=[Side.of("phong", params)])


def test_theta_steps_and_bounds():
    s = ViewerState(theta_i=30.0)
    assert s.step_theta(1) is None and s.theta_i == 31.0
    assert s.step_theta(-10) is None and s.theta_i == 21.0
    s.theta_i = 85.0
    assert s.step_theta(10) is None and s.theta_i == 90.0  # clamped to the bound
    msg = s.step_theta(1)
    assert msg and "90" in msg and s.theta_i == 90.0  # refused at the bound
    s.theta_i = 0.0
    assert s.step_theta(-1) and s.theta_i == 0.0
    assert s.set_theta(float("nan")) and s.theta_i == 0.0


def test_param_step_uses_declared_step_and_coarse_step():
    s = phong_state()  # kd 0.2 (step 0.01), ks 0.5, n 20 (step 1, coarse 10)
    assert s.step_param(+1) is None
    assert s.side.values["kd"] == 0.21  # 0.2 + 0.01, exactly: float noise rounded away
    s.select(2)
    assert s.row.param.name == "n"
    # n is declared relative (issue 12: an exponent spans decades): coarse ×2, fine ÷1.1
    assert s.step_param(+1, coarse=True) is None and s.side.values["n"] == 40.0
    assert s.step_param(-1) is None and s.side.values["n"] == 36.4  # 40 / 1.1 to 3 digits


def test_relative_steps_reach_every_decade_in_few_presses():
    # issue 12 item 7: phong n 20 → 1000 took 98 presses of }; a factor 2 per press needs
    # ceil(log2(1000 / 20)) = 6 presses (20·2⁵ = 640 < 1000 ≤ 20·2⁶)
    s = phong_state()
    s.select(2)
    presses = 0
    while s.side.values["n"] < 1000:
        assert s.step_param(+1, coarse=True) is None
        presses += 1
    assert presses == 6
    # ggx α = 0.01: a fine step is 10 % of the value (was 0.005 = 50 %)
    g = ViewerState(sides=[Side.of("ggx", {"alpha": 0.01})])
    g.side.selected = [r.param.name for r in g.side.rows()].index("alpha")
    assert g.step_param(+1) is None and g.side.values["alpha"] == 0.011
    assert g.step_param(-1) is None and g.side.values["alpha"] == 0.01
    # from n = 0 a factor cannot move: the declared absolute step starts it
    z = phong_state(n=0.0)
    z.select(2)
    assert z.step_param(+1) is None and z.side.values["n"] == 1.0


def test_typed_values_are_validated_against_the_declaration():
    s = phong_state()
    s.select(2)  # n in [0, 10000]
    assert s.type_value("1000") is None and s.side.values["n"] == 1000.0
    msg = s.type_value("20000")
    assert msg and "out of range" in msg and "10000" in msg and s.side.values["n"] == 1000.0
    msg = s.type_value("lots")
    assert msg and "not a number" in msg and s.side.values["n"] == 1000.0
    assert s.type_value("nan") and s.side.values["n"] == 1000.0
    s.select(-2)  # kd: the constraint kd + ks ≤ 1 (ks = 0.5) still holds for typed values
    msg = s.type_value("0,7")  # a decimal comma is read as a point
    assert msg and "kd + ks" in msg
    assert s.type_value("0,3") is None and s.side.values["kd"] == 0.3
    assert s.type_theta("45") is None and s.theta_i == 45.0
    assert s.type_theta("91") and s.theta_i == 45.0


def test_typed_choice_accepts_names_and_aliases():
    from tuibrdf.core.registry import MODELS

    s = ViewerState(sides=[Side.of("abc")])
    p = MODELS["abc"].param("material")
    s.side.selected = [r.param.name for r in s.side.rows()].index("material")
    name = p.choices[37]
    assert s.type_value(name.upper()) is None and s.side.values["material"] == name
    if p.aliases:
        alias, canonical = p.aliases[0]
        assert s.type_value(alias) is None and s.side.values["material"] == canonical
    msg = s.type_value("no-such-material")
    assert msg and "unknown choice" in msg


def test_preset_cycle_returns_to_the_users_settings():
    # issue 12 item 3: ggx α = 0.05 → p → ... must come back to α = 0.05
    s = ViewerState(sides=[Side.of("ggx", {"alpha": 0.05})])
    seen = []
    for _ in range(len(COMPARE_PRESETS)):
        assert s.next_preset() is None
        seen.append(s.preset)
    assert seen == [p.name for p in COMPARE_PRESETS]
    msg = s.next_preset()
    assert msg and "back" in msg
    assert not s.compare and s.side.model == "ggx" and s.side.values["alpha"] == 0.05
    # and the per-model memory kept it too: cycling away and back
    s.next_preset()
    s.cycle_model(1)
    assert s.memory["ggx"]["alpha"] == 0.05


def test_constraint_refused_with_message_and_value_kept():
    s = phong_state(kd=0.5, ks=0.5)  # kd + ks = 1, the edge of the constraint
    msg = s.step_param(+1)
    assert msg and "kd + ks ≤ 1" in msg
    assert s.side.values["kd"] == 0.5


def test_range_bound_refused():
    s = phong_state(kd=0.0)
    msg = s.step_param(-1)
    assert msg and "minimum" in msg and s.side.values["kd"] == 0.0
    s.select(2)
    s.side.material = s.side.material.with_values(n=10000.0)
    assert s.step_param(+1) and s.side.values["n"] == 10000.0


def test_reset_restores_default_and_select_wraps():
    s = phong_state(n=70.0)
    s.select(-1)  # wraps to the last row: n
    assert s.row.param.name == "n"
    assert s.reset_param() is None and s.side.values["n"] == 20.0


def test_model_cycle_keeps_theta_and_remembers_values():
    s = phong_state()
    s.theta_i = 47.0
    s.step_param(+1)
    names = list(MODELS)
    s.cycle_model(+1)
    assert s.side.model == names[(names.index("phong") + 1) % len(names)]
    assert s.theta_i == 47.0
    s.cycle_model(-1)
    assert s.side.model == "phong" and s.side.values["kd"] == 0.21


def test_every_model_panel_has_rows_and_rgb_gives_three():
    for m in MODELS.values():
        rows = panel_rows(m)
        n_rgb = sum(p.kind == "rgb" for p in m.params)
        assert len(rows) == len(m.params) + 2 * n_rgb


def test_views_cycle_and_toggles():
    s = ViewerState()
    seen = [s.view]
    for _ in MAIN_VIEWS:
        s.cycle_view()
        seen.append(s.view)
    assert seen[0] == seen[-1] and set(seen) == set(MAIN_VIEWS)
    s.toggle_log()
    s.toggle_cosine()
    assert s.log and s.cosine


def test_compare_and_tab():
    s = phong_state()
    assert s.switch_side()  # refused outside compare mode
    s.toggle_compare()
    assert s.compare and s.active == 1
    s.step_param(+1)
    assert s.sides[1].values["kd"] == 0.21 and s.sides[0].values["kd"] == 0.2
    s.switch_side()
    assert s.active == 0
    s.toggle_compare()
    assert not s.compare


def test_seed_presets():
    s = ViewerState()
    s.theta_i = 60.0
    msg = s.apply_preset("specular")
    if "cook-torrance" not in MODELS:
        assert msg and "cook-torrance" in msg
        return
    assert msg is None and s.theta_i == 60.0
    a, b = s.sides
    assert (a.model, a.values["kd"], a.values["ks"], a.values["n"]) == ("phong", 0, 0.08, 70)
    assert (b.model, b.values["kd"], b.values["f0"], b.values["m"]) == \
        ("cook-torrance", 0, 0.04, 0.07)


def test_rotate_clamps_elevation():
    s = ViewerState(elevation=85.0, view="solid")
    assert s.rotate(0, 10) is None and s.elevation == 90.0
    assert s.rotate(0, 10) and s.elevation == 90.0
    s.rotate(200, 0)
    assert -180 <= s.azimuth < 180


@pytest.fixture
def config(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path))
    return tmp_path


def test_preset_round_trip_restores_every_value(config):
    s = phong_state(kd=0.13, ks=0.07, n=123.0)
    s.theta_i = 61.0
    s.toggle_compare()
    s.cycle_model(+1)
    path = presets.save_preset(s, "mine")
    assert path == config / "tuibrdf" / "presets" / "mine.toml"
    assert [p.name for p in path.parent.iterdir()] == ["mine.toml"]  # no temporary left
    theta, sides, _ = presets.load_preset("mine")
    assert theta == 61.0
    assert [(x.model, x.values) for x in sides] == [(x.model, x.values) for x in s.sides]


def test_preset_round_trip_every_model(config):
    for name, m in MODELS.items():
        if any(p.kind == "path" for p in m.params):
            continue
        s = ViewerState(sides=[Side(name, m.resolve({}))])
        presets.save_preset(s, name)
        assert presets.load_preset(name)[1][0].values == s.sides[0].values


@pytest.mark.parametrize("text, words", [
    ("theta_i = [", "not valid TOML"),
    ("theta_i = 120.0\n[[sides]]\nmodel='lambert'", "theta_i"),
    ("theta_i = 10.0", "[[sides]]"),
    ("[[sides]]\nmodel='nope'", "unknown model"),
    ("[[sides]]\nmodel='lambert'\nparams={kd=3.0}", "kd"),
    ("[[sides]]\nmodel='phong'\nparams={kd=0.9, ks=0.9}", "kd + ks"),
])
def test_malformed_preset_is_a_message(config, text, words):
    d = presets.preset_dir()
    d.mkdir(parents=True)
    (d / "bad.toml").write_text(text)
    with pytest.raises(presets.PresetError, match=None) as e:
        presets.load_preset("bad")
    assert words in str(e.value) and "\n" not in str(e.value)


def test_missing_and_badly_named_preset(config):
    with pytest.raises(presets.PresetError, match="no preset"):
        presets.load_preset("absent")
    with pytest.raises(presets.PresetError, match="invalid"):
        presets.preset_path("../evil")


def test_a_model_file_is_titled_by_its_name_reread_when_edited_and_cycled_back_to(tmp_path):
    # issues 14/12: a file model's name is its absolute path; titles show the file's name, an
    # edited file (mtime/size change) is another material (another cache key), m returns to it
    import os
    import shutil

    from tuibrdf.core.material import Material

    src = DATA_DIR / "brdf" / "lambert.brdf"
    path = tmp_path / "mine.brdf"
    shutil.copy(src, path)
    s = ViewerState(sides=[Side.of(str(path))])
    assert s.side.material.label == "mine.brdf"
    before = s.side.material
    assert before.refreshed() is before  # unchanged on disk: the same material
    path.write_text(path.read_text() + "\n")  # a size change, still a valid file
    st = os.stat(path)
    os.utime(path, ns=(st.st_atime_ns, st.st_mtime_ns + 10**9))
    after = before.refreshed()
    assert after is not before and after != before and hash(after) != hash(before)
    assert after == Material(str(path), before.values)
    s.cycle_model(1)
    assert s.side.model != str(path)
    for _ in range(len(MODELS) + 1):
        if s.side.model == str(path):
            break
        s.cycle_model(1)
    assert s.side.model == str(path)


def test_issue13_view_settings_stay_in_range():
    from tuibrdf.core.display import DISPLAY

    s = ViewerState()
    assert s.step_fixed(5) is not None  # map view: no fixed angle, refused with a reason
    s.view = "theta-h"
    for _ in range(30):
        s.step_fixed(5)
    assert s.theta_d == 90.0 and s.step_fixed(5) is not None  # clamped, then refused
    s.view = "theta-d"
    assert s.step_fixed(-5) is not None and s.theta_h == 0.0
    s.view = "slice"
    s.step_fixed(5)
    assert s.phi_d == 95.0
    for _ in range(20):
        s.scale_exposure(2.0)
    assert s.exposure == DISPLAY.exposure.hi == 4096.0 and s.scale_exposure(2.0) is not None
    s.step_gamma(10)
    assert s.gamma <= 3.0
    for _ in range(13):
        s.step_section(15)  # 90 + 195 = 285 → −75 in (−180, 180]
    assert s.section_azimuth == -75.0
    for _ in range(24):
        s.step_phi_i(15)
    assert s.phi_i == 180.0  # a full turn
    s.view = "slice"
    assert s.move_probe(1, 0) is not None and s.probe is None  # the probe reads the map
    s.view = "map"
    s.move_probe(1, 0)
    for _ in range(100):
        s.move_probe(1, 0)
    assert s.probe[0] == pytest.approx(2**0.5) and s.probe[1] == 0.0  # held on the horizon
    assert len(MAIN_VIEWS) == 9


@pytest.mark.parametrize("step", [1, -1, 2])
def test_model_after_names_where_the_model_key_goes_and_changes_nothing(tmp_path, step):
    # where m / M goes (model_after, which cycle_model follows): the answer is where
    # cycle_model then goes, from every model and a model file, and asking changes nothing
    import shutil

    path = tmp_path / "mine.brdf"
    shutil.copy(DATA_DIR / "brdf" / "lambert.brdf", path)
    s = ViewerState(sides=[Side.of(str(path))])
    s.memory["ggx"] = {**MODELS["ggx"].defaults(), "alpha": 0.05}
    def seen(s):  # what cycle_model changes
        return ([x.material for x in s.sides], {k: dict(v) for k, v in s.memory.items()},
                list(s.files), s.preset)

    for _ in range(2 * len(MODELS) + 2):
        before = seen(s)
        name = s.model_after(step)
        assert seen(s) == before  # asked, nothing changed
        s.cycle_model(step)
        assert s.side.model == name
    assert s.files == [str(path)]


def test_a_model_key_to_values_the_model_refuses_says_so_and_changes_no_side():
    # a remembered value the model refuses must not raise: the key says why and the side
    # stays
    s = phong_state()
    s.memory["blinn-phong"] = {**MODELS["blinn-phong"].defaults(), "kd": 5.0}
    assert s.model_after(1) == "blinn-phong"
    said = s.cycle_model(1)
    assert said and "blinn-phong" in said and "kd" in said
    assert s.side.model == "phong" and s.files == []


def test_the_module_docstring_lists_every_transition():
    # the table in tuibrdf/state/viewer.py's docstring names every public method of
    # ViewerState that answers a key (returns str | None), and nothing else
    import inspect
    import re

    from tuibrdf.state import viewer

    listed = re.findall(r"^``([a-z_]+)``  ", viewer.__doc__, flags=re.M)
    transitions = [name for name, fn in inspect.getmembers(viewer.ViewerState,
                                                          inspect.isfunction)
                   if not name.startswith("_")
                   and inspect.signature(fn).return_annotation == "str | None"]
    assert len(listed) == len(set(listed))
    assert set(listed) == set(transitions)
