"""Mooring lines beyond the paper's springs: MoorDyn input files (``moordyn_file``), MoorPy's
quasi-static catenaries tabulated for the compiled kernel (``catenary_tables``) and MoorDyn-C's
lumped-mass lines stepped beside it (``moordyn_lines``). The load component that applies them
is ``physics.loads.mooring``."""
