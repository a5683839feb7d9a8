"""A controller library with the Bladed-style DISCON interface (NREL's ROSCO among them),
called through its C entry point with ctypes.

``DISCON(float *avrSWAP, int *aviFAIL, char *accINFILE, char *avcOUTNAME, char *avcMSG)``
exchanges every measurement and command through one single-precision swap array; the
indices below are those of the Bladed convention, counted from zero here (the Fortran
record k is ``swap[k - 1]``). Only ``ctypes`` and numpy are needed: the library's Python
toolbox (and the design tools it imports) is not.

The library keeps its state in globals: one controller per library per process.
"""
from __future__ import annotations

import contextlib
import ctypes
import logging
import os
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path

import numpy as np

log = logging.getLogger(__name__)

SWAP_SIZE = 500
MESSAGE_SIZE = 1000

# swap-array records (Bladed numbering minus one)
STATUS = 0  # 0 first call, 1 running, -1 last call
TIME_S = 1
STEP_S = 2
PITCH_1_RAD = 3
POWER_W = 14
MEASURED_TORQUE_NM = 22
GENERATOR_SPEED_RAD_S = 19
ROTOR_SPEED_RAD_S = 20
YAW_ERROR_RAD = 23
WIND_SPEED_M_S = 26
INDIVIDUAL_PITCH = 27
PITCH_2_RAD = 32
PITCH_3_RAD = 33
NACELLE_HEADING_RAD = 36
DEMANDED_PITCH_RAD = 41
DEMANDED_TORQUE_NM = 46
DEMANDED_YAW_RATE_RAD_S = 47
MESSAGE_LENGTH = 48
INFILE_LENGTH = 49
OUTNAME_LENGTH = 50
TOWER_TOP_FORE_AFT_ACCELERATION_M_S2 = 52
BLADE_COUNT = 60
NACELLE_FORE_AFT_ANGULAR_ACCELERATION_RAD_S2 = 82


class ControllerError(RuntimeError):
    """The controller library reported a failure (its message is in the text)."""


class Discon:
    """One controller library, started with its parameter file ``infile`` at step ``dt_s``.

    ``call`` sets the measurements, calls the library and returns the demanded generator
    torque [N m], collective pitch [rad] and yaw rate [rad/s]; a failure the library reports
    raises ControllerError with its message, the controller named by ``name``."""

    def __init__(self, library: Path | str, infile: Path | str, outname: str, dt_s: float,
                 pitch_rad: float = 0.0, blades: int = 3, name: str = "the controller"):
        self.name = name
        self._library = ctypes.CDLL(str(library))
        self._library.DISCON.argtypes = [ctypes.POINTER(ctypes.c_float), ctypes.POINTER(ctypes.c_int32),
                                         ctypes.c_char_p, ctypes.c_char_p, ctypes.c_char_p]
        self._library.DISCON.restype = None
        self.swap = np.zeros(SWAP_SIZE, dtype=np.float32)
        self._swap_pointer = self.swap.ctypes.data_as(ctypes.POINTER(ctypes.c_float))  # made once: every call
        self._fail = ctypes.c_int32()
        self._infile = str(infile).encode()
        self._outname = outname.encode()
        self._message = ctypes.create_string_buffer(MESSAGE_SIZE)
        s = self.swap
        s[STEP_S], s[BLADE_COUNT] = dt_s, blades
        # the state before the first call: the library's filters and integrators start from it
        s[GENERATOR_SPEED_RAD_S] = s[ROTOR_SPEED_RAD_S] = 1.0
        s[WIND_SPEED_M_S] = 10.0
        s[PITCH_1_RAD] = s[PITCH_2_RAD] = s[PITCH_3_RAD] = pitch_rad
        s[INDIVIDUAL_PITCH] = 1
        s[MESSAGE_LENGTH], s[INFILE_LENGTH] = MESSAGE_SIZE // 2, len(self._infile)
        s[OUTNAME_LENGTH], s[51] = len(self._outname), MESSAGE_SIZE // 2
        s[STATUS] = 0
        self.finished = False  # the last call (status -1) made: the library closed its files
        with _standard_output_logged(f"{self.name} at start-up"):  # (ROSCO's banner: not the command's output)
            self._call("starting")

    @property
    def message(self) -> str:
        """The library's last message (empty if none)."""
        return self._message.value.decode(errors="replace").strip()

    def _call(self, when: str) -> None:
        self._library.DISCON(self._swap_pointer, ctypes.byref(self._fail), self._infile, self._outname,
                             self._message)
        if self._fail.value < 0:
            raise ControllerError(f"{self.name} failed {when}: {self.message or 'no message'}")

    def call(self, t_s: float, wind_m_s: float, rotor_speed_rad_s: float, generator_speed_rad_s: float,
             pitch_rad: float, generator_torque_nm: float, generator_efficiency: float,
             nacelle_angular_acceleration_rad_s2: float = 0.0, tower_top_acceleration_m_s2: float = 0.0,
             last: bool = False) -> tuple[float, float, float]:
        """One controller step (status 1, or -1 for the last call)."""
        s = self.swap
        s[STATUS], s[TIME_S] = -1 if last else 1, t_s
        s[PITCH_1_RAD] = s[PITCH_2_RAD] = s[PITCH_3_RAD] = pitch_rad
        s[POWER_W] = generator_speed_rad_s * generator_torque_nm * generator_efficiency
        s[MEASURED_TORQUE_NM] = generator_torque_nm
        s[GENERATOR_SPEED_RAD_S], s[ROTOR_SPEED_RAD_S] = generator_speed_rad_s, rotor_speed_rad_s
        s[YAW_ERROR_RAD], s[WIND_SPEED_M_S], s[NACELLE_HEADING_RAD] = 0.0, wind_m_s, 0.0
        s[NACELLE_FORE_AFT_ANGULAR_ACCELERATION_RAD_S2] = nacelle_angular_acceleration_rad_s2
        s[TOWER_TOP_FORE_AFT_ACCELERATION_M_S2] = tower_top_acceleration_m_s2
        self._call(f"at t = {t_s:.3f} s")
        self.finished = last
        return float(s[DEMANDED_TORQUE_NM]), float(s[DEMANDED_PITCH_RAD]), float(s[DEMANDED_YAW_RATE_RAD_S])

    def finish(self) -> None:
        """The last call (status -1) with the last measurements, if not made yet: the library
        ends its run (ROSCO closes its debug files)."""
        if not self.finished:
            self.swap[STATUS] = -1
            self.finished = True
            self._call(f"finishing at t = {float(self.swap[TIME_S]):.3f} s")


@contextlib.contextmanager
def _standard_output_logged(source: str) -> Iterator[None]:
    """What a library writes on the process's standard output (file descriptor 1) inside the
    block goes to the log instead: its lines that say error or warning as a warning, the rest
    (a banner) at debug level."""
    sys.stdout.flush()
    saved = os.dup(1)
    with tempfile.TemporaryFile() as captured:
        os.dup2(captured.fileno(), 1)
        try:
            yield
        finally:
            os.dup2(saved, 1)
            os.close(saved)
            captured.seek(0)
            for line in captured.read().decode(errors="replace").splitlines():
                if line.strip():
                    alarm = any(word in line.lower() for word in ("error", "warning"))
                    log.log(logging.WARNING if alarm else logging.DEBUG, f"{source}: {line.strip()}")
