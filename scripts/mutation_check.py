"""Mutation check: does changing any one constant of any model formula fail a core test?

For every numeric literal in the formula modules (``tuibrdf/core/brdf/*.py``
but the tables' reader) this makes two mutants, the
literal scaled by ``1 ± delta`` (a zero becomes ``± delta``), one at a time, in a temporary copy
of the package, and runs the non-snapshot core tests on each (``pytest -x``: the first failure
kills the mutant).  A mutant that passes every test *survives*: either a test is missing, or
the mutant is equivalent (the changed constant cannot change any result); the equivalent ones
are listed in :data:`EQUIVALENT` with the reason, everything else is reported as a survivor.

Not mutated: arguments of the declarations ``Param(...)``, ``Model(...)``, ``replace(...)``
(defaults, ranges and steps: the docs test checks those), subscript indices and ``axis=``
(they pick a component, they are not constants of a formula).

Usage::

    PYTHONPATH=$PWD python scripts/mutation_check.py            # all mutants, 2 workers
    PYTHONPATH=$PWD python scripts/mutation_check.py --list     # only list them
    PYTHONPATH=$PWD python scripts/mutation_check.py --match oren --jobs 1
    PYTHONPATH=$PWD python scripts/mutation_check.py --json out.json   # per-mutant results
    PYTHONPATH=$PWD python scripts/mutation_check.py --rerun out.json  # only its survivors
    PYTHONPATH=$PWD python scripts/mutation_check.py --report out.json # its summary again

Exit status 1 if a mutant survives that is not in :data:`EQUIVALENT`.
"""

from __future__ import annotations

import argparse
import ast
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FILES = sorted(str(p.relative_to(ROOT)) for p in (ROOT / "tuibrdf/core/brdf").glob("*.py")
               if p.name != "materials.py")  # the published tables' reader: no formula
#: the non-snapshot core tests, in stages: a mutant that survives a stage runs the next one
#: (the slow hypothesis stability suite only runs for the few mutants the fast tests miss)
STAGES = [["tests/core/brdf/test_fitted.py", "tests/core/brdf/test_reference_values.py",
           "tests/core/brdf/test_models.py", "tests/core/brdf/test_materials.py",
           "tests/core/brdf/test_kernel_paths.py", "tests/core/brdf/test_precision.py"],
          ["tests/core/brdf/test_stability.py"],
          ["tests/core/sphere/test_chi2.py"]]  # the samplers (core/brdf/sampling.py)
DECLARATIONS = {"Param", "Model", "replace", "Constraint"}

#: Mutants that cannot change any result, keyed as printed (``file::function::literal#k::±``),
#: with the reason.  Most are guards whose threshold cannot matter for unit directions and the
#: parameters' ranges, or fills that a later ``np.where`` replaces.
_MF = "tuibrdf/core/brdf/microfacet.py"
_DF = "tuibrdf/core/brdf/diffuse.py"
_MM = "tuibrdf/core/brdf/microfacet_models.py"
_GGX_DEN = ("den = 2(cos θ + √(cos²θ + α² sin²θ)) ≥ 2α ≥ 0.002 for a unit vector and "
            "α ≥ ALPHA_MIN = 0.001: 'den > t' holds everywhere for any t < 0.002")
_TAN_FILL = ("tan β's fill where `ok` is False: oren_nayar and oren_nayar_simple return "
             "np.where(ab.ok, ..., 0.0), so the filled elements never reach a result")
_UNIT = ("r = |w| = 1 to a few ulps for a direction (evaluate normalises them): a floor of "
         "1e-300·(1 ± 0.001) under it never acts")
_BELOW = ("cos θ < 0 only below the horizon, where the result is replaced by 0 (g.above): "
          "the lower clip at −0.001 changes nothing that is returned")
_UNIT_COS = "cos θ ≤ 1 for a unit vector: an upper clip at 1.001 never acts"
_FLAT_TOP = ("equivalent to float64 precision: a clip of cos θ at 0.999 turns (1 − cos θ)⁵ < 1e-15 "
             "into 1e-15, so 1 + (FD90 − 1)(1 − cos θ)⁵ moves by < 2e-15 relative, the size of "
             "its rounding: no test of values can see it")
