"""The mapper's pose graph: robot poses as nodes, measured relative poses as edges, optimized with gtsam.

**Model.** Node ``k`` is the robot's pose ``X_k = (x [m], y [m], yaw [rad])`` in the map frame when scan ``k`` was
taken. An edge ``i -> j`` measures ``Z_ij``, the pose of ``j`` in ``i``'s frame, with a (3, 3) covariance over
(x, y, yaw) of that measurement. Each edge is a gtsam ``BetweenFactorPose2`` whose residual is the 3-vector
``r = Log(Z_ij^-1 * X_i^-1 * X_j)`` (the SE(2) logarithm, gtsam's Pose2 chart), whitened by the covariance: its
cost is ``0.5 * r^T Sigma^-1 r``. The first node gets a ``PriorFactorPose2`` at its initial pose with standard
deviations ``prior_sigmas`` (it fixes the map frame; without it the graph could slide and turn freely). The
optimizer minimises the sum of the costs over the poses (the estimate moves by ``X <- X * Exp(delta)``).

**Edge kinds.** ODOMETRY (wheel odometry between consecutive nodes) and SCAN_MATCH (a scan matched against the
last scans) are plain Gaussian factors. LOOP edges (a scan matched against a part of the map seen long ago) get a
robust kernel on the whitened residual's length ``u = sqrt(r^T Sigma^-1 r)``: their cost is ``rho(u)`` instead of
``u^2 / 2``.

**Why Cauchy.** ``rho(u) = k^2 / 2 * log(1 + u^2 / k^2)`` (:attr:`LoopKernel.CAUCHY`, ``k = loop_kernel_width``,
in standard deviations). Its pull on the map, ``rho'(u) = u / (1 + u^2 / k^2)``, is largest at ``u = k`` and falls
off as ``k^2 / u`` beyond: a closure many standard deviations wrong pulls hardly at all, so one false closure cannot
bend the whole map. Huber's pull (quadratic up to ``k``, linear beyond) stays at ``k`` however wrong the closure is,
so a false closure still bends the map, the more the larger ``k``. The price of Cauchy is a cost that is not
convex: a true closure far beyond what the odometry covariances allow is taken for an outlier too. So the
covariances must be honest, drift included, and ``k`` is not small. Measured on the 6 m square of
test/unit/mapping/test_pose_graph.py (a one-off sweep over seeds 0-19; largest position error, median / worst):

| | no kernel | Huber k=1 | Huber k=3 | Cauchy k=3 | Cauchy k=5 |
|---|---|---|---|---|---|
| true closure only | 3.8 / 8.0 cm | 4.5 / 8.7 | 3.8 / 8.0 | 3.9 / 8.2 | 3.8 / 8.1 |
| and a false one, 1.1 m / 0.2 rad off | 71 / 73 cm | 4.0 / 7.0 | 9.1 / 12.1 | 3.8 / 8.0 | 3.6 / 7.7 |
| yaw bias twice what the covariance covers, true closure | 5.0 / 9.8 | 12.3 / 18.0 | 5.0 / 9.8 | 44 / 69 | 5.5 / 10.5 |
| the same and the false closure | 70 / 72 | 6.4 / 11.6 | 7.6 / 10.4 | 43 / 68 | 4.7 / 9.8 |

Cauchy with ``k = 5`` (the default) is never far from the best; ``k = 3`` drops the true closure when the odometry
is overconfident, Huber with ``k = 1`` pulls true closures short. On bench/bench_pose_graph.py's 500-node graph a
false closure (1.8 m, 0.3 rad off) raises the ATE from 6.3 cm to 6.6 cm with Cauchy, 10.7 cm with Huber and 19.5 cm
with no kernel (k = 5). A correct 3-DoF closure has ``u`` below 3.4 with 99 % probability, so ``k = 5`` weighs it at
0.68 or more; :attr:`OptimizeResult.outlier_loops` names the closures left more than ``k`` standard deviations off
after optimizing (weight below 1/2): the ones the map set aside.

**Why Levenberg-Marquardt.** ``optimize`` runs gtsam's Levenberg-Marquardt (COLAMD ordering, sparse Cholesky) on
the whole graph from the current estimate, until the cost decreases by less than 1e-5 relative. Measured on
bench/bench_pose_graph.py's 500-node graph with 34 closures: 15 ms from the odometry (6 iterations), 3-4 ms from
an optimized estimate. iSAM2 took as long to reach the same cost in batch (18-22 ms, 6 updates: a Gauss-Newton
step each), and added node by node (0.07 ms a node, 3-5 ms at a closure) it lagged behind the optimum (cost 60.24
against 59.62; its relinearisation is lazy). LM's damping copes with the large first residuals of a closure after a long
drift, and its stopping rule makes "optimized" mean converged. (METIS ordering was no faster.)

**Why gtsam.** The field's factor-graph library (Georgia Tech; the back end of many SLAM systems): exact SE(2)
factors and Jacobians, robust noise models, sparse elimination in C++. 500 poses optimize in 15 ms, under a tenth
of the 200 ms budget; the same model solved by a plain sparse Gauss-Newton in numpy + scipy.sparse took 3.6-5.2
times as long (bench/README.md).

The graph is saved as plain JSON (:meth:`PoseGraph.to_dict`, :meth:`PoseGraph.from_dict`): lists, floats and
strings, never a pickle. No global state: every graph owns its gtsam factor graph and estimate.
"""

