"""The Dash app: the page and what each click does. Files and the running analysis live in
the :class:`Session` of the page (each page load opens one: its key is in the page, and
every callback reads it); every message names the file or field and the value, and nothing
loaded or computed is dropped on an error."""

import math
import threading
import time

import numpy as np
from dash import ALL, Dash, Input, Output, State, ctx, dcc, html, no_update, set_props

from ..excitation import Record
from ._analysis import Settings, analyse, displacement_figure, history_figure, parse_settings
from ._design_page import design_callbacks, design_section
from ._page import HIDDEN, MESSAGES, SHOWN, layout
from ._records import record_figure
from ._session import BATCH_LIMIT_BYTES, FILE_LIMIT_BYTES, SessionEnded, Sessions
from ._views import case_options, csv_text, data_url, drawn, records_view, results_view

#: how long a click on Run waits for the analysis before showing progress instead [s]
_WAIT_S = 0.8
_FORM = ("method", "ky-mode", "ky", "factor-of-safety", "thrust-angle", "ky-table", "height", "vs", "damping",
         "reference-strain", "pga", "polarity")


#: how often an open page tells the app it is still there [ms]
_HEARTBEAT_MS = 60_000


def create_app(sessions: Sessions) -> Dash:
    """The app, each page load a session of ``sessions``; it prepares the solvers on a thread
    (their first run after an install compiles them) while the page loads."""
    app = Dash(__name__, title="blockdae", serve_locally=True, update_title=None,
               on_error=lambda err: _session_ended(err, sessions.expiry_s))
    app.validation_layout = _page(None)
    app.layout = lambda: _page(sessions.new())
    # a batch's files in base64 (4/3 of their bytes) and the request around them
    app.server.config["MAX_CONTENT_LENGTH"] = BATCH_LIMIT_BYTES * 4 // 3 + 1_000_000
    warm = _WarmUp()
    _record_callbacks(app, sessions)
    _analysis_callbacks(app, sessions)
    _result_callbacks(app, sessions)
    design_callbacks(app, sessions)

    @app.callback(Input("session-heartbeat", "n_intervals"), State("session", "data"), prevent_initial_call=True)
    def heartbeat(_, key):
        sessions.heard_from(key)

    @app.callback(Output("engine-status", "children"), Output("engine-poll", "disabled"),
                  Input("engine-poll", "n_intervals"))
    def engine_status(_):
        if warm.seconds is None:
            return ("Preparing the solvers (on a first start after an install they are compiled: about 30 s of "
                    "one core, the default coupled analysis's in the first 20 s; an analysis started now waits "
                    "only for the solvers it needs)."), False
        if warm.error:
            return f"The solvers could not be prepared ({warm.error}).", True
        return f"Solvers ready ({warm.seconds:.1f} s to prepare).", True

    return app


def _page(key):
    """The page's components, holding the key of its session (None: the validation layout)."""
    return html.Div([dcc.Store(id="session", data=key),
                     dcc.Store(id="upload-batch"),
                     dcc.Store(id="upload-limits", data={"file": FILE_LIMIT_BYTES, "batch": BATCH_LIMIT_BYTES}),
                     dcc.Interval(id="session-heartbeat", interval=_HEARTBEAT_MS),
                     html.Div(id="session-ended", role="alert", style=MESSAGES),
                     layout(design_section())])


def _session_ended(err, expiry_s):
    """A callback's error: where the page's session has ended (``expiry_s`` [s] unheard, or
    the app restarted), the page says so and stops polling (its outputs unchanged);
    anything else is raised on."""
    if not isinstance(err, SessionEnded):
        raise err
    set_props("session-ended", {"children": "This page's session has ended (the app was restarted, or the page was "
                                            f"not heard from for {expiry_s / 60:.3g} minutes): reload the page to "
                                            "start again."})
    for interval in ("poll", "design-poll", "engine-poll", "session-heartbeat"):
        set_props(interval, {"disabled": True})


