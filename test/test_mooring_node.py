"""The node with MoorDyn's lines (``-p mooring:=moordyn``) over real DDS (loopback): each line's
tensions published and recorded, ``fowt-sim analyze`` reading them from the bag, and MoorDyn
failing mid-run ending the run with one line and a readable bag."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import yaml

pytest.importorskip("rclpy")

from fowt_hydro_sim.physics.config import load_platform, platform_document  # noqa: E402
from fowt_hydro_sim.rosbag.reader import Bag  # noqa: E402
from fowt_hydro_sim.testing import fowt_sim  # noqa: E402
from fowt_hydro_sim.testing.ros import finish, start  # noqa: E402
from msg_adapters import topics  # noqa: E402

VOLTURNUS_LINES = (Path(__file__).parents[1] / "fowt_hydro_sim" / "physics" / "data" / "platforms" / "volturnus_s"
                   / "IEA-15-240-RWT-UMaineSemi_MoorDyn.dat")


def catenary_platform(folder: Path, lines: Path = VOLTURNUS_LINES) -> Path:
    """windmoor12's hull on the lines of ``lines`` (moorpy unless the run says otherwise) in
    200 m of water."""
    document = platform_document(load_platform("windmoor12"))
    document["environment"]["water_depth_m"] = 200.0
    document["mooring"] = {"model": "moorpy", "file": str(lines)}
    (folder / "catenary.yaml").write_text(yaml.safe_dump(document))
    return folder / "catenary.yaml"


@pytest.mark.ros
@pytest.mark.slow
def test_the_node_publishes_records_and_analyze_reports_moordyns_tensions(tmp_path):
    bag = tmp_path / "run"
    node = start("node", platform=str(catenary_platform(tmp_path)), mooring="moordyn", duration_s=5.0,
                 real_time_factor=0.0, record=str(bag), load_case="lc5.3")
    output = finish(node, 180)
    assert node.returncode == 0, output
    assert "mooring moordyn" in output
    recorded = Bag(bag)
    for line in (1, 2, 3):
        series = recorded.series(topics.tension_topic(line))
        assert len(series.time_s) == 101 and series.time_s[-1] == pytest.approx(5.0)
        fairlead, anchor = series.values[:, 0], series.values[:, 1]
        assert np.all((2.0e6 < fairlead) & (fairlead < 3.0e6)) and np.all(anchor < fairlead)
    report = fowt_sim("analyze", str(bag), "--transient", "0", "-o", str(tmp_path / "report"))
    assert report.returncode == 0, report.stderr
    assert "line3_fairlead" in report.stdout and "DEL" in report.stdout


@pytest.mark.ros
@pytest.mark.slow
def test_moordyn_failing_mid_run_ends_the_run_with_one_line_and_a_readable_bag(tmp_path):
    """A MoorDyn time step too long for the lines (dtM 0.02 s) makes MoorDyn's state go NaN
    after a few steps: the node names the file and the time, exits 1, and the bag is readable,
    holding what was published before (the batch being stepped is lost with MoorDyn's state)."""
    unstable = tmp_path / "unstable.dat"
    unstable.write_text(VOLTURNUS_LINES.read_text().replace("0.001    dtM", "0.02    dtM"))
    bag = tmp_path / "run"
    node = start("node", platform=str(catenary_platform(tmp_path, unstable)), mooring="moordyn", duration_s=30.0,
                 real_time_factor=0.0, record=str(bag))
    output = finish(node, 180)
    assert node.returncode == 1, output
    failure = [line for line in output.splitlines() if "MoorDyn failed" in line]
    assert failure and "unstable.dat: MoorDyn failed at t = " in failure[0], output
    assert "NaN" in failure[0] and "Traceback" not in output
    recorded = Bag(bag)
    stamps = recorded.series(topics.tension_topic(1)).time_s
    assert stamps.size >= 1 and stamps[-1] < 30.0
