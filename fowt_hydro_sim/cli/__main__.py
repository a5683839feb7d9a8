"""``python -m fowt_hydro_sim.cli``: the ``fowt-sim`` command."""
import sys

from fowt_hydro_sim.cli import main

sys.exit(main())