_EXP_CAP = ("the floor sin²θh/HUGE caps tan²θh/m² at HUGE·(1 ± 0.001) instead of HUGE, and "
            "exp(−x) is 0 for every x ≥ 746: D is 0 either way")
_D_FLOOR = ("where exp(−x) > 0, cos²θh ≥ 1.3e-3 and π m² cos⁴θh ≥ 5e-12 (m ≥ 0.001): the floor "
            "1e-300·(1 ± 0.001) only acts where the numerator is 0, and 0/floor = 0")
_BP_FILL = ("the divisor's fill where H is undefined: np.where(valid, …, 0.0) replaces the "
            "quotient there")
_BRANCH = ("the threshold picks one of two forms equal in exact arithmetic, each within a few "
           "ulp at the threshold (sin²Δφ/(1 + |cos Δφ|) or 1 − |cos Δφ| at |cos Δφ| = 1/2; "
           "log1p(−(1 − c)) or log c at c = 1/2): moving it by 0.1 % changes values by rounding")
_SHARP_FILL = ("fills where the other branch is taken (1 − c where c ≤ 1/2, c where c ≤ 0): "
               "np.where(near, …) and np.where(inside, …, 0) replace what they give")
_BP_ONE_MINUS = ("Blinn-Phong's 1 − N·H is read by sharp_lobe only where N·H > 0 (inside): the "
                 "fills where H is undefined or N·H ≤ 0 (|h|, 1 − N·H, any value ≥ 1/2) and a "
                 "mask N·H > ±0.001 (where it leaves the fill 1, sharp_lobe takes log c, the "
                 "same value; where it divides, |h| + hz > 0) change no result")
_TIR_FILL = ("a fill where total reflection holds (g² ≤ 0; also where (g + c)² is 0, which "
             "needs g = 0, i.e. total reflection): np.where(tir, 1.0, …) replaces it")
_G1_FLAT = ("G1 − 1 = −Λ·expm1(c_g·t^k) for t ≤ 0.001 is above −3.3e-18 in every channel of "
            "the 100 tables (k ≥ 5.57; light-red-paint's red is the largest): below half an "
            "ulp of 1, so G1 rounds to 1 either way; sgd's parameters come only from the tables")
_HUGE_LEVEL = ("a guard's level, 1/HUGE or 0.25/HUGE: it moves a quotient between computed and "
               "'infinite' only within 0.1% of 1e300, i.e. with both directions within ~1e-150 "
               "of the horizon, where G/(cos θi cos θo) has no limit (docs/reference/models.md) "
               "and 0 is the documented value; exp(−x) is 0 at either side of it in D")
_SGD_LEVEL = ("sgd's 1/(cos θi cos θo) has no limit on the horizon (it diverges like 1/cos θ), "
              "so below a level of cos θi cos θo the specular term counts as 0: within 0.1% of "
              "1e-290 a direction is within 1e-290 of the horizon (the other at most 1 away)")
_CROSSOVER = ("a speed crossover (integer powers by squaring; RGB channels together or one by "
              "one): both paths give the same values to the ulps "
              "tests/core/brdf/test_kernel_paths.py "
              "bounds; an integer size or exponent ≤ 64/256 is ≤ 64.064/256.256 as well")
_ABC_ETA = ("η ∈ [1.039, 100] in the abc table (η comes only from it): η² − 1 ≥ 0.080, so "
            "'η² − 1 ≤ ±0.001' is False everywhere, as 'η² − 1 ≤ 0' is")
_INT_LEN = "len() is an integer: '> 1.001' is '> 1'"
_FLAT_1D = ("'len(shape) > 0.999' also flattens 1-D results: _flat returns a 1-D grey array "
            "itself, or its broadcast to the result's shape, whose elements the (3, 1) columns "
            "meet as they do by broadcasting: the same operations on the same numbers")
_SKIP_UP = ("sgd's skip level 746.746·max α instead of 746·max α: the points in between are "
            "computed, with a = tan²θh/α + α ≥ 745.9 in every channel, exp(−a) = 0 (it "
            "underflows to 0 below −745.13), so the term is 0·(finite) and (ρd + 0)/π = ρd/π, "
            "the skipped value")
