"""Progress bars over the units of a long run (records, tasks): tqdm on stderr, shown
only where stderr is a terminal unless asked for; nothing is written to a file or a pipe."""

import sys


def show_progress(progress=None) -> bool:
    """Whether to show a bar: ``progress`` if it is True or False; None: only when stderr
    is a terminal (a script's log, a pipe or a test sees none)."""
    return sys.stderr.isatty() if progress is None else bool(progress)


def progress_bar(total: int, desc: str, unit: str, progress=None):
    """A tqdm bar on stderr over ``total`` ``unit`` s, labelled ``desc``; a disabled one
    (updates do nothing) where :func:`show_progress` says no."""
    show = show_progress(progress)
    if show:
        from tqdm.auto import tqdm
    else:  # plain tqdm: tqdm.auto in a notebook without ipywidgets warns even for a bar never shown
        from tqdm import tqdm

    return tqdm(total=total, desc=desc, unit=unit, disable=not show, file=sys.stderr)
