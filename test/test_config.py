"""Configuration: the packaged windmoor12 platform and the paper's load cases against the spec
text, and the validation errors (ConfigError naming the offending field).

Oracles: the numbers of docs/platform_windmoor12.md and docs/load_cases.md (typed in
here from those documents), hydrostatic equilibrium (mass = rho x displaced volume computed from
the member geometry), and the documented error-message format.
"""
from __future__ import annotations

import copy
import math
import re
from collections.abc import Callable
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import yaml

from fowt_hydro_sim.physics.config import (
    ConfigError,
    DragBand,
    DragCoefficients,
    LoadCase,
    SeaState,
    load_case,
    load_cases,
    load_platform,
    platform_from_dict,
    run_from_dict,
    sea_state_from_dict,
)

PACKAGED_YAML = Path(str(resources.files("fowt_hydro_sim.physics") / "data" / "platforms" / "windmoor12.yaml"))

# load_cases.md, table "Load cases": name -> (role, Hs m, Tp s, gamma); 5.0's gamma is "not
# given (use 1.0)"; 6.2-6.5 are the paper's commented-out blind cases listed under the table.
SPEC_LOAD_CASES = {
    "5.0": ("tuning", 2.00, 7.0, 1.0),
    "5.1": ("tuning", 3.74, 7.0, 4.90),
    "5.2": ("tuning", 6.19, 9.0, 4.90),
    "5.3": ("tuning", 11.0, 12.0, 4.90),
    "5.4": ("tuning", 3.74, 12.0, 1.00),
    "6.1": ("blind", 3.74, 9.0, 1.49),
    "6.2": ("blind", 6.19, 9.0, 4.90),
    "6.3": ("blind", 11.0, 12.0, 4.90),
    "6.4": ("blind", 6.19, 12.0, 1.23),
    "6.5": ("blind", 14.97, 14.0, 4.9),
}


def packaged() -> dict[str, Any]:
    """A fresh parse of the packaged platform YAML (YAML anchors make shared sub-objects)."""
    return yaml.safe_load(PACKAGED_YAML.read_text())


def assert_clean(exc: ConfigError) -> None:
    """The error is raised by the validator itself, not chained onto an internal exception."""
    assert isinstance(exc, ValueError)
    assert exc.__context__ is None or exc.__suppress_context__


