"""The documents a clone carries (docs/): their tables say what the code does. The generated
reference tables (docs/reference/) are current, and the topic contract there is the one of
``msg_adapters.topics`` and the load registry; the load cases against the packaged YAML, the
platform's mass and mooring against the packaged platform; and no pointer to files outside
the repository."""
from __future__ import annotations

import re
import subprocess

import pytest

from fowt_hydro_sim.physics.config import load_cases, load_platform
from fowt_hydro_sim.physics.loads import PUBLISHED
from fowt_hydro_sim.testing import REPO
from msg_adapters import topics

DOCS = REPO / "docs"


def table(path, first_header: str) -> list[list[str]]:
    """The rows (cells, stripped of backquotes) of the Markdown table whose header starts with ``first_header``."""
    lines = path.read_text().splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith(f"| {first_header} |"))
    rows = []
    for line in lines[start + 2:]:
        if not line.startswith("|"):
            break
        rows.append([cell.strip().strip("`") for cell in line.strip("|").split("|")])
    return rows


@pytest.mark.ros  # the nodes' settings import rclpy
def test_the_reference_tables_are_current(tmp_path):
    """Each committed table of docs/reference/ is what the generator writes from the code now."""
    from fowt_hydro_sim.cli import reference_tables

    written = reference_tables.write(tmp_path)
    assert {p.name for p in written} == {p.name for p in (DOCS / "reference").glob("*.md")}, \
        f"docs/reference/ holds other files than the generated ones: run {reference_tables.COMMAND}"
    stale = [p.name for p in written if not (DOCS / "reference" / p.name).is_file()
             or (DOCS / "reference" / p.name).read_text() != p.read_text()]
    assert not stale, f"docs/reference/{', '.join(stale)}: not what the code says; run {reference_tables.COMMAND}"


def test_the_topic_tables_are_the_contract_the_code_uses():
    doc = DOCS / "reference" / "topics.md"
    rows = {}
    lines = doc.read_text().splitlines()
    for start in (i for i, line in enumerate(lines) if line.startswith("| topic | type |")):
        for line in lines[start + 2:]:
            if not line.startswith("|"):
                break
            cells = [cell.strip().strip("`") for cell in line.strip("|").split("|")]
            rows[cells[0]] = cells[1].replace("/", "/msg/", 1)
    assert set(rows) == set(topics.INPUTS) | {t for t, _ in topics.outputs(PUBLISHED).values()} | {
        t for t, _ in topics.TURBINE.values()}
    expected = {**topics.INPUTS, **dict(topics.outputs(PUBLISHED).values()), **dict(topics.TURBINE.values())}
    assert rows == expected


def test_the_load_case_table_is_the_packaged_one():
    rows = table(DOCS / "load_cases.md", "load case")
    cases = load_cases()
    assert [r[0] for r in rows] == list(cases)
    for name, role, hs, tp, gamma, hs_d in rows:
        sea = cases[name].sea_state
        assert (role, float(hs), float(tp), float(gamma)) == (cases[name].role, sea.hs_m, sea.tp_s, sea.gamma), name
        assert float(hs_d) == pytest.approx(sea.hs_m / 15.0, abs=0.006), name


def test_the_platform_document_gives_the_packaged_mass_and_mooring():
    text = (DOCS / "platform_windmoor12.md").read_text()
    p = load_platform()
    assert f"{p.mass.mass_kg / 1e6:.4f}e6 kg" in text and f"({', '.join(f'{c:g}' for c in p.mass.cog_m)}) m" in text
    inertia = [f"{p.mass.inertia_about_cog_kg_m2[i][i]:.2e}".replace("e+", "e") for i in range(3)]
    assert inertia[0] == inertia[1] and f"Ixx = Iyy = {inertia[0]} kg m2, Izz = {inertia[2]} kg m2" in text
    assert f"(0, 0, {p.hub_point_m[2]:g}) m" in text
    m = p.mooring
    assert f"| k, T0 | {m.stiffness_n_m / 1e3:g}e3 N/m, {m.pretension_n / 1e6:g}e6 N |" in text
    assert f"L0 = {m.unstretched_length_m:.1f} m" in text


def test_nothing_points_outside_the_repository():
    tracked = subprocess.run(["git", "ls-files"], cwd=REPO, capture_output=True, text=True, check=True).stdout.split()
    offenders = [f for f in tracked if f.endswith((".py", ".md", ".yaml")) and f != "test/test_docs.py"
                 and re.search(r"shared/spec", (REPO / f).read_text(errors="replace"))]
    assert not offenders
