"""Who may talk to the app: requests addressed to it on this computer (the ``Host`` and any
``Origin`` header name 127.0.0.1, localhost or [::1] with its port: a page of another site
that renamed itself to this address, DNS rebinding, is refused) and holding its key (the
token of the address printed at its start, then a cookie), as Jupyter does. Anything else
gets 403 and a line saying why."""

import secrets
import urllib.parse

from werkzeug.wrappers import Request, Response

#: the names this computer answers to, besides the address the app is bound to
_LOCAL_NAMES = ("127.0.0.1", "localhost", "[::1]")


class LocalOnly:
    """WSGI middleware around ``app`` (served at ``host``:``port``) that lets through only
    requests for this address holding ``token`` (in the query ``?token=``, answered with a
    cookie and the same address without it, or in that cookie)."""

    def __init__(self, app, host: str, port: int, token: str):
        self.app, self.token = app, token
        self.address = f"{host}:{port}"
        names = {*_LOCAL_NAMES, f"[{host}]" if ":" in host else host}
        self.hosts = {f"{name}:{port}" for name in names} | (names if port == 80 else set())
        self.origins = {f"http://{host}" for host in self.hosts}
        self.cookie = f"blockdae-app-{port}"

    def __call__(self, environ, start_response):
        request = Request(environ)
        refused = self._refused(request)
        if refused:
            return Response(f"blockdae app: {refused}\n", status=403, mimetype="text/plain")(environ, start_response)
        given = request.args.get("token")
        if given is not None and request.method == "GET":  # the address printed: the cookie, the same page
            query = urllib.parse.urlencode([(k, v) for k, v in request.args.items(multi=True) if k != "token"])
            response = Response(status=303, headers={"Location": request.path + (f"?{query}" if query else "")})
            response.set_cookie(self.cookie, self.token, httponly=True, samesite="Strict", path="/")
            return response(environ, start_response)
        return self.app(environ, start_response)

    def _refused(self, request) -> str | None:
        """Why ``request`` is refused (a line), None where it may pass."""
        host = request.headers.get("Host", "")
        if host.lower() not in self.hosts:
            return f"the Host header {host!r} is not this app's address ({self.address})"
        origin = request.headers.get("Origin")
        if origin is not None and origin.lower() not in self.origins:
            return f"requests from the page at {origin!r} are refused: only the app's own page may call it"
        given = request.args.get("token", request.cookies.get(self.cookie))
        if given is None or not secrets.compare_digest(given.encode(), self.token.encode()):
            return ("this address needs the app's token: open the whole address 'blockdae app' printed "
                    "(http://...?token=...)")
        return None
