"""The local web app (``blockdae app``; ``pip install 'blockdae[app]'``): records in,
displacements and figures out, in the browser, served from this computer only.

The workflow, in SLAMMER's order: records (every format the readers know; a file that
does not state its units asks for them), the analysis (rigid block, decoupled, coupled,
equivalent-linear; ky directly, from a factor of safety and thrust angle, or a ky(D) table;
a target PGA; both polarities), the results (D per record, the history of a case, D against
ky; CSV and PNG), and the design (the slope's properties uncertain: the probability that D
exceeds a threshold, the mean ky a design needs). Built on Dash, whose scripts come from
its installed wheel: nothing is loaded from the internet.
"""

__all__ = ["LocalApp", "serve"]


def __getattr__(name):
    """``LocalApp`` and ``serve`` on first use, so that a missing extra is one clear error."""
    if name not in __all__:
        raise AttributeError(f"module 'blockdae.app' has no attribute {name!r}")
    try:
        from . import _server
    except ImportError as err:
        raise ImportError(f"the app needs its extra, Dash: pip install 'blockdae[app]' ({err})") from err
    return getattr(_server, name)
