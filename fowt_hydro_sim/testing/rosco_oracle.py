"""ROSCO's own 1-DOF simulator (``rosco.toolbox.sim.Sim``) on a packaged turbine: the
oracle of the turbine model. Run as a script in a child process (ROSCO keeps its state in
the library's globals, one controller per process); writes JSON trajectories to OUT:

    python -m fowt_hydro_sim.testing.rosco_oracle OUT TURBINE DT_S DURATION_S STEP_S FROM TO RPM0
"""
from __future__ import annotations

import json
import sys
import tempfile
import types
from pathlib import Path

import numpy as np


def simulate(turbine_name: str, dt_s: float, duration_s: float, step_s: float, from_m_s: float, to_m_s: float,
             rotor_rpm: float) -> dict[str, list[float]]:
    from rosco import discon_lib_path
    from rosco.toolbox.control_interface import ControllerInterface
    from rosco.toolbox.sim import Sim
    from rosco.toolbox.turbine import RotorPerformance
    from rosco.toolbox.utilities import load_from_txt

    from fowt_hydro_sim.turbine.description import load_turbine
    from fowt_hydro_sim.turbine.rosco import discon_copy

    d = load_turbine(turbine_name)
    pitch, tsr, cp, _, cq = load_from_txt(str(d.performance_path))
    turbine = types.SimpleNamespace(rotor_radius=d.rotor_radius_m, Ng=d.gearbox_ratio, J=d.drivetrain_inertia_kg_m2,
                                    rho=d.air_density_kg_m3, GBoxEff=100 * d.gearbox_efficiency,
                                    GenEff=100 * d.generator_efficiency, Cp=RotorPerformance(cp, pitch, tsr),
                                    Cq=RotorPerformance(cq, pitch, tsr))
    with tempfile.TemporaryDirectory() as folder:
        param = discon_copy(d.discon_path, Path(folder))
        interface = ControllerInterface(discon_lib_path, param_filename=str(param), sim_name=f"{folder}/oracle",
                                        DT=dt_s)
        t = np.arange(0.0, duration_s + dt_s / 2, dt_s)
        wind = np.where(t < step_s, from_m_s, to_m_s)
        sim = Sim(turbine, interface)
        sim.sim_ws_series(t, wind, rotor_rpm_init=rotor_rpm, make_plots=False)
    return {"time_s": t.tolist(), "rotor_speed_rad_s": sim.rot_speed.tolist(),
            "pitch_rad": sim.bld_pitch.tolist(), "generator_torque_nm": sim.gen_torque.tolist()}


def in_child_process(folder: Path, turbine_name: str, dt_s: float, duration_s: float, step_s: float,
                     from_m_s: float, to_m_s: float, rotor_rpm: float) -> dict[str, np.ndarray]:
    """``simulate`` run as this script in a child process (a fresh ROSCO), its trajectories as arrays."""
    import subprocess

    from fowt_hydro_sim.testing import REPO
    out = Path(folder) / "oracle.json"
    done = subprocess.run([sys.executable, "-m", "fowt_hydro_sim.testing.rosco_oracle", str(out), turbine_name,
                           *(str(v) for v in (dt_s, duration_s, step_s, from_m_s, to_m_s, rotor_rpm))], cwd=REPO,
                          capture_output=True, text=True, timeout=300)
    if done.returncode != 0:
        raise RuntimeError(f"ROSCO's simulator failed: {done.stderr[-2000:]}")
    return {k: np.array(v) for k, v in json.loads(out.read_text()).items()}


if __name__ == "__main__":
    out, name, *numbers = sys.argv[1:]
    Path(out).write_text(json.dumps(simulate(name, *map(float, numbers))))
