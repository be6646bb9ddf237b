"""``blockdae app``: the local web app (``pip install 'blockdae[app]'``)."""

from ._common import UsageError


def add_app_parser(subparsers):
    """The ``app`` subcommand on an argparse ``subparsers`` object."""
    p = subparsers.add_parser("app", help="the local web app in the browser: records in, displacements and "
                                          "figures out (pip install 'blockdae[app]')")
    p.add_argument("--port", type=int, default=0, help="port on 127.0.0.1 (default: a free one)")
    p.add_argument("--no-browser", action="store_true", help="print the address only; open no browser")
    p.set_defaults(command=run_app)
    return p


def run_app(args) -> int:
    """Serve the app until Ctrl+C; the exit status."""
    if not 0 <= args.port <= 65535:
        raise UsageError(f"--port {args.port}: a port is 0 (a free one) to 65535")
    try:
        from ..app import serve

        serve(open_browser=not args.no_browser, port=args.port)
    except ImportError as err:
        raise UsageError(str(err)) from None
    except OSError as err:
        raise UsageError(f"--port: {err}") from None
    return 0
