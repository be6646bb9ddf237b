"""The design section of the page (Dash components, their ids prefixed "design-"), what its
clicks do, and what the callbacks put in it: P(D > threshold) with its interval, the
exceedance curve, each record's part, the samples as CSV, the mean ky a design needs."""

from dash import Dash, Input, Output, State, ctx, dcc, html, no_update

from ._analysis import METHODS
from ._design import POLARITIES, SAMPLINGS, DesignJob, parse_design, parse_inverse
from ._page import HIDDEN, MESSAGES, NOTES, SECTION, SHOWN, field, radio
from ._views import data_url, drawn, table

#: how long a click waits for the study before showing progress instead [s]
_WAIT_S = 0.8
#: the form's fields: (id, the key parse_design and parse_inverse read)
FORM = tuple((f"design-{name.replace('_', '-')}", name) for name in (
    "method", "polarity", "ky_mean", "ky_cov", "height_mean", "height_cov", "vs_mean", "vs_cov", "damping",
    "reference_strain", "pga", "sampling", "seed", "rse", "halfwidth", "runs_per_block", "max_runs", "threshold",
    "allowable", "target", "inverse_runs"))


def design_section():
    """The design section's components."""
    return html.Div(style=SECTION, children=[
        html.H3("4. Design"),
        html.Div("On the records loaded above: the slope's properties are uncertain, each log-normal by its mean "
                 "and coefficient of variation (a cov of 0 keeps the value fixed). Each run draws one set of "
                 "properties per record.", style={"color": "#555", "fontSize": "small"}),
        radio("design-method", "coupled", METHODS),
        radio("design-polarity", "normal", {key: f"D {label}" for key, label in POLARITIES.items()}),
        html.H4("The slope"),
        field("mean ky [g]", "design-ky-mean", "0.1"), field("cov of ky [-]", "design-ky-cov", "0.3"),
        html.Div(id="design-flexible-box", children=[
            field("mean slope height H [m]", "design-height-mean", "20"),
            field("cov of slope height H [-]", "design-height-cov", "0"),
            field("mean shear-wave velocity Vs [m/s]", "design-vs-mean", "300"),
            field("cov of shear-wave velocity Vs [-]", "design-vs-cov", "0.15"),
            field("damping ratio [-] (impedance damping added)", "design-damping", "0.05")]),
        html.Div(id="design-strain-box", style=HIDDEN,
                 children=field("reference strain [-] (a fraction)", "design-reference-strain", "0.0005")),
        field("target PGA [g] (empty: as recorded)", "design-pga", ""),
        html.H4("Sampling"),
        radio("design-sampling", "sobol", SAMPLINGS),
        field("seed (an integer: the same seed, the same samples)", "design-seed", "0"),
        field("stop at a relative standard error of the mean D [-]", "design-rse", "0.05"),
        field("and a half-width of the 95 % interval of P [-] (empty: none)", "design-halfwidth", ""),
        field("runs per block (Sobol: a power of 2)", "design-runs-per-block", "16"),
        field("at most runs (with neither precision: exactly these)", "design-max-runs", "256"),
        html.H4("Probability of exceedance"),
        field("threshold displacement [m]", "design-threshold", "0.1"),
        html.Button("Run the design", id="design-run", n_clicks=0, style={"fontSize": "large", "padding": "4px 24px"}),
        html.H4("The ky a design needs"),
        field("allowable displacement [m]", "design-allowable", "0.1"),
        field("target probability of exceeding it [-]", "design-target", "0.1"),
        field("samples per record (Sobol: a power of 2)", "design-inverse-runs", "64"),
        html.Button("Find the ky", id="design-inverse-run", n_clicks=0,
                    style={"fontSize": "large", "padding": "4px 24px"}),
        html.Div(style={"margin": "10px 0"}, children=[
            html.Button("Cancel", id="design-cancel", n_clicks=0, disabled=True),
            html.Span(id="design-progress", style={"marginLeft": "16px"})]),
        dcc.Interval(id="design-poll", interval=250, disabled=True),
        html.Div(id="design-messages", role="alert", style=MESSAGES),
        html.Div(id="design-notes", style=NOTES),
        html.Div(id="design-result", children="Run the design to see P(D > threshold)."),
        html.Button("Download the samples (CSV)", id="design-download-button", n_clicks=0),
        dcc.Download(id="design-download"),
        html.Img(id="design-figure", style={"maxWidth": "100%"}),
        html.Div(id="design-inverse-result")])


