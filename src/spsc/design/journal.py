"""The Optuna study of an inverse design, on disk: a JournalStorage on ``OUT/study.journal``.

The journal is an append-only log with a file lock, which several processes may read and write
(Optuna documents it for runs sharing a file over NFS). Only the ``spsc design`` process writes
it here: the Dask workers evaluate designs and never touch the study. A run on a folder that
holds a study continues it, if it is the study of the same problem (goal, space, model,
process, points, stroke); the trials a killed run left RUNNING are marked FAIL first, and a lock
file keeps a second live run off the folder.
"""

from __future__ import annotations

import json
import os
import socket
from pathlib import Path
from typing import TYPE_CHECKING

from spsc.core.errors import ParameterError

if TYPE_CHECKING:
    from spsc.design.problem import Problem

__all__ = ["STUDY_NAME", "JOURNAL", "INTERRUPTED", "optuna_module", "check_resumable",
           "open_study", "Lock"]

STUDY_NAME = "spsc-design"
JOURNAL = "study.journal"
_LOCK = ".design.lock"
#: A trial the run that asked it never told (killed, interrupted): marked FAIL with this.
INTERRUPTED = "interrupted: the run that asked it stopped before its result"


def optuna_module():
    import optuna

    optuna.logging.set_verbosity(optuna.logging.WARNING)
    return optuna


def _storage(out: Path):
    optuna = optuna_module()
    from optuna.storages.journal import JournalFileBackend

    return optuna.storages.JournalStorage(JournalFileBackend(str(out / JOURNAL)))


def check_resumable(out: Path, problem: Problem) -> int:
    """Trials already in ``out``'s study (0 if none); ParameterError when it holds a study of
    another problem. Cheap: the command calls it before any work."""
    out = Path(out)
    if not (out / JOURNAL).exists():
        return 0
    optuna = optuna_module()
    try:
        study = optuna.load_study(study_name=STUDY_NAME, storage=_storage(out))
    except KeyError:
        return 0
    except (ValueError, TypeError, IndexError, AttributeError, AssertionError) as exc:
        # a journal cut short or written over: optuna's reader fails on it (a JSON error,
        # a missing field); say which file, not an internal error
        raise ParameterError("out", str(out), f"a new folder, or one whose {JOURNAL} is a "
                             f"study spsc design wrote (this one cannot be read: "
                             f"{type(exc).__name__}); move it away to start again") from None
    stored = study.user_attrs.get("problem")
    if stored is not None and stored != _json_safe(problem.to_dict()):
        diff = [k for k in stored if stored.get(k) != _json_safe(problem.to_dict()).get(k)]
        raise ParameterError("out", str(out), "a new folder, or one whose study has the same "
                             f"goal, space, model, process, points and stroke (this one's "
                             f"{', '.join(diff)} differ)")
    return len(study.trials)


def _sampler(name: str, seed: int, trials: int):
    optuna = optuna_module()
    if name == "nsga2":
        population = max(8, min(50, trials // 4))
        return optuna.samplers.NSGAIISampler(population_size=population, seed=seed)
    return optuna.samplers.TPESampler(seed=seed, multivariate=True, constant_liar=True)


def open_study(problem: Problem, out: Path, *, sampler: str, seed: int, trials: int):
    """The study of ``out`` (created, or loaded to continue), its sampler seeded from ``seed``
    and the number of trials already there (a continued study reseeds with that count, so a
    continued run is reproducible too). Trials left RUNNING are marked FAIL."""
    import warnings

    optuna = optuna_module()
    storage = _storage(out)
    before = check_resumable(out, problem)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", optuna.exceptions.ExperimentalWarning)
        smp = _sampler(sampler, (seed + 7919 * before) % 2**32, trials)
    study = optuna.create_study(storage=storage, sampler=smp, study_name=STUDY_NAME,
                                directions=problem.goal.directions, load_if_exists=True)
    if before == 0:
        study.set_user_attr("problem", _json_safe(problem.to_dict()))
    for t in study.get_trials(deepcopy=False, states=(optuna.trial.TrialState.RUNNING,)):
        storage.set_trial_user_attr(t._trial_id, "reason", INTERRUPTED)
        storage.set_trial_state_values(t._trial_id, optuna.trial.TrialState.FAIL)
    return study, before


class Lock:
    """``out/.design.lock`` while a run writes the study: a second run on the same folder is
    refused (it would mark the first one's running trials as failed)."""

    def __init__(self, out: Path):
        self.path = Path(out) / _LOCK

    def __enter__(self):
        me = f"{socket.gethostname()} {os.getpid()}"
        for _ in range(2):
            try:
                fd = os.open(self.path, os.O_CREAT | os.O_EXCL | os.O_WRONLY)
            except FileExistsError:
                if self._alive():
                    raise ParameterError("out", str(self.path.parent), "a folder no other "
                                         f"spsc design is writing ({self.path.read_text()})")
                self.path.unlink(missing_ok=True)
                continue
            with os.fdopen(fd, "w") as f:
                f.write(me)
            return self
        raise ParameterError("out", str(self.path.parent), "a folder whose lock can be taken")

    def _alive(self) -> bool:
        try:
            host, pid = self.path.read_text().split()
            if host != socket.gethostname():
                return True  # another machine's run: cannot tell, assume alive
            os.kill(int(pid), 0)
            return True
        except (ValueError, OSError):
            return False

    def __exit__(self, *exc):
        self.path.unlink(missing_ok=True)


def _json_safe(obj):
    """The problem as it reads back from the journal (tuples as lists)."""
    return json.loads(json.dumps(obj))
