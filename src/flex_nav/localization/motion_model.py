"""The odometry motion model of a differential drive (Probabilistic Robotics, table 5.6), in the variant amcl
calls ``diff-corrected``: standard deviations are the square roots of the variance sums.

The motion between two odometry poses is taken apart into a turn towards the direction travelled (rot1), a
straight translation (trans) and a final turn (rot2). Each particle moves by the same three, each disturbed
by zero-mean Gaussian noise of variance

    rot1:  alpha1 * rot1² + alpha2 * trans²
    trans: alpha3 * trans² + alpha4 * (rot1² + rot2²)
    rot2:  alpha1 * rot2² + alpha2 * trans²

(alpha1: rotation from rotation, alpha2: rotation from translation, alpha3: translation from translation,
alpha4: translation from rotation). Backwards driving shows up as rot1 and rot2 near ±pi; the rotations in the
variances are therefore measured to the nearer of 0 and pi, so that reversing is not mistaken for two half
turns. The random numbers come from the caller's numpy Generator (deterministic for a seed); the per-particle
loop is compiled with numba (:func:`move_numba`), with a plain-numpy twin (:func:`move_numpy`).
"""

from __future__ import annotations

import math
from typing import NamedTuple, Tuple

import numpy as np

from flex_nav.localization.jit import Kernel, cached_njit
from flex_nav.nav.angles import wrap_angle
from flex_nav.nav.planar import Pose2D

MIN_TRANSLATION_FOR_HEADING = 0.01  # [m] below this the direction of travel (atan2 of the odometry step) is
#   noise, and the motion is taken as a turn on the spot (rot1 = 0)

Alphas = Tuple[float, float, float, float]  # (alpha1, alpha2, alpha3, alpha4)
_TWO_PI = 2.0 * math.pi


class OdometryMotion(NamedTuple):
    """One odometry step taken apart: turn, drive, turn."""

    rot1: float  # [rad] turn towards the direction travelled
    trans: float  # [m] distance travelled (>= 0)
    rot2: float  # [rad] turn after the translation


def decompose(old: Pose2D, new: Pose2D) -> OdometryMotion:
    """The motion from odometry pose ``old`` to ``new`` (both in the odom frame)."""
    dx, dy = new[0] - old[0], new[1] - old[1]
    trans = math.hypot(dx, dy)
    rot1 = wrap_angle(math.atan2(dy, dx) - old[2]) if trans >= MIN_TRANSLATION_FOR_HEADING else 0.0
    rot2 = wrap_angle(new[2] - old[2] - rot1)
    return OdometryMotion(rot1, trans, rot2)


def _turn_size(angle: float) -> float:
    """|angle| measured to the nearer of 0 and pi [rad] (driving backwards is no half turn)."""
    return min(abs(wrap_angle(angle)), abs(wrap_angle(angle - math.pi)))


def noise_stds(motion: OdometryMotion, alphas: Alphas) -> Tuple[float, float, float]:
    """Standard deviations of the noise on (rot1 [rad], trans [m], rot2 [rad])."""
    a1, a2, a3, a4 = alphas
    turn1, turn2, trans = _turn_size(motion.rot1), _turn_size(motion.rot2), motion.trans
    return (
        math.sqrt(a1 * turn1 * turn1 + a2 * trans * trans),
        math.sqrt(a3 * trans * trans + a4 * (turn1 * turn1 + turn2 * turn2)),
        math.sqrt(a1 * turn2 * turn2 + a2 * trans * trans),
    )


def sample_motion(
    particles: np.ndarray, motion: OdometryMotion, alphas: Alphas, rng: np.random.Generator,
    kernel: Kernel = Kernel.NUMBA,
) -> None:
    """Move every particle (rows ``[x [m], y [m], yaw [rad]]`` of ``particles``, C-contiguous float64, changed in
    place) by ``motion`` with independent noise; yaws stay wrapped into [-pi, pi]. ``kernel`` picks the compiled
    loop or its numpy twin (the same maths; the random numbers are drawn here either way)."""
    count = particles.shape[0]
    if count == 0:
        return
    std_rot1, std_trans, std_rot2 = noise_stds(motion, alphas)
    noise = rng.standard_normal((3, count))
    move = move_numba if kernel is Kernel.NUMBA else move_numpy
    move(particles, noise, motion.rot1, motion.trans, motion.rot2, std_rot1, std_trans, std_rot2)


@cached_njit
def move_numba(  # noqa: PLR0917 - a compiled kernel takes plain positional arguments
    particles: np.ndarray, noise: np.ndarray, rot1: float, trans: float, rot2: float, std_rot1: float,
    std_trans: float, std_rot2: float,
) -> None:  # pragma: no cover  (compiled; move_numpy is the readable twin)
    """Particle i turns by ``rot1 + std_rot1 * noise[0, i]``, drives ``trans + std_trans * noise[1, i]``, turns by
    ``rot2 + std_rot2 * noise[2, i]``; the yaw is wrapped into [-pi, pi]."""
    for i in range(particles.shape[0]):
        heading = particles[i, 2] + (rot1 + std_rot1 * noise[0, i])
        distance = trans + std_trans * noise[1, i]
        particles[i, 0] += distance * math.cos(heading)
        particles[i, 1] += distance * math.sin(heading)
        yaw = heading + (rot2 + std_rot2 * noise[2, i])
        particles[i, 2] = yaw - _TWO_PI * math.floor((yaw + math.pi) / _TWO_PI)


def move_numpy(  # noqa: PLR0917 - the same arguments as its compiled twin
    particles: np.ndarray, noise: np.ndarray, rot1: float, trans: float, rot2: float, std_rot1: float,
    std_trans: float, std_rot2: float,
) -> None:
    """:func:`move_numba` in plain numpy."""
    heading = particles[:, 2] + (rot1 + std_rot1 * noise[0])
    distance = trans + std_trans * noise[1]
    particles[:, 0] += distance * np.cos(heading)
    particles[:, 1] += distance * np.sin(heading)
    yaw = heading + (rot2 + std_rot2 * noise[2])
    particles[:, 2] = yaw - _TWO_PI * np.floor((yaw + math.pi) / _TWO_PI)
