"""OpenFAST SeaState input files as wave components: the first-order sea SeaState synthesises
for a deck, component by component, so that a HydroDyn case can be rerun on the same waves.

For WaveMod 1 (regular), 1P# (regular, phase given), 2 (JONSWAP / Pierson-Moskowitz) and 3
(white noise) SeaState draws each frequency's phase (and, with WaveNDAmp, its amplitude) from
its RANLUX generator (``WaveSeed(2)`` = ``RANLUX``, seeded with ``WaveSeed(1)``, luxury level
3: the NWTC library's ``Ran_Lux_Mod``, F. James's RANLUX in single precision steps of 2^-24,
reproduced exactly here). Frequencies are the harmonics i of 1 / WaveTMax, WaveTMax rounded up
to NStepWave WaveDT with NStepWave / 2 a product of primes up to 23; for every i from 1 to
NStepWave / 2 - 1 two uniform numbers are drawn (Box-Muller: U1, then U2, the phase
2 pi U2), whether or not the frequency lies inside the cut-offs [WvLowCOff, WvHiCOff]. A
component's amplitude is sqrt(2 S(w) dw) (times sqrt(-ln U1) with WaveNDAmp), its phase the
drawn one, in SeaState's convention eta = sum a cos(w t - k s + phase) (``components.py``).
WaveMod 7 reads the file WvKinFile names (``.Comp``), inside the cut-offs.

Refused, in one line naming the field: WaveMod 4, 5, 6 (a user spectrum routine, an elevation
record, full kinematics), ``WaveSeed(2)`` other than RANLUX (the Fortran compiler's intrinsic
generator, which depends on the compiler) unless the wave is 1P# (its phase given, its amplitude
Hs / 2: the draws are not used), WaveDirMod 1 with more than one direction (the
directions' random assignment is not reproduced), ConstWaveMod (constrained waves),
WvDiffQTF / WvSumQTF (second-order waves) and CurrMod (current).

``python -m fowt_hydro_sim.physics.waves.seastate SEASTATE.dat -o waves.Comp`` writes the
components as a ``.Comp`` file for ``fowt-sim loads --waves-comp``.
"""
from __future__ import annotations

import argparse
import logging
import math
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fowt_hydro_sim.physics.config import ConfigError
from fowt_hydro_sim.physics.waves.components import WaveComponents, read_comp_file, write_comp_file

log = logging.getLogger(__name__)

_FIELDS_FLOAT = ("WaveTMax", "WaveDT", "WaveHs", "WaveTp", "WvLowCOff", "WvHiCOff", "WaveDir", "MCFD",
                 "X_HalfWidth", "Y_HalfWidth", "Z_Depth")
_FIELDS_INT = ("WaveStMod", "WaveDirMod", "WaveNDir", "ConstWaveMod", "CurrMod", "NX", "NY", "NZ")


class RanLux:
    """F. James's RANLUX (subtract-with-borrow with Luescher's skipping), as the NWTC library's
    ``Ran_Lux_Mod`` implements it: ``RLuxGo(lux, seed, 0, 0)``, then one number per ``next()``
    (small numbers padded, zero replaced, as there). Every value is a multiple of 2^-24 or
    2^-48, so double precision reproduces the Fortran values exactly."""

    _SKIP = (0, 24, 73, 199, 365)

    def __init__(self, seed: int, luxury: int = 3):
        self._skip = self._SKIP[luxury]
        self._two_m24 = 2.0**-24
        self._two_m12 = self._two_m24 * 4096.0
        j = seed if seed > 0 else 314159265
        seeds = [0.0] * 25  # 1-based, as the Fortran array
        for i in range(1, 25):
            k = j // 53668
            j = 40014 * (j - k * 53668) - k * 12211
            if j < 0:
                j += 2147483563
            seeds[i] = (j % 2**24) * self._two_m24
        self._seeds = seeds
        self._i24, self._j24, self._in24 = 24, 10, 0
        self._carry = self._two_m24 if seeds[24] == 0.0 else 0.0
        self._next = [0, 24, *range(1, 24)]

    def _rcarry(self, n: int) -> float:
        seeds, following, i24, j24, carry = self._seeds, self._next, self._i24, self._j24, self._carry
        uni = 0.0
        for _ in range(n):
            uni = seeds[j24] - seeds[i24] - carry
            if uni < 0.0:
                uni += 1.0
                carry = self._two_m24
            else:
                carry = 0.0
            seeds[i24] = uni
            i24, j24 = following[i24], following[j24]
        self._i24, self._j24, self._carry = i24, j24, carry
        return uni

    def next(self) -> float:
        """The next uniform number in (0, 1)."""
        pad = self._two_m24 * self._seeds[self._j24]
        value = self._rcarry(1)
        self._in24 += 1
        if self._in24 == 24:
            self._in24 = 0
            self._rcarry(self._skip)
        if value < self._two_m12:
            value += pad
        return value if value != 0.0 else self._two_m24 * self._two_m24