_SKIP_DOWN = ("sgd's skip level 745.254·max α: the newly skipped points have a ≥ 745.254·(1 − "
              "3ε) > 745.14 in every channel, where exp(−a) is 0 (it underflows below "
              "−745.13): their specular term was 0, ρd/π either way.  Not true of a much lower "
              "level: at tan²θh = 41·max α with θi 1e-12 rad from the horizon the term is "
              "still > 1e-12 for 64 materials (1/(cos θi cos θo) is large there)")
_TAN2_CAP = ("the floor sin²θh·(1 ± 0.001)/HUGE caps tan²θh at HUGE/(1 ± 0.001) instead of "
             "HUGE: where either acts tan²θh ≥ 0.99e300 ≥ 746·max α (α ≤ 0.86), the point is "
             "skipped and ρd/π returned either way; tan²θh is used nowhere else")
_AP_CAP = ("the cap of a in a^p at 746·(1 ± 0.001): it changes a^p only where a > 745.254, "
           "where exp(−a) = 0 (it underflows below −745.13): the term is 0·(finite) whatever "
           "a^p is (> 0, ≤ 747^1.78)")
_W_FLOOR = ("the floor of cos⁴θh·ci·co at 1e-300·(1 ± 0.001): computed points have ci·co > "
            "1e-290, and exp(−a) > 0 in a channel needs tan²θh < 745.14·α ≤ 637, so cos²θh > "
            "1.5e-3 and the product > 2e-296; the floor acts only where exp(−a) = 0 in every "
            "channel, where the term is 0·(w ≤ 1.001e300) = 0 either way")
_G1_BAND = ("the width of the band around t* where sgd's G1 takes the logarithmic test "
            "instead of the clip at t*·(1 + band): for any width between the test's rounding "
            "(≲ 1e-13) and ~1e-3 every G1 is the value as written (below the band 1 − Λ·expm1(x) "
            "> 0 and the test says live; above it the clipped x gives < −5.6e-9, clamped to 0, "
            "and the test says dead), so 1e-9·(1 ± 0.001) gives the same bits")
_G1_TOWARD_LIVE = (
    "moves G1's clamp test (or the band where the kernel takes it) toward 'live': the points "
    "it newly calls live have x = c_g·t^k ≥ x* = log(1 + 1/Λ), where 1 − Λ·expm1(x) ≤ 0 and "
    "the clamp at 0 gives G1 = 0, as the test did.  The two differ only where x is within the "
    "test's own rounding of x* (|log x − log x*| ≲ 1e-13), where G1 = 0 and a rounding "
    "residue of a few 1e-16 (≤ (1 + Λ)·x*·1e-13) are the same value to float64 precision: "
    "which of the two comes out there depends on the CPU's log and expm1 (0 against 7.8e-16 "
    "for pink-plastic with AVX-512), so no test that holds on every machine can tell them "
    "apart (tests/core/brdf/test_fitted.py, plain_g1's bound).  The other direction, toward "
    "'dead', zeroes G1 > 0 and is killed")
