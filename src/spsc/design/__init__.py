"""Inverse design with Optuna on Dask: the goal (:mod:`.goal`), the space (:mod:`.space`), the
problem a study answers (:mod:`.problem`), the study's journal (:mod:`.journal`), the search
loop (:mod:`.loop`), the FEM check of the best design (:mod:`.verify`) and the outputs."""