# --------------------------------------------------------------------------- windmoor12
def test_windmoor12_matches_spec() -> None:
    """Oracle: platform_windmoor12.md tables (environment, mass, hull, mooring, coefficients)."""
    p = load_platform("windmoor12")
    assert p.name == "windmoor12"
    env = p.environment
    assert (env.water_density_kg_m3, env.gravity_m_s2, env.water_depth_m) == (1025.0, 9.80665, 150.0)
    assert p.mass.mass_kg == pytest.approx(14.0807e6, rel=1e-12)
    assert p.mass.cog_m == pytest.approx((0.0, 0.0, 3.12))
    np.testing.assert_allclose(p.mass.inertia_about_cog_kg_m2, np.diag([2.49e10, 2.49e10, 1.30e10]))
    assert p.hub_point_m == pytest.approx((0.0, 0.0, 131.7))
    assert len(p.members) == 6 and len(p.mooring.lines) == 3

    columns = [m for m in p.members if m.section == "circular"]
    pontoons = [m for m in p.members if m.section == "rectangular"]
    assert len(columns) == 3 and len(pontoons) == 3
    centres = {(round(m.end_a_m[0], 4), round(m.end_a_m[1], 4)) for m in columns}
    assert centres == {(-35.2184, 0.0), (17.6092, 30.5), (17.6092, -30.5)}
    for m in columns:
        assert (m.width_m, m.height_m) == (15.0, 15.0)
        assert (m.end_a_m[2], m.end_b_m[2]) == (-15.5, 15.0)
        assert math.hypot(*m.end_a_m[:2]) == pytest.approx(35.2184, abs=1e-4)
        submerged, splash = m.zones
        assert submerged.below_z_m == -5.0 and splash.below_z_m == math.inf
        assert submerged.ca == (1.0, 1.0) and splash.ca == (1.0, 1.0)
        assert submerged.cd == (DragCoefficients(0.8, (0.4, 1.0)),) * 2
        assert splash.cd == (DragCoefficients(0.6, (0.3, 0.8)),) * 2
        assert m.end_a_plate is not None and (m.end_a_plate.ca, m.end_a_plate.cp, m.end_a_plate.cd) == (1, 1, 4.8)
        assert m.end_b_plate is None
    for m in pontoons:
        assert (m.width_m, m.height_m) == (10.0, 4.0)
        assert m.end_a_m[2] == m.end_b_m[2] == -13.5
        assert math.dist(m.end_a_m, m.end_b_m) == pytest.approx(46.0, abs=1e-3)  # wetted length
        (zone,) = m.zones
        cd_h, cd_v = zone.cd
        assert cd_h == DragCoefficients(2.0, (1.0, 2.5))
        assert cd_v == DragCoefficients(3.0)  # vertical drag: one Cd at every frequency

    mo = p.mooring
    assert (mo.stiffness_n_m, mo.pretension_n, mo.unstretched_length_m) == (63.2e3, 1.2e6, 600.0)
    for line in mo.lines:
        assert line.fairlead_m[2] == line.anchor_m[2] == -10.0
        assert math.hypot(*line.fairlead_m[:2]) == pytest.approx(42.7184, abs=1e-4)
        # anchors on the fairlead's azimuth, 600 m further out; 1 mm tolerance: the packaged
        # anchors of lines 2 and 3 have y = +-556.60993 where the spec's radius gives +-556.61038
        assert math.hypot(*line.anchor_m[:2]) == pytest.approx(642.7184, abs=1e-3)
        assert math.dist(line.fairlead_m, line.anchor_m) == pytest.approx(600.0, abs=1e-3)
        assert math.atan2(line.fairlead_m[1], line.fairlead_m[0]) == pytest.approx(
            math.atan2(line.anchor_m[1], line.anchor_m[0]), abs=1e-6)


def test_windmoor12_mass_equals_displaced_mass() -> None:
    """Oracle: hydrostatic equilibrium with no vertical mooring load: m = rho V, V from the member
    geometry (3 columns pi R^2 x draft + 3 pontoons w h L) = 13,737.2 m^3 (spec)."""
    p = load_platform("windmoor12")
    volume = 0.0
    for m in p.members:
        if m.section == "circular":
            draft = -min(m.end_a_m[2], m.end_b_m[2])
            volume += math.pi * (m.width_m / 2) ** 2 * draft
        else:
            volume += m.width_m * m.height_m * math.dist(m.end_a_m, m.end_b_m)
    assert volume == pytest.approx(13737.2, abs=0.1)
    assert p.mass.mass_kg == pytest.approx(p.environment.water_density_kg_m3 * volume, rel=1e-4)


def test_load_platform_by_path_equals_by_name(tmp_path: Path) -> None:
    """Oracle: the same YAML read from a copied file gives the same platform."""
    path = tmp_path / "copy.yaml"
    path.write_text(PACKAGED_YAML.read_text())
    assert load_platform(path) == load_platform("windmoor12")
    assert platform_from_dict(packaged(), "x") == load_platform("windmoor12")


# --------------------------------------------------------------------------- load cases
@pytest.mark.parametrize("number", list(SPEC_LOAD_CASES))
def test_load_cases_match_spec(number: str) -> None:
    """Oracle: load_cases.md table (Hs, Tp, gamma, role), by name 'lcX.Y' and by 'X.Y'."""
    role, hs, tp, gamma = SPEC_LOAD_CASES[number]
    case = load_case(f"lc{number}")
    assert isinstance(case, LoadCase) and case.name == f"lc{number}"
    assert case.role == role
    sea = case.sea_state
    assert (sea.hs_m, sea.tp_s, sea.gamma) == (hs, tp, gamma)
    assert sea.spectrum == "jonswap" and sea.heading_deg == 0.0  # JONSWAP, heading 0 (spec)
    assert load_case(number) == case
    assert load_case(f"LC{number}") == case