_PH = "tuibrdf/core/brdf/phong.py"
_FT = "tuibrdf/core/brdf/fitted.py"
EQUIVALENT: dict[str, str] = {
    f"{_MF}::beckmann_d::1.0#0::+": _EXP_CAP,
    f"{_MF}::beckmann_d::1.0#0::-": _EXP_CAP,
    f"{_MF}::beckmann_d::1e-300#0::+": _D_FLOOR,
    f"{_MF}::beckmann_d::1e-300#0::-": _D_FLOOR,
    f"{_MF}::ggx_lambda_cos::0.0#0::+": _GGX_DEN,
    f"{_MF}::ggx_lambda_cos::0.0#0::-": _GGX_DEN,
    f"{_DF}::_AlphaBeta.__init__::0.0#0::+": _TAN_FILL,
    f"{_DF}::_AlphaBeta.__init__::0.0#0::-": _TAN_FILL,
    f"{_DF}::_polar::1e-300#0::+": _UNIT,
    f"{_DF}::_polar::1e-300#0::-": _UNIT,
    f"{_DF}::disney_diffuse::0.0#0::-": _BELOW,
    f"{_DF}::disney_diffuse::0.0#1::-": _BELOW,
    f"{_DF}::disney_diffuse::1.0#1::+": _UNIT_COS,
    f"{_DF}::disney_diffuse::1.0#2::+": _UNIT_COS,
    f"{_DF}::disney_diffuse::1.0#1::-": _FLAT_TOP,
    f"{_DF}::disney_diffuse::1.0#2::-": _FLAT_TOP,
    f"{_MM}::ue4::0.0#0::+": "fill below the horizon, replaced by 0 in the result (g.above)",
    f"{_MM}::ue4::0.0#0::-": "fill below the horizon, replaced by 0 in the result (g.above)",
    f"{_DF}::_AlphaBeta.one_minus_abs_cos_dphi::0.5#0::+": _BRANCH,
    f"{_DF}::_AlphaBeta.one_minus_abs_cos_dphi::0.5#0::-": _BRANCH,
    f"{_DF}::_AlphaBeta.one_minus_abs_cos_dphi::0.0#0::-": (
        "den = sin²θi sin²θo (1 + |cos Δφ|) ≥ 0 is 0 only at the normal, where cos Δφ = 0 "
        "takes the other branch: 'den > −0.001' selects no other element"),
    f"{_PH}::sharp_lobe::0.5#0::+": _BRANCH,
    f"{_PH}::sharp_lobe::0.5#0::-": _BRANCH,
    f"{_PH}::sharp_lobe::0.0#1::+": _SHARP_FILL,
    f"{_PH}::sharp_lobe::0.0#1::-": _SHARP_FILL,
    f"{_PH}::sharp_lobe::1.0#0::+": _SHARP_FILL,
    f"{_PH}::sharp_lobe::1.0#0::-": _SHARP_FILL,
    f"{_PH}::blinn_phong::1.0#2::+": _BP_ONE_MINUS,
    f"{_PH}::blinn_phong::1.0#2::-": _BP_ONE_MINUS,
    f"{_PH}::blinn_phong::0.0#2::+": _BP_ONE_MINUS,
    f"{_PH}::blinn_phong::0.0#2::-": _BP_ONE_MINUS,
    f"{_PH}::blinn_phong::1.0#3::+": _BP_ONE_MINUS,
    f"{_PH}::blinn_phong::1.0#3::-": _BP_ONE_MINUS,
    f"{_PH}::blinn_phong::1.0#1::+": _BP_FILL,
    f"{_PH}::blinn_phong::1.0#1::-": _BP_FILL,
    f"{_PH}::blinn_phong::0.0#1::-": (
        "N·H = −0.001 where H is undefined: lobe_power gives 0 for c ≤ 0, as for c = 0"),
    f"{_FT}::fresnel_dielectric::0.0#2::-": (
        "−0.001 < g² ≤ 0 counted as no total reflection: safe_sqrt makes g = 0, and then "
        "(g − c)²/(g + c)² = 1 and (c·c − 1)² / (1 − c·c)² = 1 exactly, F = 1 as under the mask"),
    f"{_FT}::fresnel_dielectric::1.0#5::+": _TIR_FILL,
    f"{_FT}::fresnel_dielectric::1.0#5::-": _TIR_FILL,
    f"{_FT}::fresnel_dielectric::1.0#8::+": _TIR_FILL,
    f"{_FT}::fresnel_dielectric::1.0#8::-": _TIR_FILL,
    f"{_FT}::abc::0.0#0::-": (
        "cos θh < 0 only where H points below the horizon: never for two directions above it "
        "(H's z is (zi + zo)/|wi + wo| ≥ 0); below it rgb() returns 0"),
    f"{_FT}::_fresnel_abc::0.0#0::+": _ABC_ETA,
    f"{_FT}::_fresnel_abc::0.0#0::-": _ABC_ETA,
    f"{_FT}::abc::1#0::+": _INT_LEN,
    f"{_FT}::abc::1#0::-": _FLAT_1D,
    f"{_FT}::_Sgd.__init__::1.0#3::-": (
        "t_lo = t*·(0.999 − band): a wider band, where the logarithmic test as written decides "
        "'dead' and the live values are the same operations on the same t (t < t_hi is not "
        "clipped): the same G1 to the bit"),
    f"{_FT}::_Sgd.__init__::1.0#4::+": (
        "t_hi = t*·(1.001 + band): the band reaches up to it, and the log test as written "
        "decides there (dead, 0); above it t is clipped to t_hi, where x = x*·1.001^k "
        "(≤ 2.4·x* ≤ 41 for k ≤ 856: finite) makes 1 − Λ·expm1(x) < 0: 0 by the clamp, as "
        "written"),
    f"{_FT}::_Sgd.__init__::1.0#1::+": _G1_TOWARD_LIVE,
    f"{_FT}::_Sgd.__init__::1.0#2::+": _G1_TOWARD_LIVE,
    f"{_FT}::_Sgd.__init__::1.0#3::+": _G1_TOWARD_LIVE,
    f"{_FT}::_sgd_g1_plain::1.0#0::+": _G1_TOWARD_LIVE,
    f"{_FT}::_Sgd.__init__::746.0#0::+": _SKIP_UP,
    f"{_FT}::_Sgd.__init__::746.0#0::-": _SKIP_DOWN,
    f"{_FT}::_sgd_g1::0.0#0::+": (
        "t = max(θ − θ0, 0.001) before the clip at t_hi: t* ≥ 0.375 in every channel of the "
        "table, so 0.001 stays below the band, and " + _G1_FLAT),
    f"{_FT}::_sgd_g1_cached::64#0::-": "len() is an integer: '≥ 63.936' is '≥ 64'",
    f"{_FT}::sgd::1.0#0::+": _TAN2_CAP,
    f"{_FT}::sgd::1.0#0::-": _TAN2_CAP,
    f"{_FT}::sgd::1#1::+": _INT_LEN,
    f"{_FT}::sgd::1#1::-": _FLAT_1D,
    f"{_FT}::_sgd_total::746.0#0::+": _AP_CAP,
    f"{_FT}::_sgd_total::746.0#0::-": _AP_CAP,
    f"{_FT}::_sgd_total::1e-300#0::+": _W_FLOOR,
    f"{_FT}::_sgd_total::1e-300#0::-": _W_FLOOR,
    f"{_FT}::_sgd_total::0.0#0::-": (
        "the clamp at 0 never acts for the 100 tables: only blue-fabric, white-fabric2 and "
        "white-paint have f1 > f0 (F < 0 near cos θd = 1), and their f is ≥ 0.0077 over "
        "0.96 M direction pairs about H (θh 0…89.9°, θd 0…30°, φd every 10°; beyond, "
        "exp(−tan²θh/α) vanishes); a clamp at −0.001 returns the same values"),
    f"{_FT}::_sgd_g1_plain::0.0#0::-": (
        "t = max(θ − θ0, −0.001): t = −0.001 fails 't > 0' as t = 0 does, and t only enters "
        "where it is > 0"),
    f"{_FT}::_sgd_g1_plain::1.0#2::+": (
        "x ≥ 0 and Λ > 0, so 1 − Λ·expm1(x) ≤ 1: an upper clip at 1.001 never acts"),
}

