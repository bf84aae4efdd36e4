"""φi adjustable (issue 13 §5): one function turns (θi, φi) into wi; every view and the albedo
follow; for an isotropic model nothing changes but the picture's rotation, for an anisotropic
one the values change.

Expected values: the spherical-coordinate formula written out here for wi; the invariant of
isotropy (f(R wi, R wo) = f(wi, wo) for a rotation R about the normal), evaluated through the
public ``tuibrdf.evaluate`` at the light at φi = 180° and the directions turned back.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import tuibrdf
from tests import DATA_DIR
from tuibrdf.core.directions import incident
from tuibrdf.core.material import Material
from tuibrdf.core.registry import get_model
from tuibrdf.core.sphere.albedo import albedo_resolved
from tuibrdf.core.views import frame as core_frame
from tuibrdf.core.views.hemimap import geometry, map_values

WARD = str(DATA_DIR / "brdf" / "ward.brdf")


def turn(w: np.ndarray, deg: float) -> np.ndarray:
    a = math.radians(deg)
    c, s = math.cos(a), math.sin(a)
    return np.stack([c * w[..., 0] - s * w[..., 1], s * w[..., 0] + c * w[..., 1], w[..., 2]],
                    axis=-1)


@pytest.mark.parametrize("theta,phi", [(0, 0), (30, 180), (45, 90), (60, -30), (90, 270)])
def test_incident_is_the_spherical_direction(theta, phi):
    t, p = math.radians(theta), math.radians(phi)
    want = [math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)]
    assert incident(theta, phi) == pytest.approx(want, abs=1e-15)
    # the default is the seed's φi = 180°, exactly (−sin θi, 0, cos θi)
    w = incident(float(theta))
    assert w[1] == 0.0 and w[0] == pytest.approx(-math.sin(t), abs=1e-15)


@pytest.mark.parametrize("name,params", [("phong", {"kd": 0.2, "ks": 0.6, "n": 30}),
                                         ("cook-torrance", {"m": 0.3}), ("gltf", {})])
@pytest.mark.parametrize("phi_i", [90.0, 37.0])
def test_isotropic_map_is_the_phi_180_map_turned(name, params, phi_i):
    m = get_model(name)
    v = m.resolve(params)
    px = (40, 40)
    got, info = map_values(m, v, incident(50.0, phi_i), *px)
    dirs = geometry(*px).dirs
    # the same configuration turned by 180° − φi about the normal: light back at φi = 180°
    back = turn(dirs, 180.0 - phi_i)
    want = np.asarray(tuibrdf.evaluate(name, params, incident(50.0), back))
    assert got[geometry(*px).inside] == pytest.approx(want, rel=1e-9, abs=1e-12)


@pytest.mark.parametrize("name", ["phong", "cook-torrance", "oren-nayar"])
def test_isotropic_albedo_does_not_depend_on_phi_i(name):
    m = get_model(name)
    v = m.resolve({})
    a = [float(np.max(albedo_resolved(m, v, 40.0, p))) for p in (180.0, 0.0, 77.0)]
    assert a[1] == pytest.approx(a[0], rel=1e-4) and a[2] == pytest.approx(a[0], rel=1e-4)


def test_frame_follows_phi_i_peak_turns_value_stays():
    mat = Material("phong", {"kd": 0.0, "ks": 0.5, "n": 50})
    base = core_frame.compute_frame(core_frame.FrameRequest((mat,), 40.0), slow=False)
    turned = core_frame.compute_frame(core_frame.FrameRequest((mat,), 40.0, phi_i=90.0), slow=False)
    # the mirror direction of a light at φi = 90° is at φ = −90°; same value (isotropy)
    assert turned.sides[0].peak.value == pytest.approx(base.sides[0].peak.value, rel=1e-9)
    assert turned.sides[0].peak.phi_deg == pytest.approx(-90.0, abs=0.01)
    assert turned.sides[0].peak.theta_deg == pytest.approx(40.0, abs=0.01)
    # the sections through the normal turn with the light: the same curves
    for plane in core_frame.PLANES:
        assert turned.sides[0].sections[plane] == pytest.approx(
            base.sides[0].sections[plane], rel=1e-9, abs=1e-15)


def test_anisotropic_user_model_changes_with_phi_i():
    # Ward anisotropic (αx = 0.15, αy = 0.35): turning the light turns it against the tangent
    # frame, so the map is NOT the φi = 180° map turned, and the albedo changes
    m = get_model(WARD)
    v = m.resolve({})
    px = (40, 40)
    got, _ = map_values(m, v, incident(50.0, 90.0), *px)
    dirs = geometry(*px).dirs
    want = np.asarray(tuibrdf.evaluate(WARD, {}, incident(50.0), turn(dirs, 90.0)))
    diff = np.abs(got[geometry(*px).inside] - want).max()
    assert diff > 0.05 * np.abs(want).max()
    a180 = float(np.max(albedo_resolved(m, v, 60.0, 180.0)))
    a90 = float(np.max(albedo_resolved(m, v, 60.0, 90.0)))
    assert abs(a90 - a180) > 1e-3


def test_cli_eval_takes_phi_i(capsys):
    from tuibrdf.cli import main

    assert main(["eval", "phong", "--theta-i", "30", "--phi-i", "90", "--theta-r", "30",
                 "--phi-r", "-90", "--json"]) == 0
    import json

    doc = json.loads(capsys.readouterr().out)
    wi = [0.0, math.sin(math.radians(30)), math.cos(math.radians(30))]
    wo = [0.0, -math.sin(math.radians(30)), math.cos(math.radians(30))]  # the mirror of wi
    assert doc["phi_i"] == 90.0
    assert doc["values"][0]["f"] == pytest.approx(float(tuibrdf.evaluate("phong", {}, wi, wo)))
