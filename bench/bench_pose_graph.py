#!/usr/bin/env python3
"""Pose-graph speed: flex_nav.mapping.PoseGraph (gtsam's Levenberg-Marquardt) on a 500-node graph with loop
closures, against a plain sparse Gauss-Newton written here in numpy + scipy.sparse, measured in the same run on the
same factors and initial values; both must reach the same optimum.

The graph: a robot drives laps around a building's corridor loop, a 24 m x 16 m rectangle (80 m a lap), with a
node every 0.5 m (Karto's minimum travel): 500 nodes, 3.1 laps. Odometry between consecutive nodes with noise
(0.01 m, 0.005 m, 0.005 rad) per step and a yaw bias of 0.001 rad per step (the covariance covers both). Every
10th node is closed to the nearest node of an earlier lap (at least 100 nodes back) within 1 m: a scan-matched
LOOP edge with noise (0.03 m, 0.03 m, 0.01 rad). The first node is at the true start; the initial values are the
odometry chained from there.

The reference solver minimises the same cost: gtsam's factors (residual Log(Z^-1 X_i^-1 X_j), the SE(2) logarithm,
whitened by the covariance; the prior on node 0; Cauchy kernel on the closures, applied as iteratively reweighted
least squares as gtsam's robust noise model does) with the exact SE(2) Jacobians, the same update X <- X Exp(dx),
and solves each normal equation with scipy's sparse LU (SuperLU, COLAMD ordering), halving a step that raises the
cost; it stops when the cost changes by less than 1e-12 relative.

Printed: the median wall time of each over several runs (interleaved, so load changes hit both alike), the ratio to
the 200 ms budget and gtsam / Gauss-Newton, the largest difference between the two optima, the ATE (RMS position
error after the best rigid alignment, as the TUM benchmark defines it) of the odometry and of the optimum against
the synthetic truth, and the machine's load average before and after. For information: iSAM2 on the same graph
(the solver not chosen; see pose_graph's docstring) and a false closure with each loop kernel.

Targets: gtsam median <= 200 ms; the two optima within 1 mm and 1 mrad of each other.
"""

from __future__ import annotations

import math
import os
import statistics
import sys
import time
from pathlib import Path
from typing import Callable, List, NamedTuple, Tuple

import gtsam
import numpy as np
import scipy.sparse
import scipy.sparse.linalg

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "src"))

from flex_nav.mapping.pose_graph import EdgeKind, LoopKernel, PoseGraph  # noqa: E402
from flex_nav.nav.planar import Pose2D, compose_poses, inverse_pose  # noqa: E402

NODES = 500
WIDTH, HEIGHT = 24.0, 16.0  # [m] the corridor loop
STEP = 0.5  # [m] between nodes
ODOM_SIGMAS = (0.01, 0.005, 0.005)  # [m, m, rad] per step
ODOM_YAW_BIAS = 0.001  # [rad] per step
LOOP_SIGMAS = (0.03, 0.03, 0.01)  # [m, m, rad]
LOOP_EVERY = 10  # [nodes] a closure is looked for at every 10th node
LOOP_RADIUS = 1.0  # [m] to the nearest node of an earlier lap
LOOP_MIN_SEPARATION = 100  # [nodes]
FALSE_CLOSURE = (150, 330, (1.5, -1.0, 0.3))  # nodes i, j and the offset of the measurement [m, m, rad]
RUNS = 11
BUDGET_S = 0.2  # [s] optimizing a 500-node graph with loop closures
SAME_POSITION = 1e-3  # [m]
SAME_YAW = 1e-3  # [rad]
KERNEL_WIDTH = 5.0  # PoseGraph's default loop_kernel_width


class Problem(NamedTuple):
    truth: np.ndarray  # (N, 3)
    initial: np.ndarray  # (N, 3) odometry chained from the true start
    i: np.ndarray  # (M,) edge from
    j: np.ndarray  # (M,) edge to
    z: np.ndarray  # (M, 3) measured pose of j in i's frame
    covariance: np.ndarray  # (M, 3, 3)
    loop: np.ndarray  # (M,) bool: a LOOP edge (robust kernel)


