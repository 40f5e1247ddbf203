"""The chamber in time: the pneumatic circuit of the paper's Fig. 1 (chamber, valve, reservoir,
the gas in each with its energy balance, a pressure sensor) driven by a press profile, on the
quasi-static chamber map of a static model (:mod:`.chamber_map`).

:func:`~spsc.dynamics.simulate.simulate` integrates a :class:`~spsc.dynamics.scenario.Scenario`
(``spsc simulate SCENARIO.toml``) into a trace.
"""

from .valve import Valve, sonic_conductance
from .gas import Gas
from .sensor import Sensor

__all__ = ["Valve", "sonic_conductance", "Gas", "Sensor"]
