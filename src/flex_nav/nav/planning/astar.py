"""Compiled (numba) search kernels of the global planner: 8-connected A* on a cost grid, and line checks.

The graph: every cell is a node; a move to one of the 8 neighbours costs ``step · weight[cost of the
cell entered]`` with ``step`` 1 (straight) or ``diagonal_factor`` (diagonal); ``weight`` comes from a
256-entry table indexed by the uint8 cell cost, ``inf`` for impassable costs. The heuristic is the octile
distance times the smallest finite weight, which is admissible and consistent for this graph, so the
first time the goal is taken off the queue its cost is optimal. Ties on f are broken towards larger g
(deeper nodes), which keeps the search narrow in open space.

The queue is a 4-ary heap of rows ``[f, -g, cell]`` (one contiguous record per entry) plus a LIFO
stack: a successor whose f equals the current minimum f would be popped next anyway, so it skips the
heap. In free space, where the heuristic is exact, most cells go through the stack.

To avoid clearing H·W arrays on every query, the per-cell arrays are reused across queries and a cell's
entries count only when its ``seen`` stamp equals the query's generation number.
"""

from __future__ import annotations

import numpy as np
from numba import njit

NO_PARENT = -1

# neighbour order: 4 straight moves, then 4 diagonal moves
_D_ROW = np.array([-1, 1, 0, 0, -1, -1, 1, 1], dtype=np.int64)
_D_COL = np.array([0, 0, -1, 1, -1, 1, -1, 1], dtype=np.int64)


@njit(cache=True, nogil=True)
def _push(heap: np.ndarray, size: int, key: float, tie: float, item: int) -> None:  # pragma: no cover - compiled
    # 4-ary min-heap on (key, tie) with rows [key, tie, item]; the caller has made room for one more
    pos = size
    while pos > 0:
        parent = (pos - 1) >> 2
        pk = heap[parent, 0]
        if pk < key or (pk == key and heap[parent, 1] <= tie):
            break
        heap[pos, 0] = pk
        heap[pos, 1] = heap[parent, 1]
        heap[pos, 2] = heap[parent, 2]
        pos = parent
    heap[pos, 0] = key
    heap[pos, 1] = tie
    heap[pos, 2] = item


@njit(cache=True, nogil=True)
def _pop(heap: np.ndarray, size: int) -> int:  # pragma: no cover - compiled
    # removes the root of a heap of ``size`` rows and returns its item
    top = int(heap[0, 2])
    size -= 1
    if size == 0:
        return top
    key = heap[size, 0]
    tie = heap[size, 1]
    item = heap[size, 2]
    pos = 0
    while True:
        first = 4 * pos + 1
        if first >= size:
            break
        best = first
        best_key = heap[first, 0]
        best_tie = heap[first, 1]
        for child in range(first + 1, min(first + 4, size)):
            child_key = heap[child, 0]
            if child_key < best_key or (child_key == best_key and heap[child, 1] < best_tie):
                best = child
                best_key = child_key
                best_tie = heap[child, 1]
        if key < best_key or (key == best_key and tie <= best_tie):
            break
        heap[pos, 0] = best_key
        heap[pos, 1] = best_tie
        heap[pos, 2] = heap[best, 2]
        pos = best
    heap[pos, 0] = key
    heap[pos, 1] = tie
    heap[pos, 2] = item
    return top


