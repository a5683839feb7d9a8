"""NREL's ROSCO, the compiled controller shipped in the rosco wheel, called through its own
Python interface (``rosco.toolbox.control_interface.ControllerInterface``).

ROSCO keeps its state in the library's globals: one controller per process. It reads its
DISCON.IN and writes its debug files under a folder of its own (a copy of the DISCON.IN
with the performance table's path made absolute, debug output off unless asked)."""
from __future__ import annotations

import math
import re
import tempfile
from pathlib import Path

from fowt_hydro_sim.physics.config import ConfigError


class ControllerError(RuntimeError):
    """ROSCO reported an error (its message is in the text)."""


def discon_copy(source: Path, folder: Path, logging_level: int = 0) -> Path:
    """DISCON.IN in ``folder``: its PerfFileName made absolute, its LoggingLevel set."""
    try:
        text = source.read_text()
    except OSError as exc:
        raise ConfigError(f"DISCON file {source}: cannot be read ({exc.strerror})") from None

    def absolute(match: re.Match) -> str:
        path = Path(match.group(1))
        return f'"{path if path.is_absolute() else (source.parent / path).resolve()}"{match.group(2)}'

    text = re.sub(r'^\s*"([^"]*)"(\s+!\s*PerfFileName)', absolute, text, flags=re.M)
    text = re.sub(r"^\s*\d+(\s+!\s*LoggingLevel)", rf"{logging_level}\1", text, flags=re.M)
    target = folder / "DISCON.IN"
    target.write_text(text)
    return target


class Rosco:
    """One ROSCO instance: ``step`` passes the turbine's measurements and returns the
    generator torque [N m] and collective blade pitch [rad] it commands."""

    def __init__(self, discon: Path, dt_s: float, generator_efficiency: float, logging_level: int = 0,
                 pitch_rad: float = 0.0):
        from rosco import discon_lib_path
        from rosco.toolbox.control_interface import ControllerInterface

        self._folder = tempfile.TemporaryDirectory(prefix="fowt_rosco_")
        folder = Path(self._folder.name)
        param = discon_copy(Path(discon), folder, logging_level)
        self.dt_s, self._efficiency = dt_s, generator_efficiency
        self._interface = ControllerInterface(discon_lib_path, param_filename=str(param),
                                              sim_name=str(folder / "rosco"), DT=dt_s,
                                              pitch=math.degrees(pitch_rad))  # its integrators start there
        self._check("starting")  # the interface swallows a failed start: ask the library

    def _check(self, when: str) -> None:
        fail = self._interface.aviFAIL.value
        if fail < 0:
            message = self._interface.avcMSG.value.decode(errors="replace").strip() or "no message"
            raise ControllerError(f"ROSCO failed {when}: {message}")

    def step(self, t_s: float, wind_m_s: float, rotor_speed_rad_s: float, generator_speed_rad_s: float,
             pitch_rad: float, generator_torque_nm: float, pitch_acceleration_rad_s2: float = 0.0,
             last: bool = False) -> tuple[float, float]:
        """One controller call (``iStatus`` 1, or -1 for the last); ControllerError if ROSCO fails."""
        state = {"iStatus": -1 if last else 1, "t": t_s, "dt": self.dt_s, "ws": wind_m_s,
                 "bld_pitch": pitch_rad, "gen_torque": generator_torque_nm, "gen_speed": generator_speed_rad_s,
                 "gen_eff": self._efficiency, "rot_speed": rotor_speed_rad_s, "Yaw_fromNorth": 0.0,
                 "Y_MeasErr": 0.0, "NacIMU_FA_RAcc": pitch_acceleration_rad_s2}
        torque, pitch, _ = self._interface.call_controller(state)
        self._check(f"at t = {t_s:.3f} s")
        return float(torque), float(pitch)

    def close(self) -> None:
        self._folder.cleanup()
