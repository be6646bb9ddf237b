"""The page: records, analysis and results, in the order SLAMMER's users know, then the
design (Dash components; the ids are what the callbacks and the browser tests address)."""

from dash import dcc, html

from ._analysis import METHODS

SECTION = {"border": "1px solid #ccc", "borderRadius": "6px", "padding": "10px 16px", "margin": "12px 0"}
_DROP = {"border": "2px dashed #888", "borderRadius": "6px", "padding": "14px", "textAlign": "center",
         "width": "100%", "cursor": "pointer"}
_LABEL = {"display": "inline-block", "width": "260px"}
MESSAGES = {"color": "#a00000", "whiteSpace": "pre-wrap"}
NOTES = {"color": "#7a5a00", "whiteSpace": "pre-wrap"}
HIDDEN, SHOWN = {"display": "none"}, {"display": "block"}


def field(label, id_, value="", placeholder=""):
    """A labelled text field (text, so that what was typed reaches the checks as typed)."""
    return html.Div([html.Label(label, htmlFor=id_, style=_LABEL),
                     dcc.Input(id=id_, type="text", value=value, placeholder=placeholder, debounce=False,
                               style={"width": "220px"})], style={"margin": "4px 0"})


def radio(id_, value, options: dict):
    """Radio items in a row (``options``: value -> label)."""
    return dcc.RadioItems(id=id_, value=value, inline=True,
                          options=[{"label": label, "value": key} for key, label in options.items()],
                          inputStyle={"marginLeft": "12px", "marginRight": "4px"})


def layout(*sections):
    """The page's components, ``sections`` (components) after the results."""
    return html.Div(style={"fontFamily": "sans-serif", "maxWidth": "1100px", "margin": "0 auto"}, children=[
        html.H2("blockdae: sliding displacements of slopes"),
        html.Div(id="engine-status", style={"color": "#555"}),
        dcc.Interval(id="engine-poll", interval=500),
        html.Div(style=SECTION, children=[
            html.H3("1. Records"),
            html.Div(style={"display": "flex", "gap": "2%"}, children=[
                dcc.Upload(id="upload-files", multiple=True, style=_DROP,
                           children=html.Div(["Drop record files here or ", html.A("pick files")])),
                dcc.Upload(id="upload-folder", multiple=True, enable_folder_selection=True, style=_DROP,
                           children=html.Div(["Pick a folder of records"]))]),
            html.Div("Every format blockdae reads: two columns (time [s], acceleration), one column with its step, "
                     "PEER AT2, COSMOS V1/V2, K-NET/KiK-net, ESM; each also .gz. A file whose header does not "
                     "state its units asks for them here.", style={"color": "#555", "fontSize": "small"}),
            html.Div(id="record-messages", role="alert", style=MESSAGES),
            html.Div(id="records-view"),
        ]),
        html.Div(style=SECTION, children=[
            html.H3("2. Analysis"),
            dcc.RadioItems(id="method", value="coupled", inline=True,
                           options=[{"label": label, "value": key} for key, label in METHODS.items()],
                           inputStyle={"marginLeft": "12px", "marginRight": "4px"}),
            html.H4("Yield acceleration"),
            dcc.RadioItems(id="ky-mode", value="direct", inline=True,
                           options=[{"label": "ky directly", "value": "direct"},
                                    {"label": "from a factor of safety and thrust angle", "value": "safety"},
                                    {"label": "a ky(D) table", "value": "table"}],
                           inputStyle={"marginLeft": "12px", "marginRight": "4px"}),
            html.Div(id="ky-direct", children=field("ky [g] (one or several: 0.05, 0.1)", "ky", "0.1")),
            html.Div(id="ky-safety", style=HIDDEN, children=[
                field("factor of safety [-]", "factor-of-safety", "1.2"),
                field("thrust angle [°]", "thrust-angle", "25")]),
            html.Div(id="ky-table-box", style=HIDDEN, children=[
                html.Label("ky(D) table: lines 'D [m], ky [g]', D increasing", htmlFor="ky-table"),
                dcc.Textarea(id="ky-table", value="0, 0.15\n0.5, 0.05", style={"width": "300px", "height": "70px"})]),
            html.Div(id="flexible-box", children=[
                html.H4("Flexible sliding mass"),
                field("slope height H [m]", "height", "20"),
                field("shear-wave velocity Vs [m/s]", "vs", "300"),
                field("damping ratio [-] (impedance damping added)", "damping", "0.05")]),
            html.Div(id="strain-box", style=HIDDEN,
                     children=field("reference strain [-] (a fraction: 0.0005 is 0.05 %)", "reference-strain",
                                     "0.0005")),
            html.H4("Motions"),
            field("target PGA [g] (empty: as recorded)", "pga", ""),
            dcc.RadioItems(id="polarity", value="both", inline=True,
                           options=[{"label": "both polarities", "value": "both"},
                                    {"label": "normal", "value": "normal"}, {"label": "inverse", "value": "inverse"}],
                           inputStyle={"marginLeft": "12px", "marginRight": "4px"}),
            html.Div(style={"margin": "10px 0"}, children=[
                html.Button("Run", id="run", n_clicks=0, style={"fontSize": "large", "padding": "4px 24px"}),
                html.Button("Cancel", id="cancel", n_clicks=0, disabled=True, style={"marginLeft": "12px"}),
                html.Span(id="progress", style={"marginLeft": "16px"})]),
            dcc.Interval(id="poll", interval=150, disabled=True),
            html.Div(id="analysis-messages", role="alert", style=MESSAGES),
            html.Div(id="analysis-notes", style=NOTES),
        ]),
        html.Div(style=SECTION, children=[
            html.H3("3. Results"),
            html.Div(id="results-view", children="Run an analysis to see D per record."),
            html.Div(style={"margin": "8px 0"}, children=[
                html.Button("Download the table (CSV)", id="download-csv-button", n_clicks=0),
                html.Button("Download D against ky (PNG)", id="download-dky-button", n_clicks=0,
                            style={"marginLeft": "8px"}),
                html.Button("Download the history (PNG)", id="download-history-button", n_clicks=0,
                            style={"marginLeft": "8px"})]),
            dcc.Download(id="download"),
            dcc.Store(id="results-stamp"),
            html.Img(id="dky-figure", style={"maxWidth": "100%"}),
            html.H4("History of one case"),
            html.Div(style={"display": "flex", "gap": "12px", "alignItems": "center"}, children=[
                dcc.Dropdown(id="case", options=[], clearable=False, style={"width": "520px"}),
                dcc.RadioItems(id="history-polarity", value="normal", inline=True,
                               options=[{"label": "normal", "value": "normal"},
                                        {"label": "inverse", "value": "inverse"}],
                               inputStyle={"marginLeft": "12px", "marginRight": "4px"})]),
            html.Div(id="history-messages", role="alert", style=MESSAGES),
            html.Img(id="history-figure", style={"maxWidth": "100%"}),
        ]),
        *sections,
    ])