from __future__ import annotations

import enum
import math
import time
from dataclasses import dataclass
from typing import Any, Dict, List, Mapping, Optional, Tuple

import gtsam
import numpy as np

from flex_nav import validation
from flex_nav.exceptions import ConfigError, MappingError, choices_message
from flex_nav.nav.planar import Pose2D

OWNER = "pose graph"
DICT_FORMAT = "flex_nav/pose_graph"  # the "format" field of to_dict
DICT_VERSION = 1
MAX_ITERATIONS = 100  # [iterations] of Levenberg-Marquardt (gtsam's default); a pose graph needs 3-10
RELATIVE_ERROR_TOL = 1e-5  # [-] LM stops when the cost decreases by less than this fraction (gtsam's default)
SYMMETRY_TOL = 1e-9  # [-] |C - C^T| allowed in a covariance, relative to its largest entry
SHOWN_NODES = 10  # unconstrained nodes named in a MappingError


class EdgeKind(enum.Enum):
    """Where an edge's measurement comes from (only LOOP edges get the robust kernel)."""

    ODOMETRY = "odometry"  # wheel odometry between consecutive nodes
    SCAN_MATCH = "scan_match"  # a scan matched against the last scans (consecutive or nearby nodes)
    LOOP = "loop"  # a loop closure: a scan matched against a part of the map seen long ago


class LoopKernel(enum.Enum):
    """The robust kernel of LOOP edges (see the module's docstring for the choice)."""

    CAUCHY = "cauchy"  # rho(u) = k^2/2 log(1 + u^2/k^2): a far-off closure loses its pull (the default)
    HUBER = "huber"  # quadratic up to k, linear beyond: bounded pull, never zero
    NONE = "none"  # plain Gaussian, as the other edges (for comparison)


@dataclass(frozen=True)
class Edge:
    """One edge of the graph, as it was added."""

    i: int  # node the measurement is expressed in
    j: int  # node measured
    relative: Pose2D  # pose of j in i's frame (x [m], y [m], yaw [rad])
    covariance: np.ndarray  # (3, 3) over x [m], y [m], yaw [rad]; read-only
    kind: EdgeKind


@dataclass(frozen=True)
class OptimizeResult:
    """What one :meth:`PoseGraph.optimize` did."""

    iterations: int  # Levenberg-Marquardt iterations
    error_before: float  # [-] the graph's cost at the estimate it started from (sum of the factors' costs)
    error_after: float  # [-] the cost at the optimized estimate
    wall_time_s: float  # [s] the whole call
    converged: bool  # False: stopped at MAX_ITERATIONS with the cost still decreasing
    outlier_loops: Tuple[int, ...]  # indices into PoseGraph.edges of the LOOP edges left more than
    #   loop_kernel_width standard deviations off (the closures the robust kernel set aside)


