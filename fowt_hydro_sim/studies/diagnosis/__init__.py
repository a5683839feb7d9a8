"""The sim-to-real gap diagnosis: ``gap`` (where a model and a measured run differ),
``decay`` (free decays: their half-periods and damping as gap cells),
``method`` (which catalogue effect explains the gap: fits, scores, the verdict; no files,
no cluster), ``runner`` (the model runs in process or on a Dask cluster, progress,
``fowt-sim diagnose``), ``report`` (report.md, diagnosis.json, figures), ``effects`` (the
catalogue), ``benchmark`` (the diagnosis checked on runs whose effect is withheld) and
``independent`` (the independent Cummins/BEM simulator those runs may come from)."""
