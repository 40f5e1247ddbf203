"""Hyperelastic laws fitted to tension tests (``spsc fit-material``): the laws and their
residuals (:mod:`.laws`), the weighted least-squares fit with intervals and the choice between
laws (:mod:`.fitting`), how well a test resolves a law's constants (:mod:`.resolution`), the
report and the figure (:mod:`.report`, :mod:`.figure`).

The package imports nothing itself: each verb loads the modules it needs.
"""