@dataclass(frozen=True)
class SeaStateInput:
    """The fields of a SeaState input file this module uses, by name (value as written)."""

    path: Path
    fields: dict[str, str]

    def text(self, name: str) -> str:
        """A field's value as written (quotes removed); ConfigError if the file lacks it."""
        if name not in self.fields:
            raise ConfigError(f"{self.path}: no {name} line (not a SeaState input file of a known layout)")
        return self.fields[name]

    def number(self, name: str) -> float:
        """A real field."""
        try:
            return float(self.text(name))
        except ValueError:
            raise ConfigError(f"{self.path}: {name} {self.text(name)!r} is not a number") from None

    def integer(self, name: str) -> int:
        """An integer field."""
        value = self.number(name)
        if value != int(value):
            raise ConfigError(f"{self.path}: {name} {self.text(name)!r} is not an integer")
        return int(value)

    def flag(self, name: str) -> bool:
        """A logical field."""
        value = self.text(name).upper().strip(".")
        if value not in ("TRUE", "FALSE", "T", "F"):
            raise ConfigError(f"{self.path}: {name} {self.text(name)!r} is not TRUE or FALSE")
        return value.startswith("T")


def read_seastate(path: str | Path) -> SeaStateInput:
    """A SeaState input file's ``value NAME - description`` lines."""
    path = Path(path)
    try:
        lines = path.read_text().splitlines()
    except (OSError, UnicodeDecodeError) as exc:
        raise ConfigError(f"{path}: cannot be read ({getattr(exc, 'strerror', None) or exc})") from None
    fields: dict[str, str] = {}
    for line in lines:
        words = line.split()
        if len(words) >= 2 and not words[0].startswith("-"):
            fields.setdefault(words[1], words[0].strip("\"'"))
    if "WaveMod" not in fields:
        raise ConfigError(f"{path}: no WaveMod line (not a SeaState input file)")
    return SeaStateInput(path, fields)


def product_of_small_primes(n: int) -> int:
    """The smallest integer >= n whose prime factors are all at most 23 (the NWTC library's
    PSF with 9 primes)."""
    while True:
        m = n
        for p in (2, 3, 5, 7, 11, 13, 17, 19, 23):
            while m % p == 0:
                m //= p
        if m == 1:
            return n
        n += 1


def _jonswap(omega: np.ndarray, hs: float, tp: float, gamma: float) -> np.ndarray:
    """SeaState's JONSWAP one-sided spectrum S(w) (m^2 s/rad), IEC 61400-3's form."""
    f = omega / (2 * np.pi)
    fp_over_f4 = (1.0 / (tp * f)) ** 4
    sigma = np.where(f <= 1.0 / tp, 0.07, 0.09)
    alpha = np.exp(-0.5 * ((f * tp - 1.0) / sigma) ** 2)
    return (1.0 / (2 * np.pi)) * (1.0 - 0.287 * np.log(gamma)) * (0.3125 * hs * hs * fp_over_f4 / f) \
        * np.exp(-1.25 * fp_over_f4) * gamma**alpha


def _peak_shape(sea: SeaStateInput, hs: float, tp: float) -> float:
    if sea.text("WavePkShp").upper() != "DEFAULT":
        return sea.number("WavePkShp")
    ratio = tp / math.sqrt(hs)
    return 5.0 if ratio <= 3.6 else 1.0 if ratio >= 5.0 else math.exp(5.75 - 1.15 * ratio)


def _wave_mod(sea: SeaStateInput) -> tuple[int, float | None]:
    """WaveMod, and the phase (rad) of ``1P#``."""
    text = sea.text("WaveMod").upper()
    if text.startswith("1P"):
        try:
            return 10, math.radians(float(text[2:]))
        except ValueError:
            raise ConfigError(f"{sea.path}: WaveMod {text!r}: 1P must be followed by a phase in degrees") from None
    return sea.integer("WaveMod"), None


def _refuse_unsupported(sea: SeaStateInput, wave_mod: int) -> None:
    if wave_mod in (4, 5, 6) or wave_mod not in (0, 1, 2, 3, 7, 10):
        raise ConfigError(f"{sea.path}: WaveMod {wave_mod}: only 0, 1, 1P#, 2, 3 and 7 are reproduced "
                          "(4: a user spectrum routine, 5: an elevation record, 6: full kinematics)")
    if wave_mod == 0:
        return
    if "WvDiffQTF" in sea.fields and (sea.flag("WvDiffQTF") or sea.flag("WvSumQTF")):
        raise ConfigError(f"{sea.path}: WvDiffQTF / WvSumQTF: second-order waves are not reproduced")
    if "CurrMod" in sea.fields and sea.integer("CurrMod") != 0:
        raise ConfigError(f"{sea.path}: CurrMod {sea.integer('CurrMod')}: current is not reproduced")
    if wave_mod == 7:
        return
    if wave_mod != 10 and sea.text("WaveSeed(2)").upper() != "RANLUX":  # 1P#: no random number is used
        raise ConfigError(f"{sea.path}: WaveSeed(2) {sea.text('WaveSeed(2)')}: an integer seed selects the "
                          "Fortran compiler's intrinsic generator, which is not reproduced (RANLUX is)")
    if wave_mod == 2 and "ConstWaveMod" in sea.fields and sea.integer("ConstWaveMod") != 0:
        raise ConfigError(f"{sea.path}: ConstWaveMod {sea.integer('ConstWaveMod')}: constrained waves are "
                          "not reproduced")
    if wave_mod in (2, 3) and sea.integer("WaveDirMod") == 1 and sea.integer("WaveNDir") > 1:
        raise ConfigError(f"{sea.path}: WaveDirMod 1 with WaveNDir {sea.integer('WaveNDir')}: the random "
                          "assignment of directions is not reproduced")


