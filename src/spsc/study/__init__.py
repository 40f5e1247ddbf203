"""Runs as data and their engine: a study's runs (:mod:`.runs`: inputs, code version, cache
key), the cache (:mod:`.cache`), the Dask executor (:mod:`.executor`), the runner that computes
what is missing (:mod:`.runner`), the metrics defined once (:mod:`.metrics`) and the provenance
of a result (:mod:`.provenance`)."""
