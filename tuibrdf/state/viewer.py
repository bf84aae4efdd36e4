"""The viewer's state and every transition on it, as plain Python (no Textual).

The app is a thin layer: a key calls one method here (the key table, :mod:`tuibrdf.app.keys`),
which changes the state and returns ``None`` (or a note for the status line), or refuses and
returns a short message saying why.  Parameter values are validated by the side's
:class:`~tuibrdf.core.material.Material` (:meth:`Model.resolve`), so a key can never push a
value out of its range or break a declared constraint (``kd + ks ≤ 1``).

====================  =====================================================================
method                what it does
====================  =====================================================================
``step_theta``        θi by ± degrees, clamped to [0°, 90°]
``set_theta``         θi set to a value in [0°, 90°] (a value out of range is refused)
``type_theta``        θi typed as text (key t)
``no_params``         why the parameter keys cannot act (a model without parameters), or None
``select``            move the parameter cursor (wraps)
``step_param``        the selected parameter ± its step (or coarse step); a choice cycles
``reset_param``       the selected parameter back to its default
``type_value``        the selected parameter typed as text (Enter or =)
``cycle_model``       next / previous model of the active side (files shown come back), θi kept
``cycle_view``        the main view: :data:`MAIN_VIEWS` in order, either way
``toggle_log``        linear / log colour scale (in the slice view: the slice's own, log first)
``cycle_cmap``        next / previous colour map (:data:`~tuibrdf.render.CMAPS`)
``cycle_channel``     the curves of RGB models: all three → luminance → R → G → B
``toggle_cosine``     show f or f·cos θr
``toggle_compare``    one side ↔ two sides (B starts as a copy of A)
``switch_side``       which side the parameter keys act on (compare mode)
``apply_preset``      one of :data:`COMPARE_PRESETS` (the seed's comparisons)
``next_preset``       the next of them; after the last, the sides as they were before
``rotate``            azimuth / elevation of the 3D solid (solid view only)
``step_phi_i``        the light's azimuth φi (wraps; 180° by default)
``step_section``      the section azimuth ψ of the section through the peak (wraps)
``scale_exposure``    the lit views' exposure × a factor (keys: ×2, ÷2)
``step_gamma``        the lit views' display gamma
``step_fixed``        the half/difference view's fixed angle (θd, θh or φd)
``step_phi_d``        φd of the half/difference views
``toggle_sqrt_h``     √θh or linear θh axis of the slice
``move_probe``        the probe on the map (Lambert coordinates; shown from the first move)
``set_probe``         the probe at a point of the map (a click on the map or a section)
``toggle_probe``      probe on / off
``set_light``         θi and φi at once (a drag on the lit sphere or plane)
``zoom_by``           the 3D solid's and the sections' zoom × a factor (the mouse wheel)
====================  =====================================================================
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from tuibrdf.core.display import DISPLAY
from tuibrdf.core.material import Material
from tuibrdf.core.params import Model, Param, Value
from tuibrdf.core.registry import MODELS
from tuibrdf.render import CMAPS
from tuibrdf.state import sandbox

CHANNEL_NAMES = {"rgb": "R, G and B", "lum": "luminance (Rec.709)", "R": "red only",
                 "G": "green only", "B": "blue only", "all": "R, G and B of both sides"}

#: the main views ``v`` cycles through (the cross-sections are always shown beside them)
MAIN_VIEWS = ("map", "solid", "albedo", "sphere", "plane", "slice", "theta-h", "theta-d",
              "energy")
#: the mouse wheel's zoom of the 3D solid and the sections: smallest, largest
ZOOM_RANGE = (0.125, 64.0)
#: the half/difference views and the angle each one's ``d`` key steps
FIXED_ANGLE = {"theta-h": "theta_d", "theta-d": "theta_h", "slice": "phi_d"}
#: the probe's step on the map, in Lambert units (the disc's radius is √2)
PROBE_STEP = 0.05
SQRT2 = 2.0**0.5


@dataclass(frozen=True)
class ComparePreset:
    """Two (model, parameters) pairs compared at the same θi."""

    name: str
    title: str
    a: tuple[str, dict[str, Any]]
    b: tuple[str, dict[str, Any]]


#: The seed's "Exemples de comparaison entre modèles" (BRDF Viewer doc, section 8).
COMPARE_PRESETS = (
    ComparePreset("diffuse", "diffuse: Lambert vs Oren-Nayar",
                  ("lambert", {}), ("oren-nayar", {})),
    ComparePreset("specular", "specular: Phong vs Cook-Torrance",
                  ("phong", {"kd": 0.0, "ks": 0.08, "n": 70.0}),
                  ("cook-torrance", {"kd": 0.0, "f0": 0.04, "m": 0.07})),
)


@dataclass(frozen=True)
class Row:
    """One line of the parameter panel: a parameter, or one channel of an RGB parameter."""

    param: Param
    channel: int | None = None  # 0, 1, 2 for r, g, b

    @property
    def label(self) -> str:
        if self.channel is None:
            return self.param.symbol
        return f"{self.param.symbol}.{'rgb'[self.channel]}"


def panel_rows(model: Model) -> list[Row]:
    """The panel's rows, generated from the model's declarations (RGB → three rows)."""
    rows: list[Row] = []
    for p in model.params:
        if p.kind == "rgb":
            rows.extend(Row(p, c) for c in range(3))
        else:
            rows.append(Row(p))
    return rows


def _next_value(p: Param, old: float, direction: int, coarse: bool) -> float:
    """One step from ``old``: ± the declared step, or for a :attr:`Param.relative` parameter
    × / ÷ 1.1 (coarse: 2), rounded to 3 significant digits, so every decade takes the same
    number of presses (α 0.01 → 0.011, n 20 → 1000 in six coarse presses)."""
    if not p.relative:
        return _round(old + direction * (p.coarse_step if coarse else p.step))
    factor = 2.0 if coarse else 1.1
    if direction > 0:
        # from 0 (phong n = 0) a factor cannot move: the absolute step starts it
        new = old * factor if old > 0 else p.step
        new = float(f"{new:.3g}")
        return new if new > old else _round(old + p.step)
    new = float(f"{old / factor:.3g}")
    return p.min if new < max(p.min, p.step / 2) and p.min == 0 else new


def parse_number(text: str) -> float:
    """A number typed by the user: ``0.05``, ``5e-2``, ``1,5`` (a decimal comma); raises
    ``ValueError`` with a short reason."""
    t = text.strip().replace(",", ".").rstrip("°")
    try:
        return float(t)
    except ValueError:
        raise ValueError(f"{text.strip()!r} is not a number") from None


def _round(v: float) -> float:
    """Forget the float noise of repeated steps (0.2 + 0.01 = 0.21000000000000002)."""
    return float(round(v, 10))


class Side:
    """One side of the viewer: a :class:`~tuibrdf.core.material.Material` (immutable,
    validated) and the panel cursor, the only thing about a side that changes in place."""

    def __init__(self, model: str | Material, values: dict[str, Any] | None = None,
                 selected: int = 0) -> None:
        if not isinstance(model, Material):
            sandbox.check_name(model)  # before the file is read (a .py runs when read)
            model = Material(model, values)
        sandbox.check_material(model)  # served (tuibrdf serve): only the files it allows
        self.material = model
        if selected == 0:  # start on a row keys can step (not a data file's path)
            selected = next((i for i, r in enumerate(self.rows()) if r.param.kind != "path"),
                            0)
        self.selected = selected

    @classmethod
    def of(cls, model: str, params: dict[str, Any] | None = None) -> Side:
        return cls(model, params)

    @property
    def model(self) -> str:
        return self.material.name

    @property
    def values(self) -> dict[str, Value]:
        return self.material.values

    @property
    def spec(self) -> Model:
        return self.material.model

    def rows(self) -> list[Row]:
        return panel_rows(self.spec)

    def copy(self) -> Side:
        return Side(self.material, selected=self.selected)


def usable(model: Model, values: dict[str, Value] | None = None) -> bool:
    """A model the viewer can cycle to: every path parameter (a MERL file) has a value."""
    vals = values if values is not None else model.defaults()
    return all(vals.get(p.name) not in ("", None) for p in model.params if p.kind == "path")


@dataclass
class ViewerState:
    """Everything the viewer shows, with pure transitions (no Textual, no I/O)."""

    sides: list[Side] = field(default_factory=lambda: [Side.of("lambert")])
    active: int = 0
    theta_i: float = DISPLAY.theta_i.default
    view: str = "map"
    log: bool = False
    cmap: str = DISPLAY.cmap
    cosine: bool = False
    azimuth: float = DISPLAY.azimuth.default
    elevation: float = DISPLAY.elevation.default
    preset: str = ""  # name of the compare preset last applied, if any
    #: the sides (and active side) before the first preset: ``p`` past the last preset
    #: returns to them, so a preset never throws tuned values away
    before_preset: tuple[list[Side], int] | None = None
    #: the curves of an RGB model (sections, albedo curve): all three, luminance or one
    channel: str = "rgb"
    #: models read from files (absolute paths) the session has shown: ``m`` cycles back
    files: list[str] = field(default_factory=list)
    section_azimuth: float = DISPLAY.section_azimuth.default  # ψ of the section through the peak
    phi_i: float = DISPLAY.phi_i.default  # the light's azimuth (180°: on the left of the map)
    exposure: float = DISPLAY.exposure.default  # lit sphere / plane
    gamma: float = DISPLAY.gamma.default
    theta_d: float = DISPLAY.theta_d.default  # half/difference views: the fixed angles
    theta_h: float = DISPLAY.theta_h.default
    phi_d: float = DISPLAY.phi_d.default
    sqrt_h: bool = DISPLAY.sqrt_h
    #: the θh×θd slice's scale: log by default (in linear, Cook-Torrance's slice is black but
    #: for the grazing blow-up: its specular strip at θh ≈ 0 cannot be seen)
    slice_log: bool = True
    #: the probe's Lambert coordinates on the map (None: hidden)
    probe: tuple[float, float] | None = None
    #: the 3D solid's and the sections' magnification (the mouse wheel; 1: the peak fills it)
    zoom: float = 1.0
    #: values last used for each model, so cycling away and back keeps them
    memory: dict[str, dict[str, Value]] = field(default_factory=dict)

    # -- reading -------------------------------------------------------------------------
    @property
    def compare(self) -> bool:
        return len(self.sides) == 2

    @property
    def side(self) -> Side:
        return self.sides[self.active]

    @property
    def row(self) -> Row:
        rows = self.side.rows()
        return rows[min(self.side.selected, len(rows) - 1)]

    def row_value(self, row: Row, side: Side | None = None) -> Value:
        v = (side or self.side).values[row.param.name]
        return v[row.channel] if row.channel is not None else v

    # -- θi ---------------------------------------------------------------------------------
    def step_theta(self, delta: float) -> str | None:
        new = DISPLAY.theta_i.clamp(_round(self.theta_i + delta))
        if new == self.theta_i:
            edge = "90° (grazing)" if delta > 0 else "0° (normal incidence)"
            return f"θi is already {edge}; range {DISPLAY.theta_i.range_text()}"
        self.theta_i = new
        return None

    def set_theta(self, deg: float) -> str | None:
        if not DISPLAY.theta_i.accepts(deg):  # also refuses NaN
            return f"θi = {deg:g}° is out of range {DISPLAY.theta_i.range_text()}"
        self.theta_i = float(deg)
        return None

    # -- parameters -------------------------------------------------------------------------
    def no_params(self) -> str | None:
        """Why the parameter keys cannot act on the active side (a model without parameters:
        a ``.bsdf`` file, a ``.brdf`` with an empty parameter block), else None."""
        if self.side.rows():
            return None
        return f"{self.side.spec.title} has no parameters to select, step or type"

    def select(self, delta: int) -> str | None:
        if (why := self.no_params()) is not None:
            return why
        n = len(self.side.rows())
        self.side.selected = (self.side.selected + delta) % n
        return None

    def _commit(self, name: str, value: Value) -> str | None:
        """Validate the side's values with ``name = value``; apply them or return why not."""
        side = self.side
        try:
            new = side.material.with_values(**{name: value})
            sandbox.check_material(new)  # a typed file path (served: only allowed files)
            side.material = new
        except ValueError as e:
            return str(e)
        self.memory[side.model] = side.values
        return None

    def step_param(self, direction: int, coarse: bool = False) -> str | None:
        """The selected parameter by ± one step; a choice cycles.  At a bound the value is
        clamped to it; already there, or against a constraint, the key is refused."""
        if (why := self.no_params()) is not None:
            return why
        row = self.row
        p = row.param
        if p.kind == "path":
            return f"{p.name} is a file: set it on the command line (-p {p.name}=PATH)"
        if p.kind == "choice":
            i = p.choices.index(self.side.values[p.name])
            return self._commit(p.name, p.choices[(i + direction) % len(p.choices)])
        old = float(self.row_value(row))
        new = min(p.max, max(p.min, _next_value(p, old, direction, coarse)))
        if new == old:
            return f"{row.label} is already at its {'maximum' if direction > 0 else 'minimum'}" \
                   f" ({p.range_text()})"
        return self._commit(p.name, self._with_channel(row, new))

    def _with_channel(self, row: Row, new: float) -> Value:
        if row.channel is None:
            return new
        rgb = list(self.side.values[row.param.name])
        rgb[row.channel] = new
        return tuple(rgb)

    def reset_param(self) -> str | None:
        if (why := self.no_params()) is not None:
            return why
        row = self.row
        default = row.param.default
        if row.channel is not None:
            return self._commit(row.param.name, self._with_channel(row, default[row.channel]))
        return self._commit(row.param.name, default)

    def type_value(self, text: str) -> str | None:
        """A value typed for the selected row (Enter or = opens the input): a number checked
        against the declared range, a choice (name or alias), or a file path."""
        if (why := self.no_params()) is not None:
            return why
        row = self.row
        p = row.param
        if p.kind == "choice":
            canonical = p.choice(text.strip())
            if canonical is None:
                return p.unknown_choice(text.strip(), self.side.model)
            return self._commit(p.name, canonical)
        if p.kind == "path":
            return self._commit(p.name, text.strip())
        try:
            v = parse_number(text)
        except ValueError as e:
            return f"{row.label}: {e}; expected {p.range_text()}"
        if not (v == v and p.min <= v <= p.max):  # v == v refuses NaN
            return f"{row.label} = {v:g} is out of range: expected {p.range_text()}"
        return self._commit(p.name, self._with_channel(row, v))

    def type_theta(self, text: str) -> str | None:
        """θi typed (key t), degrees."""
        try:
            return self.set_theta(parse_number(text))
        except ValueError as e:
            return f"θi: {e}; expected {DISPLAY.theta_i.range_text()}"

    # -- models, views, toggles ----------------------------------------------------------------
    def model_after(self, delta: int) -> str:
        """The model :meth:`cycle_model` ``(delta)`` goes to (nothing changes)."""
        files = self.files + ([self.side.model] if self.side.model not in MODELS
                              and self.side.model not in self.files else [])
        names = [n for n, m in MODELS.items() if usable(m, self.memory.get(n))] + files
        if self.side.model in names:
            i = names.index(self.side.model)
        else:
            i = -1 if delta > 0 else 0
        return names[(i + delta) % len(names)]

    def cycle_model(self, delta: int) -> str | None:
        """Next / previous registered model on the active side; θi and the view stay."""
        name = self.model_after(delta)
        if self.side.model not in MODELS and self.side.model not in self.files:
            self.files.append(self.side.model)  # a model file: m comes back to it
        self.memory[self.side.model] = self.side.values
        try:
            self.sides[self.active] = Side(name, self.memory.get(name))
        except ValueError as e:  # a model file edited or removed meanwhile (or values refused)
            if name in self.files:
                self.files.remove(name)
            return f"cannot read {name}: {e}"
        self.preset = ""
        return None

    def cycle_view(self, delta: int = 1) -> str | None:
        self.view = MAIN_VIEWS[(MAIN_VIEWS.index(self.view) + delta) % len(MAIN_VIEWS)]
        return None

    def toggle_log(self) -> str | None:
        if self.view == "slice":  # the slice has its own scale: log unless asked otherwise
            self.slice_log = not self.slice_log
            return None
        self.log = not self.log
        return None

    def cycle_cmap(self, delta: int = 1) -> str | None:
        i = CMAPS.index(self.cmap) if self.cmap in CMAPS else -1
        self.cmap = CMAPS[(i + delta) % len(CMAPS)]
        return None

    def cycle_channel(self) -> str | None:
        """The curves of RGB models: R, G, B → luminance → R → G → B → all three.  In compare
        mode "rgb" shows each side's luminance (render.curves.side_curves), so the cycle is
        luminance → R → G → B → all three channels of both sides ("all")."""
        order = ("rgb", "R", "G", "B", "all") if self.compare else ("rgb", "lum", "R", "G", "B")
        cur = self.channel if self.channel in order else "rgb"
        self.channel = order[(order.index(cur) + 1) % len(order)]
        names = dict(CHANNEL_NAMES, rgb="luminance (Rec.709)") if self.compare else CHANNEL_NAMES
        if not any(x.spec.rgb for x in self.sides):
            return f"curves of RGB models: {names[self.channel]} (no RGB model shown)"
        return f"curves of RGB models: {names[self.channel]}"

    def toggle_cosine(self) -> str | None:
        self.cosine = not self.cosine
        return None

    def toggle_compare(self) -> str | None:
        if self.compare:
            self.sides = [self.side]
            self.active = 0
            self.preset = ""
        else:
            self.sides = [self.side, self.side.copy()]
            self.active = 1
        return None

    def switch_side(self) -> str | None:
        if not self.compare:
            return "tab switches sides in compare mode (press c)"
        self.active = 1 - self.active
        return None

    def apply_preset(self, name: str) -> str | None:
        """Load a seed comparison: both sides, compare mode on, θi kept."""
        preset = next((p for p in COMPARE_PRESETS if p.name == name), None)
        if preset is None:
            return f"unknown preset {name!r}"
        try:
            sides = [Side.of(m, params) for m, params in (preset.a, preset.b)]
        except ValueError as e:
            return f"preset {name}: {e}"
        if not self.preset:  # the user's own sides: kept for the way back
            for side in self.sides:
                self.memory[side.model] = side.values
            self.before_preset = ([x.copy() for x in self.sides], self.active)
        self.sides, self.active, self.preset = sides, 0, name
        return None

    def next_preset(self) -> str | None:
        """The next seed comparison; after the last one, the sides as they were before the
        first (tuned values kept)."""
        names = [p.name for p in COMPARE_PRESETS]
        i = names.index(self.preset) if self.preset in names else -1
        if i == len(names) - 1 and self.before_preset is not None:
            self.sides, self.active = self.before_preset
            self.before_preset, self.preset = None, ""
            return "back to your own settings (before the presets)"
        return self.apply_preset(names[(i + 1) % len(names)])

    def rotate(self, d_azimuth: float, d_elevation: float) -> str | None:
        if self.view != "solid":
            return ", . e E (or ctrl+arrows) rotate the 3D solid (press v for that view)"
        self.azimuth = (self.azimuth + d_azimuth + 180.0) % 360.0 - 180.0
        el = DISPLAY.elevation.clamp(self.elevation + d_elevation)
        if d_elevation and el == self.elevation:
            return f"elevation is already {el:g}° (range {DISPLAY.elevation.range_text()})"
        self.elevation = el
        return None

    def step_phi_i(self, delta: float) -> str | None:
        """φi by ± degrees, wrapped into [0°, 360°)."""
        self.phi_i = _round((self.phi_i + delta) % 360.0)
        return None

    # -- the views of the peak section, the lit and the half/difference views -----------------
    def step_section(self, delta: float) -> str | None:
        """ψ of the section through the peak, wrapped into (−180°, 180°]."""
        a = (self.section_azimuth + delta) % 360.0
        self.section_azimuth = a - 360.0 if a > 180.0 else a
        return None

    def scale_exposure(self, factor: float) -> str | None:
        new = DISPLAY.exposure.clamp(self.exposure * factor)
        if new == self.exposure:
            return f"exposure is already {new:g} (range {DISPLAY.exposure.range_text()})"
        self.exposure = new
        return None

    def step_gamma(self, delta: float) -> str | None:
        new = DISPLAY.gamma.clamp(_round(self.gamma + delta))
        if new == self.gamma:
            return f"gamma is already {new:g} (range {DISPLAY.gamma.range_text()})"
        self.gamma = new
        return None

    def step_fixed(self, delta: float) -> str | None:
        """The fixed angle of the half/difference view shown: θd (f(θh)), θh (f(θd)) or φd
        (slice); θd, θh in [0°, 90°], φd in [0°, 180°]."""
        name = FIXED_ANGLE.get(self.view)
        if name is None:
            return "d/D step the fixed angle of the slice, θh and θd views (press v)"
        if name == "phi_d":
            return self.step_phi_d(delta)
        old = getattr(self, name)
        setting = getattr(DISPLAY, name)
        new = setting.clamp(_round(old + delta))
        if new == old:
            return (f"{'θd' if name == 'theta_d' else 'θh'} is already {new:g}° "
                    f"(range {setting.range_text()})")
        setattr(self, name, new)
        return None

    def step_phi_d(self, delta: float) -> str | None:
        new = DISPLAY.phi_d.clamp(_round(self.phi_d + delta))
        if new == self.phi_d:
            return f"φd is already {new:g}° (range {DISPLAY.phi_d.range_text()})"
        self.phi_d = new
        return None

    def toggle_sqrt_h(self) -> str | None:
        self.sqrt_h = not self.sqrt_h
        return None

    def move_probe(self, du: float, dv: float) -> str | None:
        """Move the probe by ``(du, dv)`` probe steps on the map, kept inside the disc
        (r ≤ √2); it appears at the centre (the normal) on the first move."""
        if self.view != "map":
            return "the probe reads the map (press v for that view)"
        if self.probe is None:
            self.probe = (0.0, 0.0)
            return None
        u = self.probe[0] + du * PROBE_STEP
        v = self.probe[1] + dv * PROBE_STEP
        r = (u * u + v * v) ** 0.5
        if r > SQRT2:  # r > √2 > 0: back onto the horizon
            u, v = u * SQRT2 / r, v * SQRT2 / r
        self.probe = (_round(u), _round(v))
        return None

    def set_probe(self, u: float, v: float) -> str | None:
        """The probe at Lambert point ``(u, v)`` (a click), clamped onto the disc."""
        r = (u * u + v * v) ** 0.5
        if not r <= SQRT2 + 1e-9:  # also refuses NaN
            return "that point is outside the hemisphere"
        self.probe = (float(u), float(v))
        return None

    def set_light(self, theta_deg: float, phi_deg: float) -> str | None:
        """θi and φi at once (a drag on the lit sphere or plane): θi clamped to its range,
        φi wrapped into [0°, 360°), both to 0.1° (a drag is not finer than that)."""
        if not (theta_deg == theta_deg and phi_deg == phi_deg):  # refuses NaN
            return "no light direction there"
        self.theta_i = DISPLAY.theta_i.clamp(round(float(theta_deg), 1))
        self.phi_i = round(float(phi_deg), 1) % 360.0
        return None

    def zoom_by(self, factor: float) -> str | None:
        """The solid's and the sections' zoom × ``factor``, kept in [1/8, 64]."""
        new = min(ZOOM_RANGE[1], max(ZOOM_RANGE[0], self.zoom * factor))
        if new == self.zoom:
            return f"zoom is already ×{new:g} (range ×{ZOOM_RANGE[0]:g} to ×{ZOOM_RANGE[1]:g})"
        self.zoom = new
        return None

    def toggle_probe(self) -> str | None:
        self.probe = None if self.probe is not None else (0.0, 0.0)
        return None

    # -- text ---------------------------------------------------------------------------------
    def describe(self, side: Side | None = None) -> str:
        """``phong kd=0.2 ks=0.5 n=20`` — for titles and messages."""
        return (side or self.side).material.describe()
