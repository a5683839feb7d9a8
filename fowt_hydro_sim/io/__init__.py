"""Readers and importers of other codes' file formats (OpenFAST HydroDyn decks)."""
