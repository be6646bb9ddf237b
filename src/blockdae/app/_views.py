"""What the callbacks put in the page: the records' table, the units each waiting file asks
for, the results table, figures as PNG data (matplotlib, drawn one at a time)."""

import base64
import io
import math
import threading

from dash import dcc, html

from ._analysis import COLUMNS
from ._page import NOTES
from ._records import unit_choices, summary

_FIGURES = threading.Lock()  # pyplot's figure list is not thread-safe; requests come on threads
_CELL = {"border": "1px solid #ddd", "padding": "2px 8px", "textAlign": "right"}
_HEAD = {**_CELL, "background": "#f0f0f0", "position": "sticky", "top": "0"}
_SCROLL = {"maxHeight": "480px", "overflowY": "auto"}  # a long list scrolls in its box
#: the records table's (key, heading, format)
RECORD_COLUMNS = (("file", "file", "{}"), ("record", "record", "{}"), ("format", "format", "{}"),
                  ("units", "units", "{}"), ("dt_s", "dt [s]", "{:.4g}"), ("samples", "samples", "{}"),
                  ("duration_s", "duration [s]", "{:.2f}"), ("pga_g", "PGA [g]", "{:.4f}"),
                  ("station", "station", "{}"), ("component", "component", "{}"))
#: the results table's headings, by column
HEADINGS = {"record": "record", "pga_g": "PGA [g]", "ky_g": "ky [g]", "normal_m": "D normal [m]",
            "inverse_m": "D inverse [m]", "mean_m": "D mean [m]", "max_m": "D max [m]", "kmax_g": "kmax [g]"}


def png(figure) -> bytes:
    """``figure`` (matplotlib) as PNG bytes; a pyplot figure is closed."""
    import matplotlib.pyplot as plt

    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=100)
    plt.close(figure)
    return buffer.getvalue()


def drawn(make_figure, *args) -> bytes:
    """PNG bytes of ``make_figure(*args)``, one figure at a time."""
    with _FIGURES:
        return png(make_figure(*args))


def data_url(data: bytes) -> str:
    return "data:image/png;base64," + base64.b64encode(data).decode()


def table(id_, headings, rows):
    return html.Table(id=id_, style={"borderCollapse": "collapse", "fontSize": "small", "margin": "6px 0"}, children=[
        html.Thead(html.Tr([html.Th(h, style=_HEAD) for h in headings])),
        html.Tbody([html.Tr([html.Td(cell, style=_CELL) for cell in row]) for row in rows])])


def records_view(session, thumbnails: dict):
    """The loaded records (table and a figure of each) and the files waiting for units or a step."""
    ready = [f for f in session.files.values() if f.record is not None]
    waiting = [f for f in session.files.values() if f.record is None]
    parts = []
    if waiting:
        parts.append(html.Div(id="waiting", children=[_waiting(f) for f in waiting]))
    if ready:
        rows = []
        for loaded in ready:
            row = summary(loaded)
            rows.append([fmt.format(row[key]) for key, _, fmt in RECORD_COLUMNS] +
                        [html.Button("remove", id={"type": "remove", "file": loaded.label}, n_clicks=0)])
        parts.append(html.Div(table("records-table", [h for _, h, _ in RECORD_COLUMNS] + [""], rows), style=_SCROLL))
        notes = [f"{f.label}: {note}" for f in ready for note in f.notes]
        if notes:
            parts.append(html.Div("\n".join(notes), style={**NOTES, "fontSize": "small"}))
        parts.append(html.Div(id="record-figures", style=_SCROLL, children=[
            html.Img(src=thumbnails[f.label], title=f.label, style={"width": "49%"}) for f in ready
            if f.label in thumbnails]))
    return parts


def _waiting(loaded):
    """The question a file asks: its units (the peak in each) or its sample step."""
    if loaded.needs == "units":
        return html.Div(className="needs-units", style={"margin": "6px 0", "padding": "6px",
                                                        "background": "#fff6e0"}, children=[
            html.B(loaded.label), " does not state the units of its accelerations; they are:",
            dcc.RadioItems(id={"type": "units", "file": loaded.label}, value=None,
                           options=[{"label": label, "value": units} for units, label in unit_choices(loaded.raw_peak)],
                           inputStyle={"marginLeft": "12px", "marginRight": "4px"})])
    return html.Div(className="needs-step", style={"margin": "6px 0", "padding": "6px", "background": "#fff6e0"},
                    children=[html.B(loaded.label), " is one column of accelerations; its sample step dt [s]: ",
                              dcc.Input(id={"type": "step", "file": loaded.label}, type="text", value=""),
                              html.Button("use this step", id={"type": "step-apply", "file": loaded.label},
                                          n_clicks=0)])


def _shown(value, key):
    if isinstance(value, str):
        return value
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    return f"{value:.4f}" if key.endswith("_g") else f"{value:.5g}"


def result_columns(settings):
    """The results table's columns: kmax only for a flexible mass."""
    return [c for c in COLUMNS if c != "kmax_g" or settings.flexible]


def results_view(results):
    """The table of D per (record, PGA, ky)."""
    columns = result_columns(results.settings)
    rows = [[_shown(row[c], c) for c in columns] for row in results.rows]
    return [html.Div(table("results-table", [HEADINGS[c] for c in columns], rows), style=_SCROLL)]


def case_options(results):
    """The cases to draw (dropdown options): one per row, labelled by record and ky."""
    return [{"label": f"{row['record']}, ky = {row['ky_g']:g} g, PGA {row['pga_g']:.3g} g", "value": i}
            for i, row in enumerate(results.rows)]


def csv_text(results) -> str:
    """The results table as CSV (units in the column names), full precision."""
    import pandas as pd

    return pd.DataFrame([{c: row[c] for c in result_columns(results.settings)} for row in results.rows]).to_csv(
        index=False)