def seastate_waves(sea: SeaStateInput) -> WaveComponents | None:
    """The components of the sea the file asks SeaState for (None: still water, WaveMod 0)."""
    wave_mod, phase_given = _wave_mod(sea)
    _refuse_unsupported(sea, wave_mod)
    if wave_mod == 0:
        return None
    low, high = sea.number("WvLowCOff"), sea.number("WvHiCOff")
    if wave_mod == 7:
        waves = read_comp_file(sea.path.parent / sea.text("WvKinFile"), direct_sum=True)
        keep = (2 * np.pi * waves.frequency_hz >= low) & (2 * np.pi * waves.frequency_hz <= high)
        return WaveComponents(waves.frequency_hz[keep], waves.amplitude_m[keep], waves.phase_rad[keep],
                              waves.direction_rad[keep], waves.period_s)
    step_s, hs, tp = sea.number("WaveDT"), sea.number("WaveHs"), sea.number("WaveTp")
    if step_s <= 0 or sea.number("WaveTMax") <= 0:
        raise ConfigError(f"{sea.path}: WaveTMax and WaveDT must be positive")
    n_steps = math.ceil(sea.number("WaveTMax") / step_s)
    n_steps += n_steps % 2
    half = product_of_small_primes(max(n_steps // 2, 1))
    period_s = 2 * half * step_s
    d_omega = 2 * np.pi / period_s
    omega = np.arange(1, half) * d_omega
    random_amplitude = sea.flag("WaveNDAmp") if "WaveNDAmp" in sea.fields else False
    generator = RanLux(abs(sea.integer("WaveSeed(1)")))
    draws = np.array([(generator.next(), generator.next()) for _ in range(half - 1)])
    # the phase as SeaState computes it, TwoPi * U2 in single precision
    phase = (np.float32(2 * np.pi) * draws[:, 1].astype(np.float32)).astype(float)
    if phase_given is not None:
        phase[:] = phase_given
    scale = np.sqrt(-np.log(draws[:, 0])) if random_amplitude else np.ones(half - 1)
    peak = int(round(period_s / tp)) if tp > 0 else -1
    # SeaState compares each frequency with the cut-offs in single precision
    omega32 = np.arange(1, half).astype(np.float32) * np.float32(d_omega)
    inside = (omega32 >= np.float32(low)) & (omega32 <= np.float32(high))
    if wave_mod in (1, 10):
        spectrum_s = np.where(np.arange(1, half) == peak, 0.5 * (hs / 2) ** 2 / d_omega, 0.0)
        scale[:] = 1.0  # the regular wave's amplitude is Hs / 2 whatever WaveNDAmp
    elif wave_mod == 2:
        spectrum_s = np.where(inside, _jonswap(omega, hs, tp, _peak_shape(sea, hs, tp)), 0.0)
    else:
        spectrum_s = np.where(inside, hs * hs / (16.0 * (high - low)), 0.0)
    amplitude = np.sqrt(2 * spectrum_s * d_omega) * scale
    keep = amplitude > 0
    if not np.any(keep):
        raise ConfigError(f"{sea.path}: no wave frequency inside the cut-offs [{low:g}, {high:g}] rad/s")
    harmonic = np.arange(1, half)[keep]
    direction = np.full(harmonic.size, math.radians(sea.number("WaveDir")))
    return WaveComponents(harmonic / period_s, amplitude[keep], phase[keep], direction, period_s)


def main(argv: list[str] | None = None) -> int:
    """Write a SeaState file's components as a ``.Comp`` file; exit code 2 on bad input."""
    parser = argparse.ArgumentParser(prog="python -m fowt_hydro_sim.physics.waves.seastate",
                                     description="the wave components of an OpenFAST SeaState input file, "
                                                 "as a .Comp file for fowt-sim loads --waves-comp")
    parser.add_argument("seastate", type=Path, help="SeaState input file")
    parser.add_argument("-o", "--output", type=Path, required=True, help=".Comp file to write")
    args = parser.parse_args(argv)
    try:
        waves = seastate_waves(read_seastate(args.seastate))
    except ConfigError as exc:
        sys.stderr.write(f"error: {exc}\n")
        return 2
    if waves is None:
        sys.stderr.write(f"error: {args.seastate}: WaveMod 0 (still water): no components to write\n")
        return 2
    write_comp_file(args.output, waves, header=f"wave components of {args.seastate.name} (SeaState's synthesis)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
