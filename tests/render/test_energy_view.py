"""The energy view (render --view energy, the viewer's `v` cycle) and the check report."""

from __future__ import annotations

import numpy as np
import pytest

from tests.render.test_views import to_text
from tuibrdf.core.directions import incident
from tuibrdf.core.registry import MODELS, get_model
from tuibrdf.core.sphere.checks import reciprocity_on_map, run_checks
from tuibrdf.core.sphere.energy import energy_view
from tuibrdf.render.check_view import check_report
from tuibrdf.render.views import render_view


def test_lambert_verdict_is_one_minus_kd():
    # Lambert: E = kd at every μ, so it loses (1 − kd) of the energy, and never gains
    m = MODELS["lambert"]
    v = energy_view(m, m.resolve({"kd": 0.7}), 30.0)
    assert v.verdict.startswith("loses 30 % at Kd = 0.7, θi = 30°")
    assert not v.gains
    assert abs(v.E - 0.7) <= max(v.error, 1e-12) and abs(v.E_avg - 0.7) <= max(v.E_avg_error,
                                                                                1e-12)
    t = v.table
    assert t.values[0] == 0.0 and t.values[-1] == 1.0  # the parameter's whole range
    assert np.all(np.abs(t.E - t.values[:, None]) <= np.maximum(t.error, 1e-12))


def test_ggx_gains_at_kd_1_and_says_where():
    # ggx adds kd/π to the specular lobe unweighted: at kd = 1 and grazing E > 1
    # (docs/reference/checks.md; tests/cli/test_check.py finds the same end)
    m = MODELS["ggx"]
    v = energy_view(m, m.resolve({}), 0.0, "kd")
    assert v.gains and "gains energy" in v.verdict and "Kd = 1, θi = 90°" in v.verdict


def test_the_view_marks_the_current_entry_and_fits():
    m = MODELS["ggx"]
    out = to_text(render_view("energy", m, m.resolve({"kd": 0.5}), 60, 60, 20, color="none"))
    lines = out.rstrip("\n").split("\n")
    assert len(lines) <= 20 and max(len(s) for s in lines) <= 60
    assert "white furnace" in lines[0]
    assert sum(s.count("O") for s in lines) == 2  # on the heat map and on the E_avg strip


def test_a_model_without_a_real_parameter_says_so():
    m = MODELS["abc"]
    out = to_text(render_view("energy", m, m.resolve({}), 30, 60, 20, color="none"))
    assert "no real parameter" in out


@pytest.mark.parametrize("width", [12, 30, 45])
def test_that_note_is_whole_in_a_narrow_pane(width):
    # compare mode's pane of a MERL file: the sentence wraps, no word is cut off
    m = MODELS["abc"]
    out = to_text(render_view("energy", m, m.resolve({}), 40, width, 20, color="none"),
                  width=width)
    lines = [s.rstrip() for s in out.rstrip("\n").split("\n")]
    assert max(len(s) for s in lines) <= width and len(lines) <= 20
    assert "…" not in out
    assert " ".join(lines).split() == ("abc: no real parameter for an energy table E(μ, p); "
                                        "its albedo at θi is on the status line").split()


def test_check_report_draws_verdicts_and_maps():
    m = get_model("ggx")
    v = m.resolve({})
    rec = reciprocity_on_map(m, v, incident(30.0, 180.0), 16)
    inside = np.isfinite(rec)
    assert inside.sum() > 100 and np.all(rec[inside] <= 1e-12)  # reciprocal: rounding only
    out = to_text(check_report("ggx", run_checks(m, v, chi2=False), rec, None, color="none"),
                  width=100)
    assert "reciprocity" in out and "FAIL" in out  # energy fails at kd = 1


def test_the_views_looser_table_stays_honest():
    # the view's table is integrated at VIEW_RTOL (1e-3 of each albedo), not the albedo's
    # 1e-5: each entry must still lie within its estimate of the same albedo at 1e-9
    # (whose own estimate is added), and the estimate within the tolerance asked
    from tuibrdf.core.sphere.albedo import albedo_rule
    from tuibrdf.core.sphere.energy import VIEW_RTOL, e_avg_resolved, theta_of_mu, view_table

    m = MODELS["ggx"]
    v = m.resolve({"kd": 0.0})
    t = view_table(m, v, m.param("alpha"))
    for i in (0, 3, len(t.values) - 1):  # the sharpest lobe, a middle one, the roughest
        vals = m.resolve({"kd": 0.0, "alpha": float(t.values[i])})
        ref = albedo_rule(m, vals, theta_of_mu(t.mu), rtol=1e-9)
        assert np.all(np.abs(t.E[i] - ref.value) <= t.error[i] + ref.error)
        assert np.all(t.error[i] <= VIEW_RTOL * np.abs(t.E[i]) + 1e-13)
        # E_avg's μ panels at a tolerance in proportion (1e-4, not the CLI's 1e-6): within
        # its estimate of E_avg at the CLI's tolerances, and that estimate within VIEW_RTOL
        avg, avg_err = e_avg_resolved(m, vals)
        assert abs(t.E_avg[i] - avg) <= t.E_avg_error[i] + avg_err
        assert t.E_avg_error[i] <= VIEW_RTOL * abs(t.E_avg[i])
    # the E_avg the view prints for the current value: the same looser rule, as honest
    for alpha in (0.05, 0.5):
        vals = m.resolve({"kd": 0.0, "alpha": alpha})
        view = energy_view(m, vals, 30.0, "kd")
        avg, avg_err = e_avg_resolved(m, vals)
        assert abs(view.E_avg - avg) <= view.E_avg_error + avg_err
        assert view.E_avg_error <= VIEW_RTOL * view.E_avg


