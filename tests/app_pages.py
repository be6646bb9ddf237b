"""A page of a running app as a browser tab talks to it, over HTTP: its address opened with
the token (the cookie kept), the layout read for the page's session key, and the app's
callbacks called as Dash's renderer calls them (``/_dash-update-component``)."""

import base64
import http.client
import json
import pathlib
import time
import urllib.parse


def request(port, method, path, headers=None, body=None):
    """(status, headers, body bytes) of one request to 127.0.0.1:``port``."""
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=120)
    try:
        connection.request(method, path, body=body, headers=headers or {})
        response = connection.getresponse()
        return response.status, dict(response.getheaders()), response.read()
    finally:
        connection.close()


def data_url(path) -> str:
    """A file's bytes as the browser sends them (a base64 data URL)."""
    return "data:application/octet-stream;base64," + base64.b64encode(pathlib.Path(path).read_bytes()).decode()


class Page:
    """The page at ``url`` (the address the app printed, with its token)."""

    def __init__(self, url):
        parts = urllib.parse.urlsplit(url)
        self.port = parts.port
        status, headers, _ = request(self.port, "GET", f"/?{parts.query}")
        assert status == 303, status
        self.cookie = headers["Set-Cookie"].split(";")[0]
        self.key = _props(self.get("/_dash-layout"), "session")["data"]
        self.callbacks = [dep for dep in self.get("/_dash-dependencies") if not dep.get("clientside_function")]

    def get(self, path):
        status, _, body = request(self.port, "GET", path, {"Cookie": self.cookie})
        assert status == 200, (status, body)
        return json.loads(body)

    def call(self, trigger, values=None, changed=None) -> dict:
        """The JSON answer of the callback that ``trigger`` ("id.property") fires, the page's
        values by "id.property" (a pattern's: the list of its matches; the session key
        added); ``changed``: the prop id that changed where not ``trigger``."""
        values = {**(values or {}), "session.data": self.key}
        callback = next(c for c in self.callbacks if any(f"{i['id']}.{i['property']}" == trigger for i in c["inputs"]))

        def given(items):
            return [values.get(f"{i['id']}.{i['property']}", []) if i["id"].startswith("{") else
                    {"id": i["id"], "property": i["property"], "value": values.get(f"{i['id']}.{i['property']}")}
                    for i in items]

        output = callback["output"]
        outputs = ([dict(zip(("id", "property"), part.rsplit(".", 1))) for part in output.strip(".").split("...")]
                   if output.startswith("..") else dict(zip(("id", "property"), output.rsplit(".", 1))))
        body = {"output": output, "outputs": outputs, "inputs": given(callback["inputs"]),
                "state": given(callback["state"]), "changedPropIds": [changed or trigger]}
        status, _, data = request(self.port, "POST", "/_dash-update-component",
                                  {"Cookie": self.cookie, "Content-Type": "application/json"}, json.dumps(body))
        assert status == 200, (status, data[-2000:])
        return json.loads(data)

    def upload(self, files: dict) -> str:
        """Files given at once (name -> data URL); the page's message about them."""
        answer = self.call("upload-batch.data", {"upload-batch.data": {"names": list(files),
                                                                       "contents": list(files.values())}})
        return answer["response"]["record-messages"]["children"]

    def remove(self, label):
        pattern = '{"file":["ALL"],"type":"remove"}.n_clicks'
        match = {"id": {"file": label, "type": "remove"}, "property": "n_clicks", "value": 1}
        self.call(pattern, {pattern: [match]}, changed=json.dumps(match["id"], sort_keys=True,
                                                                   separators=(",", ":")) + ".n_clicks")

    def run(self, form: dict) -> dict:
        """Click Run with the analysis form's ``form`` ("id.value" -> text), then poll until it
        is done; the last answer's outputs."""
        answer = self.call("run.n_clicks", {**form, "run.n_clicks": 1})["response"]
        deadline = time.monotonic() + 300
        while not answer["poll"]["disabled"]:
            assert time.monotonic() < deadline, answer
            time.sleep(0.15)  # the page's own poll interval
            answer = self.call("poll.n_intervals", {**form, "poll.n_intervals": 1})["response"]
        return answer

    def csv(self) -> str:
        """The results table's CSV as downloaded."""
        return self.call("download-csv-button.n_clicks", {"download-csv-button.n_clicks": 1})["response"][
            "download"]["data"]["content"]


def _props(node, id_):
    """The props of the component ``id_`` in a layout's JSON."""
    if isinstance(node, dict):
        if node.get("props", {}).get("id") == id_:
            return node["props"]
        node = list(node.values())
    if isinstance(node, list):
        return next((found for value in node if (found := _props(value, id_)) is not None), None)
    return None