#: Not formula constants: a guard's level ("a quotient at or above HUGE counts as infinite")
#: and the sizes where a kernel switches between two ways of computing the same values.
#: Moving one by 0.1% changes a result only for inputs in a band 0.1% wide at the level, where
#: both sides are the documented behaviour, or by the ulps the two ways differ by (tests check
#: those bounds, not the level).  Counted apart from the equivalent mutants.
THRESHOLDS: dict[str, str] = {
    f"{_MF}::<module>::1e300#0::+": _HUGE_LEVEL,
    f"{_MF}::<module>::1e300#0::-": _HUGE_LEVEL,
    f"{_MF}::ggx_g2_over_cos::0.25#1::+": _HUGE_LEVEL,
    f"{_MF}::ggx_g2_over_cos::0.25#1::-": _HUGE_LEVEL,
    f"{_MF}::vcavity_g_over_cos::1.0#1::+": _HUGE_LEVEL,
    f"{_MF}::vcavity_g_over_cos::1.0#1::-": _HUGE_LEVEL,
    f"{_MF}::vcavity_g_over_cos::1.0#2::+": _HUGE_LEVEL,
    f"{_MF}::vcavity_g_over_cos::1.0#2::-": _HUGE_LEVEL,
    f"{_PH}::<module>::64#0::+": _CROSSOVER,
    f"{_PH}::<module>::64#0::-": _CROSSOVER,
    f"{_PH}::<module>::256#0::+": _CROSSOVER,
    f"{_PH}::<module>::256#0::-": _CROSSOVER,
    f"{_FT}::<module>::1e-290#0::+": _SGD_LEVEL,
    f"{_FT}::<module>::1e-290#0::-": _SGD_LEVEL,
    f"{_FT}::<module>::1e-9#0::+": _G1_BAND,
    f"{_FT}::<module>::1e-9#0::-": _G1_BAND,
    f"{_FT}::_sgd_g1_cached::64#0::+": (
        "a cache size: 65 lights' G1 kept per material instead of 64; the cached G1 is the "
        "uncached one to the bit (tests/core/brdf/test_fitted.py)"),
    f"{_FT}::fresnel_dielectric::0.0#1::+": (
        "the fast branch for η² − 1 > 0 (no total reflection possible) against the general "
        "one: for 0 < η² − 1 ≤ 0.001 the general branch computes the same expression, to the "
        "bit (no mask acts there)"),
    "tuibrdf/core/brdf/rgb.py::<module>::256#0::+": _CROSSOVER,
    "tuibrdf/core/brdf/rgb.py::<module>::256#0::-": _CROSSOVER,
}


