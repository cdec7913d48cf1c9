"""The likelihood-field laser model over all particles: how well each particle's pose explains a scan.

For a particle and a beam, the beam's end point (range measured, direction from the particle's pose and the
laser's mount) falls in some cell; the beam's probability is ``p = z_hit * exp(-e² / (2 sigma²)) +
z_rand / range_max`` with ``e`` that cell's distance to the obstacle's edge
(:attr:`~flex_nav.localization.likelihood_field.LikelihoodField.edge_distance`; outside the map and in unknown
cells only the floor ``z_rand / range_max``). The per-cell ``log p`` is tabulated once per map, range_max and
sigma, so the hot loop is one look-up per beam.

How beams combine into a particle's likelihood of the whole scan: amcl sums cubes, ``1 + sum(p³)``, a heuristic
that keeps one particle's weight within a factor (1 + K) of another's and is never sharp. Here the beams'
log-probabilities are summed and tempered, ``TEMPERATURE * sum(log p)``: the product of the beam probabilities is
what independent beams give, and the tempering (< 1) allows for beams that are not independent (neighbours see
the same wall, a map error repeats along it). In ``bench/bench_localization_accuracy.py`` (TurtleBot 2 on the
lab lap, everything else equal, three seeds) the cube sum gave a position error of 3.1 cm median, 5.3 cm p95,
and global localization in 8 to 21 s; this gives 1.1 cm, 2.4 cm and 1 to 4 s: a particle a few cm off loses
weight by a large factor, so the cloud stays on the scans.

Coarse to fine (:func:`annealed_sigma`): with a narrow Gaussian, a particle 30 cm off scores no better than one
3 m off, so a wide cloud (a rough initial pose, global localization) would have nothing to climb. While the
cloud is wide, sigma is widened with it (in steps of 2x from laser_sigma_hit, following half the cloud's spread),
and comes back to laser_sigma_hit as the cloud converges.

Two implementations of the same maths: :func:`beam_sums_numba` (the hot loop, particles x beams, compiled with
numba) and :func:`beam_sums_numpy` (plain numpy, the reference of the benchmark and of a test that both agree).
Both take the same inputs, prepared once per update by :class:`SensorModel` in numpy (the cosines included, so
that both see bit-identical coordinates and pick the same cells).
"""

from __future__ import annotations

import math
from typing import Dict, Optional, Tuple

import numpy as np

from flex_nav.localization.jit import Kernel, cached_njit
from flex_nav.localization.likelihood_field import LikelihoodField
from flex_nav.localization.params import FilterParams
from flex_nav.localization.scan import SelectedBeams

KernelInputs = Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]  # px .. by
TEMPERATURE = 0.5  # [-] weight of the summed beam log-likelihoods (1 = beams independent)
ANNEAL_GAIN = 0.5  # [-] the Gaussian's std follows this fraction of the cloud's spread ...
ANNEAL_LEVELS = 5  # ... in steps of 2x from laser_sigma_hit, at most 2^(levels - 1) times it
TABLES_KEPT = 3  # per-cell tables kept (one per range_max and Gaussian width in use)


def annealed_sigma(sigma_hit: float, spread: float) -> float:
    """The Gaussian's std [m] for a cloud of ``spread`` [m]: ``sigma_hit * 2^j``, the largest such value up to
    ``ANNEAL_GAIN * spread``, j at most ``ANNEAL_LEVELS - 1``; ``sigma_hit`` for a converged cloud."""
    if not spread > 0.0:
        return sigma_hit
    level = math.floor(math.log2(max(ANNEAL_GAIN * spread / sigma_hit, 1.0)))
    return sigma_hit * 2.0 ** min(level, ANNEAL_LEVELS - 1)


@cached_njit
def beam_sums_numba(  # noqa: PLR0917 - a compiled kernel takes plain positional arguments
    px: np.ndarray, py: np.ndarray, cos_yaw: np.ndarray, sin_yaw: np.ndarray, bx: np.ndarray, by: np.ndarray,
    table: np.ndarray, height: int, width: int,
) -> np.ndarray:  # pragma: no cover  (compiled; the numpy twin below is the readable version)
    """For each particle i: the sum over beams j of ``table[cell]``, the cell of the end point
    ``(px[i] + cos_yaw[i] * bx[j] - sin_yaw[i] * by[j], py[i] + sin_yaw[i] * bx[j] + cos_yaw[i] * by[j])``
    in grid coordinates [cells]; ``table[height * width]`` for an end point outside the grid."""
    count = px.shape[0]
    beams = bx.shape[0]
    outside = height * width
    out = np.empty(count)
    for i in range(count):
        x0, y0, c, s = px[i], py[i], cos_yaw[i], sin_yaw[i]
        total = 0.0
        for j in range(beams):
            gx = x0 + c * bx[j] - s * by[j]
            gy = y0 + s * bx[j] + c * by[j]
            if gx >= 0.0 and gx < width and gy >= 0.0 and gy < height:  # also False for NaN
                total += table[int(gy) * width + int(gx)]
            else:
                total += table[outside]
        out[i] = total
    return out


