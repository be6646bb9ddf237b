"""A model's states in tables and on axes: their names with the units it declares
(``state_units``)."""


def unit_suffix(unit: str) -> str:
    """A unit as a column name's suffix: "m/s" -> "m_s", "m/s²" -> "m_s2", "-" -> "ratio"."""
    if unit == "-":
        return "ratio"
    return unit.replace("/", "_").replace("²", "2").replace("³", "3").replace(" ", "")


def state_columns(model) -> list[str]:
    """The table columns of ``model``'s states: each name with its unit where the model
    declares ``state_units`` ("u_m", "u_rate_m_s"), else the names as they are."""
    units = getattr(model, "state_units", None)
    if units is None:
        return list(model.state_names)
    if len(units) != len(model.state_names):
        raise ValueError(f"{type(model).__name__}.state_units has {len(units)} units for {len(model.state_names)} "
                         f"states {tuple(model.state_names)}")
    return [f"{name}_{unit_suffix(unit)}" for name, unit in zip(model.state_names, units)]


def state_labels(model, n_states) -> list[str]:
    """Axis labels of ``model``'s states ("u [m]"), the names alone where no units are
    declared ("y0", ... without a model)."""
    if model is None:
        return [f"y{i}" for i in range(n_states)]
    units = getattr(model, "state_units", None) or (None,) * len(model.state_names)
    return [name if unit is None else f"{name} [{unit}]" for name, unit in zip(model.state_names, units)]
