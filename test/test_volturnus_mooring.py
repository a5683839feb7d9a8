"""VolturnUS-S on the lines of its OpenFAST MoorDyn deck: run from the command line with
MoorDyn-C's lumped-mass lines, tensions written and analysed, and the lines' own damping of a
free surge decay against the quasi-static catenaries (MoorPy), which have none."""
from __future__ import annotations

import json

import numpy as np
import pytest

from fowt_hydro_sim.physics.config import load_platform
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.studies.simulate import fit_free_decay, read_run
from fowt_hydro_sim.testing import fowt_sim


@pytest.mark.slow
def test_volturnus_s_runs_on_moordyns_lines_and_analyze_reports_their_tensions(tmp_path):
    out = tmp_path / "run"
    done = fowt_sim("simulate", "--platform", "volturnus_s", "--mooring", "moordyn", "--load-case", "lc5.2",
                    "--duration", "60", "-o", str(out))
    assert done.returncode == 0, done.stderr
    summary = json.loads((out / "summary.json").read_text())
    assert summary["mooring"] == "moordyn"
    columns = read_run(out)
    assert not np.any(columns["linear_mooring_fx_n"])  # the matrix is off: the lines hold the platform
    for line in (1, 2, 3):  # MoorPy's pretension at rest: 2.44 MN at each fairlead
        fairlead = columns[f"line{line}_fairlead_tension_n"]
        assert 2.0e6 < fairlead.mean() < 3.0e6 and np.all(columns[f"line{line}_anchor_tension_n"] < fairlead)
    report = fowt_sim("analyze", str(out), "--transient", "0", "-o", str(tmp_path / "report"))
    assert report.returncode == 0, report.stderr
    assert "mooring tensions" in report.stdout and "S-N slope m = 3" in report.stdout
    rows = (tmp_path / "report" / "tensions.csv").read_text().splitlines()
    assert len(rows) == 7 and all(float(row.split(",")[5]) > 0 for row in rows[1:])  # each tension's DEL


@pytest.mark.slow
def test_moordyns_lines_damp_a_free_surge_decay_that_moorpys_do_not():
    """A free surge decay from 10 m in still water: the same period with either line model
    (MoorDyn's line mass and inertia are small against the platform's), and MoorDyn's line drag
    adds damping that the quasi-static catenaries lack: a few tenths of a percent of critical,
    as the lumped-mass models of semisubmersible moorings give."""
    platform = load_platform("volturnus_s")
    fits = {}
    for model_name in ("moorpy", "moordyn"):
        model = PlatformModel(platform, None, dt_s=0.05, mooring_model=model_name)
        model.reset(motion=np.array([10.0, 0, 0, 0, 0, 0]))
        result = model.run(420.0, 0.05)
        fits[model_name] = fit_free_decay(result.time_s, result.motion[:, 0])
    assert fits["moordyn"]["period_s"] == pytest.approx(fits["moorpy"]["period_s"], rel=0.03), fits
    extra = fits["moordyn"]["damping_ratio"] - fits["moorpy"]["damping_ratio"]
    assert 0.0005 < extra < 0.03, fits