class PoseGraph:
    """A 2D pose graph optimized with gtsam (see the module's docstring for the model).

    ``prior_sigmas`` are the standard deviations (x [m], y [m], yaw [rad]) of the prior that anchors the first
    node at its initial pose; ``loop_kernel`` and ``loop_kernel_width`` (``k``, in standard deviations of the
    closure's covariance) the robust kernel of LOOP edges. Bad arguments raise :class:`ConfigError` naming the
    value; a graph that cannot be optimized raises :class:`MappingError`.
    """

    def __init__(
        self,
        prior_sigmas: Tuple[float, float, float] = (0.01, 0.01, 0.01),
        loop_kernel: LoopKernel = LoopKernel.CAUCHY,
        loop_kernel_width: float = 5.0,
    ) -> None:
        if not isinstance(prior_sigmas, (tuple, list)) or len(prior_sigmas) != 3:
            raise ConfigError(f"{OWNER}: prior_sigmas must be 3 numbers (x [m], y [m], yaw [rad]), got "
                              f"{validation.shown(prior_sigmas)}")
        self._prior_sigmas = (
            validation.number(OWNER, "prior_sigmas[0]", prior_sigmas[0], positive=True, unit="[m]"),
            validation.number(OWNER, "prior_sigmas[1]", prior_sigmas[1], positive=True, unit="[m]"),
            validation.number(OWNER, "prior_sigmas[2]", prior_sigmas[2], positive=True, unit="[rad]"),
        )
        if not isinstance(loop_kernel, LoopKernel):
            raise ConfigError(choices_message(f"{OWNER}: loop_kernel", loop_kernel, [str(k) for k in LoopKernel]))
        self._loop_kernel = loop_kernel
        self._loop_kernel_width = validation.number(OWNER, "loop_kernel_width", loop_kernel_width, positive=True,
                                                    unit="[standard deviations]")
        self._graph = gtsam.NonlinearFactorGraph()
        self._values = gtsam.Values()
        self._anchor: Optional[Pose2D] = None  # where the prior holds node 0
        self._edges: List[Edge] = []
        # the factor and inverse covariance of each LOOP edge, by edge index (for the outlier report)
        self._loops: Dict[int, Tuple[gtsam.BetweenFactorPose2, np.ndarray]] = {}
        self._component: List[int] = []  # union-find parents: which nodes an edge chain ties together

    # --- building ---------------------------------------------------------------------------------------------

    @property
    def prior_sigmas(self) -> Tuple[float, float, float]:
        return self._prior_sigmas

    @property
    def loop_kernel(self) -> LoopKernel:
        return self._loop_kernel

    @property
    def loop_kernel_width(self) -> float:
        """[standard deviations] ``k`` of the loop kernel; also the threshold of ``outlier_loops``."""
        return self._loop_kernel_width

    def add_node(self, pose: Pose2D) -> int:
        """Add a node with ``pose`` (map frame) as its initial guess; returns its id (0, 1, 2, ...). The first node
        is anchored there by the prior."""
        x, y, yaw = _pose(pose, "pose")
        node = self.node_count
        if node == 0:
            self._anchor = (x, y, yaw)
            self._graph.add(gtsam.PriorFactorPose2(
                0, gtsam.Pose2(x, y, yaw), gtsam.noiseModel.Diagonal.Sigmas(np.array(self._prior_sigmas))))
        self._values.insert(node, gtsam.Pose2(x, y, yaw))
        self._component.append(node)
        return node

    def add_edge(self, i: int, j: int, relative: Pose2D, covariance: np.ndarray, kind: EdgeKind) -> None:
        """Add the measurement ``relative`` (pose of node ``j`` in node ``i``'s frame) with its (3, 3)
        ``covariance`` over x [m], y [m], yaw [rad]; a LOOP edge gets the loop kernel."""
        i, j = self._check_node(i, "edge node i"), self._check_node(j, "edge node j")
        if i == j:
            raise ConfigError(f"{OWNER}: an edge must join two nodes, got i = j = {i}")
        if not isinstance(kind, EdgeKind):
            raise ConfigError(choices_message(f"{OWNER}: edge {i} -> {j} kind", kind, [str(k) for k in EdgeKind]))
        measured = _pose(relative, f"edge {i} -> {j} relative")
        cov = _covariance(covariance, f"edge {i} -> {j} covariance")
        gaussian = gtsam.noiseModel.Gaussian.Covariance(cov)
        noise = self._robust(gaussian) if kind is EdgeKind.LOOP else gaussian
        factor = gtsam.BetweenFactorPose2(i, j, gtsam.Pose2(*measured), noise)
        self._graph.add(factor)
        if kind is EdgeKind.LOOP:
            self._loops[len(self._edges)] = (factor, np.linalg.inv(cov))
        cov.flags.writeable = False
        self._edges.append(Edge(i, j, measured, cov, kind))
        self._join(i, j)

    def _check_node(self, node: object, what: str) -> int:
        """``node`` as an int if it is a node's id, or ConfigError naming it and the valid ids."""
        if isinstance(node, bool) or not isinstance(node, (int, np.integer)) or not 0 <= node < self.node_count:
            valid = f"0..{self.node_count - 1}" if self.node_count else "none: the graph has no node yet"
            raise ConfigError(f"{OWNER}: {what} = {validation.shown(node)} is not a node (valid: {valid})")
        return int(node)

    def _robust(self, gaussian: Any) -> Any:
        estimator = gtsam.noiseModel.mEstimator
        if self._loop_kernel is LoopKernel.CAUCHY:
            return gtsam.noiseModel.Robust.Create(estimator.Cauchy.Create(self._loop_kernel_width), gaussian)
        if self._loop_kernel is LoopKernel.HUBER:
            return gtsam.noiseModel.Robust.Create(estimator.Huber.Create(self._loop_kernel_width), gaussian)
        return gaussian

    # --- reading ----------------------------------------------------------------------------------------------

    @property
    def node_count(self) -> int:
        return len(self._component)

    @property
    def edges(self) -> Tuple[Edge, ...]:
        """Every edge in the order added (read-only records)."""
        return tuple(self._edges)

    @property
    def loop_count(self) -> int:
        """How many LOOP edges the graph has."""
        return sum(1 for edge in self._edges if edge.kind is EdgeKind.LOOP)

    def pose(self, i: int) -> Pose2D:
        """The current estimate of node ``i`` (the initial guess until optimized), yaw in (-pi, pi]."""
        pose = self._values.atPose2(self._check_node(i, "node"))
        return (float(pose.x()), float(pose.y()), float(pose.theta()))

    def poses(self) -> np.ndarray:
        """(N, 3) the current estimate of every node, row k = node k: x [m], y [m], yaw [rad]."""
        if self.node_count == 0:
            return np.zeros((0, 3))
        return np.array(gtsam.utilities.extractPose2(self._values), dtype=np.float64).reshape(-1, 3)

    def error(self) -> float:
        """[-] The graph's cost at the current estimate (the quantity :meth:`optimize` minimises)."""
        return float(self._graph.error(self._values))

    # --- optimizing -------------------------------------------------------------------------------------------

    def optimize(self) -> OptimizeResult:
        """Optimize every pose from the current estimate (Levenberg-Marquardt to convergence) and keep the result
        as the new estimate. Raises :class:`MappingError` when a node is not tied to the first by a chain of
        edges (its pose would be undetermined) or when the solver fails."""
        start = time.perf_counter()
        if self.node_count == 0:
            return OptimizeResult(0, 0.0, 0.0, time.perf_counter() - start, True, ())
        loose = [node for node in range(self.node_count) if self._root(node) != self._root(0)]
        if loose:
            shown = ", ".join(str(node) for node in loose[:SHOWN_NODES]) + (", ..." if len(loose) > SHOWN_NODES else "")
            raise MappingError(f"{OWNER}: {len(loose)} node(s) not tied to node 0 by any chain of edges, their poses "
                               f"are undetermined: {shown}")
        params = gtsam.LevenbergMarquardtParams()
        params.setMaxIterations(MAX_ITERATIONS)
        params.setRelativeErrorTol(RELATIVE_ERROR_TOL)
        error_before = float(self._graph.error(self._values))
        try:
            optimizer = gtsam.LevenbergMarquardtOptimizer(self._graph, self._values, params)
            result = optimizer.optimize()
        except RuntimeError as err:
            raise MappingError(f"{OWNER}: gtsam's Levenberg-Marquardt failed on {self.node_count} nodes and "
                               f"{len(self._edges)} edges: {err}") from err
        error_after = float(self._graph.error(result))
        if not math.isfinite(error_after):
            raise MappingError(f"{OWNER}: the optimized cost is {error_after} (from {error_before}): a covariance is "
                               "too small or a measurement too large")
        iterations = int(optimizer.iterations())
        self._values = result
        return OptimizeResult(iterations, error_before, error_after, time.perf_counter() - start,
                              iterations < MAX_ITERATIONS, self._outlier_loops())

    def _outlier_loops(self) -> Tuple[int, ...]:
        limit = self._loop_kernel_width * self._loop_kernel_width
        outliers = []
        for index, (factor, information) in self._loops.items():
            residual = np.asarray(factor.unwhitenedError(self._values))
            if float(residual @ information @ residual) > limit:
                outliers.append(index)
        return tuple(sorted(outliers))

    # --- the chains of edges (union-find) ---------------------------------------------------------------------

    def _root(self, node: int) -> int:
        parents = self._component
        while parents[node] != node:
            parents[node] = parents[parents[node]]
            node = parents[node]
        return node

    def _join(self, i: int, j: int) -> None:
        root_i, root_j = self._root(i), self._root(j)
        if root_i != root_j:
            self._component[max(root_i, root_j)] = min(root_i, root_j)

    # --- saving -----------------------------------------------------------------------------------------------

    def to_dict(self) -> Dict[str, Any]:
        """The graph as plain JSON values (dicts, lists, floats, ints, strings): settings, the anchor of the first
        node, the current estimate of every node and every edge. :meth:`from_dict` rebuilds it."""
        return {
            "format": DICT_FORMAT,
            "version": DICT_VERSION,
            "prior_sigmas": list(self._prior_sigmas),
            "loop_kernel": self._loop_kernel.value,
            "loop_kernel_width": self._loop_kernel_width,
            "anchor": list(self._anchor) if self._anchor is not None else None,
            "poses": [[float(v) for v in row] for row in self.poses()],
            "edges": [
                {"i": edge.i, "j": edge.j, "relative": list(edge.relative),
                 "covariance": [[float(v) for v in row] for row in edge.covariance], "kind": edge.kind.value}
                for edge in self._edges
            ],
        }

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> PoseGraph:
        """The graph :meth:`to_dict` gave (e.g. read back from a JSON file). A missing or bad field raises
        :class:`ConfigError` naming it."""
        if not isinstance(data, Mapping):
            raise ConfigError(f"{OWNER} dict: must be a mapping, got {validation.shown(data)}")
        where = f"{OWNER} dict"
        if data.get("format") != DICT_FORMAT or data.get("version") != DICT_VERSION:
            raise ConfigError(f"{where}: format/version must be {DICT_FORMAT!r}/{DICT_VERSION}, got "
                              f"{validation.shown(data.get('format'))}/{validation.shown(data.get('version'))}")
        kernel_name = _field(data, "loop_kernel", where)
        kernels = {kernel.value: kernel for kernel in LoopKernel}
        if kernel_name not in kernels:
            raise ConfigError(choices_message(f"{where}: loop_kernel", kernel_name, list(kernels)))
        poses = _field(data, "poses", where)
        edges = _field(data, "edges", where)
        if not isinstance(poses, list) or not isinstance(edges, list):
            raise ConfigError(f"{where}: poses and edges must be lists, got {validation.shown(type(poses))} and "
                              f"{validation.shown(type(edges))}")
        prior = _field(data, "prior_sigmas", where)
        graph = cls(tuple(prior) if isinstance(prior, list) else prior, kernels[kernel_name],
                    _field(data, "loop_kernel_width", where))
        if poses:
            graph._restore_nodes(_field(data, "anchor", where), poses, where)
        for index, edge in enumerate(edges):
            graph._restore_edge(edge, f"{where}: edges[{index}]")
        return graph

    def _restore_nodes(self, anchor: Any, poses: List[Any], where: str) -> None:
        """Nodes from a dict: node 0 anchored at ``anchor``, every estimate from ``poses``."""
        try:
            self.add_node(anchor)
        except ConfigError as err:
            raise ConfigError(f"{where}: anchor: {err}") from err
        for index, pose in enumerate(poses):
            try:
                if index == 0:
                    self._values.update(0, gtsam.Pose2(*_pose(pose, "pose")))
                else:
                    self.add_node(pose)
            except ConfigError as err:
                raise ConfigError(f"{where}: poses[{index}]: {err}") from err

    def _restore_edge(self, edge: object, where: str) -> None:
        """One edge from a dict."""
        if not isinstance(edge, Mapping):
            raise ConfigError(f"{where} must be a mapping, got {validation.shown(edge)}")
        kinds = {kind.value: kind for kind in EdgeKind}
        kind = _field(edge, "kind", where)
        if kind not in kinds:
            raise ConfigError(choices_message(f"{where}.kind", kind, list(kinds)))
        try:
            self.add_edge(_field(edge, "i", where), _field(edge, "j", where), _field(edge, "relative", where),
                          _field(edge, "covariance", where), kinds[kind])
        except ConfigError as err:
            raise ConfigError(f"{where}: {err}") from err