def test_the_energy_views_albedo_is_the_frames_computed_once(monkeypatch):
    # the view's E at θi and the status line's a(θi) are one number: the frame integrates it
    # once (for a user's kernel, each albedo is a whole adaptive integration)
    from tuibrdf.core.material import Material
    from tuibrdf.core.sphere import albedo as sphere_albedo
    from tuibrdf.core.sphere import energy as sphere_energy
    from tuibrdf.core.views import frame as core_frame

    at_41 = []
    real = sphere_albedo.albedo_rule

    def counted(model, values, thetas, *a, **kw):
        if list(np.atleast_1d(thetas)) == [41.0]:
            at_41.append(1)
        return real(model, values, thetas, *a, **kw)

    for module in (sphere_albedo, sphere_energy):  # (energy.py imports it by name)
        monkeypatch.setattr(module, "albedo_rule", counted)
    m = Material("gltf", {"roughness": 0.37})  # a value no other test's frame has cached
    req = core_frame.FrameRequest((m,), 41.0, extra="energy", energy_param="metallic")
    res = core_frame.compute_frame(req)
    side = res.sides[0]
    view = side.extra[0]
    assert len(at_41) == 1
    assert view.E == max(side.albedo) and view.error == max(side.albedo_error)


#: a model file whose albedo depends on the light's azimuth, in closed form:
#: f = kd/π · (1 + a·wi_x²), so a(θi, φi) = kd · (1 + a·sin²θi·cos²φi)
AZIMUTHAL = '''
import numpy as np
from tuibrdf.core.params import Model, Param

KD = Param("kd", "kd", 0.5, 0.0, 1.0, 0.01)
A = Param("a", "a", 0.5, 0.0, 1.0, 0.01)


def f(wi, wo, kd, a):
    return np.broadcast_to(kd / np.pi * (1.0 + a * wi[..., 0] ** 2), np.broadcast_shapes(
        wi.shape, wo.shape)[:-1])


MODEL = Model("azimuthal", "Azimuthal", (KD, A), f, summary="albedo kd(1 + a sin²θi cos²φi)")
'''


def test_the_energy_table_is_at_the_lights_azimuth(tmp_path):
    # the table, its E_avg strip and the numbers printed beside them are all at the light's
    # φi: at φi = 90° this model's albedo is kd at every θi (at 180°, kd·(1 + a·sin²θi)),
    # so each row of the table holds its kd, and its E_avg = 2∫ kd μ dμ = kd
    from tuibrdf.core.formats.userfiles import load_model_file
    from tuibrdf.core.sphere.energy import mu_grid

    path = tmp_path / "azimuthal.py"
    path.write_text(AZIMUTHAL)
    m = load_model_file(path)
    kd, a = 0.5, 0.5
    vals = m.resolve({"kd": kd, "a": a})
    mu = mu_grid(16)
    theta = float(np.degrees(np.arccos(mu[9])))  # the current θi on the table's μ grid
    for phi, expect in ((90.0, lambda k, u: k + 0 * u),
                        (180.0, lambda k, u: k * (1.0 + a * (1.0 - u * u)))):
        view = energy_view(m, vals, theta, "kd", phi)
        t = view.table
        want = expect(t.values[:, None], t.mu[None, :])
        assert np.all(np.abs(t.E - want) <= t.error + 1e-12)
        assert abs(view.E - expect(kd, mu[9])) <= view.error + 1e-12
        # E_avg = 2∫ a(μ) μ dμ: kd at 90°, kd·(1 + a/2) at 180°
        avg = kd if phi == 90.0 else kd * (1.0 + a / 2)
        assert abs(view.E_avg - avg) <= view.E_avg_error + 1e-12
        assert np.all(np.abs(t.E_avg - (t.values if phi == 90.0 else t.values * (1 + a / 2)))
                      <= t.E_avg_error + 1e-12)


#: a model file that is fine at its default but returns NaN above kd = 0.9
NAN_ABOVE = '''
import numpy as np
from tuibrdf.core.params import Model, Param

KD = Param("kd", "kd", 0.5, 0.0, 1.0, 0.01)


def f(wi, wo, kd):
    v = np.full(np.broadcast_shapes(wi.shape, wo.shape)[:-1], kd / np.pi)
    return v * np.nan if kd > 0.9 else v


MODEL = Model("nan_above", "NaN above 0.9", (KD,), f, summary="NaN for kd > 0.9")
'''


def test_a_kernel_failing_in_the_tables_range_leaves_the_other_panes(tmp_path):
    # the energy table sweeps kd over 0–1, where this kernel returns NaN above 0.9; at the
    # current kd = 0.5 it is fine: the energy pane says why it has no table, and the sections
    # and the status line's albedo (kd = 0.5: a = 0.5 at every θi) still come
    from tuibrdf.core.formats.userfiles import load_model_file
    from tuibrdf.core.material import Material
    from tuibrdf.core.views import frame as core_frame
    from tuibrdf.render import panes

    path = tmp_path / "nan_above.py"
    path.write_text(NAN_ABOVE)
    m = Material(load_model_file(path), {"kd": 0.5})
    res = core_frame.compute_frame(core_frame.FrameRequest((m,), 30.0, extra="energy"))
    side = res.sides[0]
    assert abs(side.albedo - 0.5) <= side.albedo_error + 1e-12
    assert abs(side.section_max - 0.5 / np.pi) <= 1e-15  # the sections: f = kd/π
    assert side.extra is None and "NaN" in side.extra_problem
    text = " ".join(to_text(panes.pane("extra", res, 0, 60, 20, panes.Look(color="none")),
                            width=60).split())
    assert "no energy E(μ, p)" in text and "returned NaN" in text
