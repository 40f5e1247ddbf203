"""The chamber as a sensor (the paper's sec. 4): force, depth and their uncertainty from the
chamber's pressure through its quasi-static map, contact, release, slip, the object's
compliance and valve switches as events, and the haptic loop of sec. 4.2 — one sample at a
time (:class:`~spsc.sensing.stream.SenseStream`), the code ``spsc sense`` runs.
"""

from .estimator import Estimate, Estimator, EstimatorParams
from .stream import SenseParams, SenseStream, State
from .table import DenseMap, ForceTable

__all__ = ["Estimate", "Estimator", "EstimatorParams", "SenseParams", "SenseStream", "State",
           "DenseMap", "ForceTable"]
