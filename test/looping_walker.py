"""A scripted walker for unit tests of the walker lanes and of giving way: up and down a line x = const."""

from __future__ import annotations

from flex_nav.perception.moving_obstacles import Track


def walker_on_lane(t: float, x: float, y_low: float, y_high: float, speed: float, *, radius: float = 0.2,
                   track_id: int = 1) -> Track:
    """The track at time ``t`` [s] of a walker going up and down x = ``x`` [m] between ``y_low`` and ``y_high``
    [m] at ``speed`` [m/s], at y_low going up at t = 0 (position and velocity exact)."""
    span = y_high - y_low
    phase = (speed * t) % (2 * span)
    if phase <= span:
        return Track(track_id, x, y_low + phase, 0.0, speed, radius, t, 10)
    return Track(track_id, x, y_high - (phase - span), 0.0, -speed, radius, t, 10)