@dataclass(frozen=True)
class Mutant:
    path: str
    line: int
    col: int
    end_col: int
    scope: str
    literal: str
    occurrence: int
    sign: str
    replacement: str

    @property
    def key(self) -> str:
        return f"{self.path}::{self.scope}::{self.literal}#{self.occurrence}::{self.sign}"


def _mutated_value(value: float, sign: str, delta: float) -> str:
    if value == 0:
        new = delta if sign == "+" else -delta
    else:
        new = value * (1.0 + delta) if sign == "+" else value * (1.0 - delta)
    return f"({new!r})"


def find_mutants(path: str, delta: float) -> list[Mutant]:
    """Every mutable numeric literal of ``path`` (see the module docstring), two mutants each."""
    source = (ROOT / path).read_text()
    tree = ast.parse(source)
    skip: set[int] = set()  # id() of Constant nodes that are not formula constants
    scope_of: dict[int, str] = {}

    def mark(node: ast.AST) -> None:
        for sub in ast.walk(node):
            if isinstance(sub, ast.Constant):
                skip.add(id(sub))

    def visit(node: ast.AST, scope: str) -> None:
        if isinstance(node, ast.FunctionDef | ast.ClassDef):
            scope = f"{scope}.{node.name}" if scope != "<module>" else node.name
        if isinstance(node, ast.Call):
            name = node.func.id if isinstance(node.func, ast.Name) else getattr(
                node.func, "attr", "")
            if name in DECLARATIONS:
                mark(node)
            for kw in node.keywords:
                if kw.arg == "axis":
                    mark(kw.value)
        if isinstance(node, ast.Subscript):
            mark(node.slice)
        if isinstance(node, ast.Constant):
            scope_of[id(node)] = scope
        for child in ast.iter_child_nodes(node):
            visit(child, scope)

    visit(tree, "<module>")
    mutants = []
    seen: dict[tuple[str, str], int] = {}
    lines = source.splitlines()
    constants = [node for node in ast.walk(tree)
                 if isinstance(node, ast.Constant) and type(node.value) in (int, float)
                 and id(node) not in skip]
    for node in sorted(constants, key=lambda n: (n.lineno, n.col_offset)):  # k in source order
        text = lines[node.lineno - 1][node.col_offset:node.end_col_offset]
        scope = scope_of[id(node)]
        k = seen.get((scope, text), 0)
        seen[(scope, text)] = k + 1
        for sign in "+-":
            mutants.append(Mutant(path, node.lineno, node.col_offset, node.end_col_offset, scope,
                                  text, k, sign, _mutated_value(node.value, sign, delta)))
    mutants.sort(key=lambda m: (m.path, m.line, m.col, m.sign))
    return mutants