def design_callbacks(app: Dash, sessions):
    @app.callback(Output("design-flexible-box", "style"), Output("design-strain-box", "style"),
                  Input("design-method", "value"))
    def visible(method):
        return HIDDEN if method == "rigid" else SHOWN, SHOWN if method == "equivalent-linear" else HIDDEN

    @app.callback(Output("design-poll", "disabled"), Output("design-progress", "children"),
                  Output("design-messages", "children"), Output("design-notes", "children"),
                  Output("design-cancel", "disabled"), Output("design-result", "children"),
                  Output("design-figure", "src"), Output("design-inverse-result", "children"),
                  Input("design-run", "n_clicks"), Input("design-inverse-run", "n_clicks"),
                  Input("design-cancel", "n_clicks"), Input("design-poll", "n_intervals"),
                  *(State(id_, "value") for id_, _ in FORM), State("session", "data"), prevent_initial_call=True)
    def run(_run, _inverse, _cancel, _poll, *values):
        *values, key = values
        session = sessions[key]
        trigger = ctx.triggered_id
        unchanged = (no_update, no_update, no_update)
        if trigger in ("design-run", "design-inverse-run"):
            form = dict(zip((key for _, key in FORM), values))
            try:
                settings = parse_design(form)
                inverse = parse_inverse(form, settings) if trigger == "design-inverse-run" else None
                job = session.start_design(settings, "exceedance" if inverse is None else "inverse", inverse)
            except ValueError as err:  # a FieldError too
                return True, "", str(err), no_update, True, *unchanged
            job.finished.wait(_WAIT_S)
        elif trigger == "design-cancel" and session.design_job is not None:
            session.design_job.cancelled.set()
            session.design_job.finished.wait(_WAIT_S)
        job = session.design_job
        if job is None:
            return True, "", no_update, no_update, True, *unchanged
        if not job.finished.is_set():
            return False, f"running: {_progress(job)}", "", "", False, *unchanged
        if job.kind == "exceedance" and job.result is not None:
            session.design = job.result  # what the CSV downloads
        return True, _done(job), job.error or "", "\n".join(job.notes), True, *_views(job)

    @app.callback(Output("design-download", "data"), Output("design-messages", "children", allow_duplicate=True),
                  Input("design-download-button", "n_clicks"), State("session", "data"), prevent_initial_call=True)
    def download(_, key):
        session = sessions[key]
        if session.design is None:
            return no_update, "nothing to download yet: run the design first"
        return dcc.send_string(session.design.table.to_csv(index=False), "blockdae-design-samples.csv"), ""


def _progress(job: DesignJob):
    if job.kind == "exceedance":
        settings = job.settings
        return f"{job.analyses} analyses of at most {settings.max_runs * len(job.records)}"
    return f"{job.analyses} analyses (root finding per sample and record)"


def _done(job: DesignJob):
    what = "design" if job.kind == "exceedance" else "ky a design needs"
    if job.cancelled.is_set() and job.result is None:
        return f"{what}: cancelled after {job.analyses} analyses ({job.seconds:.3f} s)"
    if job.result is None:
        return ""
    return f"{what}: done, {job.analyses} analyses in {job.seconds:.3f} s"


def _views(job: DesignJob):
    """(the exceedance's view, its figure, the inverse's view) for a finished ``job``, made
    once: the page polls every 250 ms and applies only the answer to its latest poll, so
    an answer that drew the figure each time (longer than that on a busy computer) would
    never be shown."""
    if job.result is None:
        return no_update, no_update, no_update
    if job.kind == "inverse":
        return no_update, no_update, inverse_view(job.result, job.inverse)
    if "figure" not in vars(job):
        job.figure = data_url(drawn(job.result.figure))
    return exceedance_view(job.result, job.settings), job.figure, no_update


def _stopping(result, settings):
    if settings.rse is None and settings.halfwidth is None:
        return "none: a fixed number of runs"
    return "met" if result.converged else "not met: the runs allowed are done"


def exceedance_view(result, settings):
    """P(D > threshold) with its interval and the study's numbers (``settings``: the
    study's :class:`DesignSettings`); each record's part."""
    low, high = result.probability_interval
    d = result.table["D_m"].to_numpy()
    above = int((d > result.threshold_m).sum())
    runs = int(result.table["run"].max()) + 1
    rows = [["P(D > threshold) [-]", f"{result.probability:.4f} ({above} of {d.size} analyses)"],
            [f"{result.confidence:.0%} interval (Wilson) [-]", f"{low:.4f} to {high:.4f}"],
            ["threshold [m]", f"{result.threshold_m:g}"],
            ["mean D [m]", f"{result.mean_m:.4g}"],
            ["relative standard error of the mean D [-]", f"{result.rse:.3g}"],
            ["runs (one set of properties per record each)", f"{runs}"],
            ["stopping rule", _stopping(result, settings)]]
    parts = [[row["record"], f"{row['samples']}", f"{row['mean_D_m']:.4g}", f"{row['P_exceed']:.4f}",
              f"{row['share']:.3f}"] for _, row in result.contributions().iterrows()]
    return [table("design-summary", ["", "value"], rows),
            html.H4("Each record's part"),
            table("design-contributions", ["record", "samples", "mean D [m]", "P(D > threshold) [-]",
                                           "share of the exceedances [-]"], parts)]


def inverse_view(inverse, settings):
    """The mean ky a design needs and each record's ky for the allowable."""
    design = inverse.design
    samples = len(design.table)
    text = (f"mean ky needed: {design.mean_ky_g:.4f} g for P(D > {design.allowable_m:g} m) <= {design.target:g} "
            f"over {samples} samples (cov of ky kept); there P = {design.probability(design.mean_ky_g):.4f}")
    rows = [[name, "as recorded" if pga is None else f"{pga:.4g}",
             "none needed (D < allowable at ky = 0.0001 g)" if ky is None else f"{ky:.4f}"]
            for name, pga, ky in inverse.per_record]
    return [html.Div(text, id="design-mean-ky", style={"fontWeight": "bold", "margin": "6px 0"}),
            table("design-ky-table", ["record", "target PGA [g]",
                                      f"ky for D = {settings.allowable:g} m [g] (properties at their means)"], rows)]
