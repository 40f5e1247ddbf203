"""Materials: the hyperelastic laws every model solves with (W(I1, I2), and Ogden's in the
principal stretches), the catalogue with the
source of each constant, the material file ``spsc fit-material`` writes, tension-test data,
the fitting of laws to it and their Drucker stability.

Below both ``membrane`` and ``fem``: a law is written once and every solver uses it. Fitting
(:mod:`.fit`, :mod:`.fit_laws`, :mod:`.data`, :mod:`.drucker`) is imported on demand.
"""

from .catalogue import CATALOGUE, LAW_KINDS, PRONY, material, viscosity
from .ogden import Ogden
from .file import LAW_CONSTANTS, load_material, material_record, read_material_file
from .law import (PROVENANCES, Material, mooney_rivlin, neo_hookean, polynomial_d2W,
                  polynomial_dW, polynomial_energy, yeoh)

__all__ = [
    "CATALOGUE",
    "LAW_CONSTANTS",
    "LAW_KINDS",
    "Material",
    "Ogden",
    "PRONY",
    "PROVENANCES",
    "load_material",
    "material",
    "material_record",
    "mooney_rivlin",
    "neo_hookean",
    "polynomial_d2W",
    "polynomial_dW",
    "polynomial_energy",
    "read_material_file",
    "viscosity",
    "yeoh",
]
