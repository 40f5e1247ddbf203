"""Training and checking the wall model's surrogate (:mod:`spsc.models.surrogate`): wall
maps of sampled designs on Dask, the fit, the check against fresh designs."""
