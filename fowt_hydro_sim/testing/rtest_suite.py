"""The OpenFAST r-test HydroDyn cases of ``test/data/openfast_rtest/manifest.yaml`` run through
the command line as a user would (``fowt-sim platform import``, then ``fowt-sim loads``), and
compared with HydroDyn's baselines channel by channel.

Relative RMS of a channel: RMS(ours - HydroDyn) / RMS(HydroDyn) over the baseline's rows. A
channel whose baseline RMS is below 1e-6 of the largest of its kind (forces, moments) is
round-off: it agrees when ours is below that too. Channels the baseline lacks (its deck did
not ask for them) are not compared ("-" in the table).

``python -m fowt_hydro_sim.testing.rtest_suite`` prints the table of every case (Markdown,
as docs/validation_rtest.md holds it).
"""
from __future__ import annotations

import contextlib
import io
import sys
import tempfile
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import yaml

from fowt_hydro_sim.cli import main
from fowt_hydro_sim.physics.waves import seastate
from fowt_hydro_sim.physics.waves.components import read_comp_file
from fowt_hydro_sim.physics.waves.grid import SeaStateGrid
from fowt_hydro_sim.testing import REPO
from fowt_hydro_sim.testing.references import read_hydrodyn_out

RTEST = REPO / "test" / "data" / "openfast_rtest"
MANIFEST = RTEST / "manifest.yaml"
CHANNELS = ("HydroFxi", "HydroFyi", "HydroFzi", "HydroMxi", "HydroMyi", "HydroMzi")
ROUND_OFF = 1e-6


@dataclass(frozen=True)
class Case:
    """One manifest entry (paths resolved in the case's folder)."""

    name: str
    deck: Path
    driver: Path
    waves: Path | None  # None: still water; a .Comp file, or a SeaState input file (its synthesised sea)
    options: tuple[str, ...]
    baseline: Path
    tolerance: float
    expect: str  # "pass", "refused: FIELD" or "gap: WHY"
    environment: dict[str, str] = field(default_factory=dict)  # driver values the driver file lacks
    seastate_grid: Path | None = None  # a SeaState input file: the waves sampled on its grid (--wave-kinematics grid)

    @property
    def loads_options(self) -> tuple[str, ...]:
        """The ``fowt-sim loads`` options: the manifest's, and the SeaState grid's if it names one."""
        if self.seastate_grid is None:
            return self.options
        return (*self.options, "--wave-kinematics", "grid", "--seastate-grid", str(self.seastate_grid))

    @property
    def expected_refusal(self) -> str | None:
        """The deck field the case is refused for, if it is."""
        return self.expect.split(":", 1)[1].strip() if self.expect.startswith("refused:") else None


@dataclass
class Result:
    """A case's outcome: its relative RMS per channel (None: round-off on both sides) or the
    one-line refusal."""

    case: Case
    rows: int = 0
    errors: dict[str, float | None] = field(default_factory=dict)
    elevation_error_m: float | None = None  # |Wave1Elev ours - HydroDyn| at most, if printed
    refusal: str = ""

    @property
    def passed(self) -> bool:
        """Every channel within the case's tolerance."""
        return not self.refusal and bool(self.errors) and all(
            e is None or e < self.case.tolerance for e in self.errors.values())

    @property
    def status(self) -> str:
        """pass, fail or refused."""
        if self.refusal:
            return "refused"
        return "pass" if self.passed else "fail"


def load_manifest(path: Path = MANIFEST) -> list[Case]:
    """The manifest's cases."""
    cases = []
    for entry in yaml.safe_load(path.read_text())["cases"]:
        folder = path.parent / entry["name"]
        waves = None if entry["waves"] == "still" else folder / entry["waves"]
        grid = entry.get("seastate_grid")
        cases.append(Case(entry["name"], folder / entry["deck"], folder / entry["driver"], waves,
                          tuple(str(o) for o in entry["options"]), folder / entry["baseline"],
                          float(entry["tolerance"]), str(entry["expect"]),
                          {k: str(v) for k, v in entry.get("environment", {}).items()},
                          None if grid is None else folder / grid))
    return cases


def driver_settings(path: Path) -> dict[str, str]:
    """A HydroDyn driver file's ``value name`` lines as {name: value} (quotes removed)."""
    settings = {}
    for line in path.read_text().splitlines():
        words = line.split()
        if len(words) >= 2:
            settings.setdefault(words[1], words[0].strip('"'))
    return settings


def steady_prp_inputs(path: Path) -> np.ndarray:
    """A driver file's uPRPInSteady, uDotPRPInSteady and uDotDotPRPInSteady (PRPInputsMod 1) as
    the 18 values of a PRP motion row (displacements and rotations, their rates, their
    accelerations; m, rad)."""
    rows = {}
    for line in path.read_text().splitlines():
        words = line.replace(",", " ").split()
        if len(words) >= 7 and words[6] in ("uPRPInSteady", "uDotPRPInSteady", "uDotDotPRPInSteady"):
            rows[words[6]] = [float(w) for w in words[:6]]
    missing = {"uPRPInSteady", "uDotPRPInSteady", "uDotDotPRPInSteady"} - set(rows)
    if missing:
        raise ValueError(f"{path}: PRPInputsMod 1 without the line(s) {', '.join(sorted(missing))}")
    return np.array(rows["uPRPInSteady"] + rows["uDotPRPInSteady"] + rows["uDotDotPRPInSteady"])


def _cli(arguments: list[str]) -> tuple[int, str]:
    """``fowt-sim`` in this process: its exit code and the last line it wrote to stderr."""
    return _cli_module(main, arguments)


