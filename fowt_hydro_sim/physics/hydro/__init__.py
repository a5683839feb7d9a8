"""Potential-flow hydrodynamics from frequency-domain (WAMIT) coefficients: pure numpy functions."""
