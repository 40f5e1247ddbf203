"""Sweeps of the design space on Dask: the space (:mod:`.space`: a grid or a Latin hypercube),
one design evaluated into one row (:mod:`.evaluate`), the resumable Parquet store
(:mod:`.store`), the run (:mod:`.run`), its figures and page."""
