"""``fowt-sim stability``: the surge and pitch modes with the rotor and its controller."""
from __future__ import annotations

import math
import re

import numpy as np
import pytest

from fowt_hydro_sim.studies.stability import era_modes, pick
from fowt_hydro_sim.testing import fowt_sim


def test_the_identification_finds_two_damped_modes():
    """Two damped sinusoids (100 s at 3 %, 28 s at 15 %) on two channels, an offset: the
    realisation gives their frequencies and damping ratios (closed form)."""
    t = np.arange(0.0, 600.0, 0.5)
    modes = [(0.01, 0.03), (1 / 28, 0.15)]
    response = np.zeros((t.size, 2))
    for j, (f, zeta) in enumerate(modes):
        w = 2 * math.pi * f
        wave = np.exp(-zeta * w * t) * np.cos(w * math.sqrt(1 - zeta ** 2) * t)
        response[:, 0] += wave * (1.0 if j == 0 else 0.2)
        response[:, 1] += wave * (0.1 if j == 0 else 1.0)
    response += np.array([5.0, -1.0])
    found = era_modes(t, response)
    surge, pitch = pick(found, (0.003, 0.02), 0), pick(found, (0.02, 0.08), 1)
    assert surge.frequency_hz == pytest.approx(0.01 * math.sqrt(1 - 0.03 ** 2), rel=1e-3)
    assert surge.damping_ratio == pytest.approx(0.03, abs=1e-3)
    assert pitch.frequency_hz == pytest.approx(math.sqrt(1 - 0.15 ** 2) / 28, rel=1e-3)
    assert pitch.damping_ratio == pytest.approx(0.15, abs=2e-3)


@pytest.mark.slow
@pytest.mark.rosco
def test_windmoor12_with_the_15_mw_rotor_shows_its_negative_surge_damping():
    """The assembly the closed loop ran before (WINDMOOR 12 MW hull, IEA 15 MW rotor with
    ROSCO's UMaineSemi tuning) at 13 m/s: the surge mode with ROSCO is negatively damped,
    the quasi-steady aerodynamic damping with the controller's response about -5 % of
    critical (the surge swing's growth seen in its 600 s closed loop: 9.5 -> 15.8 m in 4
    cycles, about -2 % per cycle of logarithmic growth, with the hull's drag at that
    amplitude), and the command says so."""
    done = fowt_sim("stability", "--platform", "windmoor12", "--wind-speed", "13", "--duration", "600")
    assert done.returncode == 0, done.stderr
    surge = re.search(r"^surge\s+([\d.]+) s\s+([-+\d.]+) %\s+([\d.]+) s\s+([-+\d.]+) %\s+([\d.]+) s\s+([-+\d.]+) %"
                      r"\s+([-+\d.]+) % / ([-+\d.]+) %", done.stdout, flags=re.M)
    assert surge, done.stdout
    alone, held, rosco, aero_controlled = (float(surge.group(i)) for i in (2, 4, 6, 8))
    assert 90.0 < float(surge.group(1)) < 105.0  # the 97 s surge mode
    assert rosco < 0 < alone < held
    assert -7.0 < aero_controlled < -4.0
    assert "the surge mode is negatively damped with the controller" in done.stdout


@pytest.mark.slow
@pytest.mark.parametrize("args, line", [
    (("--wind-speed", "0", "13"), "--wind-speed: each must be above 0 and at most 80 m/s, got 0 13"),
    (("--duration", "50"), "--duration: at least 200 s (two surge periods), got 50"),
    (("--system", "iea15_volturnus_s", "--turbine", "mine.yaml"),
     "system iea15_volturnus_s sets turbine 'iea15_umaine'; turbine 'mine.yaml' was given too"),
])
def test_bad_input_is_one_line(args, line):
    done = fowt_sim("stability", *args)
    assert done.returncode == 2
    assert done.stderr.strip().splitlines() == [f"fowt-sim stability: error: {line}"]