class _WarmUp:
    """Runs each analysis once on a short synthetic motion, with its figures, on a thread;
    ``seconds`` is its wall time [s] when done (None before), ``error`` what stopped it
    (None if nothing). It waits, between analyses, while the user's analysis or design study
    runs: theirs then compiles what it needs at once instead of after the rest."""

    def __init__(self):
        self.seconds, self.error = None, None
        threading.Thread(target=self._run, name="blockdae-app-warm-up", daemon=True).start()

    def _run(self):
        start = time.perf_counter()
        t = np.arange(0.0, 2.0, 0.01)
        motion = Record(0.3 * np.sin(2 * np.pi * 2.0 * t), 0.01, name="warm-up", units="g")
        # the form's default analysis first (its kernels are ready first), then the rigid block;
        # the other two flexible analyses reuse the coupled one's kernels
        cases = [Settings("coupled", (0.1,), 10.0, 200.0, 0.05), Settings("rigid", (0.1,)),
                 Settings("decoupled", (0.1,), 10.0, 200.0, 0.05),
                 Settings("equivalent-linear", (0.1,), 10.0, 200.0, 0.05, 0.0005)]
        try:  # what a click on Run calls, and the figures that follow
            for settings in cases:
                _wait_for_user_work()
                rows, _ = analyse("warm-up", motion, settings)
                _wait_for_user_work()
                history_figure(motion, settings, rows[0], "normal")
                if settings.method == "coupled":
                    displacement_figure(rows)
        except Exception as err:  # the page says so; each analysis then reports its own error
            self.error = f"{type(err).__name__}: {err}"
        self.seconds = time.perf_counter() - start


#: the threads of the user's analyses and design studies (see Session)
_USER_WORK = ("blockdae-app-analysis", "blockdae-app-design")


def _wait_for_user_work():
    """Return once no analysis or design study of the user's is running."""
    while any(thread.name in _USER_WORK for thread in threading.enumerate()):
        time.sleep(0.05)


def _record_callbacks(app, sessions):
    app.clientside_callback(_BATCH, Output("upload-batch", "data"), Output("upload-files", "contents"),
                            Output("upload-folder", "contents"), Input("upload-files", "contents"),
                            Input("upload-folder", "contents"), State("upload-files", "filename"),
                            State("upload-folder", "filename"), State("upload-limits", "data"),
                            prevent_initial_call=True)

    @app.callback(Output("records-view", "children", allow_duplicate=True),
                  Output("record-messages", "children", allow_duplicate=True), Output("upload-batch", "data"),
                  Input("upload-batch", "data"), State("session", "data"), prevent_initial_call=True)
    def upload(batch, key):
        session = sessions[key]
        if not batch:
            return no_update, no_update, no_update
        messages = list(batch.get("refused") or [])
        for name, content in zip(batch.get("names") or [], batch.get("contents") or []):
            try:
                loaded = session.add_upload(name, content)
            except ValueError as err:  # the name, the size, the file: named; the rest of the batch goes on
                messages.append(str(err))
                continue
            if loaded.record is not None:
                session.thumbnails[loaded.label] = data_url(drawn(record_figure, loaded.record))
        return records_view(session, session.thumbnails), "\n".join(messages), None  # the files sent once

    @app.callback(Output("records-view", "children"), Output("record-messages", "children"),
                  Input({"type": "units", "file": ALL}, "value"),
                  Input({"type": "step-apply", "file": ALL}, "n_clicks"),
                  Input({"type": "remove", "file": ALL}, "n_clicks"),
                  State({"type": "step", "file": ALL}, "value"), State("session", "data"), prevent_initial_call=True)
    def records(_units, _step_clicks, _removes, typed_steps, key):
        session = sessions[key]
        trigger = ctx.triggered_id
        if not (isinstance(trigger, dict) and ctx.triggered[0]["value"]):
            return no_update, no_update
        label, messages = trigger["file"], []
        try:
            if trigger["type"] == "units":
                loaded = session.give(label, units=ctx.triggered[0]["value"])
            elif trigger["type"] == "step-apply":
                typed = next((value for spec, value in zip(ctx.states_list[0], typed_steps)
                              if spec["id"]["file"] == label), "")
                loaded = session.give(label, dt=_step(label, typed))
            else:
                session.remove(label)
                loaded = None
            if loaded is not None and loaded.record is not None:
                session.thumbnails[label] = data_url(drawn(record_figure, loaded.record))
        except ValueError as err:
            messages.append(str(err))
        return records_view(session, session.thumbnails), "\n".join(messages)