def corridor(nodes: int) -> List[Pose2D]:
    """Poses every STEP counter-clockwise around the WIDTH x HEIGHT rectangle from its south-west corner."""
    lap = 2 * (WIDTH + HEIGHT)
    corners = ((0.0, 0.0, 0.0), (WIDTH, 0.0, math.pi / 2), (WIDTH, HEIGHT, math.pi), (0.0, HEIGHT, -math.pi / 2))
    lengths = (WIDTH, HEIGHT, WIDTH, HEIGHT)
    poses: List[Pose2D] = []
    for k in range(nodes):
        s = (k * STEP) % lap
        side = 0
        while s >= lengths[side]:
            s -= lengths[side]
            side += 1
        x, y, yaw = corners[side]
        poses.append((x + s * math.cos(yaw), y + s * math.sin(yaw), yaw))
    return poses


def build_problem(seed: int = 0) -> Problem:
    rng = np.random.default_rng(seed)
    truth = corridor(NODES)
    initial = [truth[0]]
    edges: List[Tuple[int, int, Pose2D, np.ndarray, bool]] = []
    odom_cov = np.diag([ODOM_SIGMAS[0] ** 2, ODOM_SIGMAS[1] ** 2, ODOM_SIGMAS[2] ** 2 + ODOM_YAW_BIAS**2])
    for k in range(NODES - 1):
        x, y, yaw = compose_poses(inverse_pose(truth[k]), truth[k + 1])
        noise = rng.standard_normal(3) * ODOM_SIGMAS
        step = (x + noise[0], y + noise[1], yaw + ODOM_YAW_BIAS + noise[2])
        edges.append((k, k + 1, step, odom_cov, False))
        initial.append(compose_poses(initial[-1], step))
    positions = np.array(truth)[:, :2]
    loop_cov = np.diag(np.square(LOOP_SIGMAS))
    for j in range(LOOP_EVERY, NODES, LOOP_EVERY):
        if j <= LOOP_MIN_SEPARATION:
            continue
        earlier = positions[: j - LOOP_MIN_SEPARATION]
        distances = np.hypot(*(earlier - positions[j]).T)
        i = int(np.argmin(distances))
        if distances[i] < LOOP_RADIUS:
            x, y, yaw = compose_poses(inverse_pose(truth[i]), truth[j])
            noise = rng.standard_normal(3) * LOOP_SIGMAS
            edges.append((i, j, (x + noise[0], y + noise[1], yaw + noise[2]), loop_cov, True))
    return Problem(np.array(truth), np.array(initial), np.array([e[0] for e in edges]),
                   np.array([e[1] for e in edges]), np.array([e[2] for e in edges]), np.array([e[3] for e in edges]),
                   np.array([e[4] for e in edges]))


def pose_graph(problem: Problem, kernel: LoopKernel = LoopKernel.CAUCHY) -> PoseGraph:
    graph = PoseGraph(loop_kernel=kernel, loop_kernel_width=KERNEL_WIDTH)
    for pose in problem.initial:
        graph.add_node((float(pose[0]), float(pose[1]), float(pose[2])))
    for i, j, z, cov, loop in zip(problem.i, problem.j, problem.z, problem.covariance, problem.loop):
        graph.add_edge(int(i), int(j), (float(z[0]), float(z[1]), float(z[2])), cov,
                       EdgeKind.LOOP if loop else EdgeKind.ODOMETRY)
    return graph


# --- the reference: sparse Gauss-Newton on SE(2) -------------------------------------------------------------------


def wrap(angle: np.ndarray) -> np.ndarray:
    return np.asarray((angle + np.pi) % (2 * np.pi) - np.pi)


