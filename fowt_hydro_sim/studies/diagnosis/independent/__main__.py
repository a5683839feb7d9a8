"""``python -m fowt_hydro_sim.studies.diagnosis.independent bem|drift``: rebuild the BEM database
or the mean drift table."""
from __future__ import annotations

import argparse
import logging
import math
import sys

from fowt_hydro_sim.physics.config import ConfigError, load_platform
from fowt_hydro_sim.studies.diagnosis.independent import bem, drift

LOG = logging.getLogger(__name__)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m fowt_hydro_sim.studies.diagnosis.independent")
    sub = parser.add_subparsers(dest="command", required=True)
    build = sub.add_parser("bem", help="mesh the hull and solve radiation and diffraction with capytaine")
    build.add_argument("--platform", default="windmoor12")
    build.add_argument("--panel-size-m", type=float, default=bem.PANEL_SIZE_M)
    build.add_argument("--out", default=str(bem.DATABASE))
    second = sub.add_parser("drift", help="the hull's mean surge drift coefficients (capytaine, Maruo)")
    second.add_argument("--platform", default="windmoor12")
    second.add_argument("--panel-size-m", type=float, default=bem.PANEL_SIZE_M)
    second.add_argument("--out", default=str(drift.DRIFT_TABLE))
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    logging.getLogger("capytaine").setLevel(logging.WARNING)
    if args.panel_size_m <= 0.0:
        parser.error(f"--panel-size-m: must be > 0, got {args.panel_size_m:g}")
    try:
        platform = load_platform(args.platform)
    except (ConfigError, OSError) as error:
        parser.error(f"--platform: {error}")
    if args.command == "drift":
        table = drift.hull_drift(platform, 2.0 * math.pi / drift.DRIFT_PERIODS_S[::-1], args.panel_size_m)
        drift.save_table(table, args.out)
        LOG.info("wrote %s (%d frequencies)", args.out, table.omega_rad_s.size)
        return 0
    database = bem.solve(platform, panel_size_m=args.panel_size_m)
    bem.save_database(database, args.out)
    LOG.info("wrote %s (%d panels, %d frequencies)", args.out, database.panels, len(database.omega_rad_s))
    return 0


if __name__ == "__main__":
    sys.exit(main())
