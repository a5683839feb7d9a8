"""``fowt-sim platform import``: an OpenFAST HydroDyn v5 deck as a platform YAML."""
from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

import yaml

from fowt_hydro_sim.io import hydrodyn
from fowt_hydro_sim.physics.config import ConfigError


def import_deck(args: argparse.Namespace) -> int:
    out = Path(args.output)
    if out.exists() and not args.overwrite:
        raise ConfigError(f"{out}: exists (pass --overwrite to replace it)")
    source = Path(args.deck)
    if not source.is_file():
        raise ConfigError(f"{source}: no such file")
    document = hydrodyn.platform_from_deck(hydrodyn.read_deck(source), args.name or source.stem, source.name,
                                           args.water_density, args.gravity, args.water_depth)
    if "potential_flow" in document:  # the WAMIT files relative to the YAML, as the platform reader takes them
        root = document["potential_flow"]["wamit_root"]
        document["potential_flow"]["wamit_root"] = os.path.relpath(root, out.resolve().parent)
    out.write_text(yaml.safe_dump(document, sort_keys=False))
    flow = " and WAMIT potential flow" if "potential_flow" in document else ""
    sys.stdout.write(f"wrote {out}: {len(document['members'])} members{flow} (placeholder mass, no mooring)\n")
    return 0


def add_parsers(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("platform", help="platform files: import an OpenFAST HydroDyn deck")
    commands = p.add_subparsers(dest="platform_command", required=True, metavar="COMMAND")
    imp = commands.add_parser("import", help="write a platform YAML from a HydroDyn v5 input file",
                              description=hydrodyn.__doc__.split("\n\n")[0])
    imp.add_argument("deck", type=Path, help="HydroDyn v5 primary input file")
    imp.add_argument("-o", "--output", required=True, type=Path, help="platform YAML to write")
    imp.add_argument("--name", help="platform name (default the deck's file name)")
    imp.add_argument("--water-density", type=float, default=1025.0, help="[kg/m^3] (the driver's WtrDens)")
    imp.add_argument("--gravity", type=float, default=9.80665, help="[m/s^2] (the driver's Gravity)")
    imp.add_argument("--water-depth", type=float, default=150.0, help="[m] (the driver's WtrDpth)")
    imp.add_argument("--overwrite", action="store_true", help="replace the output file")
    imp.set_defaults(func=import_deck)
