"""The app on this computer only: 127.0.0.1, a free port (or the one asked for), answering
only requests for that address that hold the token of its start (:mod:`._guard`), the
browser opened on it; the uploaded files in a temporary folder removed at the end (Ctrl+C,
SIGTERM, or the terminal closed)."""

import logging
import secrets
import signal
import socket
import tempfile
import threading
import webbrowser

from werkzeug.serving import make_server

from ._app import create_app
from ._guard import LocalOnly
from ._session import SESSION_EXPIRY_S, Sessions


class LocalApp:
    """The app served on ``host`` at ``port`` (0: a free one), files under a temporary folder
    (``blockdae-app-*``); each page opened is a session of its own, ended
    ``session_expiry_s`` [s] after the page was last heard from.

    Attributes:
        url: its address with the token of this start, e.g.
            ``http://127.0.0.1:53817/?token=...`` (what a browser opens).
        address: its address without the token, e.g. ``http://127.0.0.1:53817/``.
        app: the Dash app.
        sessions: the pages' sessions (:class:`Sessions`).
    """

    def __init__(self, port: int = 0, host: str = "127.0.0.1", session_expiry_s: float = SESSION_EXPIRY_S):
        if port:
            _check_free(host, port)
        self._folder = tempfile.TemporaryDirectory(prefix="blockdae-app-")
        self.sessions = Sessions(self._folder.name, session_expiry_s)
        self.app = create_app(self.sessions)
        logging.getLogger("werkzeug").setLevel(logging.WARNING)  # no line per request
        self._server = make_server(host, port, self.app.server, threaded=True)
        bound = self._server.server_port
        token = secrets.token_urlsafe(32)
        self.app.server.wsgi_app = LocalOnly(self.app.server.wsgi_app, host, bound, token)
        self.address = f"http://{host}:{bound}/"
        self.url = f"{self.address}?token={token}"
        self._thread = None

    def serve_forever(self):
        """Serve until :meth:`stop` (or Ctrl+C in a terminal)."""
        self._server.serve_forever()

    def start(self) -> "LocalApp":
        """Serve on a thread of its own; returns self."""
        self._thread = threading.Thread(target=self.serve_forever, name="blockdae-app-server", daemon=True)
        self._thread.start()
        return self

    def stop(self):
        """Stop serving, cancel the runs and remove the uploaded files."""
        if self._thread is not None:
            self._server.shutdown()
            self._thread.join()
        self._server.server_close()
        self.sessions.close()
        self._folder.cleanup()


def _check_free(host, port):
    """OSError naming ``port`` where another program serves on it (werkzeug would exit)."""
    with socket.socket() as probe:
        try:
            probe.bind((host, port))
        except OSError as err:
            raise OSError(f"port {port} on {host} is not free ({err.strerror}): give another, or 0 for a free one") \
                from None


def serve(open_browser: bool = True, port: int = 0):
    """Serve the app on 127.0.0.1 (``port``; 0: a free one) until Ctrl+C, SIGTERM or the
    terminal closed (SIGHUP), printing its address and, with ``open_browser``, opening it
    in the browser; its temporary folder is removed on each."""
    local = LocalApp(port)
    if threading.current_thread() is threading.main_thread():  # each stops serving as Ctrl+C does
        for name in ("SIGINT", "SIGTERM", "SIGHUP"):  # SIGINT too: a shell's background job inherits it ignored
            if hasattr(signal, name):
                signal.signal(getattr(signal, name), signal.default_int_handler)
    print(f"blockdae app: {local.url} (Ctrl+C stops it)", flush=True)
    try:
        if open_browser:
            webbrowser.open(local.url)
        local.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        local.stop()