def test_load_cases_contain_all_spec_cases() -> None:
    """Oracle: the spec's six cases of the table (plus the extra blind cases) are all listed."""
    cases = load_cases()
    assert {f"lc{n}" for n in SPEC_LOAD_CASES} <= set(cases)
    assert {"lc5.0", "lc5.1", "lc5.2", "lc5.3", "lc5.4", "lc6.1"} <= set(cases)
    assert all(isinstance(c.sea_state, SeaState) for c in cases.values())


def test_unknown_load_case() -> None:
    """Oracle: the documented ConfigError naming the case and listing the known ones."""
    with pytest.raises(ConfigError) as info:
        load_case("lc9.9")
    assert "lc9.9" in str(info.value) and "unknown" in str(info.value) and "lc5.3" in str(info.value)
    assert_clean(info.value)


# --------------------------------------------------------------------------- bad platform files
def _set(path: list[Any], value: Any) -> Callable[[dict], None]:
    def edit(d: dict) -> None:
        for key in path[:-1]:
            d = d[key]
        d[path[-1]] = value
    return edit


def _delete(path: list[Any]) -> Callable[[dict], None]:
    def edit(d: dict) -> None:
        for key in path[:-1]:
            d = d[key]
        del d[path[-1]]
    return edit


def _unsorted_zones(d: dict) -> None:
    first = dict(d["members"][0]["zones"][0])
    d["members"][0]["zones"] = [first, dict(first, name="deeper", below_z_m=-10.0)]


# (edit, field path named in the message, the rest of the message)
BAD_PLATFORMS = {
    "negative diameter": (_set(["members", 2, "diameter_m"], -1), r"members\[2\]\.diameter_m",
                          r"must be a positive number, got -1$"),
    "missing mass_kg": (_delete(["mass", "mass_kg"]), r"mass\.mass_kg", r"missing$"),
    "missing mass": (_delete(["mass"]), r"mass", r"missing$"),
    "unknown top field": (_set(["colour"], "red"), r"", r"unknown field\(s\) colour$"),
    "unknown member field": (_set(["members", 4, "diamter_m"], 3.0), r"members\[4\]",
                             r"unknown field\(s\) diamter_m$"),
    "string for a number": (_set(["mooring", "stiffness_n_m"], "stiff"), r"mooring\.stiffness_n_m",
                            r"must be a number, got 'stiff'$"),
    "string in a vector": (_set(["mass", "cog_m"], [0.0, "up", 3.12]), r"mass\.cog_m",
                           r"must be a list of 3 numbers"),
    "bad section": (_set(["members", 1, "section"], "hexagonal"), r"members\[1\]\.section",
                    r"must be one of circular, rectangular, got 'hexagonal'$"),
    "zones not increasing": (_unsorted_zones, r"members\[0\]\.zones", r"below_z_m must increase"),
    "negative inertia": (_set(["mass", "inertia_about_cog_kg_m2", "izz"], -5.0),
                         r"mass\.inertia_about_cog_kg_m2\.izz", r"must be a positive number, got -5$"),
    "empty members": (_set(["members"], []), r"members", r"must be a non-empty list$"),
    "NaN depth": (_set(["environment", "water_depth_m"], float("nan")), r"environment\.water_depth_m",
                  r"must be finite"),
    "band Cd missing": (_delete(["members", 0, "zones", 0, "cd", "wave"]), r"members\[0\]\.zones\[0\]\.cd",
                        r"a Cd for every drag band or for none; missing wave$"),
    "Cd of an unknown band": (_set(["members", 0, "zones", 0, "cd", "swell"], 0.5), r"members\[0\]\.zones\[0\]\.cd",
                              r"unknown field\(s\) swell$"),
    "unknown filter": (_set(["drag_bands", 0, "filter"], "chebyshev"), r"drag_bands\[0\]\.filter",
                       r"must be one of lowpass, highpass, bandpass, allpass, got 'chebyshev'$"),
    "fractional order": (_set(["drag_bands", 0, "order"], 2.5), r"drag_bands\[0\]\.order",
                         r"must be a whole number, got 2.5$"),
    "band without cutoff": (_delete(["drag_bands", 1, "cutoff_hz"]), r"drag_bands\[1\]\.cutoff_hz", r"missing$"),
    "duplicate band names": (_set(["drag_bands", 1, "name"], "low_frequency"), r"drag_bands",
                             r"band names must be unique and not 'constant'"),
}


