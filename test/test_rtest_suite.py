"""The OpenFAST r-test HydroDyn cases of test/data/openfast_rtest/manifest.yaml, each imported
and run through the command line (``fowt_hydro_sim.testing.rtest_suite``) and compared with
HydroDyn's baseline: a "pass" case within its tolerance on every channel (relative RMS; round-
off channels both below 1e-6 of their kind), a "refused: FIELD" case refused in one line naming
the field, a "gap: WHY" case expected to fail until the gap is closed (strict: a gap that
closes fails here, so the manifest is kept true)."""
from __future__ import annotations

import pytest

from fowt_hydro_sim.testing.rtest_suite import load_manifest, run_case, table

pytestmark = pytest.mark.reference

CASES = load_manifest()


def _param(case):
    marks = [pytest.mark.xfail(strict=True, reason=case.expect)] if case.expect.startswith("gap:") else []
    return pytest.param(case, id=case.name, marks=marks)


@pytest.mark.slow
@pytest.mark.parametrize("case", [_param(c) for c in CASES])
def test_rtest_case_agrees_with_hydrodyn_or_is_refused_naming_the_field(case, tmp_path):
    result = run_case(case, tmp_path)
    print(table([result]))  # shown with -s, and on failure
    if case.expected_refusal:
        assert case.expected_refusal in result.refusal and len(result.refusal.splitlines()) == 1, result.refusal
        return
    assert not result.refusal, result.refusal
    assert result.passed, result.errors
    if result.elevation_error_m is not None:  # the waves file gives the baseline's Wave1Elev (7 digits)
        assert result.elevation_error_m < 1e-5, result.elevation_error_m


def test_manifest_cases_have_their_files_and_a_known_expectation():
    """Every file the manifest names is in the repository; every expectation is one of the three."""
    assert len({c.name for c in CASES}) == len(CASES) >= 4
    for case in CASES:
        for path in (case.deck, case.driver, case.baseline, *([case.waves] if case.waves else []),
                     *([case.seastate_grid] if case.seastate_grid else [])):
            assert path.is_file(), path
        assert case.expect == "pass" or case.expect.split(":")[0] in ("refused", "gap"), case.expect