def apply(source: str, m: Mutant) -> str:
    lines = source.splitlines(keepends=True)
    line = lines[m.line - 1]
    lines[m.line - 1] = line[:m.col] + m.replacement + line[m.end_col:]
    return "".join(lines)


def make_copy(dest: Path) -> None:
    for name in ("tuibrdf", "tests"):
        shutil.copytree(ROOT / name, dest / name,
                        ignore=shutil.ignore_patterns("__pycache__", "__snapshots__", "golden"))
    shutil.copy(ROOT / "pyproject.toml", dest / "pyproject.toml")


def run_stages(workdir: Path, stages: list[list[str]], timeout: float) -> tuple[int, str]:
    """Run the stages in order until one fails: ``(exit status, pytest's last line)``."""
    code, summary = 0, ""
    for tests in stages:
        code, summary = run_tests(workdir, tests, timeout)
        if code != 0:
            break
    return code, summary


def run_tests(workdir: Path, tests: list[str], timeout: float) -> tuple[int, str]:
    shutil.rmtree(workdir / ".hypothesis", ignore_errors=True)  # no replay between mutants
    env = dict(os.environ, PYTHONPATH=str(workdir), PYTHONDONTWRITEBYTECODE="1")
    cmd = [sys.executable, "-m", "pytest", "-q", "-x", "-p", "no:cacheprovider", *tests]
    try:
        r = subprocess.run(cmd, cwd=workdir, env=env, capture_output=True, text=True,
                           timeout=timeout)
    except subprocess.TimeoutExpired:
        return -1, "timeout"
    last = [ln for ln in r.stdout.splitlines() if ln.strip()]
    return r.returncode, (last[-1] if last else r.stderr.strip()[-200:])


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--files", nargs="+", default=FILES)
    ap.add_argument("--tests", nargs="+", help="one stage of these tests instead of the default")
    ap.add_argument("--delta", type=float, default=1e-3, help="relative change (default 1e-3)")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=600.0)
    ap.add_argument("--match", default="", help="only mutants whose key contains this")
    ap.add_argument("--rerun", type=Path, help="run again only the mutants that this earlier "
                    "--json output did not kill (the others count as killed in the summary)")
    ap.add_argument("--report", type=Path, help="only print the summary of this earlier --json "
                    "output (with the current list of equivalent mutants)")
    ap.add_argument("--list", action="store_true", help="list the mutants and stop")
    ap.add_argument("--json", type=Path, help="write the per-mutant results here")
    args = ap.parse_args(argv)
    if args.report:
        return report(args.report, args.delta)
    stages = [args.tests] if args.tests else STAGES
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(3))  # clean the temporary copies up

    everything = [m for f in FILES for m in find_mutants(f, args.delta)]
    stale = stale_keys(everything)
    if stale:
        print("these explained mutants no longer exist (the code changed; update the reasons):\n"
              + "\n".join(f"  {k}" for k in stale), file=sys.stderr)
        return 2
    mutants = [m for f in args.files for m in find_mutants(f, args.delta) if args.match in m.key]
    earlier: list[tuple[Mutant, str, str]] = []
    if args.rerun:
        before = {r["key"]: r for r in json.loads(args.rerun.read_text())}
        earlier = [(m, "killed", before[m.key]["pytest"]) for m in mutants
                   if before.get(m.key, {}).get("status") == "killed"]
        mutants = [m for m in mutants if before.get(m.key, {}).get("status") != "killed"]
    if args.list:
        for m in mutants:
            print(f"{m.path}:{m.line}:{m.col}  {m.key}  {m.literal} -> {m.replacement}")
        print(f"{len(mutants)} mutants")
        return 0

    with tempfile.TemporaryDirectory(prefix="tuibrdf-mutants-") as tmp:
        workers = []
        for j in range(max(1, args.jobs)):
            d = Path(tmp) / f"w{j}"
            make_copy(d)
            workers.append(d)
        start = time.perf_counter()
        code, summary = run_tests(workers[0], [t for s in stages for t in s], args.timeout)
        if code != 0:
            print(f"baseline fails ({summary}): fix the tests first", file=sys.stderr)
            return 2
        print(f"baseline passes ({summary}, {time.perf_counter() - start:.1f} s); "
              f"{len(mutants)} mutants, {len(workers)} workers", flush=True)

        free = list(workers)
        results: list[tuple[Mutant, str, str]] = []

        def run_one(m: Mutant):
            d = free.pop()
            try:
                target = d / m.path
                original = target.read_text()
                target.write_text(apply(original, m))
                try:
                    code, summary = run_stages(d, stages, args.timeout)
                finally:
                    target.write_text(original)
            finally:
                free.append(d)
            status = "killed" if code != 0 else (
                "equivalent" if m.key in EQUIVALENT else
                "threshold" if m.key in THRESHOLDS else "SURVIVED")
            return m, status, summary

        with ThreadPoolExecutor(max_workers=len(workers)) as pool:
            for i, (m, status, summary) in enumerate(pool.map(run_one, mutants), 1):
                results.append((m, status, summary))
                print(f"[{i:3d}/{len(mutants)}] {status:10s} {m.path}:{m.line}  "
                      f"{m.literal} -> {m.replacement}  ({m.key})", flush=True)
        elapsed = time.perf_counter() - start

    if earlier:
        print(f"(and {len(earlier)} mutants killed in {args.rerun})")
    results = earlier + results
    survived = summarize(results, f"delta {args.delta:g}, {elapsed:.0f} s")
    if args.json:
        args.json.write_text(json.dumps([
            {"key": m.key, "file": m.path, "line": m.line, "literal": m.literal,
             "mutant": m.replacement, "status": s, "pytest": out} for m, s, out in results],
            indent=1))
    return 1 if survived else 0