def _field(data: Mapping[str, Any], key: str, where: str) -> Any:
    """``data[key]``, or ConfigError naming the key and the keys there are."""
    if key not in data:
        raise ConfigError(f"{where}: {key!r} is missing (keys: {', '.join(sorted(map(str, data))) or 'none'})")
    return data[key]


def _is_number(value: object) -> bool:
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, (bool, np.bool_))


def _pose(pose: object, what: str) -> Pose2D:
    """``pose`` as three finite floats (x [m], y [m], yaw [rad]), or ConfigError naming ``what``."""
    if (
        not isinstance(pose, (tuple, list, np.ndarray))
        or len(pose) != 3
        or not all(_is_number(v) and math.isfinite(v) for v in pose)
    ):
        raise ConfigError(f"{OWNER}: {what} must be 3 finite numbers (x [m], y [m], yaw [rad]), got "
                          f"{validation.shown(pose)}")
    return (float(pose[0]), float(pose[1]), float(pose[2]))


def _covariance(covariance: object, what: str) -> np.ndarray:
    """``covariance`` as a new (3, 3) float array, finite, symmetric and positive definite, or ConfigError."""
    try:
        raw = np.array(covariance)
    except ValueError as err:  # ragged nested lists
        raise ConfigError(f"{OWNER}: {what} must be a (3, 3) array of numbers, got "
                          f"{validation.shown(covariance)}") from err
    if raw.dtype.kind not in "iuf" and not (raw.dtype.kind == "O" and all(_is_number(v) for v in raw.flat)):
        raise ConfigError(f"{OWNER}: {what} must be a (3, 3) array of numbers, got {validation.shown(covariance)}")
    cov = raw.astype(np.float64)
    if cov.shape != (3, 3):
        raise ConfigError(f"{OWNER}: {what} must have shape (3, 3) over x, y, yaw, got shape {cov.shape}")
    if not np.all(np.isfinite(cov)):
        raise ConfigError(f"{OWNER}: {what} must be finite, got {cov.tolist()}")
    if np.max(np.abs(cov - cov.T)) > SYMMETRY_TOL * max(float(np.max(np.abs(cov))), 1e-300):
        raise ConfigError(f"{OWNER}: {what} must be symmetric, got {cov.tolist()}")
    cov = 0.5 * (cov + cov.T)
    try:
        np.linalg.cholesky(cov)
    except np.linalg.LinAlgError as err:
        raise ConfigError(f"{OWNER}: {what} must be positive definite (eigenvalues "
                          f"{np.linalg.eigvalsh(cov).tolist()}), got {cov.tolist()}") from err
    return cov