#: in the browser, the files just picked or dropped: those above the size limits are not
#: sent (a message names each), the others go to the server once (the uploads then hold none)
_BATCH = """
function (files, folder, fileNames, folderNames, limits) {
    const fromFolder = dash_clientside.callback_context.triggered.some(t => t.prop_id.startsWith("upload-folder"));
    const contents = (fromFolder ? folder : files) || [], names = (fromFolder ? folderNames : fileNames) || [];
    if (!contents.length) { return [dash_clientside.no_update, null, null]; }
    const megabytes = bytes => (bytes / 1e6).toFixed(1) + " MB";
    const batch = {names: [], contents: [], refused: []};
    let total = 0;
    contents.forEach((content, i) => {
        const data = content.slice(content.indexOf(",") + 1);
        const size = Math.floor(data.length * 3 / 4) - (data.endsWith("==") ? 2 : data.endsWith("=") ? 1 : 0);
        if (size > limits.file) {
            batch.refused.push(`${names[i]}: ${megabytes(size)} is above the app's limit of ` +
                               `${limits.file / 1e6} MB per file: not loaded`);
        } else if (total + size > limits.batch) {
            batch.refused.push(`${names[i]}: not loaded: the files given at once are at most ` +
                               `${limits.batch / 1e6} MB together; give it again in another batch`);
        } else {
            total += size;
            batch.names.push(names[i]);
            batch.contents.push(content);
        }
    });
    return [batch, null, null];
}
"""


def _step(label, typed):
    """The sample step [s] typed for the file ``label``; ValueError naming both."""
    try:
        dt = float(typed)
    except (TypeError, ValueError):
        raise ValueError(f"{label}: sample step dt [s] {typed!r} is not a number") from None
    if not (math.isfinite(dt) and dt > 0):
        raise ValueError(f"{label}: sample step dt [s] {typed!r} must be a positive number")
    return dt


def _analysis_callbacks(app, sessions):
    @app.callback(Output("ky-direct", "style"), Output("ky-safety", "style"), Output("ky-table-box", "style"),
                  Output("flexible-box", "style"), Output("strain-box", "style"),
                  Input("ky-mode", "value"), Input("method", "value"))
    def visible(mode, method):
        return (SHOWN if mode == "direct" else HIDDEN, SHOWN if mode == "safety" else HIDDEN,
                SHOWN if mode == "table" else HIDDEN, HIDDEN if method == "rigid" else SHOWN,
                SHOWN if method == "equivalent-linear" else HIDDEN)

    @app.callback(Output("poll", "disabled"), Output("progress", "children"), Output("analysis-messages", "children"),
                  Output("analysis-notes", "children"), Output("results-view", "children"),
                  Output("case", "options"), Output("case", "value"), Output("cancel", "disabled"),
                  Output("results-stamp", "data"), Output("dky-figure", "src"),
                  Output("history-figure", "src", allow_duplicate=True),
                  Input("run", "n_clicks"), Input("cancel", "n_clicks"), Input("poll", "n_intervals"),
                  *(State(name, "value") for name in _FORM), State("session", "data"), prevent_initial_call=True)
    def run(_run, _cancel, _poll, *values):
        *values, key = values
        session = sessions[key]
        trigger = ctx.triggered_id
        if trigger == "run":
            form = dict(zip((name.replace("-", "_") for name in _FORM), values))
            try:
                job = session.start(parse_settings(form))
            except ValueError as err:  # a FieldError too
                return True, "", str(err), no_update, no_update, no_update, no_update, True, *_UNCHANGED
            job.finished.wait(_WAIT_S)
        elif trigger == "cancel" and session.job is not None:
            session.job.cancelled.set()
            session.job.finished.wait(_WAIT_S)
        job = session.job
        if job is None:
            return True, "", no_update, no_update, no_update, no_update, no_update, True, *_UNCHANGED
        if not job.finished.is_set():
            return (False, f"running: {job.done} of {_records(job.total)}", "", "", no_update, no_update, no_update,
                    False, *_UNCHANGED)
        return _finished(session, job)


