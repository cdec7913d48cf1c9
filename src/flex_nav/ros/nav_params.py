"""Algorithm parameter sets read from a node's private parameters (validated; units in the docstrings)."""

from __future__ import annotations

import dataclasses

from flex_nav.exceptions import ConfigError
from flex_nav.nav.planning.planner import PlannerParams
from flex_nav.ros.params import param_bool, param_float, param_int, reject_unknown


def planner_params(ns: str = "~planner/") -> PlannerParams:
    """:class:`PlannerParams` from ``<ns>``: ``neutral_cost``, ``cost_factor``, ``lethal_cost`` (1..255),
    ``allow_unknown``, ``unknown_cost`` (0..254), ``diagonal_factor`` (1..2), ``goal_tolerance`` [m],
    ``start_escape`` [m],
    ``smooth``, ``smoothing_slack``,
    ``simplify``; defaults are PlannerParams' own."""
    reject_unknown(ns, [f.name for f in dataclasses.fields(PlannerParams)])
    d = PlannerParams()
    try:
        return PlannerParams(
            neutral_cost=param_float(ns + "neutral_cost", d.neutral_cost, 1e-9),
            cost_factor=param_float(ns + "cost_factor", d.cost_factor, 0.0),
            lethal_cost=param_int(ns + "lethal_cost", d.lethal_cost, 1, 255),
            allow_unknown=param_bool(ns + "allow_unknown", d.allow_unknown),
            unknown_cost=param_int(ns + "unknown_cost", d.unknown_cost, 0, 254),
            diagonal_factor=param_float(ns + "diagonal_factor", d.diagonal_factor, 1.0, 2.0),
            goal_tolerance=param_float(ns + "goal_tolerance", d.goal_tolerance, 0.0, 100.0),
            start_escape=param_float(ns + "start_escape", d.start_escape, 0.0, 10.0),
            smooth=param_bool(ns + "smooth", d.smooth),
            smoothing_slack=param_float(ns + "smoothing_slack", d.smoothing_slack, 0.0, 10.0),
            simplify=param_bool(ns + "simplify", d.simplify),
        )
    except ConfigError as err:
        raise ConfigError(f"{ns}: {err}") from err
