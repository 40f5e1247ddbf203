"""A validation study as data: which chambers, materials, setups and models to run.

A :class:`Study` expands into :class:`Run` s (one model, one chamber, one setup). A run is a
frozen, hashable description of its inputs; its cache key is a hash of those inputs and of the
*code version* of what computes it: the source files its model imports (followed statically from
the entry module, so an edit elsewhere in the tree does not invalidate it). Units: mm, kPa gauge,
mm³ — as at the command line.
"""

from __future__ import annotations

import ast
import functools
import hashlib
import importlib.util
import json
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path

from spsc.core.errors import ParameterError, require
from spsc.cad.geometry import TYPES, SPSCGeometry, preset
from spsc.models import MODELS

__all__ = ["Run", "Study", "code_version", "model", "source_closure", "imported_names",
           "quick_study", "full_study"]


#: bump when the runner changes what it stores for a run (2: the curve's JSON with its solver)
PAYLOAD_VERSION = 2


def model(name: str):
    """The :class:`~spsc.models.CurveModel` called ``name`` (:data:`spsc.models.MODELS`)."""
    from spsc.models import get

    return get(name)


@dataclass(frozen=True)
class Run:
    """One model run: ``model`` (membrane, simplified, fem) of preset ``type`` (footprint
    ``size``) in ``material`` at setup pressure ``pressure_kPa`` (kPa gauge; 0 with ``fem`` is
    the open chamber, F_el), reservoir ``reservoir_mm3`` (mm³; 0 = high stiffness), over
    ``points`` plate positions on [0, ``stroke_mm``] mm. FEM only: ``mesh_mm`` and ``layers``."""

    model: str
    type: str
    material: str
    pressure_kPa: float
    reservoir_mm3: float
    stroke_mm: float
    points: int
    mesh_mm: float | None = None
    layers: int | None = None
    size: str = "table1"

    def __post_init__(self):
        model(self.model)
        require("pressure", self.pressure_kPa, ge=0, unit="kPa gauge")
        require("reservoir", self.reservoir_mm3, ge=0, unit="mm³")
        require("stroke", self.stroke_mm, gt=0, unit="mm")
        require("points", self.points, ge=2)
        if model(self.model).meshed:
            require("mesh size", self.mesh_mm, gt=0, unit="mm")
            require("layers", self.layers, ge=1)
        elif self.mesh_mm is not None or self.layers is not None:
            raise ParameterError("mesh_mm/layers", (self.mesh_mm, self.layers),
                                 f"None for a {self.model} run (no mesh)")

    @property
    def mode(self) -> str:
        """``open`` (p_i = 0), ``high`` (no reservoir) or ``low``."""
        if self.pressure_kPa == 0:
            return "open"
        return "high" if self.reservoir_mm3 == 0 else "low"

    def geometry(self) -> SPSCGeometry:
        return preset(self.type, size=self.size)

    @property
    def label(self) -> str:
        """Short readable name, unique within a study (file names, progress bar)."""
        s = f"{self.model}-{self.type}-{self.material}-{self.mode}-p{self.pressure_kPa:g}"
        if self.mode == "low":
            s += f"-vr{self.reservoir_mm3:g}"
        s += f"-y{self.stroke_mm:g}x{self.points}"
        if self.mesh_mm is not None:
            s += f"-h{self.mesh_mm:g}l{self.layers}"
        return s

    def inputs(self) -> dict:
        """Everything the result depends on, resolved (geometry parameters, material law)."""
        from spsc.materials import material

        mat = material(self.material)
        return {**asdict(self), "geometry": self.geometry().as_dict(),
                "material_law": mat.identity()}

    def key(self) -> str:
        """sha256 of the inputs, the code version of the model and the payload version."""
        text = json.dumps({"inputs": self.inputs(), "code": code_version(self.model),
                           "payload": PAYLOAD_VERSION}, sort_keys=True, default=str)
        return hashlib.sha256(text.encode()).hexdigest()


def _module_file(name: str) -> Path | None:
    try:
        spec = importlib.util.find_spec(name)
    except (ImportError, ValueError):
        return None
    return Path(spec.origin) if spec and spec.origin and spec.origin.endswith(".py") else None


