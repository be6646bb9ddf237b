"""The app on this computer only: 127.0.0.1, a free port (or the one asked for), the browser
opened on it; the uploaded files in a temporary folder removed at the end."""

import logging
import socket
import tempfile
import threading
import webbrowser

from werkzeug.serving import make_server

from ._app import create_app


class LocalApp:
    """The app served on ``host`` at ``port`` (0: a free one), files under a temporary folder.

    Attributes:
        url: its address, e.g. ``http://127.0.0.1:53817/``.
        app: the Dash app.
    """

    def __init__(self, port: int = 0, host: str = "127.0.0.1"):
        if port:
            _check_free(host, port)
        self._folder = tempfile.TemporaryDirectory(prefix="blockdae-app-")
        self.app = create_app(self._folder.name)
        logging.getLogger("werkzeug").setLevel(logging.WARNING)  # no line per request
        self._server = make_server(host, port, self.app.server, threaded=True)
        self.url = f"http://{host}:{self._server.server_port}/"
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
        """Stop serving and remove the uploaded files."""
        self._server.shutdown()
        self._server.server_close()
        if self._thread is not None:
            self._thread.join()
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
    """Serve the app on 127.0.0.1 (``port``; 0: a free one) until Ctrl+C, printing its
    address and, with ``open_browser``, opening it in the browser."""
    local = LocalApp(port)
    print(f"blockdae app: {local.url} (Ctrl+C stops it)", flush=True)
    if open_browser:
        webbrowser.open(local.url)
    try:
        local.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        local._server.server_close()
        local._folder.cleanup()
