"""Frequency-dependent drag (the seed paper's band-split Cd): the low-frequency band's Cd is
a ratio of the constant Cd, the other bands keep the constant Cd; drag model ``filtered``."""
from __future__ import annotations

from ..replay import MeasuredRun, Variant
from .base import Effect, Parameter, coefficient_holders, copied


def band_split(document: dict, low_frequency_ratio: float) -> dict:
    """A copy in which every per-band Cd has its low-pass bands at ``low_frequency_ratio`` x
    its constant Cd and its other bands at the constant Cd."""
    document = copied(document)
    low_pass = {b["name"] for b in document.get("drag_bands", []) if b.get("filter") == "lowpass"}
    for holder in coefficient_holders(document):
        for key, value in holder.items():
            if key.startswith("cd") and isinstance(value, dict) and "constant" in value:
                constant = float(value["constant"])
                holder[key] = {band: low_frequency_ratio * constant if band in low_pass else constant
                               for band in value}
    return document


def apply(variant: Variant, run: MeasuredRun, values: dict[str, float]) -> Variant:
    return Variant(band_split(variant.document, values["low_frequency_cd_ratio"]), "filtered",
                   variant.extension, variant.elevation_shift_s)


EFFECT = Effect(
    "frequency_dependent_drag",
    "the low-frequency band's Cd differs from the wave band's (Butterworth band split)",
    (Parameter("low_frequency_cd_ratio", "-", start=0.6, low=0.05, high=4.0, off=1.0),),
    apply)
