"""The CI entry point and the test configuration: what keeps two checkouts testing on one
host apart (their own ROS domain, loopback discovery)."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]


def domain_after_conftest(env: dict[str, str]) -> tuple[str, str]:
    """ROS_DOMAIN_ID and ROS_AUTOMATIC_DISCOVERY_RANGE as a test session sees them."""
    code = ("import os, runpy; runpy.run_path('test/conftest.py'); "
            "print(os.environ['ROS_DOMAIN_ID'], os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'])")
    done = subprocess.run([sys.executable, "-c", code], cwd=REPO, env=env, capture_output=True, text=True,
                          timeout=60, check=True)
    domain, scope = done.stdout.split()
    return domain, scope


def test_the_callers_domain_is_kept_and_otherwise_each_session_gets_its_own():
    env = {k: v for k, v in os.environ.items()
           if k not in ("ROS_DOMAIN_ID", "ROS_AUTOMATIC_DISCOVERY_RANGE", "PYTEST_XDIST_WORKER")}
    assert domain_after_conftest({**env, "ROS_DOMAIN_ID": "63"}) == ("63", "LOCALHOST")
    # pytest -n: the first worker keeps the caller's domain, the others take the next ones
    assert domain_after_conftest({**env, "ROS_DOMAIN_ID": "63", "PYTEST_XDIST_WORKER": "gw0"})[0] == "63"
    assert domain_after_conftest({**env, "ROS_DOMAIN_ID": "63", "PYTEST_XDIST_WORKER": "gw1"})[0] == "64"
    assert domain_after_conftest({**env, "ROS_DOMAIN_ID": "101", "PYTEST_XDIST_WORKER": "gw1"})[0] == "1"
    chosen = {domain_after_conftest(env)[0] for _ in range(4)}
    assert len(chosen) > 1 and all(1 <= int(d) <= 101 for d in chosen)  # not one fixed id for everyone


def test_ci_does_not_force_a_domain():
    script = (REPO / ".ci" / "run").read_text()
    assert "export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST" in script
    assert not [line for line in script.splitlines() if "ROS_DOMAIN_ID=" in line and not line.lstrip().startswith("#")]