@njit(cache=True, nogil=True)
def astar(  # noqa: PLR0917, PLR0912, PLR0915 - one compiled kernel
    costs: np.ndarray,
    width: int,
    weights: np.ndarray,
    diagonal_factor: float,
    heuristic_scale: float,
    start: int,
    goal: int,
    g: np.ndarray,
    parent: np.ndarray,
    state: np.ndarray,
    generation: int,
    heap: np.ndarray,
    stack: np.ndarray,
) -> tuple[float, int]:  # pragma: no cover - compiled
    """Search from flat cell ``start`` to ``goal`` on ``costs`` (uint8, H·W flat, row-major).

    Returns (cost of the optimal path or inf, number of expanded cells). ``parent`` then links the path
    back from ``goal``. ``heap`` (float64 (R, 3): rows [f, -g, cell]) and ``stack`` (int64) are the queue's
    storage; when one of them is full the search stops and returns (inf, -1) (heap) or (inf, -2) (stack),
    and the caller searches again with a bigger one (growing an array inside this kernel makes numba's
    compile time explode). ``g`` (float64), ``parent`` (int32) and ``state`` (uint32) are H·W work arrays
    reused across calls: ``state == generation`` marks an open cell (its ``g`` is valid) and
    ``state == generation + 1`` a closed one, so ``generation`` must grow by 2 per call.
    """
    height = costs.shape[0] // width
    goal_row = goal // width
    goal_col = goal - goal_row * width
    diag_extra = diagonal_factor - 1.0
    closed_mark = generation + 1
    offsets = np.empty(8, dtype=np.int64)
    for k in range(8):
        offsets[k] = _D_ROW[k] * width + _D_COL[k]

    g[start] = 0.0
    parent[start] = NO_PARENT
    state[start] = generation
    size = 0
    _push(heap, size, 0.0, 0.0, start)
    size += 1
    top = 0
    f_min = 0.0
    expanded = 0
    while size > 0 or top > 0:
        if top > 0:
            top -= 1
            node = stack[top]
        else:
            f_min = heap[0, 0]
            node = _pop(heap, size)
            size -= 1
        if state[node] == closed_mark:
            continue
        state[node] = closed_mark
        expanded += 1
        g_node = g[node]
        if node == goal:
            return g_node, expanded
        row = node // width
        col = node - row * width
        interior = row > 0 and row < height - 1 and col > 0 and col < width - 1
        for k in range(8):
            if not interior:
                nr = row + _D_ROW[k]
                nc = col + _D_COL[k]
                if nr < 0 or nr >= height or nc < 0 or nc >= width:
                    continue
            nb = node + offsets[k]
            st = state[nb]
            if st == closed_mark:
                continue
            w = weights[costs[nb]]
            if w == np.inf:
                continue
            cand = g_node + (w if k < 4 else w * diagonal_factor)
            if st == generation and cand >= g[nb]:
                continue
            state[nb] = generation
            g[nb] = cand
            parent[nb] = node
            nr = row + _D_ROW[k]
            nc = col + _D_COL[k]
            d_row = abs(nr - goal_row)
            d_col = abs(nc - goal_col)
            if d_row < d_col:
                h = heuristic_scale * (d_col + diag_extra * d_row)
            else:
                h = heuristic_scale * (d_row + diag_extra * d_col)
            f = cand + h
            if f <= f_min:
                # f is the queue's minimum: it would be popped next anyway (order among equal f is free)
                if top == stack.shape[0]:
                    return np.inf, -2  # stack full: the caller grows it and searches again
                stack[top] = nb
                top += 1
                continue
            if size == heap.shape[0]:
                return np.inf, -1  # heap full: the caller grows it and searches again
            _push(heap, size, f, -cand, nb)
            size += 1
    return np.inf, expanded


@njit(cache=True, nogil=True)
def trace_back(parent: np.ndarray, goal: int, width: int) -> np.ndarray:  # pragma: no cover - compiled
    """(N, 2) int64 (row, col) cells from the start to ``goal`` following ``parent`` links."""
    count = 1
    node = goal
    while parent[node] != NO_PARENT:
        node = parent[node]
        count += 1
    cells = np.empty((count, 2), dtype=np.int64)
    node = goal
    for i in range(count - 1, -1, -1):
        cells[i, 0] = node // width
        cells[i, 1] = node % width
        node = parent[node]
    return cells


@njit(cache=True, nogil=True)
def line_cost(  # noqa: PLR0917 - compiled kernel
    costs2d: np.ndarray,
    weights: np.ndarray,
    diagonal_factor: float,
    row0: int,
    col0: int,
    row1: int,
    col1: int,
) -> float:  # pragma: no cover - compiled
    """Cost of the 8-connected Bresenham walk from cell 0 to cell 1 under the planner's model (inf if blocked)."""
    d_row = row1 - row0
    d_col = col1 - col0
    step_row = 1 if d_row >= 0 else -1
    step_col = 1 if d_col >= 0 else -1
    abs_row = abs(d_row)
    abs_col = abs(d_col)
    col_major = abs_col >= abs_row
    major = abs_col if col_major else abs_row
    minor = abs_row if col_major else abs_col
    error = major // 2
    row = row0
    col = col0
    total = 0.0
    for _ in range(major):
        diagonal = False
        if col_major:
            col += step_col
        else:
            row += step_row
        error += minor
        if error >= major:
            if col_major:
                row += step_row
            else:
                col += step_col
            error -= major
            diagonal = True
        w = weights[costs2d[row, col]]
        if w == np.inf:
            return np.inf
        total += w * diagonal_factor if diagonal else w
    return total


@njit(cache=True, nogil=True)
def shortcut(
    costs2d: np.ndarray, weights: np.ndarray, diagonal_factor: float, cells: np.ndarray, slack: float
) -> np.ndarray:  # pragma: no cover - compiled
    """Indices of ``cells`` kept by greedy line-of-sight shortcutting.

    From each kept cell, the next kept cell is the farthest one whose straight (Bresenham) walk is
    passable and costs at most ``(1 + slack)`` times the path's own cost between them.
    """
    n = cells.shape[0]
    along = np.zeros(n, dtype=np.float64)  # cost of the path up to each cell
    for i in range(1, n):
        w = weights[costs2d[cells[i, 0], cells[i, 1]]]
        diagonal = cells[i, 0] != cells[i - 1, 0] and cells[i, 1] != cells[i - 1, 1]
        along[i] = along[i - 1] + (w * diagonal_factor if diagonal else w)
    keep = np.empty(n, dtype=np.int64)
    count = 0
    keep[count] = 0
    count += 1
    i = 0
    while i < n - 1:
        j = i + 1
        while j + 1 < n:
            c = line_cost(costs2d, weights, diagonal_factor, cells[i, 0], cells[i, 1], cells[j + 1, 0], cells[j + 1, 1])
            if c > (along[j + 1] - along[i]) * (1.0 + slack) + 1e-9:
                break
            j += 1
        keep[count] = j
        count += 1
        i = j
    return keep[:count]