def beam_sums_numpy(  # noqa: PLR0917 - the same arguments as its compiled twin
    px: np.ndarray, py: np.ndarray, cos_yaw: np.ndarray, sin_yaw: np.ndarray, bx: np.ndarray, by: np.ndarray,
    table: np.ndarray, height: int, width: int,
) -> np.ndarray:
    """:func:`beam_sums_numba` in plain numpy ((N, K) arrays)."""
    gx = px[:, None] + cos_yaw[:, None] * bx[None, :] - sin_yaw[:, None] * by[None, :]
    gy = py[:, None] + sin_yaw[:, None] * bx[None, :] + cos_yaw[:, None] * by[None, :]
    inside = (gx >= 0.0) & (gx < width) & (gy >= 0.0) & (gy < height)
    cells = np.where(inside, np.where(inside, gy, 0.0).astype(np.int64) * width + np.where(inside, gx, 0.0)
                     .astype(np.int64), height * width)
    return np.asarray(table[cells].sum(axis=1, dtype=np.float64))


class SensorModel:
    """Scores particles against a scan on one map's likelihood field."""

    def __init__(self, params: FilterParams, field: LikelihoodField) -> None:
        self.params = params
        self.field = field
        self._tables: Dict[Tuple[float, float], np.ndarray] = {}  # (range_max [m], sigma [m]) -> flat table

    def table(self, range_max: float, sigma: float) -> np.ndarray:
        """The flat per-cell table of ``log p`` for scans of this ``range_max`` [m] and a Gaussian of std ``sigma``
        [m] (built at first use, then kept; the few most recent are kept)."""
        key = (range_max, sigma)
        table = self._tables.pop(key, None)
        if table is None:
            p = self.params
            table = self.field.beam_table(p.laser_z_hit, p.laser_z_rand, sigma, range_max)
            while len(self._tables) >= TABLES_KEPT:
                del self._tables[next(iter(self._tables))]  # the least recently used
        self._tables[key] = table
        return table

    def log_likelihoods(
        self, particles: np.ndarray, beams: SelectedBeams, range_max: float, sigma: Optional[float] = None,
        kernel: Kernel = Kernel.NUMBA,
    ) -> np.ndarray:
        """(N,) tempered log-likelihood of the scan for each particle (rows ``[x [m], y [m], yaw [rad]]``, map
        frame), with the Gaussian's std ``sigma`` [m] (default: laser_sigma_hit)."""
        px, py, cos_yaw, sin_yaw, bx, by = self.grid_inputs(particles, beams)
        height, width = self.field.shape
        table = self.table(range_max, self.params.laser_sigma_hit if sigma is None else sigma)
        sums = (beam_sums_numba if kernel is Kernel.NUMBA else beam_sums_numpy)(
            px, py, cos_yaw, sin_yaw, bx, by, table, height, width
        )
        return np.asarray(TEMPERATURE * sums)

    def grid_inputs(self, particles: np.ndarray, beams: SelectedBeams) -> KernelInputs:
        """Particle positions in grid coordinates [cells], their headings' cosines and sines relative to the grid,
        and the beam end points in the robot frame in cells: the inputs of both kernels."""
        grid = self.field.grid
        ox, oy, oyaw = grid.origin
        dx = particles[:, 0] - ox
        dy = particles[:, 1] - oy
        if oyaw != 0.0:
            c, s = math.cos(oyaw), math.sin(oyaw)
            dx, dy = c * dx + s * dy, -s * dx + c * dy
        inv = 1.0 / grid.resolution
        yaw = particles[:, 2] - oyaw
        return (
            np.ascontiguousarray(dx * inv), np.ascontiguousarray(dy * inv), np.cos(yaw), np.sin(yaw),
            np.ascontiguousarray(beams.x * inv), np.ascontiguousarray(beams.y * inv),
        )