def compose(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(M, 3) a * b."""
    c, s = np.cos(a[:, 2]), np.sin(a[:, 2])
    return np.column_stack([a[:, 0] + c * b[:, 0] - s * b[:, 1], a[:, 1] + s * b[:, 0] + c * b[:, 1],
                            wrap(a[:, 2] + b[:, 2])])


def inverse(p: np.ndarray) -> np.ndarray:
    c, s = np.cos(p[:, 2]), np.sin(p[:, 2])
    return np.column_stack([-(c * p[:, 0] + s * p[:, 1]), s * p[:, 0] - c * p[:, 1], -p[:, 2]])


SMALL_ANGLE = 1e-2  # [rad] below this the functions of the angle are taken from their Taylor series (no 0/0, no
#   cancellation in t - sin(t); the series' next term is below 1e-19)


def _series(theta: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """sin(t)/t, (1-cos(t))/t, (t-sin(t))/t^2, (1-cos(t))/t^2 (1 - cos(t) as 2 sin(t/2)^2: no cancellation)."""
    small = np.abs(theta) < SMALL_ANGLE
    t = np.where(small, 1.0, theta)
    s2, t2 = 2.0 * np.sin(t / 2.0) ** 2, theta * theta
    return (np.where(small, 1.0 - t2 / 6.0 + t2 * t2 / 120.0, np.sin(t) / t),
            np.where(small, theta * (0.5 - t2 / 24.0 + t2 * t2 / 720.0), s2 / t),
            np.where(small, theta * (1.0 / 6.0 - t2 / 120.0 + t2 * t2 / 5040.0), (t - np.sin(t)) / (t * t)),
            np.where(small, 0.5 - t2 / 24.0 + t2 * t2 / 720.0, s2 / (t * t)))


def expmap(v: np.ndarray) -> np.ndarray:
    """(M, 3) tangent (vx, vy, w) -> poses: translation V(w) v, V = [[sin w / w, -(1 - cos w) / w], [(1 - cos w) / w,
    sin w / w]]."""
    a, b, _, _ = _series(v[:, 2])
    return np.column_stack([a * v[:, 0] - b * v[:, 1], b * v[:, 0] + a * v[:, 1], v[:, 2]])


def logmap(p: np.ndarray) -> np.ndarray:
    """(M, 3) poses -> tangent: V(w)^-1 t, V^-1 = [[a, w/2], [-w/2, a]] with a = (w/2) / tan(w/2)."""
    w = p[:, 2]
    small = np.abs(w) < SMALL_ANGLE
    half = np.where(small, 1.0, w / 2.0)
    w2 = w * w
    a = np.where(small, 1.0 - w2 / 12.0 - w2 * w2 / 720.0, half / np.tan(half))
    b = w / 2.0
    return np.column_stack([a * p[:, 0] + b * p[:, 1], -b * p[:, 0] + a * p[:, 1], w])


def right_jacobian_inverse(e: np.ndarray) -> np.ndarray:
    """(M, 3, 3) inverse of SE(2)'s right Jacobian at tangent e = (r1, r2, w): Log(Exp(e) Exp(d)) ~ e + Jr^-1 d."""
    r1, r2 = e[:, 0], e[:, 1]
    sin_t, one_minus_cos_t, t_minus_sin_t2, one_minus_cos_t2 = _series(e[:, 2])
    jr = np.zeros((len(e), 3, 3))
    jr[:, 0, 0] = jr[:, 1, 1] = sin_t
    jr[:, 0, 1] = one_minus_cos_t
    jr[:, 1, 0] = -one_minus_cos_t
    jr[:, 0, 2] = r1 * t_minus_sin_t2 - r2 * one_minus_cos_t2
    jr[:, 1, 2] = r1 * one_minus_cos_t2 + r2 * t_minus_sin_t2
    jr[:, 2, 2] = 1.0
    return np.asarray(np.linalg.inv(jr))


def adjoint(p: np.ndarray) -> np.ndarray:
    """(M, 3, 3) Ad(p) for tangent (vx, vy, w): [[R, (y, -x)], [0, 1]]."""
    c, s = np.cos(p[:, 2]), np.sin(p[:, 2])
    ad = np.zeros((len(p), 3, 3))
    ad[:, 0, 0], ad[:, 0, 1], ad[:, 0, 2] = c, -s, p[:, 1]
    ad[:, 1, 0], ad[:, 1, 1], ad[:, 1, 2] = s, c, -p[:, 0]
    ad[:, 2, 2] = 1.0
    return ad


class GaussNewton:
    """The reference solver (module docstring). Factors: the prior on node 0, then the edges."""

    def __init__(self, problem: Problem, prior_sigmas: Tuple[float, float, float], kernel_width: float) -> None:
        self.problem = problem
        self.anchor = problem.initial[:1].copy()
        self.prior_information = np.diag(1.0 / np.square(prior_sigmas))
        self.information = np.linalg.inv(problem.covariance)
        self.z_inverse = inverse(problem.z)
        self.k2 = kernel_width * kernel_width
        n = len(problem.initial)
        # sparsity: the 3x3 blocks (i,i), (i,j), (j,i), (j,j) of every edge and (0,0) of the prior
        blocks_r = np.concatenate([problem.i, problem.i, problem.j, problem.j, [0]])
        blocks_c = np.concatenate([problem.i, problem.j, problem.i, problem.j, [0]])
        offsets = np.arange(3)
        self.rows = (3 * blocks_r[:, None, None] + offsets[None, :, None] + 0 * offsets[None, None, :]).ravel()
        self.cols = (3 * blocks_c[:, None, None] + 0 * offsets[None, :, None] + offsets[None, None, :]).ravel()
        self.size = 3 * n

    def residuals(self, x: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Edge residuals e (M, 3), between poses T_ij (M, 3), and the prior's residual (1, 3)."""
        p = self.problem
        between = compose(inverse(x[p.i]), x[p.j])
        return logmap(compose(self.z_inverse, between)), between, logmap(compose(inverse(self.anchor), x[:1]))

    def cost(self, x: np.ndarray) -> float:
        """gtsam's graph error: 0.5 e' W e per Gaussian factor, 0.5 k^2 log(1 + u^2 / k^2) per closure."""
        e, _, prior = self.residuals(x)
        u2 = np.einsum("mi,mij,mj->m", e, self.information, e)
        per_edge = np.where(self.problem.loop, 0.5 * self.k2 * np.log1p(u2 / self.k2), 0.5 * u2)
        return float(per_edge.sum() + 0.5 * prior[0] @ self.prior_information @ prior[0])

    def step(self, x: np.ndarray) -> np.ndarray:
        """The Gauss-Newton step (3N,) at x, closures reweighted by the Cauchy weight of their current residual."""
        p = self.problem
        e, between, prior = self.residuals(x)
        u2 = np.einsum("mi,mij,mj->m", e, self.information, e)
        weight = np.where(p.loop, self.k2 / (self.k2 + u2), 1.0)
        omega = self.information * weight[:, None, None]
        jj = right_jacobian_inverse(e)
        ji = -np.einsum("mij,mjk->mik", jj, adjoint(inverse(between)))
        jp = right_jacobian_inverse(prior)[0]
        h_ii = np.einsum("mji,mjk,mkl->mil", ji, omega, ji)
        h_ij = np.einsum("mji,mjk,mkl->mil", ji, omega, jj)
        h_jj = np.einsum("mji,mjk,mkl->mil", jj, omega, jj)
        h_00 = jp.T @ self.prior_information @ jp
        data = np.concatenate([h_ii.ravel(), h_ij.ravel(), np.transpose(h_ij, (0, 2, 1)).ravel(), h_jj.ravel(),
                               h_00.ravel()])
        hessian = scipy.sparse.csc_matrix((data, (self.rows, self.cols)), shape=(self.size, self.size))
        gradient = np.zeros((len(x), 3))
        np.add.at(gradient, p.i, np.einsum("mji,mjk,mk->mi", ji, omega, e))
        np.add.at(gradient, p.j, np.einsum("mji,mjk,mk->mi", jj, omega, e))
        gradient[0] += jp.T @ self.prior_information @ prior[0]
        return np.asarray(scipy.sparse.linalg.spsolve(hessian, -gradient.ravel()))

    def solve(self, max_iterations: int = 100) -> Tuple[np.ndarray, int]:
        x = self.problem.initial.copy()
        cost = self.cost(x)
        for iteration in range(1, max_iterations + 1):
            delta = self.step(x).reshape(-1, 3)
            for _ in range(20):  # halve a step that raises the cost
                candidate = compose(x, expmap(delta))
                new_cost = self.cost(candidate)
                if new_cost <= cost:
                    break
                delta = delta / 2.0
            else:
                return x, iteration
            x, done = candidate, cost - new_cost <= 1e-12 * cost
            cost = new_cost
            if done:
                return x, iteration
        return x, max_iterations


# --- figures -------------------------------------------------------------------------------------------------------


def ate(estimate: np.ndarray, truth: np.ndarray) -> float:
    """[m] RMS position error after the rigid 2D motion that best aligns the estimate with the truth."""
    a, b = estimate[:, :2], truth[:, :2]
    a0, b0 = a - a.mean(axis=0), b - b.mean(axis=0)
    u, _, vt = np.linalg.svd(a0.T @ b0)
    d = np.sign(np.linalg.det(u @ vt))
    rotation = (u @ np.diag([1.0, d]) @ vt).T
    return float(np.sqrt(np.mean(np.sum((a0 @ rotation.T - b0) ** 2, axis=1))))


def difference(a: np.ndarray, b: np.ndarray) -> Tuple[float, float]:
    """Largest position [m] and yaw [rad] difference between two (N, 3) pose sets."""
    return float(np.max(np.hypot(*(a[:, :2] - b[:, :2]).T))), float(np.max(np.abs(wrap(a[:, 2] - b[:, 2]))))


def timed(function: Callable[[], object]) -> float:
    start = time.perf_counter()
    function()
    return time.perf_counter() - start


def bench_isam2(problem: Problem, reference_cost: float) -> None:
    """For information: gtsam's iSAM2 on the same factors, in batch to the same cost and node by node."""
    graph = pose_graph(problem)
    factors = graph._graph  # the same gtsam factors PoseGraph optimizes
    initial = gtsam.Values()
    for k, pose in enumerate(problem.initial):
        initial.insert(k, gtsam.Pose2(*pose))
    params = gtsam.ISAM2Params()
    params.relinearizeSkip = 1
    params.setRelinearizeThreshold(1e-6)
    start = time.perf_counter()
    isam = gtsam.ISAM2(params)
    isam.update(factors, initial)
    updates, cost = 1, float(factors.error(isam.calculateEstimate()))
    while updates < 50:
        isam.update()
        updates += 1
        new_cost = float(factors.error(isam.calculateEstimate()))
        if abs(cost - new_cost) < 1e-5 * cost:
            break
        cost = new_cost
    batch = time.perf_counter() - start
    by_newest: dict = {}
    for index in range(factors.size()):
        by_newest.setdefault(max(factors.at(index).keys()), []).append(factors.at(index))
    isam = gtsam.ISAM2(gtsam.ISAM2Params())
    estimate, per_node = None, []
    for k in range(NODES):
        new_factors, new_values = gtsam.NonlinearFactorGraph(), gtsam.Values()
        for factor in by_newest.get(k, []):
            new_factors.add(factor)
        if estimate is None:
            new_values.insert(k, gtsam.Pose2(*problem.initial[0]))
        else:  # the last estimate moved on by the odometry (edge k - 1 is the step k - 1 -> k)
            new_values.insert(k, estimate.atPose2(k - 1).compose(gtsam.Pose2(*problem.z[k - 1])))
        start = time.perf_counter()
        isam.update(new_factors, new_values)
        estimate = isam.calculateEstimate()
        per_node.append(time.perf_counter() - start)
    assert estimate is not None
    print(f"  iSAM2 (for information): batch to the same tolerance {1e3 * batch:.1f} ms ({updates} updates, cost "
          f"{cost:.2f}); node by node median {1e3 * statistics.median(per_node):.3f} ms, max "
          f"{1e3 * max(per_node):.2f} ms, total {1e3 * sum(per_node):.0f} ms, final cost "
          f"{float(factors.error(estimate)):.2f} (LM's optimum {reference_cost:.2f})")


def bench_kernels(problem: Problem) -> None:
    """For information: the graph with one false closure, optimized with each loop kernel."""
    i, j, offset = FALSE_CLOSURE
    truth = problem.truth
    x, y, yaw = compose_poses(inverse_pose(tuple(truth[i])), tuple(truth[j]))
    figures = []
    for kernel in LoopKernel:
        graph = pose_graph(problem, kernel)
        graph.optimize()
        without = ate(graph.poses(), truth)
        graph.add_edge(i, j, (x + offset[0], y + offset[1], yaw + offset[2]), np.diag(np.square(LOOP_SIGMAS)),
                       EdgeKind.LOOP)
        result = graph.optimize()
        flagged = "in" if len(graph.edges) - 1 in result.outlier_loops else "not in"
        figures.append(f"{kernel.value} {100 * without:.1f} -> {100 * ate(graph.poses(), truth):.1f} cm ({flagged} "
                       "outlier_loops)")
    print(f"  a false closure {i} -> {j} off by {offset} (for information), ATE without -> with it, k = "
          f"{KERNEL_WIDTH}: " + "; ".join(figures))


def main() -> int:
    load_before = os.getloadavg()
    problem = build_problem()
    loops = int(problem.loop.sum())
    laps = NODES * STEP / (2 * (WIDTH + HEIGHT))
    print(f"{NODES} nodes on a {WIDTH:.0f} m x {HEIGHT:.0f} m corridor loop ({laps:.1f} laps), {len(problem.i)} edges "
          f"of which {loops} loop closures")
    build = timed(lambda: pose_graph(problem))
    reference = GaussNewton(problem, (0.01, 0.01, 0.01), KERNEL_WIDTH)
    mine: List[float] = []
    theirs: List[float] = []
    for _ in range(RUNS):
        graph = pose_graph(problem)
        mine.append(timed(graph.optimize))
        theirs.append(timed(reference.solve))
    graph = pose_graph(problem)
    result = graph.optimize()
    optimum, gn_iterations = reference.solve()
    position_gap, yaw_gap = difference(graph.poses(), optimum)
    load_after = os.getloadavg()
    median, ref_median = statistics.median(mine), statistics.median(theirs)
    print(f"  PoseGraph.optimize (gtsam LM): median {1e3 * median:.1f} ms (min {1e3 * min(mine):.1f}, max "
          f"{1e3 * max(mine):.1f}) over {RUNS} runs; {result.iterations} iterations, cost {result.error_before:.1f} "
          f"-> {result.error_after:.3f}; building the graph {1e3 * build:.1f} ms")
    print(f"  sparse Gauss-Newton (numpy + scipy.sparse): median {1e3 * ref_median:.1f} ms (min "
          f"{1e3 * min(theirs):.1f}, max {1e3 * max(theirs):.1f}); {gn_iterations} iterations, cost "
          f"{reference.cost(optimum):.3f}")
    print(f"  the two optima differ by at most {1e3 * position_gap:.4f} mm and {1e3 * yaw_gap:.4f} mrad")
    print(f"  ratio to the {1e3 * BUDGET_S:.0f} ms budget: {median / BUDGET_S:.3f}x; gtsam / Gauss-Newton: "
          f"{median / ref_median:.3f}x")
    print(f"  ATE against the truth: odometry {ate(problem.initial, problem.truth):.3f} m, optimized "
          f"{ate(graph.poses(), problem.truth):.3f} m (Gauss-Newton {ate(optimum, problem.truth):.3f} m); outlier "
          f"closures {len(result.outlier_loops)}")
    bench_isam2(problem, result.error_after)
    bench_kernels(problem)
    print(f"  load average (1, 5, 15 min) before {', '.join(f'{v:.2f}' for v in load_before)}; after "
          f"{', '.join(f'{v:.2f}' for v in load_after)} ({os.cpu_count()} cores)")
    ok = (median <= BUDGET_S and position_gap <= SAME_POSITION and yaw_gap <= SAME_YAW and result.converged
          and result.error_after < result.error_before)
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
