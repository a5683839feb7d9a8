"""The coupled system against RAFT (the named system iea15_volturnus_s in the offline loop;
RAFT 2.0.4's frequency-domain response of its own VolturnUS-S + IEA-15 design, stored in
test/data/raft/ by benchmarks/raft_comparison.py, which has the three conditions x 3 seeds x
1 h): one condition, above rated, one seed of 20 minutes after a 10-minute transient; the
surge, heave and pitch means and STDs against RAFT's.

The tolerance, fixed before the run was compared: the requirement's 15 % of RAFT's value,
plus for the STDs the sampling error of one 20-minute record, twice the relative standard
error of an STD estimated from n independent cycles, 2 / sqrt(2 n), with n the record's
length over the DOF's dominant period: the surge mode's for surge (106 s, 0.0094 Hz, the
loop's free decay at 13 m/s in docs/validation.md; 118 s at 19 m/s: the shorter period, the
smaller allowance, is taken), the sea's peak period (12 s) for heave and pitch.
Surge STD within 15 % + 57 %, heave and pitch STDs within 15 % + 29 %, means within 15 %.
RAFT loads its tower only under water: the loop runs without the wind's drag on the tower here
(with it, the surge mean is 15.3 % above RAFT's at 18 m/s)."""
from __future__ import annotations

import math

import numpy as np
import pytest
import yaml

from fowt_hydro_sim.testing import REPO

pytest.importorskip("rosco")

pytestmark = [pytest.mark.rosco, pytest.mark.reference, pytest.mark.slow]

RESPONSE = REPO / "test" / "data" / "raft" / "raft_response.yaml"
CONDITION = "above rated"  # 18 m/s, JONSWAP Hs 6 m, Tp 12 s, gamma 3.3
SEED, TRANSIENT_S, RECORD_S = 1, 600.0, 1200.0
TOLERANCE = 0.15
DOMINANT_PERIOD_S = {"surge": 106.0, "heave": 12.0, "pitch": 12.0}
# where the loop and RAFT part by more than the tolerance: the reasons (docs/validation.md, against RAFT)
GAPS = {
    ("heave", "mean"): "the model's VolturnUS-S rests 0.35 m deeper than OpenFAST's (its platform file's mass "
                       "balance, docs/validation.md); RAFT's design, its hull's steel and ballast of its own, "
                       "floats 0.18 m high",
    ("pitch", "mean"): "the model's VolturnUS-S rests pitched -1.45 deg without wind (the ElastoDyn rotor and "
                       "nacelle mass upwind of the tower); RAFT's design puts the RNA's mass on the tower's axis "
                       "(xCG_RNA 0) and rests at 0.00 deg: from each one's rest, ours +2.86, RAFT +2.87 deg at 18 m/s",
    ("pitch", "std"): "ours is 37 % above RAFT's, in the wave band (benchmarks/raft_comparison.py: above half the "
                      "peak frequency ours 0.338 deg against RAFT's 0.264 over 3 h): RAFT's hull is strip theory "
                      "(Morison, Ca 1, CaEnd 0.6, drag linearised), ours the BEM's potential flow with quadratic "
                      "drag; its pitch stiffness 2986 MN m/rad, ours 2750 (docs/validation.md, against RAFT)",
}


def sampling_allowance(dof: str) -> float:
    """Twice the relative standard error of an STD from a RECORD_S record of the DOF's dominant period."""
    return 2.0 / math.sqrt(2.0 * RECORD_S / DOMINANT_PERIOD_S[dof])


@pytest.fixture(scope="module")
def raft() -> dict:
    return yaml.safe_load(RESPONSE.read_text())


@pytest.fixture(scope="module")
def ours(raft: dict, tmp_path_factory) -> dict[str, float]:
    from fowt_hydro_sim.physics.config import RunConfig, SeaState, load_platform
    from fowt_hydro_sim.physics.model import RunResult
    from fowt_hydro_sim.physics.waves.components import synthesize
    from fowt_hydro_sim.studies.simulate import model_for
    from fowt_hydro_sim.turbine.coupled import run_coupled, static_offset, turbine_on_platform
    from fowt_hydro_sim.turbine.system import load_system
    from fowt_hydro_sim.turbine.wind import Wind

    case = raft["cases"][CONDITION]
    system = load_system("iea15_volturnus_s")
    platform = load_platform(system.platform)
    run = RunConfig(platform=system.platform, mooring=system.mooring, duration_s=TRANSIENT_S + RECORD_S)
    sea = SeaState(hs_m=case["hs_m"], tp_s=case["tp_s"], gamma=case["gamma"], seed=SEED)
    model = model_for(platform, run, synthesize(sea, 3600.0))
    from fowt_hydro_sim.testing.references import turbine_without_tower_drag

    turbine = str(turbine_without_tower_drag(system.turbine, tmp_path_factory.mktemp("turbine")))
    rotor = turbine_on_platform(turbine, platform, Wind(speed_m_s=case["wind_speed_m_s"]))
    try:
        model.reset(motion=static_offset(model, rotor))
        result = RunResult.joined([p.result for p in run_coupled(model, rotor, run.duration_s, run.output_interval_s)])
    finally:
        rotor.close()
    keep = result.time_s >= TRANSIENT_S
    out = {}
    for dof, i, scale in (("surge", 0, 1.0), ("heave", 2, 1.0), ("pitch", 4, 180.0 / np.pi)):
        x = result.motion[keep, i] * scale
        out[f"{dof}_mean"], out[f"{dof}_std"] = float(x.mean()), float(x.std())
    return out


def test_the_stored_response_names_its_code_and_input(raft: dict):
    """RAFT's numbers carry their provenance: RAFT's version, its input, the command."""
    provenance = raft["provenance"]
    assert provenance["code"] == "RAFT (openraft 2.0.4)"
    assert "volturnus_s_raft_design.yaml" in provenance["design"] and "sha256" in provenance["design"]
    assert provenance["command"] == "python benchmarks/raft_comparison.py --run-raft"
    assert set(raft["cases"]) == {"below rated", "at rated", "above rated"}


@pytest.mark.parametrize("dof,stat", [
    pytest.param(dof, stat, marks=pytest.mark.xfail(reason=GAPS[dof, stat], strict=True)) if (dof, stat) in GAPS
    else (dof, stat) for dof in ("surge", "heave", "pitch") for stat in ("mean", "std")])
def test_motion_against_raft_above_rated(raft: dict, ours: dict[str, float], dof: str, stat: str):
    """Surge, heave, pitch mean and STD above rated within the tolerance of RAFT's."""
    ref, mine = raft["cases"][CONDITION][f"{dof}_{stat}"], ours[f"{dof}_{stat}"]
    tolerance = TOLERANCE + (sampling_allowance(dof) if stat == "std" else 0.0)
    assert abs(mine - ref) <= tolerance * abs(ref), (
        f"{dof} {stat}: ours {mine:.4g}, RAFT {ref:.4g} ({100 * (mine - ref) / abs(ref):+.1f} %, "
        f"tolerance {100 * tolerance:.0f} %)")
