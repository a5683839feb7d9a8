"""The diagnosis's candidates that scale a term the model already has, against closed forms:
the heave period of a restoring scaled by s is the plain model's / sqrt(s); a slow-drift
table scaled by s moves the mean surge offset by s times the plain drift's; the drag scale
scales every Cd, keeps the drag's form, and moves the slow surge smoothly and the right way."""
from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.signal

from fowt_hydro_sim.physics.config import SeaState, load_platform
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.waves.components import synthesize
from fowt_hydro_sim.studies.diagnosis.effects import CATALOGUE
from fowt_hydro_sim.studies.replay import MeasuredRun, Variant

HEAVE, PITCH = 2, 4


@pytest.fixture(scope="module")
def platform():
    return load_platform("windmoor12")


@pytest.fixture(scope="module")
def stub() -> MeasuredRun:
    t = np.arange(0.0, 100.0, 0.1)
    return MeasuredRun("r", t, np.sin(t), (0.0, 0.0), t, np.zeros((t.size, 6)))


def _period(variant: Variant, dof: int, offset: float) -> float:
    model = PlatformModel(variant.platform, None, dt_s=0.05, extension=variant.extension)
    start = np.zeros(6)
    start[dof] = offset
    model.reset(motion=start)
    result = model.run(150.0, output_interval_s=0.05)
    x = result.motion[:, dof] - result.motion[-600:, dof].mean()
    peaks, _ = scipy.signal.find_peaks(x)
    return float(np.mean(np.diff(result.time_s[peaks][:4])))


@pytest.mark.slow
def test_a_scaled_restoring_changes_the_heave_and_pitch_periods_as_one_over_its_root(platform, stub):
    effect = CATALOGUE["model_restoring"]
    plain = Variant(platform)
    stiffer = effect.apply(plain, stub, {"heave_restoring_scale": 1.2, "pitch_restoring_scale": 0.9})
    assert _period(stiffer, HEAVE, 0.5) / _period(plain, HEAVE, 0.5) == pytest.approx(1 / math.sqrt(1.2), rel=0.01)
    assert _period(stiffer, PITCH, 0.02) / _period(plain, PITCH, 0.02) == pytest.approx(1 / math.sqrt(0.9), rel=0.01)


@pytest.mark.slow
def test_a_scaled_slow_drift_table_scales_the_mean_drift_offset(platform, stub):
    """In an irregular sea the mean surge offset from the slow drift is proportional to the
    drift table (linear spring lines): the offset at scale 2 minus the drift-free one is
    twice the plain model's."""
    effect = CATALOGUE["model_slow_drift"]
    waves = synthesize(SeaState(6.19, 9.0, 4.9, seed=3), 1200.0)

    def mean_surge(scale: float) -> float:
        variant = effect.apply(Variant(platform), stub, {"drift_scale": scale})
        result = PlatformModel(variant.platform, waves, dt_s=0.1).run(1200.0, output_interval_s=0.5)
        return float(result.motion[result.time_s > 300.0, 0].mean())

    none, plain, double = mean_surge(0.0), mean_surge(1.0), mean_surge(2.0)
    assert plain - none > 0.2  # a drift of some metres' worth, not noise
    assert (double - none) / (plain - none) == pytest.approx(2.0, rel=0.03)


def test_the_drag_scale_scales_every_cd_and_keeps_the_drags_form(platform, stub):
    varied = CATALOGUE["model_drag"].apply(Variant(platform), stub, {"cd_scale": 1.3})
    assert varied.drag_model == "constant"
    for member, changed in zip(platform.members, varied.platform.members):
        for zone, new in zip(member.zones, changed.zones):
            for cd, cd_new in zip(zone.cd, new.cd):
                assert cd_new.constant == pytest.approx(1.3 * cd.constant)
                if cd.bands is not None:
                    assert cd_new.bands == pytest.approx(tuple(1.3 * c for c in cd.bands))


@pytest.mark.slow
def test_the_slow_surge_moves_smoothly_with_the_drag_scale_and_the_right_way(platform, stub):
    """The constant-Cd drag damps the slow surge through the waves' velocity in |v| (by the
    equivalent linearisation 2 E|u| v: a damping proportional to Cd), so the surge
    low-frequency STD falls as the scale rises, and a scale of 0.99 or 1.01 leaves it within
    2 % of the plain model's. A band split at equal band Cds doubled it (1.9 m to 3.8 m)."""
    effect = CATALOGUE["model_drag"]
    waves = synthesize(SeaState(6.19, 9.0, 4.9, seed=3), 1800.0)
    low_pass = scipy.signal.butter(4, 0.05, fs=2.0)

    def slow_surge_std(scale: float) -> float:
        variant = effect.apply(Variant(platform), stub, {"cd_scale": scale})
        result = PlatformModel(variant.platform, waves, dt_s=0.1, drag_model=variant.drag_model).run(
            1800.0, output_interval_s=0.5)
        surge = result.motion[result.time_s > 300.0, 0]
        return float(np.std(scipy.signal.filtfilt(*low_pass, surge - surge.mean())))

    stds = {scale: slow_surge_std(scale) for scale in (0.8, 0.99, 1.0, 1.01, 1.3)}
    assert stds[0.99] == pytest.approx(stds[1.0], rel=0.02) and stds[1.01] == pytest.approx(stds[1.0], rel=0.02)
    assert stds[0.8] > stds[0.99] > stds[1.0] > stds[1.01] > stds[1.3]