def test_windmoor12_drag_bands_are_the_papers_case_2() -> None:
    """Oracle: platform_windmoor12.md, 'Case 2 uses ... a 5th-order low-pass Butterworth for the
    low-frequency band and a 1st-order high-pass Butterworth for the wave band, both with cutoff
    0.05 Hz'; a band-pass band reads centre and Q, an all-pass band nothing."""
    assert load_platform().drag_bands == (DragBand("low_frequency", "lowpass", 5, cutoff_hz=0.05),
                                          DragBand("wave", "highpass", 1, cutoff_hz=0.05))
    data = packaged()
    data["drag_bands"] = [{"name": "resonance", "filter": "bandpass", "centre_hz": 0.01, "q": 0.7},
                          {"name": "rest", "filter": "allpass"}]
    for zone in (*data["column_zones"], *data["pontoon_zones"]):
        for key in ("cd", "cd_horizontal"):
            if key in zone:
                zone[key] = {"constant": 1.0, "resonance": 0.5, "rest": 2.0}
    platform = platform_from_dict(data)
    assert platform.drag_bands == (DragBand("resonance", "bandpass", 1, centre_hz=0.01, q=0.7),
                                   DragBand("rest", "allpass", 0))
    assert platform.members[0].zones[0].cd[0] == DragCoefficients(1.0, (0.5, 2.0))
    assert platform.members[3].zones[0].cd == (DragCoefficients(1.0, (0.5, 2.0)), DragCoefficients(3.0))


@pytest.mark.parametrize("case", list(BAD_PLATFORMS))
def test_bad_platform_file_names_the_field(case: str, tmp_path: Path) -> None:
    """Oracle: the documented message '<file>: <field path>: <problem>' for an edited copy of the
    packaged YAML written to disk and read with load_platform(path)."""
    edit, field, problem = BAD_PLATFORMS[case]
    data = packaged()
    edit(data)
    path = tmp_path / "windmoor12.yaml"
    path.write_text(yaml.safe_dump(data))
    with pytest.raises(ConfigError) as info:
        load_platform(path)
    message = str(info.value)
    # the documented form: the file name, ": ", the field path, ": ", the problem
    sep = r": " if field else ""
    assert re.match(rf"windmoor12\.yaml{sep}{field}: {problem}", message), message
    assert_clean(info.value)
    # the same through platform_from_dict with a caller-chosen source name
    with pytest.raises(ConfigError, match=rf"^mine\.yaml{sep}{field}: {problem}"):
        platform_from_dict(copy.deepcopy(data), "mine.yaml")


def test_error_message_as_documented() -> None:
    """Oracle: the exact example message of config.py's module docstring."""
    data = packaged()
    data["members"][2]["diameter_m"] = -1
    with pytest.raises(ConfigError) as info:
        platform_from_dict(data, "windmoor12.yaml")
    assert str(info.value) == "windmoor12.yaml: members[2].diameter_m: must be a positive number, got -1"


def test_bad_yaml_syntax(tmp_path: Path) -> None:
    """Oracle: a YAML parse error is a ConfigError naming the file, not a yaml.YAMLError."""
    path = tmp_path / "broken.yaml"
    path.write_text("name: broken\nmembers: [1, 2\nmass: {mass_kg: 1\n")
    with pytest.raises(ConfigError) as info:
        load_platform(path)
    message = str(info.value)
    assert re.match(rf"{re.escape(str(path))}(:\d+:\d+)?: not valid YAML", message), message
    assert ":3:" in message or "line 3" in message  # the parser's position (line 3) is passed on
    assert_clean(info.value)