def summarize(results: list[tuple[Mutant, str, str]], note: str) -> list[Mutant]:
    """Print the equivalent and surviving mutants and the kill rate; return the survivors.
    A mutant that was not killed counts as equivalent if :data:`EQUIVALENT` explains it, as a
    threshold if :data:`THRESHOLDS` does."""
    killed = sum(s == "killed" for _, s, _ in results)
    equivalent = [(m, EQUIVALENT[m.key]) for m, s, _ in results
                  if s != "killed" and m.key in EQUIVALENT]
    thresholds = [(m, THRESHOLDS[m.key]) for m, s, _ in results
                  if s != "killed" and m.key in THRESHOLDS]
    survived = [m for m, s, _ in results
                if s != "killed" and m.key not in EQUIVALENT and m.key not in THRESHOLDS]
    print()
    for m, why in equivalent:
        print(f"equivalent: {m.key}: {why}")
    for m, why in thresholds:
        print(f"threshold:  {m.key}: {why}")
    for m in survived:
        print(f"SURVIVED:   {m.path}:{m.line}  {m.literal} -> {m.replacement}  ({m.key})")
    n = len(results)
    rest = n - len(equivalent) - len(thresholds)
    rate = killed / rest if rest else 1.0
    print(f"\n{n} mutants ({note}): {killed} killed, {len(equivalent)} equivalent, "
          f"{len(thresholds)} thresholds, {len(survived)} survived; kill rate "
          f"{100 * rate:.1f}% of the formula constants' mutants")
    return survived


def stale_keys(mutants: list[Mutant]) -> list[str]:
    """Keys of :data:`EQUIVALENT` and :data:`THRESHOLDS` that name no mutant of today's code
    (the code moved: a reason may now sit on another literal)."""
    keys = {m.key for m in mutants}
    return [k for k in (*EQUIVALENT, *THRESHOLDS) if k not in keys]


def report(path: Path, delta: float) -> int:
    """The summary of an earlier ``--json`` output, with today's :data:`EQUIVALENT`."""
    mutants = {m.key: m for f in FILES for m in find_mutants(f, delta)}
    records = json.loads(path.read_text())
    unknown = [r["key"] for r in records if r["key"] not in mutants]
    if unknown:
        print(f"{len(unknown)} mutants of {path} no longer exist (the code changed): run again",
              file=sys.stderr)
        return 2
    results = [(mutants[r["key"]], r["status"], r["pytest"]) for r in records]
    return 1 if summarize(results, f"from {path}") else 0


if __name__ == "__main__":
    sys.exit(main())