#: the last outputs of :func:`run` where no new results came: the results stamp, the two figures
_UNCHANGED = (no_update, no_update, no_update)


def _records(n):
    return f"{n} record{'' if n == 1 else 's'}"


def _finished(session, job):
    """The outputs of :func:`run` once ``job`` has finished: the results, or what stopped them."""
    stopped = job.cancelled.is_set() and job.done < job.total
    progress = (f"cancelled after {job.done} of {_records(job.total)} ({job.seconds:.3f} s)" if stopped else
                f"done: {_records(job.total)} in {job.seconds:.3f} s")
    results = session.finish(job)
    if results is None:
        return True, progress, "\n".join(job.errors), "\n".join(job.notes), no_update, no_update, no_update, True, \
            *_UNCHANGED
    best = int(np.nanargmax([row["max_m"] if row["max_m"] == row["max_m"] else -1.0 for row in results.rows]))
    return (True, progress, "\n".join(job.errors), "\n".join(job.notes), results_view(results), case_options(results),
            best, True, time.time(), "", "")  # the figures of the new results follow


def _result_callbacks(app, sessions):
    @app.callback(Output("dky-figure", "src", allow_duplicate=True), Input("results-stamp", "data"),
                  State("session", "data"), prevent_initial_call=True)
    def displacements(_, key):
        session = sessions[key]
        if session.results is None:
            return no_update
        return data_url(drawn(displacement_figure, session.results.rows))

    @app.callback(Output("history-figure", "src"), Output("history-messages", "children"),
                  Input("case", "value"), Input("history-polarity", "value"), Input("results-stamp", "data"),
                  State("session", "data"), prevent_initial_call=True)
    def history(case, polarity, _, key):
        results = sessions[key].results
        if results is None or case is None or case >= len(results.rows):
            return no_update, ""
        row = results.rows[case]
        if row[f"{polarity}_m"] != row[f"{polarity}_m"]:
            return "", f"the {polarity} polarity was not run: choose the other one"
        try:
            return data_url(drawn(history_figure, results.records[row["record"]], results.settings, row,
                                  polarity)), ""
        except ValueError as err:
            return "", str(err)

    @app.callback(Output("download", "data"), Output("history-messages", "children", allow_duplicate=True),
                  Input("download-csv-button", "n_clicks"), Input("download-dky-button", "n_clicks"),
                  Input("download-history-button", "n_clicks"), State("case", "value"),
                  State("history-polarity", "value"), State("session", "data"), prevent_initial_call=True)
    def download(_csv, _dky, _history, case, polarity, key):
        results = sessions[key].results
        if results is None:
            return no_update, "nothing to download yet: run an analysis first"
        trigger = ctx.triggered_id
        if trigger == "download-csv-button":
            return dcc.send_string(csv_text(results), "blockdae-results.csv"), ""
        if trigger == "download-dky-button":
            return dcc.send_bytes(drawn(displacement_figure, results.rows), "blockdae-D-against-ky.png"), ""
        if case is None:
            return no_update, "choose a case first"
        row = results.rows[case]
        try:
            data = drawn(history_figure, results.records[row["record"]], results.settings, row, polarity)
        except ValueError as err:
            return no_update, str(err)
        return dcc.send_bytes(data, f"blockdae-history-{row['record']}-{polarity}.png"), ""