def _cli_module(entry: Callable[[list[str]], int], arguments: list[str]) -> tuple[int, str]:
    """A command's ``main`` in this process: its exit code and the last line it wrote to stderr."""
    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        code = entry(arguments)
    lines = err.getvalue().strip().splitlines()
    message = lines[-1].split(": error: ", 1)[-1] if lines else ""
    return code, message.replace(f"{RTEST}/", "")


def run_case(case: Case, folder: Path) -> Result:
    """Import the case's deck and run its loads in ``folder``; compare with the baseline."""
    driver = {**case.environment, **driver_settings(case.driver)}
    reference = read_hydrodyn_out(case.baseline)
    time_s = reference["Time"]
    platform = folder / f"{case.name}.yaml"
    code, message = _cli(["platform", "import", str(case.deck), "-o", str(platform), "--overwrite",
                          "--water-depth", driver["WtrDpth"], "--water-density", driver["WtrDens"],
                          "--gravity", driver["Gravity"]])
    if code:
        return Result(case, refusal=message)
    mode = int(driver["PRPInputsMod"])
    if mode == 2:
        motion = case.driver.parent / driver["PRPInputsFile"]
    elif mode in (0, 1):  # at rest, or the driver's steady displacement, velocity and acceleration
        motion = folder / f"{case.name}_steady.dat"
        steady = np.zeros((time_s.size, 19))
        steady[:, 0] = time_s
        if mode == 1:
            try:
                steady[:, 1:] = steady_prp_inputs(case.driver)
            except ValueError as exc:
                return Result(case, refusal=str(exc))
        np.savetxt(motion, steady)
    else:
        return Result(case, refusal=f"{case.driver}: PRPInputsMod {mode}: the suite runs 0, 1 and 2 only")
    out = folder / f"{case.name}_loads.csv"
    comp = case.waves
    if comp is not None and comp.suffix.lower() != ".comp":  # a SeaState input file: its synthesised sea
        comp = folder / f"{case.name}_waves.Comp"
        code, message = _cli_module(seastate.main, [str(case.waves), "-o", str(comp)])
        if code:
            return Result(case, refusal=message)
    waves = ["--still-water"] if comp is None else ["--waves-comp", str(comp)]
    code, message = _cli(["loads", "--platform", str(platform), "--motion", str(motion), *waves, *case.loads_options,
                          "-o", str(out), "--overwrite"])
    if code:
        return Result(case, refusal=message)
    table = np.genfromtxt(out, delimiter=",", names=True)
    rows = [int(np.argmin(np.abs(table["Time"] - t))) for t in time_s]
    if np.max(np.abs(table["Time"][rows] - time_s)) > 1e-6:
        return Result(case, refusal=f"{case.name}: the loads' times miss the baseline's")
    result = Result(case, rows=time_s.size)
    present = [c for c in CHANNELS if c in reference]  # a deck may ask for some channels only
    scales = {kind: max(np.sqrt(np.mean(reference[c] ** 2)) for c in present if c[5] == kind)
              for kind in {c[5] for c in present}}
    for channel in present:
        ours, theirs = table[channel][rows], reference[channel]
        scale = scales[channel[5]]
        rms = float(np.sqrt(np.mean(theirs**2)))
        if rms <= ROUND_OFF * scale:
            ours_rms = float(np.sqrt(np.mean(ours**2)))
            result.errors[channel] = None if ours_rms <= ROUND_OFF * scale else ours_rms / scale
        else:
            result.errors[channel] = float(np.sqrt(np.mean((ours - theirs) ** 2)) / rms)
    if "Wave1Elev" in reference and comp is not None:
        waves_read = read_comp_file(comp, direct_sum=True)
        depth_m, gravity = float(driver["WtrDpth"]), float(driver["Gravity"])
        if case.seastate_grid is None:
            eta = waves_read.elevation(0.0, 0.0, time_s, depth_m, gravity)
        else:  # HydroDyn's Wave1Elev: SeaState's elevation at (0, 0), a grid node, linear in time on WaveDT
            step_s = SeaStateGrid.from_seastate_file(case.seastate_grid).dt_s
            nodes_s = np.arange(0.0, time_s.max() + 2 * step_s, step_s)
            eta = np.interp(time_s, nodes_s, waves_read.elevation(0.0, 0.0, nodes_s, depth_m, gravity))
        result.elevation_error_m = float(np.max(np.abs(eta - reference["Wave1Elev"])))
    return result


def table(results: list[Result]) -> str:
    """The suite's table (Markdown)."""
    head = "| case | rows | " + " | ".join(c[5:7] for c in CHANNELS) + " | tolerance | result |"
    lines = [head, "|" + "---|" * (len(CHANNELS) + 4)]
    for r in results:
        if r.refusal:
            cells = ["-"] * len(CHANNELS)
            outcome = f"refused: {r.refusal}" if r.case.expected_refusal else f"{r.case.expect}; refused: {r.refusal}"
        else:
            cells = ["-" if c not in r.errors else "round-off" if r.errors[c] is None else f"{r.errors[c]:.2e}"
                     for c in CHANNELS]
            outcome = r.status if r.case.expect == "pass" or r.passed else f"{r.status} ({r.case.expect})"
        lines.append(f"| {r.case.name} | {r.rows} | " + " | ".join(cells) + f" | {r.case.tolerance:g} | {outcome} |")
    return "\n".join(lines)


def run_all(cases: list[Case] | None = None) -> list[Result]:
    """Every case of the manifest, in a temporary folder."""
    with tempfile.TemporaryDirectory() as folder:
        return [run_case(case, Path(folder)) for case in cases or load_manifest()]


if __name__ == "__main__":
    sys.stdout.write(table(run_all()) + "\n")
