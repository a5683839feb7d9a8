"""Platform, sea-state and run configuration: YAML validated into typed dataclasses.

Every reader names the offending field in its error (``ConfigError``), e.g.
``windmoor12.yaml: members[2].diameter_m: must be a positive number, got -1``. A sea state's
and a run's fields are settings (``fowt_hydro_sim.settings``): their defaults, meanings and
ranges are written here once, and the command line and the ROS node derive their options
and parameters from them.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from fowt_hydro_sim.errors import ConfigError, InputError
from fowt_hydro_sim.settings import REQUIRED, SettingError, check, described, like, setting, validate

DRAG_MODELS = ("constant", "filtered")
# the mooring's models: linear springs, MoorPy's quasi-static catenary, MoorDyn's lumped-mass lines
MOORING_MODELS = ("spring", "linear", "moorpy", "moordyn")
LINE_FILE_MODELS = ("moorpy", "moordyn")  # the models that read a MoorDyn input file
SPECTRA = ("jonswap", "pierson_moskowitz")
DEFAULT_PLATFORM = "windmoor12"
FILTER_KINDS = ("lowpass", "highpass", "bandpass", "allpass")
SECTIONS = ("circular", "rectangular")
WETTED_LENGTHS = ("displaced", "undisplaced")
LOAD_DIRECTIONS = ("rotating", "fixed")
HYDROSTATICS = ("linear", "nonlinear", "free_surface")
KINEMATICS = ("undisplaced", "displaced")
STRETCHING = ("none", "vertical", "extrapolation", "wheeler")
WAVE_KINEMATICS = ("exact", "grid")
SLOW_DRIFTS = ("newman", "none")
RADIATION_MODELS = ("convolution", "state_space", "none")


class SampleError(InputError):
    """An input sample or message the simulator refuses (the message says why); the caller
    logs it and keeps the last good input."""


# --------------------------------------------------------------------------- dataclasses
@dataclass(frozen=True)
class Environment:
    water_density_kg_m3: float = 1025.0
    gravity_m_s2: float = 9.80665
    water_depth_m: float = 150.0


@dataclass(frozen=True)
class MassProperties:
    mass_kg: float
    cog_m: tuple[float, float, float]
    inertia_about_cog_kg_m2: tuple[tuple[float, ...], ...]  # 3x3, body axes


@dataclass(frozen=True)
class DragCoefficients:
    """Drag coefficients of one transverse direction.

    ``constant`` is the one Cd over all frequencies (the ``constant`` drag model, and the
    ``filtered`` model's Cd of a direction without bands). ``bands`` holds one Cd per drag
    band of the platform (``Platform.drag_bands`` order) for a direction the ``filtered``
    model splits into bands; None keeps the direction unfiltered.
    """

    constant: float
    bands: tuple[float, ...] | None = None


@dataclass(frozen=True)
class DragBand:
    """A frequency band of the ``filtered`` drag model: an analog Butterworth filter on the
    transverse relative velocity (seed paper, eqs. 3-5).

    lowpass / highpass: ``order`` and ``cutoff_hz`` (|H| = 1/sqrt 2 there); bandpass: the
    paper's (w_c/Q) s / (s^2 + (w_c/Q) s + w_c^2) with w_c = 2 pi ``centre_hz`` and ``q``;
    allpass: H = 1.
    """

    name: str
    kind: str
    order: int = 1
    cutoff_hz: float | None = None
    centre_hz: float | None = None
    q: float | None = None


@dataclass(frozen=True)
class Zone:
    """Transverse coefficients for strips whose undisplaced centre is below ``below_z_m``.

    Direction 1 is the section's width direction (horizontal for a horizontal member
    without spin), direction 2 its height direction; a circular section has the same values
    in both. ``cp`` scales the Froude-Krylov (dynamic pressure) part of the fluid inertia,
    HydroDyn's Cp.
    """

    name: str
    below_z_m: float
    ca: tuple[float, float]
    cd: tuple[DragCoefficients, DragCoefficients]
    cp: float = 1.0


@dataclass(frozen=True)
class EndPlate:
    """Axial end terms (HydroDyn's): pressure on the end area, added mass on a hemisphere.
    ``joint_area_m2`` and ``joint_volume_m3`` (body axes, outward), when given, replace the
    end's own area (pi r^2 along its outward normal) and hemisphere (2 pi r^3 / 3): HydroDyn's
    joint end effects act on the sums of these vectors over the members meeting at the joint
    (its An and Vn), the drag and pressure on An, the added mass on Vn."""

    ca: float
    cp: float
    cd: float
    joint_area_m2: tuple[float, float, float] | None = None
    joint_volume_m3: tuple[float, float, float] | None = None


@dataclass(frozen=True)
class Member:
    """A straight member. Its section's width lies along direction d1 (horizontal for a
    non-vertical member, x for a vertical one), its height along d2 = axis x d1; a rectangular
    section may be turned about the axis by ``spin_deg`` (from d1 toward d2, HydroDyn's
    MSpinOrient), and a member may taper linearly from its end-a size to its end-b size."""

    name: str
    section: str
    end_a_m: tuple[float, float, float]
    end_b_m: tuple[float, float, float]
    width_m: float  # diameter for a circular section; at end a of a tapered member (HydroDyn's side A)
    height_m: float  # diameter for a circular section; at end a of a tapered member (HydroDyn's side B)
    strip_length_m: float
    zones: tuple[Zone, ...]
    end_a_plate: EndPlate | None = None
    end_b_plate: EndPlate | None = None
    diameter_b_m: float | None = None  # circular only: the diameter at end b of a tapered member
    taper_axial: EndPlate = EndPlate(ca=0.0, cp=1.0, cd=0.0)  # HydroDyn's member AxCa, AxCp, AxCd
    width_b_m: float | None = None  # rectangular only: the width at end b of a tapered member
    height_b_m: float | None = None  # rectangular only: the height at end b of a tapered member
    spin_deg: float = 0.0  # rectangular only: the section turned about the axis (MSpinOrient)
    drag_only: bool = False  # HydroDyn's PropPot: drag only, the hull's potential flow has the rest
    maccamy_fuchs: bool = False  # HydroDyn's Cp MCF: transverse inertia on the MacCamy-Fuchs acceleration
    growth_zone: Zone | None = None  # circular only: the coefficients where it carries marine growth (HydroDyn's MG)
    # circular only: free_surface hydrostatics wet each element section by section below the surface
    # plane at its midpoint (HydroDyn's MHstLMod 2); false: cut where the axis crosses the surface (MHstLMod 1)
    hydrostatics_by_section: bool = False
    wall_thickness_m: float = 0.0  # circular only: the wall's thickness at end a (HydroDyn's PropThck; fill_groups)
    wall_thickness_b_m: float | None = None  # circular only: at end b, where it differs from end a's

    def inner_radius_at(self, fraction: float) -> float:
        """Inner radius (circular: the diameter's half less the wall) at ``fraction`` of the way
        from end a to end b, linear between the ends as HydroDyn's Rin."""
        end_b = self.wall_thickness_m if self.wall_thickness_b_m is None else self.wall_thickness_b_m
        return self.diameter_at(fraction) / 2 - (self.wall_thickness_m + fraction * (end_b - self.wall_thickness_m))

    @property
    def tapered(self) -> bool:
        if self.section == "circular":
            return self.diameter_b_m is not None and self.diameter_b_m != self.width_m
        return self.sides_at(1.0) != (self.width_m, self.height_m)

    def diameter_at(self, fraction: float) -> float:
        """Diameter (circular) at ``fraction`` of the way from end a to end b: linear taper."""
        end_b = self.width_m if self.diameter_b_m is None else self.diameter_b_m
        return self.width_m + fraction * (end_b - self.width_m)

    def sides_at(self, fraction: float) -> tuple[float, float]:
        """Width and height at ``fraction`` of the way from end a to end b (linear taper; a
        circle's are its diameter)."""
        if self.section == "circular":
            d = self.diameter_at(fraction)
            return d, d
        width_b = self.width_m if self.width_b_m is None else self.width_b_m
        height_b = self.height_m if self.height_b_m is None else self.height_b_m
        return (self.width_m + fraction * (width_b - self.width_m),
                self.height_m + fraction * (height_b - self.height_m))


@dataclass(frozen=True)
class MooringLine:
    fairlead_m: tuple[float, float, float]  # body frame
    anchor_m: tuple[float, float, float]  # world frame


@dataclass(frozen=True)
class Mooring:
    """The platform's mooring: ``model`` says which lines the model uses (``MOORING_MODELS``).
    ``spring``: the linear springs of the fields below; ``linear``: the platform's
    ``linear_mooring`` (a wrench at rest and a 6x6 stiffness); ``moorpy`` and ``moordyn``: the lines
    of the MoorDyn input file ``file`` (an absolute path; relative to the platform YAML in
    the YAML), its fairleads and anchors included. A platform may give both, so that a run
    can choose (``RunConfig.mooring``). ``moordyn_dt_s``: MoorDyn's internal time step for
    the ``moordyn`` model, in place of the file's dtM (None: the file's)."""

    stiffness_n_m: float = 0.0
    pretension_n: float = 0.0
    unstretched_length_m: float = 0.0
    lines: tuple[MooringLine, ...] = ()
    model: str = "spring"
    file: str | None = None
    moordyn_dt_s: float | None = None

    def chosen(self, model: str) -> Mooring:
        """This mooring with ``model`` in use ("" or None: as it is), or ConfigError if the
        platform does not define that model's lines."""
        model = model or self.model
        if model not in MOORING_MODELS:
            raise ConfigError(f"mooring {model!r}: must be one of {', '.join(MOORING_MODELS)}")
        if model == "spring" and not self.lines:
            raise ConfigError("mooring spring: the platform has no spring lines (mooring.lines)")
        if model in LINE_FILE_MODELS and self.file is None:
            raise ConfigError(f"mooring {model}: the platform has no MoorDyn input file (mooring.file)")
        return replace(self, model=model)


@dataclass(frozen=True)
class PotentialFlow:
    """A hull's potential-flow hydrodynamics from WAMIT files, as HydroDyn's PotMod 1 takes them
    (one body, its WAMIT origin at the platform's reference point, z up)."""

    wamit_root: str  # the WAMIT files' common path without extension (.1, .3, .hst); absolute once read
    wamit_length_m: float  # WAMITULEN: the length WAMIT's dimensionless output is scaled with [m]
    displaced_volume_m3: float  # PtfmVol0: the volume displaced at rest [m^3]
    centre_of_buoyancy_xy_m: tuple[float, float]  # PtfmCOBxt, PtfmCOByt [m]
    # the memory effect: convolution of the retardation kernel (RdtnMod 1), the .ss file's state-space
    # form (RdtnMod 2), or none
    radiation: str = "convolution"
    radiation_tmax_s: float = 60.0  # RdtnTMax: the kernel's length [s]
    added_force_n: tuple[float, ...] = (0.0,) * 6  # AddF0 [N, N m]
    added_stiffness: tuple[tuple[float, ...], ...] = ((0.0,) * 6,) * 6  # AddCLin [N/m, N/rad, N m/m, N m/rad]
    added_linear_damping: tuple[tuple[float, ...], ...] = ((0.0,) * 6,) * 6  # AddBLin [N s/m, ... N m s/rad]
    added_quadratic_damping: tuple[tuple[float, ...], ...] = ((0.0,) * 6,) * 6  # AddBQuad [N s^2/m^2, ...]
    # the filtered drag model's AddBQuad: one 6x6 per drag band (Platform.drag_bands order) on the
    # band-filtered velocity [N s^2/m^2, ...]; () keeps the plain AddBQuad in every drag model
    added_quadratic_damping_bands: tuple[tuple[tuple[float, ...], ...], ...] = ()


@dataclass(frozen=True)
class LinearMooring:
    """A mooring as a constant wrench at rest and a 6x6 stiffness about the reference point:
    F = force_at_rest - stiffness q (world axes, small motions)."""

    force_at_rest_n: tuple[float, ...]  # [N, N m]
    stiffness: tuple[tuple[float, ...], ...]  # [N/m, N/rad, N m/m, N m/rad]
    source: str = ""  # where the numbers come from


@dataclass(frozen=True)
class MarineGrowthLevel:
    """One row of a marine-growth table (HydroDyn's MGDepths): at height ``z_m`` (relative to
    the still water level, negative below it) the growth is ``thickness_m`` thick and
    ``density_kg_m3`` dense; linear in z between rows, none outside them
    (physics/marine_growth.py)."""

    z_m: float
    thickness_m: float
    density_kg_m3: float


@dataclass(frozen=True)
class FillGroup:
    """Flooded (filled) members (HydroDyn's fill group: FillMList, FillFSLoc, FillDens): the
    circular ``members`` hold fluid of ``density_kg_m3`` inside their walls up to the height
    ``free_surface_z_m`` (relative to the still water level), or to their top if it is
    higher (physics/fill.py)."""

    members: tuple[str, ...]
    free_surface_z_m: float
    density_kg_m3: float


@dataclass(frozen=True)
class Platform:
    """A floating platform: environment, mass properties, Morison members and mooring
    (``load_platform`` reads one from a YAML file or the packaged platforms)."""

    name: str
    environment: Environment
    mass: MassProperties
    hub_point_m: tuple[float, float, float]
    members: tuple[Member, ...]
    mooring: Mooring
    description: str = ""
    drag_bands: tuple[DragBand, ...] = ()  # the ``filtered`` drag model's bands
    # head-sea mean surge drift per unit amplitude squared, (w [rad/s], D [N/m^2]) ascending in w
    drift_coefficients_n_m2: tuple[tuple[float, float], ...] = ()
    potential_flow: PotentialFlow | None = None  # a WAMIT hull (HydroDyn's PotMod 1)
    linear_mooring: LinearMooring | None = None  # a mooring given as a 6x6 stiffness
    marine_growth: tuple[MarineGrowthLevel, ...] = ()  # by height, highest first (physics/marine_growth.py)
    fill_groups: tuple[FillGroup, ...] = ()  # flooded members (physics/fill.py)


@dataclass(frozen=True)
class SeaState:
    """An irregular long-crested sea. Frequencies outside [f_min_hz, f_max_hz] are left out
    (defaults: 0.5 and 5 times the peak frequency). The synthesised record repeats every
    ``repeat_period_s`` (None: the run's duration, at least 3600 s)."""

    hs_m: float = setting(REQUIRED, "significant wave height [m]", ge=0.0, le=30.0)
    tp_s: float = setting(REQUIRED, "peak period [s]", gt=0.0)
    gamma: float = setting(1.0, "JONSWAP peak enhancement factor", gt=0.0)
    spectrum: str = setting("jonswap", "wave spectrum", choices=SPECTRA)
    heading_deg: float = setting(0.0, "wave direction [deg], 0 = toward +x")
    seed: int = setting(1, "random phase seed", ge=0)
    f_min_hz: float | None = setting(None, "lowest wave frequency [Hz] (default half the peak frequency)", gt=0.0)
    f_max_hz: float | None = setting(None, "highest wave frequency [Hz] (default 5 times the peak frequency)",
                                     gt=0.0)
    repeat_period_s: float | None = setting(None, "repeat period of the synthesised sea [s] (default the run's "
                                                  "duration, at least 3600 s)", gt=0.0)

    def __post_init__(self) -> None:
        _validate(self, "sea state")

    @property
    def peak_frequency_hz(self) -> float:
        return 1.0 / self.tp_s

    @property
    def band_hz(self) -> tuple[float, float]:
        fp = self.peak_frequency_hz
        return (self.f_min_hz or 0.5 * fp, self.f_max_hz or 5.0 * fp)


@dataclass(frozen=True, kw_only=True)  # by name: the options grow
class HydroOptions:
    """How the strip model treats a moving body: choices HydroDyn makes one way and the model
    made another, silently, until this was explicit. Fluid kinematics are taken at the
    undisplaced strip points (HydroDyn's WaveDisp 0) except for a prescribed motion with
    ``kinematics="displaced"`` (``PlatformModel.prescribed_motion_loads``). The defaults are
    HydroDyn's kinematic choices plus the slow drift from the platform's BEM drift table (the
    README's evidence: the displaced wetted length and rotating directions give a body-motion
    second-order force without the rest of the second-order force, several times a BEM's slow
    drift); ``HYDRODYN`` is HydroDyn v5's (WaveDisp 0, WaveStMod 0, member hydrostatics, no drift)."""

    wetted_length: str = setting(
        "undisplaced", "wetted length of each strip: the part of its displaced length below z = 0 (heave, roll "
                     "and pitch change it; adds motion-induced second-order loads) or of its undisplaced length "
                     "(HydroDyn's WaveDisp 0, no stretching)", choices=WETTED_LENGTHS)
    load_directions: str = setting(
        "fixed", "strip load directions (member axes, section axes): rotating with the body or fixed at "
                    "the undisplaced ones (HydroDyn's projection on the undisplaced member axes)",
        choices=LOAD_DIRECTIONS)
    hydrostatics: str = setting(
        "nonlinear", "hydrostatics: linear about the undisplaced position (W0 - C q, WAMIT's C) or nonlinear, "
                  "rho g times the displaced members' exact submerged volume through its centroid (HydroDyn's "
                  "member hydrostatics, MHstLMod 1), or free_surface, the still-water pressure -rho g z over "
                  "the displaced member surfaces up to the instantaneous free surface (a plane per element; "
                  "HydroDyn's MHstLMod 2 with wave stretching for rectangular members and for circular ones "
                  "flagged hydrostatics_by_section, MHstLMod 1 with wave stretching for the other "
                  "circular ones; prescribed motion only: fowt-sim loads)", choices=HYDROSTATICS)
    kinematics: str = setting(
        "undisplaced", "where the fluid kinematics are taken: at the undisplaced strip points (HydroDyn's "
                       "WaveDisp 0) or at their displaced positions (WaveDisp 1: their depth displaced only "
                       "with stretching, as HydroDyn; prescribed motion only: fowt-sim loads)", choices=KINEMATICS)
    stretching: str = setting(
        "none", "wave stretching of the Morison loads: none (strips wetted up to z = 0, HydroDyn's WaveStMod 0) "
                "or vertical (each strip and end plate wetted up to the instantaneous elevation eta at its x, "
                "y, kinematics above z = 0 those at z = 0: WaveStMod 1) or extrapolation (wetted up to eta, "
                "the kinematics above z = 0 those at z = 0 plus z times their vertical gradient there: WaveStMod "
                "2) or wheeler (wetted up to eta, the kinematics at z taken at z' = d (z - eta) / (d + eta): "
                "WaveStMod 3); prescribed motion only: fowt-sim loads",
        choices=STRETCHING)
    slow_drift: str = setting(
        "newman", "second-order slow-drift surge force: Newman's approximation from the platform's mean-drift "
                  "coefficient table (drift_coefficients_n_m2; none without one) or none (HydroDyn's strip "
                  "theory has none)", choices=SLOW_DRIFTS)
    surface_grid_m: float | None = setting(
        None, "free_surface hydrostatics only: the elevation interpolated bilinearly between the nodes of a "
              "horizontal grid with this spacing through the origin, as HydroDyn reads it from SeaState's grid "
              "(dX = X_HalfWidth / (NX - 1), taken equal in y) [m]; default the exact elevation", gt=0.0)
    wave_kinematics: str = setting(
        "exact", "the wave kinematics and elevation: exact at each point and time, or grid, sampled at the nodes "
                 "of a SeaState input file's grid (X/Y_HalfWidth, NX/NY, Z_Depth, NZ, WaveDT) and interpolated "
                 "between them as HydroDyn does (physics/waves/grid.py); prescribed motion only: fowt-sim loads",
        choices=WAVE_KINEMATICS)

    def __post_init__(self) -> None:
        _validate(self, "hydro options")
        if self.surface_grid_m is not None and self.wave_kinematics == "grid":
            raise ConfigError("hydro options: surface_grid_m and wave_kinematics 'grid' both set the elevation's "
                              "grid: give one (the SeaState grid interpolates the elevation too)")
        if self.surface_grid_m is not None and self.hydrostatics != "free_surface":
            raise ConfigError(f"hydro options: surface_grid_m applies to hydrostatics 'free_surface' only, not "
                              f"{self.hydrostatics!r}")


HYDRO_OPTION_NAMES = ("wetted_length", "load_directions", "hydrostatics", "slow_drift")


@dataclass(frozen=True)
class LoadCase:
    """A named sea state of the packaged load cases and its role in the studies."""

    name: str
    role: str
    sea_state: SeaState


@dataclass(frozen=True)
class RunConfig:
    """A simulation run. ``initial_state`` is the 6-DOF offset (m, rad) at t = 0."""

    platform: str = setting(DEFAULT_PLATFORM, "packaged platform name or platform YAML file")
    drag_model: str = setting("constant", "drag model: constant Cd (the paper's case 1) or filtered, one Cd per "
                                          "frequency band (case 2; bands in the platform YAML)", choices=DRAG_MODELS)
    dt_s: float = setting(0.05, "model time step [s]", gt=0.0)
    duration_s: float = setting(600.0, "simulated time [s]", gt=0.0)
    output_interval_s: float = setting(0.25, "output sample interval [s]", gt=0.0)
    initial_state: tuple[float, ...] = setting((0.0,) * 6, "initial offset: surge, sway, heave [m], roll, "
                                                           "pitch, yaw [rad]")
    wave_table_dt_s: float | None = setting(None, "kinematics table step [s] (default: chosen for 1e-3 "
                                                  "interpolation error); must divide the repeat period", gt=0.0)
    wetted_length: str = like(HydroOptions, "wetted_length")
    load_directions: str = like(HydroOptions, "load_directions")
    hydrostatics: str = like(HydroOptions, "hydrostatics")
    slow_drift: str = like(HydroOptions, "slow_drift")
    mooring: str = setting("", "mooring: spring, linear (the platform's linear_mooring matrix), moorpy (quasi-static "
                               "catenary) or moordyn (lumped-mass dynamics) of the platform's mooring section; "
                               "empty = the platform's own choice",
                           choices=MOORING_MODELS, unset="")

    @property
    def hydro_options(self) -> HydroOptions:
        return HydroOptions(**{name: getattr(self, name) for name in HYDRO_OPTION_NAMES})

    def __post_init__(self) -> None:
        _validate(self, "run")
        if self.hydrostatics == "free_surface":
            raise ConfigError("run: hydrostatics 'free_surface' is implemented for a prescribed motion only "
                              "(fowt-sim loads), not for time stepping")


def _validate(instance, where: str) -> None:
    try:
        validate(instance, where)
    except SettingError as exc:
        raise ConfigError(str(exc)) from None


# HydroDyn v5's choices (WaveDisp 0, WaveStMod 0, member hydrostatics; strip theory has no slow drift)
HYDRODYN = HydroOptions(wetted_length="undisplaced", load_directions="fixed", hydrostatics="nonlinear",
                        slow_drift="none")
# the model's choices before the options were explicit
EARLIER = HydroOptions(wetted_length="displaced", load_directions="rotating", hydrostatics="linear",
                       slow_drift="none")


# --------------------------------------------------------------------------- validation
class _Fields:
    """Typed access to one YAML mapping, with the path of each field for error messages."""

    def __init__(self, data: Any, path: str, is_root: bool = True):
        if not isinstance(data, dict):
            raise ConfigError(f"{path}: expected a mapping, got {type(data).__name__}")
        self.data, self.path, self.is_root = data, path, is_root
        self.used: set[str] = set()

    def at(self, name: str) -> str:
        """The path of a field: ``file.yaml: members[2].diameter_m``."""
        return f"{self.path}: {name}" if self.is_root else f"{self.path}.{name}"

    def _raw(self, name: str, default: Any) -> Any:
        self.used.add(name)
        if name not in self.data or self.data[name] is None:
            if default is _REQUIRED:
                raise ConfigError(f"{self.at(name)}: missing")
            return default
        return self.data[name]

    def number(self, name: str, default: Any = None, *, positive: bool = False,
               non_negative: bool = False) -> float:
        default = _REQUIRED if default is None else default
        value = self._raw(name, default)
        if isinstance(value, bool):  # (strings stay: PyYAML reads 1.2e6 as one)
            raise ConfigError(f"{self.at(name)}: must be a number, got {value!r}")
        try:
            value = float(value)
        except (TypeError, ValueError):
            raise ConfigError(f"{self.at(name)}: must be a number, got {value!r}") from None
        if not math.isfinite(value):
            raise ConfigError(f"{self.at(name)}: must be finite, got {value}")
        if positive and value <= 0:
            raise ConfigError(f"{self.at(name)}: must be a positive number, got {value:g}")
        if non_negative and value < 0:
            raise ConfigError(f"{self.at(name)}: must not be negative, got {value:g}")
        return value

    def optional_number(self, name: str, *, positive: bool = False, non_negative: bool = False) -> float | None:
        if self.data.get(name) is None:
            self.used.add(name)
            return None
        return self.number(name, positive=positive, non_negative=non_negative)

    def vector(self, name: str, size: int = 3, default: Any = None) -> tuple[float, ...]:
        value = self._raw(name, _REQUIRED if default is None else default)
        if not isinstance(value, (list, tuple)) or len(value) != size:
            raise ConfigError(f"{self.at(name)}: must be a list of {size} numbers, got {value!r}")
        try:
            if any(isinstance(v, bool) for v in value):
                raise TypeError
            out = tuple(float(v) for v in value)
        except (TypeError, ValueError):
            raise ConfigError(f"{self.at(name)}: must be a list of {size} numbers, got {value!r}") from None
        if not all(math.isfinite(v) for v in out):
            raise ConfigError(f"{self.at(name)}: must be finite, got {value!r}")
        return out

    def text(self, name: str, default: Any = None, choices: tuple[str, ...] | None = None) -> str:
        value = str(self._raw(name, _REQUIRED if default is None else default))
        if choices and value not in choices:
            raise ConfigError(f"{self.at(name)}: must be one of {', '.join(choices)}, got {value!r}")
        return value

    def setting(self, item) -> Any:
        """A field that is a setting (``fowt_hydro_sim.settings``), checked against it."""
        value = self._raw(name := item.name, None if item.default is REQUIRED else item.default)
        if value is None and item.default is REQUIRED:
            raise ConfigError(f"{self.at(name)}: missing")
        try:
            return check(item, value)
        except SettingError as exc:
            raise ConfigError(f"{self.at(name)}: {exc}") from None

    def settings(self, cls: type, skip: tuple[str, ...] = ()) -> dict[str, Any]:
        """Every setting of the dataclass ``cls`` (but ``skip``) from this mapping."""
        return {name: self.setting(item) for name, item in described(cls).items() if name not in skip}

    def sub(self, name: str, default: Any = None) -> _Fields:
        return _Fields(self._raw(name, _REQUIRED if default is None else default), self.at(name), False)

    def items(self, name: str) -> list[_Fields]:
        value = self._raw(name, _REQUIRED)
        if not isinstance(value, list) or not value:
            raise ConfigError(f"{self.at(name)}: must be a non-empty list")
        return [_Fields(v, f"{self.at(name)}[{i}]", False) for i, v in enumerate(value)]

    def finish(self) -> None:
        unknown = sorted(set(self.data) - self.used)
        if unknown:
            raise ConfigError(f"{self.path}: unknown field(s) {', '.join(unknown)}")


_REQUIRED = object()


def _drag(f: _Fields, name: str, bands: tuple[str, ...]) -> DragCoefficients:
    """A Cd (one value: unfiltered) or ``{constant: .., <band>: .., ...}`` with a Cd for
    every drag band or for none."""
    if not isinstance(f.data.get(name), dict):
        return DragCoefficients(f.number(name, non_negative=True))
    d = f.sub(name)
    given = [b for b in bands if b in d.data]
    if given and len(given) < len(bands):
        missing = ", ".join(b for b in bands if b not in given)
        raise ConfigError(f"{d.path}: a Cd for every drag band or for none; missing {missing}")
    out = DragCoefficients(d.number("constant", non_negative=True),
                           tuple(d.number(b, non_negative=True) for b in bands) if given else None)
    d.finish()
    return out


def _drag_band(f: _Fields) -> DragBand:
    kind = f.text("filter", choices=FILTER_KINDS)
    name = f.text("name")
    if kind in ("lowpass", "highpass"):
        order = f.number("order", positive=True)
        if order != int(order):
            raise ConfigError(f"{f.at('order')}: must be a whole number, got {order:g}")
        band = DragBand(name, kind, int(order), cutoff_hz=f.number("cutoff_hz", positive=True))
    elif kind == "bandpass":
        band = DragBand(name, kind, 1, centre_hz=f.number("centre_hz", positive=True),
                        q=f.number("q", positive=True))
    else:
        band = DragBand(name, kind, 0)
    f.finish()
    return band


def _drag_bands(f: _Fields) -> tuple[DragBand, ...]:
    if f.data.get("drag_bands") is None:
        f.used.add("drag_bands")
        return ()
    bands = tuple(_drag_band(b) for b in f.items("drag_bands"))
    names = [b.name for b in bands]
    if "constant" in names or len(set(names)) < len(names):
        raise ConfigError(f"{f.at('drag_bands')}: band names must be unique and not 'constant', got {names}")
    return bands


def _zone(f: _Fields, section: str, is_last: bool, bands: tuple[str, ...]) -> Zone:
    below = math.inf if is_last and f.data.get("below_z_m") is None else f.number("below_z_m")
    cp = f.number("cp", 1.0, non_negative=True)
    if section == "circular":
        ca = f.number("ca", non_negative=True)
        cd = _drag(f, "cd", bands)
        zone = Zone(f.text("name", "zone"), below, (ca, ca), (cd, cd), cp)
    else:
        zone = Zone(f.text("name", "zone"), below,
                    (f.number("ca_horizontal", non_negative=True), f.number("ca_vertical", non_negative=True)),
                    (_drag(f, "cd_horizontal", bands), _drag(f, "cd_vertical", bands)), cp)
    f.finish()
    return zone


def _end_plate(f: _Fields, joint: bool = False) -> EndPlate:
    """An end plate (``joint``: a member's, which may carry its joint's summed vectors) or a
    tapered wall's axial coefficients."""
    vectors = [f.vector(name) if joint and f.data.get(name) is not None else None
               for name in ("joint_area_m2", "joint_volume_m3")]
    if joint:
        f.used.update({"joint_area_m2", "joint_volume_m3"})
        if (vectors[0] is None) != (vectors[1] is None):
            raise ConfigError(f"{f.path}: joint_area_m2 and joint_volume_m3 are given together or not at all")
    plate = EndPlate(ca=f.number("ca", non_negative=True), cp=f.number("cp", 1.0),
                     cd=f.number("cd", non_negative=True), joint_area_m2=vectors[0], joint_volume_m3=vectors[1])
    f.finish()
    return plate


RECTANGULAR_ONLY = ("width_b_m", "height_b_m", "spin_deg")
CIRCULAR_ONLY = ("diameter_b_m", "hydrostatics_by_section", "wall_thickness_m", "wall_thickness_b_m")


def _member(f: _Fields, bands: tuple[str, ...]) -> Member:
    section = f.text("section", choices=SECTIONS)
    own = CIRCULAR_ONLY if section == "rectangular" else RECTANGULAR_ONLY
    for name in own:
        if f.data.get(name) is not None:
            raise ConfigError(f"{f.at(name)}: only for {'circular' if section == 'rectangular' else 'rectangular'} "
                              f"sections (this member is {section})")
    if section == "circular":
        width = height = f.number("diameter_m", positive=True)
    else:
        width, height = f.number("width_m", positive=True), f.number("height_m", positive=True)
    diameter_b = f.optional_number("diameter_b_m", positive=True) if section == "circular" else None
    width_b, height_b = (f.optional_number(name, positive=True) if section == "rectangular" else None
                         for name in ("width_b_m", "height_b_m"))
    spin = f.number("spin_deg", 0.0) if section == "rectangular" else 0.0
    wall = f.number("wall_thickness_m", 0.0, non_negative=True) if section == "circular" else 0.0
    wall_b = f.optional_number("wall_thickness_b_m", non_negative=True) if section == "circular" else None
    f.used.update(own)
    taper_axial = _end_plate(f.sub("taper_axial")) if f.data.get("taper_axial") else EndPlate(0.0, 1.0, 0.0)
    f.used.add("taper_axial")
    rectangular_taper = (width_b or width) != width or (height_b or height) != height
    if rectangular_taper and (taper_axial.ca or taper_axial.cd):
        raise ConfigError(f"{f.at('taper_axial')}: ca {taper_axial.ca:g}, cd {taper_axial.cd:g}: the axial added "
                          "mass and drag of a tapered rectangular wall are not implemented (only cp; give 0)")
    a, b = f.vector("end_a_m"), f.vector("end_b_m")
    if math.dist(a, b) <= 0:
        raise ConfigError(f"{f.path}: end_a_m and end_b_m are the same point")
    zones = f.items("zones")
    member = Member(
        name=f.text("name"), section=section, end_a_m=a, end_b_m=b, width_m=width, height_m=height,
        strip_length_m=f.number("strip_length_m", 1.0, positive=True),
        zones=tuple(_zone(z, section, i == len(zones) - 1, bands) for i, z in enumerate(zones)),
        end_a_plate=_end_plate(f.sub("end_a_plate"), joint=True) if f.data.get("end_a_plate") else None,
        end_b_plate=_end_plate(f.sub("end_b_plate"), joint=True) if f.data.get("end_b_plate") else None,
        diameter_b_m=diameter_b, taper_axial=taper_axial, width_b_m=width_b, height_b_m=height_b, spin_deg=spin,
        drag_only=_flag(f, "drag_only"), maccamy_fuchs=_flag(f, "maccamy_fuchs"),
        hydrostatics_by_section=_flag(f, "hydrostatics_by_section"), wall_thickness_m=wall, wall_thickness_b_m=wall_b,
        growth_zone=_zone(f.sub("growth_zone"), section, True, bands) if f.data.get("growth_zone") else None,
    )
    f.used.add("growth_zone")
    if section == "circular" and min(member.inner_radius_at(0.0), member.inner_radius_at(1.0)) <= 0.0:
        raise ConfigError(f"{f.at('wall_thickness_m')}: the wall must be thinner than the radius at both ends")
    if member.growth_zone is not None and section != "circular":
        raise ConfigError(f"{f.at('growth_zone')}: marine growth is supported on circular members only")
    if member.maccamy_fuchs and (section != "circular" or member.tapered or member.drag_only):
        raise ConfigError(f"{f.at('maccamy_fuchs')}: for untapered circular members with their own inertia only "
                          "(the correction's ka is the member's diameter)")
    f.used.update({"end_a_plate", "end_b_plate"})
    if list(z.below_z_m for z in member.zones) != sorted(z.below_z_m for z in member.zones):
        raise ConfigError(f"{f.path}.zones: below_z_m must increase from the first zone to the last")
    f.finish()
    return member


def _flag(f: _Fields, name: str) -> bool:
    """An optional true/false field (default false)."""
    value = f.data.get(name, False)
    f.used.add(name)
    if not isinstance(value, bool):
        raise ConfigError(f"{f.at(name)}: must be true or false, got {value!r}")
    return value


def _inertia(f: _Fields) -> tuple[tuple[float, ...], ...]:
    ixx, iyy, izz = (f.number(k, positive=True) for k in ("ixx", "iyy", "izz"))
    ixy, ixz, iyz = (f.number(k, 0.0) for k in ("ixy", "ixz", "iyz"))
    f.finish()
    return ((ixx, ixy, ixz), (ixy, iyy, iyz), (ixz, iyz, izz))


def _drift_coefficients(f: _Fields) -> tuple[tuple[float, float], ...]:
    """``drift_coefficients_n_m2: [[w_rad_s, D_n_m2], ...]``, w ascending and positive, D >= 0."""
    value = f.data.get("drift_coefficients_n_m2")
    f.used.add("drift_coefficients_n_m2")
    if value is None:
        return ()
    where = f.at("drift_coefficients_n_m2")
    try:
        pairs = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ConfigError(f"{where}: must be a list of [omega_rad_s, n_m2] pairs") from None
    if pairs.ndim != 2 or pairs.shape[1] != 2 or len(pairs) < 2 or not np.all(np.isfinite(pairs)):
        raise ConfigError(f"{where}: must be a list of at least two finite [omega_rad_s, n_m2] pairs")
    if pairs[0, 0] <= 0 or np.any(np.diff(pairs[:, 0]) <= 0) or np.any(pairs[:, 1] < 0):
        raise ConfigError(f"{where}: frequencies must be positive and ascending, coefficients >= 0 "
                          "(Newman's approximation takes their square root)")
    return tuple((float(w), float(d)) for w, d in pairs)


def _matrix6(f: _Fields, name: str) -> tuple[tuple[float, ...], ...]:
    """A 6x6 matrix field (six rows of six numbers); zeros when absent."""
    value = f.data.get(name)
    f.used.add(name)
    if value is None:
        return ((0.0,) * 6,) * 6
    try:
        matrix = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ConfigError(f"{f.at(name)}: must be six rows of six numbers") from None
    if matrix.shape != (6, 6) or not np.all(np.isfinite(matrix)):
        raise ConfigError(f"{f.at(name)}: must be six rows of six finite numbers, got shape {matrix.shape}")
    return tuple(tuple(float(v) for v in row) for row in matrix)


def _band_matrices(f: _Fields, name: str, bands: tuple[str, ...]) -> tuple[tuple[tuple[float, ...], ...], ...]:
    """``name: {band: 6x6 matrix, ...}``, one matrix for every drag band (in ``bands`` order) or
    the field absent (())."""
    if f.data.get(name) is None:
        f.used.add(name)
        return ()
    m = f.sub(name)
    given = sorted(m.data)
    if not bands or given != sorted(bands):
        raise ConfigError(f"{f.at(name)}: one matrix for each drag band {list(bands)}, got {given}")
    out = tuple(_matrix6(m, band) for band in bands)
    m.finish()
    return out


def _potential_flow(f: _Fields, folder: Path | None, bands: tuple[str, ...] = ()) -> PotentialFlow | None:
    """``potential_flow:`` (PotentialFlow); the WAMIT root is taken relative to ``folder``;
    ``bands``: the platform's drag band names."""
    if f.data.get("potential_flow") is None:
        f.used.add("potential_flow")
        return None
    p = f.sub("potential_flow")
    root = Path(p.text("wamit_root"))
    if not root.is_absolute():
        root = (folder or Path.cwd()) / root
    for extension in (".1", ".3", ".hst"):
        if not root.with_name(root.name + extension).is_file():
            raise ConfigError(f"{p.at('wamit_root')}: no WAMIT file {root.name + extension} in {root.parent}")
    cob = p.vector("centre_of_buoyancy_xy_m", 2, (0.0, 0.0))
    radiation = p.text("radiation", "convolution", choices=RADIATION_MODELS)
    if radiation == "state_space" and not root.with_name(root.name + ".ss").is_file():
        raise ConfigError(f"{p.at('radiation')}: state_space needs the WAMIT file {root.name}.ss in {root.parent}")
    flow = PotentialFlow(
        wamit_root=str(root.resolve()), wamit_length_m=p.number("wamit_length_m", 1.0, positive=True),
        displaced_volume_m3=p.number("displaced_volume_m3", positive=True), centre_of_buoyancy_xy_m=cob,
        radiation=radiation,
        radiation_tmax_s=p.number("radiation_tmax_s", 60.0, positive=True),
        added_force_n=p.vector("added_force_n", 6, (0.0,) * 6),
        added_stiffness=_matrix6(p, "added_stiffness"), added_linear_damping=_matrix6(p, "added_linear_damping"),
        added_quadratic_damping=_matrix6(p, "added_quadratic_damping"),
        added_quadratic_damping_bands=_band_matrices(p, "added_quadratic_damping_bands", bands))
    p.finish()
    return flow


def _linear_mooring(f: _Fields) -> LinearMooring | None:
    """``linear_mooring:`` (LinearMooring)."""
    if f.data.get("linear_mooring") is None:
        f.used.add("linear_mooring")
        return None
    m = f.sub("linear_mooring")
    mooring = LinearMooring(m.vector("force_at_rest_n", 6), _matrix6(m, "stiffness"), m.text("source", ""))
    m.finish()
    return mooring


def _potential_flow_document(flow: PotentialFlow, bands: tuple[DragBand, ...]) -> dict:
    out: dict = {"wamit_root": flow.wamit_root, "wamit_length_m": flow.wamit_length_m,
                 "displaced_volume_m3": flow.displaced_volume_m3,
                 "centre_of_buoyancy_xy_m": list(flow.centre_of_buoyancy_xy_m), "radiation": flow.radiation,
                 "radiation_tmax_s": flow.radiation_tmax_s, "added_force_n": list(flow.added_force_n)}
    for name in ("added_stiffness", "added_linear_damping", "added_quadratic_damping"):
        out[name] = [list(row) for row in getattr(flow, name)]
    if flow.added_quadratic_damping_bands:
        out["added_quadratic_damping_bands"] = {b.name: [list(row) for row in matrix]
                                                for b, matrix in zip(bands, flow.added_quadratic_damping_bands)}
    return out


def _mooring(f: _Fields, folder: Path | None) -> Mooring:
    """The mooring section: ``model`` (default spring), ``file`` (a MoorDyn input file, relative
    to ``folder``, the platform YAML's), ``moordyn_dt_s`` (optional), and the spring fields
    (needed for model spring)."""
    model = f.text("model", "spring", MOORING_MODELS)
    file = None
    if f.data.get("file") is not None:
        path = Path(f.text("file"))
        path = path if path.is_absolute() or folder is None else folder / path
        if not path.is_file():
            raise ConfigError(f"{f.at('file')}: {path}: no such file")
        file = str(path.resolve())
    f.used.add("file")
    moordyn_dt_s = f.optional_number("moordyn_dt_s", positive=True)
    spring = model == "spring" or "lines" in f.data
    lines = []
    for line in f.items("lines") if spring else ():
        lines.append(MooringLine(line.vector("fairlead_m"), line.vector("anchor_m")))
        line.finish()
    mooring = Mooring(f.number("stiffness_n_m", non_negative=True) if spring else 0.0,
                      f.number("pretension_n", non_negative=True) if spring else 0.0,
                      f.number("unstretched_length_m", positive=True) if spring else 0.0,
                      tuple(lines), model, file, moordyn_dt_s)
    f.finish()
    if model in LINE_FILE_MODELS and file is None:
        raise ConfigError(f"{f.at('file')}: missing (mooring model {model} reads a MoorDyn input file)")
    return mooring


def platform_from_dict(data: Any, source: str = "platform", folder: Path | None = None) -> Platform:
    """Validate a parsed platform YAML document (``folder``: where relative file paths in it,
    the mooring's MoorDyn file and a potential-flow hull's WAMIT files, are taken from; default
    the working directory)."""
    f = _Fields(data, source)
    env_f = f.sub("environment", {})
    env = Environment(env_f.number("water_density_kg_m3", 1025.0, positive=True),
                      env_f.number("gravity_m_s2", 9.80665, positive=True),
                      env_f.number("water_depth_m", 150.0, positive=True))
    env_f.finish()
    m = f.sub("mass")
    mass = MassProperties(m.number("mass_kg", positive=True), m.vector("cog_m"),
                          _inertia(m.sub("inertia_about_cog_kg_m2")))
    m.finish()
    linear_mooring = _linear_mooring(f)
    if f.data.get("mooring") is None and linear_mooring is not None:
        f.used.add("mooring")
        mooring = Mooring(model="linear")
    else:
        mooring = _mooring(f.sub("mooring"), folder)
    if mooring.model == "linear" and linear_mooring is None:
        raise ConfigError(f"{source}: mooring model linear needs a linear_mooring section")
    drag_bands = _drag_bands(f)
    band_names = tuple(b.name for b in drag_bands)
    potential_flow = _potential_flow(f, folder, band_names)
    if potential_flow is not None and not f.data.get("members"):
        f.used.add("members")
        members: tuple[Member, ...] = ()  # a potential-flow hull needs no Morison member
    else:
        members = tuple(_member(x, band_names) for x in f.items("members"))
    platform = Platform(
        name=f.text("name"), description=f.text("description", ""), environment=env, mass=mass,
        hub_point_m=f.vector("hub_point_m"), members=members,
        mooring=mooring, drag_bands=drag_bands, drift_coefficients_n_m2=_drift_coefficients(f),
        potential_flow=potential_flow, linear_mooring=linear_mooring, marine_growth=_marine_growth(f),
        fill_groups=_fill_groups(f, members, env))
    f.used.update(k for k in f.data if k.endswith(("_zones", "_end")))  # YAML anchors' holders
    f.finish()
    return platform


def _marine_growth(f: _Fields) -> tuple[MarineGrowthLevel, ...]:
    """The platform's marine-growth table, highest row first (distinct heights)."""
    if f.data.get("marine_growth") is None:
        f.used.add("marine_growth")
        return ()
    rows = []
    for row in f.items("marine_growth"):
        rows.append(MarineGrowthLevel(row.number("z_m"), row.number("thickness_m", non_negative=True),
                                      row.number("density_kg_m3", non_negative=True)))
        row.finish()
    heights = [r.z_m for r in rows]
    if heights != sorted(heights, reverse=True) or len(set(heights)) < len(heights):
        raise ConfigError(f"{f.at('marine_growth')}: z_m must decrease from one row to the next, got {heights}")
    return tuple(rows)


def _fill_groups(f: _Fields, members: tuple[Member, ...], env: Environment) -> tuple[FillGroup, ...]:
    """The platform's fill groups: circular members of the platform, each in one group at most."""
    if f.data.get("fill_groups") is None:
        f.used.add("fill_groups")
        return ()
    sections = {m.name: m.section for m in members}
    groups, seen = [], set()
    for row in f.items("fill_groups"):
        value = row.data.get("members")
        row.used.add("members")
        if not isinstance(value, list) or not value or not all(isinstance(name, str) for name in value):
            raise ConfigError(f"{row.at('members')}: must be a list of member names")
        for name in value:
            if name not in sections:
                raise ConfigError(f"{row.at('members')}: no member named {name!r}")
            if sections[name] != "circular":
                raise ConfigError(f"{row.at('members')}: member {name} is rectangular: filled members are supported "
                                  "circular only")
            if name in seen:
                raise ConfigError(f"{row.at('members')}: member {name} is in more than one fill group")
            seen.add(name)
        groups.append(FillGroup(tuple(value), row.number("free_surface_z_m"),
                                row.number("density_kg_m3", env.water_density_kg_m3, positive=True)))
        row.finish()
    return tuple(groups)


def _cd_document(cd: DragCoefficients, bands: tuple[DragBand, ...]) -> float | dict:
    if cd.bands is None:
        return cd.constant
    return {"constant": cd.constant, **{b.name: value for b, value in zip(bands, cd.bands)}}


def _zone_document(zone: Zone, section: str, bands: tuple[DragBand, ...]) -> dict:
    out: dict = {"name": zone.name}
    if math.isfinite(zone.below_z_m):
        out["below_z_m"] = zone.below_z_m
    if zone.cp != 1.0:
        out["cp"] = zone.cp
    if section == "circular":
        return {**out, "ca": zone.ca[0], "cd": _cd_document(zone.cd[0], bands)}
    return {**out, "ca_horizontal": zone.ca[0], "ca_vertical": zone.ca[1],
            "cd_horizontal": _cd_document(zone.cd[0], bands), "cd_vertical": _cd_document(zone.cd[1], bands)}


def _band_document(band: DragBand) -> dict:
    out: dict = {"name": band.name, "filter": band.kind}
    if band.kind in ("lowpass", "highpass"):
        out.update(order=band.order, cutoff_hz=band.cutoff_hz)
    elif band.kind == "bandpass":
        out.update(centre_hz=band.centre_hz, q=band.q)
    return out


def platform_document(platform: Platform) -> dict:
    """The platform as a YAML document (``platform_from_dict`` reads it back to an equal Platform)."""
    bands = platform.drag_bands
    members = []
    for m in platform.members:
        size = {"diameter_m": m.width_m} if m.section == "circular" else {"width_m": m.width_m, "height_m": m.height_m}
        taper_axial = {"ca": m.taper_axial.ca, "cp": m.taper_axial.cp, "cd": m.taper_axial.cd}
        if m.tapered and m.section == "circular":
            size.update(diameter_b_m=m.diameter_b_m, taper_axial=taper_axial)
        elif m.growth_zone is not None and m.section == "circular":  # the growth's tapers take it
            size.update(taper_axial=taper_axial)
        elif m.tapered:
            size.update({k: getattr(m, k) for k in ("width_b_m", "height_b_m") if getattr(m, k) is not None},
                        taper_axial=taper_axial)
        if m.spin_deg:
            size["spin_deg"] = m.spin_deg
        if m.drag_only:
            size["drag_only"] = True
        if m.maccamy_fuchs:
            size["maccamy_fuchs"] = True
        if m.hydrostatics_by_section:
            size["hydrostatics_by_section"] = True
        if m.wall_thickness_m:
            size["wall_thickness_m"] = m.wall_thickness_m
        if m.wall_thickness_b_m is not None:
            size["wall_thickness_b_m"] = m.wall_thickness_b_m
        if m.growth_zone is not None:
            size["growth_zone"] = _zone_document(m.growth_zone, m.section, bands)
        member = {"name": m.name, "section": m.section, **size, "end_a_m": list(m.end_a_m),
                  "end_b_m": list(m.end_b_m), "strip_length_m": m.strip_length_m,
                  "zones": [_zone_document(z, m.section, bands) for z in m.zones]}
        for end in ("end_a_plate", "end_b_plate"):
            plate = getattr(m, end)
            if plate is not None:
                member[end] = {"ca": plate.ca, "cp": plate.cp, "cd": plate.cd}
                if plate.joint_area_m2 is not None:
                    member[end].update(joint_area_m2=list(plate.joint_area_m2),
                                       joint_volume_m3=list(plate.joint_volume_m3))
        members.append(member)
    (ixx, ixy, ixz), (_, iyy, iyz), (_, _, izz) = platform.mass.inertia_about_cog_kg_m2
    mooring = platform.mooring
    document = {
        "name": platform.name, "description": platform.description,
        "environment": dict(vars(platform.environment)),
        "mass": {"mass_kg": platform.mass.mass_kg, "cog_m": list(platform.mass.cog_m),
                 "inertia_about_cog_kg_m2": {"ixx": ixx, "iyy": iyy, "izz": izz, "ixy": ixy, "ixz": ixz, "iyz": iyz}},
        "hub_point_m": list(platform.hub_point_m),
        "drag_bands": [_band_document(b) for b in bands] or None,
        "drift_coefficients_n_m2": [list(pair) for pair in platform.drift_coefficients_n_m2] or None,
        "members": members,
        "mooring": _mooring_document(mooring),
    }
    if platform.potential_flow is not None:
        document["potential_flow"] = _potential_flow_document(platform.potential_flow, bands)
    if platform.marine_growth:
        document["marine_growth"] = [dict(vars(row)) for row in platform.marine_growth]
    if platform.fill_groups:
        document["fill_groups"] = [{"members": list(g.members), "free_surface_z_m": g.free_surface_z_m,
                                    "density_kg_m3": g.density_kg_m3} for g in platform.fill_groups]
    if platform.linear_mooring is not None:
        lm = platform.linear_mooring
        document["linear_mooring"] = {"force_at_rest_n": list(lm.force_at_rest_n),
                                      "stiffness": [list(row) for row in lm.stiffness], "source": lm.source}
    return document


def _mooring_document(mooring: Mooring) -> dict:
    out: dict = {}
    if mooring.model != "spring":
        out["model"] = mooring.model
    if mooring.file is not None:
        out["file"] = mooring.file
    if mooring.moordyn_dt_s is not None:
        out["moordyn_dt_s"] = mooring.moordyn_dt_s
    if mooring.lines:
        out.update({"stiffness_n_m": mooring.stiffness_n_m, "pretension_n": mooring.pretension_n,
                    "unstretched_length_m": mooring.unstretched_length_m,
                    "lines": [{"fairlead_m": list(line.fairlead_m), "anchor_m": list(line.anchor_m)}
                              for line in mooring.lines]})
    return out


def _read_yaml(path: Path) -> Any:
    try:
        return yaml.safe_load(path.read_text())
    except OSError as exc:
        raise ConfigError(f"{path}: cannot be read ({exc.strerror or exc})") from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f":{mark.line + 1}:{mark.column + 1}" if mark else ""
        raise ConfigError(f"{path}{where}: not valid YAML ({getattr(exc, 'problem', None) or exc})") from None


def packaged_platforms() -> list[str]:
    folder = resources.files("fowt_hydro_sim.physics") / "data" / "platforms"
    return sorted(p.name[:-5] for p in folder.iterdir() if p.name.endswith(".yaml"))


def platform_path(name_or_path: str | Path = "windmoor12") -> Path:
    """The YAML file of a packaged platform (by name) or a platform file."""
    path = Path(name_or_path)
    if not path.suffix and str(name_or_path) in packaged_platforms():
        return Path(str(resources.files("fowt_hydro_sim.physics") / "data" / "platforms" / f"{name_or_path}.yaml"))
    if not path.exists():
        raise ConfigError(f"platform {str(name_or_path)!r}: no such file and not a packaged platform "
                          f"({', '.join(packaged_platforms())})")
    return path


def load_platform(name_or_path: str | Path = "windmoor12") -> Platform:
    """A packaged platform by name (``windmoor12``) or a platform YAML file."""
    path = platform_path(name_or_path)
    return platform_from_dict(_read_yaml(path), path.name, path.parent)


def load_cases() -> dict[str, LoadCase]:
    """The paper's load cases by name (``lc5.3`` ...)."""
    data = _read_yaml(Path(str(resources.files("fowt_hydro_sim.physics") / "data" / "load_cases.yaml")))
    cases = {}
    for name, spec in data.items():
        f = _Fields(spec, name)
        role = f.text("role")
        cases[name] = LoadCase(name, role, SeaState(**f.settings(SeaState)))
        f.finish()
    return cases


def load_case(name: str) -> LoadCase:
    """A load case by name: ``lc5.3``, ``LC5.3`` or ``5.3``."""
    cases = load_cases()
    key = name.lower() if name.lower().startswith("lc") else f"lc{name}"
    if key not in cases:
        raise ConfigError(f"load case {name!r}: unknown; known: {', '.join(cases)}")
    return cases[key]


def sea_state_from_dict(data: Any, source: str = "sea_state") -> SeaState:
    return _sea_state(_Fields(data, source))


def _sea_state(f: _Fields) -> SeaState:
    sea = SeaState(**f.settings(SeaState))
    f.finish()
    lo, hi = sea.band_hz
    if lo >= hi:
        raise ConfigError(f"{f.path}: f_min_hz ({lo:g}) must be below f_max_hz ({hi:g})")
    return sea


def run_from_dict(data: Any, source: str = "run") -> RunConfig:
    return _run(_Fields(data, source))


def _run(f: _Fields, platform: str = DEFAULT_PLATFORM) -> RunConfig:
    """The run mapping of a run file (its platform is given beside it, at the top level)."""
    run = RunConfig(platform=platform, **f.settings(RunConfig, skip=("platform",)))
    f.finish()
    return run


@dataclass(frozen=True)
class RunFile:
    """A run described in one YAML file: waves (load case or sea state) and run (with its
    platform)."""

    sea_state: SeaState | None  # None: still water
    run: RunConfig
    load_case: str | None = None


def load_run_file(path: str | Path) -> RunFile:
    """Read a run file::

        platform: windmoor12          # packaged name or platform YAML path
        load_case: lc5.3              # or sea_state: {hs_m: .., tp_s: .., gamma: .., seed: ..}
        seed: 1                       # with load_case
        run: {dt_s: 0.05, duration_s: 3600, drag_model: constant, output_interval_s: 0.25}
    """
    path = Path(path)
    f = _Fields(_read_yaml(path), path.name)
    platform = f.setting(described(RunConfig)["platform"])
    case_name = f.data.get("load_case")
    f.used.add("load_case")
    if case_name is not None and f.data.get("sea_state") is not None:
        raise ConfigError(f"{path.name}: give load_case or sea_state, not both")
    if case_name is not None:
        case = load_case(str(case_name))
        sea = SeaState(case.sea_state.hs_m, case.sea_state.tp_s, case.sea_state.gamma,
                       seed=f.setting(described(SeaState)["seed"]))
        case_name = case.name
    else:
        sea = _sea_state(f.sub("sea_state")) if f.data.get("sea_state") else None
        f.used.add("sea_state")
    run = _run(f.sub("run", {}), platform)
    f.finish()
    return RunFile(sea, run, case_name)
