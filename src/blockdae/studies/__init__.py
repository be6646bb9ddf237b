"""Studies of records × friction × intensity × location (the SMiRT paper on Newmark's formula): a tidy table, its
summaries, saving and reloading, and the ``blockdae study`` command."""

from ._io import load_study, save_study
from ._study import NoWorkerError, study, summary

__all__ = ["NoWorkerError", "load_study", "save_study", "study", "summary"]
