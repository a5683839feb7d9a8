"""Readers, writers and importers of other codes' file formats: OpenFAST HydroDyn decks, WAMIT's
numeric output."""