def imported_names(name: str, path: Path) -> set[str]:
    """The dotted names module ``name`` (source at ``path``) imports, anywhere in it (relative
    and absolute imports, also inside functions; ``from pkg import mod`` as ``pkg.mod``)."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.rsplit(".", node.level - 1)[0] if node.level > 1 else package
                target = f"{base}.{node.module}" if node.module else base
            else:
                target = node.module or ""
            found |= {target} | {f"{target}.{a.name}" for a in node.names}
        elif isinstance(node, ast.Import):
            found |= {a.name for a in node.names}
    return found


@functools.lru_cache(maxsize=None)
def source_closure(module: str) -> tuple[Path, ...]:
    """The source files of ``module`` and of every ``spsc`` module it imports, followed
    statically (:func:`imported_names`), sorted."""
    seen: dict[str, Path] = {}
    todo = [module]
    while todo:
        name = todo.pop()
        if name in seen:
            continue
        path = _module_file(name)
        if path is None:
            continue
        seen[name] = path
        todo += [t for t in imported_names(name, path) if t.startswith("spsc.")]
    return tuple(sorted(set(seen.values())))


@functools.lru_cache(maxsize=None)
def code_version(name: str) -> str:
    """Hash of the source files the model's computation imports (not the git commit, so an
    unrelated edit or commit keeps the cache)."""
    h = hashlib.sha256()
    for path in source_closure(model(name).module):
        h.update(path.name.encode())
        h.update(path.read_bytes())
    return h.hexdigest()[:16]


@dataclass(frozen=True)
class Study:
    """The validation study of the report.

    types, materials : which presets and catalogue materials.
    pressures_kPa : setup pressures of the membrane/simplified runs and of the headline means.
    compare_pressure_kPa : the setup pressure of the FEM comparison (Fig. 8 uses 40 kPa).
    modes : (name, reservoir mm³) pairs; the paper's low mode has V_r = 40 cm³.
    stroke_mm : plate travel from first contact.
    fem_points : FEM plate positions; membrane curves use ``2 (fem_points − 1) + 1`` so the FEM
        grid is a subset of theirs.
    mesh : (element size mm, layers) of the FEM comparison runs.
    convergence_type, convergence_meshes : the mesh-convergence runs (high mode, compare
        pressure); the comparison mesh is added to them.
    """

    name: str = "full"
    types: tuple[str, ...] = ("A", "B", "C", "D")
    materials: tuple[str, ...] = ("tpu60a",)
    pressures_kPa: tuple[float, ...] = (10.0, 20.0, 30.0, 40.0)
    compare_pressure_kPa: float = 40.0
    modes: tuple[tuple[str, float], ...] = (("high", 0.0), ("low", 40_000.0))
    stroke_mm: float = 6.0
    fem_points: int = 13
    mesh: tuple[float, int] = (1.0, 2)
    wall_mesh: tuple[float, int] = (1.0, 2)
    convergence_type: str = "B"
    convergence_meshes: tuple[tuple[float, int], ...] = ((2.0, 1), (1.5, 2))
    fem: bool = True
    note: str = field(default="", compare=False)

    def __post_init__(self):
        for t in self.types:
            if t.upper() not in TYPES:
                raise ParameterError("type", t, "one of " + ", ".join(TYPES))
        require("stroke", self.stroke_mm, gt=0, unit="mm")
        require("fem_points", self.fem_points, ge=2)
        require("compare pressure", self.compare_pressure_kPa, gt=0, unit="kPa gauge")
        if not self.pressures_kPa:
            raise ParameterError("pressures_kPa", self.pressures_kPa, "at least one pressure")

    def replace(self, **changes) -> "Study":
        return replace(self, **changes)

    @property
    def membrane_points(self) -> int:
        return 2 * (self.fem_points - 1) + 1

    @property
    def all_pressures(self) -> tuple[float, ...]:
        return tuple(sorted(set(self.pressures_kPa) | {self.compare_pressure_kPa}))

    # -- the runs ---------------------------------------------------------------------------
    @property
    def models(self) -> tuple:
        """The models this study runs: every model of :data:`MODELS`, the FEM only with
        ``fem``."""
        return tuple(m for m in MODELS.values() if m.study and (m.sweep or self.fem))

    @property
    def sweep_models(self) -> tuple:
        """The models run at every setup pressure (membrane, simplified, …)."""
        return tuple(m for m in MODELS.values() if m.study and m.sweep)

    def membrane(self, model: str, type_: str, material: str, pressure: float, mode: str) -> Run:
        """The run of a sweep ``model`` (membrane, simplified, wall …) at one setup pressure."""
        meshed = MODELS[model].meshed
        mesh = (float(self.wall_mesh[0]), int(self.wall_mesh[1])) if meshed else (None, None)
        return Run(model, type_, material, float(pressure), self.reservoir(mode),
                   self.stroke_mm, self.membrane_points, *mesh)

    def fem_run(self, type_: str, material: str, mode: str, mesh=None) -> Run:
        """``mode`` ``open`` is the open chamber (p = 0), else the compare pressure."""
        size, layers = mesh or self.mesh
        p = 0.0 if mode == "open" else self.compare_pressure_kPa
        v = 0.0 if mode == "open" else self.reservoir(mode)
        return Run("fem", type_, material, p, v, self.stroke_mm, self.fem_points,
                   float(size), int(layers))

    def reservoir(self, mode: str) -> float:
        for name, v in self.modes:
            if name == mode:
                return float(v)
        raise ParameterError("mode", mode, "one of " + ", ".join(n for n, _ in self.modes))

    @property
    def mode_names(self) -> tuple[str, ...]:
        return tuple(n for n, _ in self.modes)

    def runs(self) -> list[Run]:
        """Every run, cheap ones first (membrane, simplified, then FEM by cost)."""
        out = []
        for mat in self.materials:
            for t in self.types:
                for mode in self.mode_names:
                    for p in self.all_pressures:
                        out += [self.membrane(m.name, t, mat, p, mode) for m in self.sweep_models]
        if self.fem:
            fem = []
            for mat in self.materials:
                for t in self.types:
                    fem += [self.fem_run(t, mat, m) for m in self.mode_names]
                    fem.append(self.fem_run(t, mat, "open"))
                fem += [self.fem_run(self.convergence_type, mat, "high", m)
                        for m in self.convergence_meshes]
            # cheapest first: coarse meshes, pressed before open (the open chamber is slower)
            out += sorted(dict.fromkeys(fem), key=lambda r: (-r.mesh_mm, r.mode == "open"))
        return list(dict.fromkeys(out))


def full_study() -> Study:
    """The committed report: converged mesh (1 mm, 2 layers), four pressures."""
    return Study()


def quick_study() -> Study:
    """``make report QUICK=1``: coarse meshes, fewer points and pressures (CI smoke run)."""
    return Study(name="quick", pressures_kPa=(10.0, 40.0), fem_points=7, mesh=(2.0, 1),
                 wall_mesh=(2.0, 1),
                 convergence_meshes=((3.0, 1),),
                 note="QUICK: coarse FEM mesh (2 mm, 1 layer), wall mesh 2 mm, 7 FEM points, "
                      "p_i = 10 and 40 kPa only — a pipeline check, not a validation.")
