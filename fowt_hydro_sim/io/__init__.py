"""Readers and writers of other codes' file formats (WAMIT's numeric output)."""
