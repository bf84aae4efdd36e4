"""A material holds the model it was validated against (tuibrdf/core/material.py): reading it
looks nothing up, and a model file edited on disk does not change a material's model; the
viewer makes a new material from the edited file (``refreshed``)."""

from __future__ import annotations

import math
import os
import shutil

import pytest

from tests import DATA_DIR
from tuibrdf.core import registry
from tuibrdf.core.formats import userfiles
from tuibrdf.core.material import Material
from tuibrdf.core.params import Model
from tuibrdf.core.views import frame as core_frame


def _file_model(tmp_path, text=None):
    path = tmp_path / "mine.brdf"
    shutil.copy(DATA_DIR / "brdf" / "lambert.brdf", path)
    if text is not None:
        path.write_text(text)
    return path


def _edit(path, text):
    """Rewrite ``path`` with ``text`` and move its mtime on (a size and time change)."""
    st = os.stat(path)
    path.write_text(text)
    os.utime(path, ns=(st.st_atime_ns, st.st_mtime_ns + 10**9))


def test_a_frame_of_a_file_model_looks_nothing_up(tmp_path, monkeypatch):
    mat = Material(str(_file_model(tmp_path)))
    core_frame.clear_caches()
    core_frame.compute_frame(core_frame.FrameRequest((mat,), 40.0, map_px=(40, 40)))

    def no_lookup(*a, **kw):
        raise AssertionError("a model lookup during a frame")

    stats = []
    real_stat = os.stat

    def counting_stat(*a, **kw):
        stats.append(a)
        return real_stat(*a, **kw)

    for mod, name in ((registry, "get_model"), (userfiles, "load_model_file")):
        monkeypatch.setattr(mod, name, no_lookup)
    monkeypatch.setattr(os, "stat", counting_stat)
    # one θi step: every part recomputed at the new θi, none from the file
    res = core_frame.compute_frame(core_frame.FrameRequest((mat,), 41.0, map_px=(40, 40)))
    monkeypatch.undo()
    assert stats == []
    assert res.sides[0].peak.value == pytest.approx(0.8 / math.pi, rel=1e-12)


def test_an_edited_file_does_not_change_a_material_until_refreshed(tmp_path):
    path = _file_model(tmp_path)
    mat = Material(str(path))
    model = mat.model
    assert mat.model is model and mat.values["reflectance"] == (0.8, 0.8, 0.8)
    # the same parameter, another formula: half the reflectance
    _edit(path, path.read_text().replace("return reflectance / PI;",
                                         "return 0.5 * reflectance / PI;"))
    assert mat.model is model  # the model the values were validated against
    core_frame.clear_caches()
    old = core_frame.compute_frame(core_frame.FrameRequest((mat,), 30.0), slow=False)
    assert old.sides[0].peak.value == pytest.approx(0.8 / math.pi, rel=1e-12)
    assert mat.with_values(reflectance=(0.4, 0.4, 0.4)).model is model
    new = mat.refreshed()  # what the viewer does when the file changed
    assert new is not mat and new != mat and new.model is not model
    assert new.values == mat.values
    res = core_frame.compute_frame(core_frame.FrameRequest((new,), 30.0), slow=False)
    assert res.sides[0].peak.value == pytest.approx(0.4 / math.pi, rel=1e-12)


def test_a_material_of_a_model_object_holds_that_model():
    # a Model that shares a registered model's name is that Model, not the registered one
    lam = registry.MODELS["lambert"]
    own = Model("lambert", "twice lambert", lam.params,
                lambda wi, wo, **kw: 2.0 * lam.kernel(wi, wo, **kw))
    mine, theirs = Material(own), Material("lambert")
    assert mine.model is own and theirs.model is lam
    assert mine != theirs  # so a frame of one is never the other's from the cache
    core_frame.clear_caches()
    a = core_frame.compute_frame(core_frame.FrameRequest((mine,), 30.0), slow=False)
    b = core_frame.compute_frame(core_frame.FrameRequest((theirs,), 30.0), slow=False)
    assert a.sides[0].peak.value == pytest.approx(2.0 * b.sides[0].peak.value, rel=1e-12)



def test_material_is_a_validated_hashable_value():
    a = Material("phong", {"kd": 0.2})
    b = Material("phong", {"kd": 0.2, "ks": registry.MODELS["phong"].param("ks").default})
    assert a == b and hash(a) == hash(b) and len({a, b}) == 1  # defaults filled: one key
    assert a != Material("phong", {"kd": 0.3}) and a != Material("blinn-phong", {"kd": 0.2})
    assert list(a.values) == [p.name for p in registry.MODELS["phong"].params]  # in order
    with pytest.raises(ValueError, match="kd"):
        Material("phong", {"kd": 2.0})  # out of the declared range [0, 1]
    with pytest.raises(ValueError, match="constraint"):
        Material("phong", {"kd": 0.8, "ks": 0.8})  # kd + ks ≤ 1
    with pytest.raises(AttributeError):
        a.name = "lambert"
    a.values["kd"] = 0.9  # a copy: the material does not change
    assert a.values["kd"] == 0.2
    c = a.with_values(kd=0.4)
    assert c.values["kd"] == 0.4 and a.values["kd"] == 0.2
    with pytest.raises(ValueError):
        a.with_values(kd=0.9)  # 0.9 + ks 0.5 > 1