def test_yaml_not_a_mapping(tmp_path: Path) -> None:
    """Oracle: a document that is a list, not a mapping, is named as such."""
    path = tmp_path / "list.yaml"
    path.write_text("- 1\n- 2\n")
    with pytest.raises(ConfigError, match=r"list\.yaml: expected a mapping, got list"):
        load_platform(path)


def test_unknown_platform_name() -> None:
    """Oracle: neither a file nor a packaged platform -> ConfigError listing the packaged ones."""
    with pytest.raises(ConfigError) as info:
        load_platform("windmoor99")
    assert "'windmoor99'" in str(info.value) and "windmoor12" in str(info.value)
    assert_clean(info.value)


# --------------------------------------------------------------------------- sea state and run
def test_sea_state_from_dict_defaults_and_band() -> None:
    """Oracle: the documented defaults (gamma 1, jonswap, heading 0, seed 1, band 0.5 fp .. 5 fp)."""
    sea = sea_state_from_dict({"hs_m": 3.74, "tp_s": 9.0})
    assert sea == SeaState(3.74, 9.0)
    assert (sea.gamma, sea.spectrum, sea.heading_deg, sea.seed) == (1.0, "jonswap", 0.0, 1)
    assert sea.band_hz == pytest.approx((0.5 / 9.0, 5.0 / 9.0))
    sea = sea_state_from_dict({"hs_m": 3.74, "tp_s": 9.0, "f_min_hz": 0.02, "f_max_hz": 0.3, "seed": 5,
                               "repeat_period_s": 7200})
    assert sea.band_hz == (0.02, 0.3) and sea.seed == 5 and sea.repeat_period_s == 7200.0


@pytest.mark.parametrize("data, pattern", [
    ({"hs_m": 3.0}, r"^sea_state: tp_s: missing$"),
    ({"hs_m": 3.0, "tp_s": -9.0}, r"^sea_state: tp_s: must be a positive number, got -9$"),
    ({"hs_m": 3.0, "tp_s": 9.0, "gama": 3.3}, r"^sea_state: unknown field\(s\) gama$"),
    ({"hs_m": "big", "tp_s": 9.0}, r"^sea_state: hs_m: must be a number, got 'big'$"),
    ({"hs_m": 3.0, "tp_s": 9.0, "spectrum": "ochi"}, r"^sea_state: spectrum: must be one of jonswap, "
                                                     r"pierson_moskowitz, got 'ochi'$"),
    ({"hs_m": 3.0, "tp_s": 9.0, "f_min_hz": 0.3, "f_max_hz": 0.2}, r"^sea_state: f_min_hz \(0\.3\) must be "
                                                                   r"below f_max_hz \(0\.2\)$"),
])
def test_bad_sea_state(data: dict, pattern: str) -> None:
    """Oracle: the documented '<source>: <field>: <problem>' messages for sea states."""
    with pytest.raises(ConfigError, match=pattern) as info:
        sea_state_from_dict(data)
    assert_clean(info.value)


def test_run_from_dict() -> None:
    """Oracle: RunConfig defaults, and field-naming errors for a bad drag model and state size."""
    run = run_from_dict({})
    assert (run.dt_s, run.duration_s, run.drag_model, run.initial_state) == (0.05, 600.0, "constant", (0.0,) * 6)
    assert run_from_dict({"dt_s": 0.02, "drag_model": "filtered"}).dt_s == 0.02
    with pytest.raises(ConfigError, match=r"^run: drag_model: must be one of constant, filtered, got 'smart'$"):
        run_from_dict({"drag_model": "smart"})
    with pytest.raises(ConfigError, match=r"^run: initial_state: must be a list of 6 numbers"):
        run_from_dict({"initial_state": [0.0, 1.0]})
    with pytest.raises(ConfigError, match=r"^run: dt_s: must be a positive number, got 0$"):
        run_from_dict({"dt_s": 0})
    with pytest.raises(ConfigError, match=r"^run: expected a mapping, got list$"):
        run_from_dict([1, 2])
