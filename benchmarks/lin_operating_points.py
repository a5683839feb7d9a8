"""Extract the operating points and platform modes of OpenFAST's linearisations of the IEA
15 MW turbine on VolturnUS-S (the 240 ``.lin`` files the rosco wheel installs under
``Examples/Test_Cases/IEA-15-240-RWT/IEA-15-240-RWT-UMaineSemi/linearizations``: 20 wind
speeds x 12 rotor azimuths) into ``test/data/volturnus_s/lin_operating_points.csv``, one
row per file: its SHA-256, the header's wind speed, rotor speed and azimuth, the platform
surge, heave and pitch of its operating point, the rotor thrust (ElastoDyn's shaft thrust
and AeroDyn's aerodynamic force along the shaft), collective blade pitch and generator
torque of its inputs and outputs, and the platform surge and pitch modes of
its state matrix A (the eigenvalue whose eigenvector is largest in that DOF, among those
below 0.1 Hz: frequency [Hz] and damping ratio; the linearisation is open loop: blade
pitch and generator torque are its inputs, held); and into ``lin_modes.csv`` beside it the
same modes per wind speed of the azimuth-averaged state matrix (the mean of its 12 A).

    python benchmarks/lin_operating_points.py [--source DIR] [--output CSV]
"""
from __future__ import annotations

import argparse
import csv
import hashlib
import re
from pathlib import Path

import numpy as np

DEFAULT_OUTPUT = Path(__file__).resolve().parents[1] / "test" / "data" / "volturnus_s" / "lin_operating_points.csv"
COLUMNS = ("file", "sha256", "wind_speed_m_s", "rotor_speed_rad_s", "azimuth_rad", "surge_m", "heave_m", "pitch_rad",
           "rotor_thrust_n", "rotor_aero_thrust_n", "blade_pitch_rad", "generator_torque_nm", "surge_mode_hz",
           "surge_mode_damping", "pitch_mode_hz", "pitch_mode_damping")
# ElastoDyn's first displacement states: surge [m], heave [m], pitch [rad], tower fore-aft [m]; a pitch
# angle weighed as the motion it gives 100 m up (the hub), so that the DOFs compare
DISPLACEMENT_SCALE = np.array([1.0, 1.0, 100.0, 1.0])
MODE_MAX_HZ = 0.1  # the platform's rigid-body modes are below (surge ~0.007 Hz, pitch ~0.036 Hz)


def _header_value(text: str, label: str) -> float:
    return float(re.search(rf"{label}:\s+([-\d.Ee+]+)", text).group(1))


def _operating_point(text: str, section: str, description: str) -> float:
    block = text.split(section, 1)[1]
    for line in block.splitlines():
        if description in line:
            return float(line.split()[1])
    raise ValueError(f"no {description!r} in {section}")


def _matrix(text: str, name: str) -> np.ndarray:
    match = re.search(rf"^{name}:\s+(\d+) x (\d+)\s*$", text, flags=re.M)
    rows, cols = int(match.group(1)), int(match.group(2))
    lines = text[match.end():].strip().splitlines()[:rows]
    return np.array([[float(v) for v in line.split()[:cols]] for line in lines])


def platform_mode(a: np.ndarray, dof: int) -> tuple[float, float]:
    """Frequency [Hz] and damping ratio of the oscillating mode below ``MODE_MAX_HZ`` whose
    eigenvector's displacement is largest in state ``dof`` (relative to its largest one)."""
    values, vectors = np.linalg.eig(a)
    best, score = None, 0.0
    for value, vector in zip(values, vectors.T):
        frequency = abs(value.imag) / (2 * np.pi)
        if value.imag <= 0 or frequency > MODE_MAX_HZ:
            continue
        displacement = np.abs(vector[:4]) * DISPLACEMENT_SCALE
        weight = displacement[dof] / max(displacement.max(), 1e-30)
        if weight > score:
            best, score = value, weight
    omega = abs(best)
    return abs(best.imag) / (2 * np.pi), -best.real / omega


def extract(path: Path) -> tuple[dict, np.ndarray]:
    """A linearisation's row of the table, and its state matrix A."""
    data = path.read_bytes()
    text = data.decode()
    a = _matrix(text, "A")
    surge_hz, surge_zeta = platform_mode(a, 0)
    pitch_hz, pitch_zeta = platform_mode(a, 2)
    return {
        "file": path.name, "sha256": hashlib.sha256(data).hexdigest(),
        "wind_speed_m_s": _header_value(text, "Wind Speed"), "rotor_speed_rad_s": _header_value(text, "Rotor Speed"),
        "azimuth_rad": _header_value(text, "Azimuth"),
        "surge_m": _operating_point(text, "Order of continuous states", "Platform horizontal surge translation DOF"),
        "heave_m": _operating_point(text, "Order of continuous states", "Platform vertical heave translation DOF"),
        "pitch_rad": _operating_point(text, "Order of continuous states", "Platform pitch tilt rotation DOF"),
        "rotor_thrust_n": 1e3 * _operating_point(text, "Order of outputs", "ED RotThrust"),
        "rotor_aero_thrust_n": _operating_point(text, "Order of outputs", "AD RtAeroFxh"),
        "blade_pitch_rad": _operating_point(text, "Order of inputs", "collective blade-pitch command"),
        "generator_torque_nm": _operating_point(text, "Order of inputs", "ED Generator torque"),
        "surge_mode_hz": surge_hz, "surge_mode_damping": surge_zeta,
        "pitch_mode_hz": pitch_hz, "pitch_mode_damping": pitch_zeta,
    }, a


def main() -> None:
    import rosco

    default = (Path(rosco.__file__).resolve().parents[1] / "Examples" / "Test_Cases" / "IEA-15-240-RWT"
               / "IEA-15-240-RWT-UMaineSemi" / "linearizations")
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--source", type=Path, default=default, help="folder of the .lin files")
    parser.add_argument("--output", type=Path, default=DEFAULT_OUTPUT, help="CSV to write")
    args = parser.parse_args()
    paths = sorted(args.source.glob("lin_*.lin"), key=lambda p: tuple(int(n) for n in re.findall(r"\d+", p.stem)))
    extracted = [extract(p) for p in paths]
    with args.output.open("w", newline="") as f:
        writer = csv.DictWriter(f, COLUMNS, lineterminator="\n")
        writer.writeheader()
        for row, _ in extracted:
            writer.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in row.items()})
    # the azimuth average: each wind speed's A matrices averaged (the platform's and the hull's states do not rotate)
    by_wind: dict[float, list[np.ndarray]] = {}
    for row, a in extracted:
        by_wind.setdefault(row["wind_speed_m_s"], []).append(a)
    modes = args.output.with_name("lin_modes.csv")
    with modes.open("w") as f:
        f.write("wind_speed_m_s,azimuths,surge_mode_hz,surge_mode_damping,pitch_mode_hz,pitch_mode_damping\n")
        for wind, matrices in sorted(by_wind.items()):
            a = np.mean(matrices, axis=0)
            surge, pitch = platform_mode(a, 0), platform_mode(a, 2)
            f.write(f"{wind:g},{len(matrices)},{surge[0]:.6g},{surge[1]:.6g},{pitch[0]:.6g},{pitch[1]:.6g}\n")
    print(f"wrote {args.output}: {len(extracted)} linearisations; {modes}: {len(by_wind)} wind speeds")


if __name__ == "__main__":
    main()
