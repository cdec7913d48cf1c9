"""Compiled (numba) search kernels of the global planner: 8-connected A* on a cost grid, and line checks.

The graph: every cell is a node; a move to one of the 8 neighbours costs ``step · weight[cost of the
cell entered]`` with ``step`` 1 (straight) or ``diagonal_factor`` (diagonal); ``weight`` comes from a
256-entry table indexed by the uint8 cell cost, ``inf`` for impassable costs. The heuristic is the octile
distance times the smallest finite weight, which is admissible and consistent for this graph, so the
first time the goal is taken off the queue its cost is optimal.

The queue pops cells in order of f = g + h, which is all optimality needs (any order among equal f will
do). It has three parts:

- a ring of f buckets (``BUCKETS`` slots, bucket k holding f in [k, k+1) / ``per_f``): a push is O(1)
  (a row [f, g, cell, next] of ``pool`` linked into its bucket). One move raises f by at most the move's
  cost plus the heuristic's change, so the live buckets always fit in the ring;
- a 4-ary min-heap on f (rows [f, cell]) holding the current bucket: when the heap runs dry, the next
  non-empty bucket is moved into it (heapified at once), dropping the entries of cells reached more
  cheaply since;
- a LIFO stack for cells whose f is the queue's minimum, which would be popped next anyway: a successor of
  the same f, or a whole bucket whose entries all have one f (a plateau reached from several sides). In
  free space most cells go through it, deepest first, so the search runs straight at the goal.

"The same f" is decided without trusting floating-point sums to be exact: a successor entered at the
cheapest weight along the heuristic's own path (its octile distance falls by exactly the move's step) has
its node's f in exact arithmetic; otherwise two f values count as one when they differ by at most
``ROUNDING`` (1e-12) relative: far below the 1e-9 to which costs are compared, above the rounding of the
sums (1.1e-16 per added term, about 1e-14 after the 1e4 steps of a long path). Two really different f
values that close may be popped in either order; the cost found can then exceed the optimum by that much
(1e-12 relative), which is the precision the costs have anyway.

To avoid clearing H·W arrays on every query, the per-cell arrays are reused across queries and a cell's
entries count only when its ``state`` stamp equals the query's generation number.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from flex_nav.exceptions import ConfigError

NO_PARENT = -1

# neighbour order: 4 straight moves, then 4 diagonal moves
_D_ROW = np.array([-1, 1, 0, 0, -1, -1, 1, 1], dtype=np.int64)
_D_COL = np.array([0, 0, -1, 1, -1, 1, -1, 1], dtype=np.int64)
BUCKETS = 4096  # ring of f buckets (a power of two)
# relative difference of two f values taken for floating-point rounding of one real value (see above)
ROUNDING = 1e-12
# what astar returns as the expanded count when one of the queue's arrays is full
FULL_HEAP = -1
FULL_STACK = -2
FULL_POOL = -3


@njit(cache=True, nogil=True)
def _push(heap: np.ndarray, size: int, key: float, item: int) -> None:  # pragma: no cover - compiled
    # 4-ary min-heap on key with rows [key, item]; the caller has made room for one more
    pos = size
    while pos > 0:
        parent = (pos - 1) >> 2
        parent_key = heap[parent, 0]
        if parent_key <= key:
            break
        heap[pos, 0] = parent_key
        heap[pos, 1] = heap[parent, 1]
        pos = parent
    heap[pos, 0] = key
    heap[pos, 1] = item


@njit(cache=True, nogil=True)
def _sift_down(heap: np.ndarray, size: int, pos: int, key: float, item: float) -> None:  # pragma: no cover
    # places row [key, item] at ``pos`` or below, in a heap of ``size`` rows
    while True:
        first = 4 * pos + 1
        if first >= size:
            break
        best = first
        best_key = heap[first, 0]
        for child in range(first + 1, min(first + 4, size)):
            if heap[child, 0] < best_key:
                best = child
                best_key = heap[child, 0]
        if key <= best_key:
            break
        heap[pos, 0] = best_key
        heap[pos, 1] = heap[best, 1]
        pos = best
    heap[pos, 0] = key
    heap[pos, 1] = item


@njit(cache=True, nogil=True)
def _pop(heap: np.ndarray, size: int) -> int:  # pragma: no cover - compiled
    # removes the root of a heap of ``size`` rows and returns its item
    top = int(heap[0, 1])
    size -= 1
    if size > 0:
        _sift_down(heap, size, 0, heap[size, 0], heap[size, 1])
    return top


@njit(cache=True, nogil=True)
def astar(  # noqa: PLR0911, PLR0917, PLR0912, PLR0915 - one compiled kernel
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
    pool: np.ndarray,
    heap: np.ndarray,
    stack: np.ndarray,
) -> tuple[float, int]:  # pragma: no cover - compiled
    """Search from flat cell ``start`` to ``goal`` on ``costs`` (uint8, H·W flat, row-major).

    Returns (cost of the optimal path or inf, number of expanded cells). ``parent`` then links the path
    back from ``goal``. ``pool`` (float64 (P, 4): rows [f, g, cell, next]: the buckets' entries), ``heap``
    (float64 (R, 2): rows [f, cell]: the current bucket) and ``stack`` (int64) are the queue's storage;
    when one of them is full the search stops and returns (inf, FULL_POOL / FULL_STACK / FULL_HEAP), and the
    caller searches again with a bigger one (growing an array inside this kernel makes numba's compile time
    explode): :func:`search` does that. ``g`` (float64), ``parent`` (int32) and ``state`` (uint32) are H·W
    work arrays reused across calls: ``state == generation`` marks an open cell (its ``g`` is valid) and
    ``state == generation + 1`` a closed one, so ``generation`` must grow by 2 per call.
    """
    height = costs.shape[0] // width
    goal_row = goal // width
    goal_col = goal - goal_row * width
    diag_extra = diagonal_factor - 1.0
    closed_mark = generation + 1
    per_row = 1.0 / width
    offsets = np.empty(8, dtype=np.int64)
    for k in range(8):
        offsets[k] = _D_ROW[k] * width + _D_COL[k]
    # buckets: f in [k·bucket, (k+1)·bucket) goes to ring slot k mod BUCKETS; one step raises f by at most
    # ``span`` (the move's cost plus the heuristic's change), so the ring never wraps onto a live bucket
    longest = max(1.0, diagonal_factor)
    span = 0.0
    for i in range(256):
        if weights[i] != np.inf and weights[i] > span:
            span = weights[i]
    span = longest * (span + heuristic_scale)
    per_f = (BUCKETS - 4) / span if span > 0.0 else 1.0  # buckets per unit of f
    head = np.full(BUCKETS, -1, dtype=np.int32)
    used = 0  # pool rows handed out so far
    free = -1  # first row of the pool's free list
    in_buckets = 0
    d_row = abs(start // width - goal_row)
    d_col = abs(start % width - goal_col)
    f_min = heuristic_scale * (max(d_row, d_col) + diag_extra * min(d_row, d_col))  # the start's f
    current = np.int64(f_min * per_f)  # absolute index of the bucket in the heap

    g[start] = 0.0
    parent[start] = NO_PARENT
    state[start] = generation
    size = 0
    _push(heap, size, f_min, start)
    size += 1
    top = 0
    expanded = 0
    while True:
        if top > 0:
            top -= 1
            node = stack[top]
        else:
            if size == 0:
                if in_buckets == 0:
                    break
                # the next bucket goes into the heap, without the entries a cheaper one has overtaken
                current += 1
                while head[current & (BUCKETS - 1)] == -1:
                    current += 1
                entry = head[current & (BUCKETS - 1)]
                head[current & (BUCKETS - 1)] = -1
                low = np.inf
                high = 0.0
                while entry != -1:
                    following = int(pool[entry, 3])
                    cell = int(pool[entry, 2])
                    if state[cell] == generation and pool[entry, 1] == g[cell]:
                        if size == heap.shape[0]:
                            return np.inf, FULL_HEAP
                        heap[size, 0] = pool[entry, 0]
                        heap[size, 1] = cell
                        size += 1
                        low = min(low, pool[entry, 0])
                        high = max(high, pool[entry, 0])
                    pool[entry, 3] = free
                    free = entry
                    in_buckets -= 1
                    entry = following
                if size == 0:
                    continue
                if high - low <= ROUNDING * high:
                    # one f, up to rounding (a plateau reached from several sides): any order will do, the
                    # stack's is the cheapest
                    if size > stack.shape[0]:
                        return np.inf, FULL_STACK
                    for i in range(size):
                        stack[i] = int(heap[i, 1])
                    top = size
                    size = 0
                    f_min = high
                    continue
                for pos in range((size - 2) // 4, -1, -1):  # heapify
                    _sift_down(heap, size, pos, heap[pos, 0], heap[pos, 1])
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
        row = np.int64(node * per_row)  # node // width without an integer division, then made exact
        if row * width > node:
            row -= 1
        elif (row + 1) * width <= node:
            row += 1
        col = node - row * width
        interior = row > 0 and row < height - 1 and col > 0 and col < width - 1
        # the node's octile distance to the goal [cells] as (longer, shorter) axis
        far = max(abs(row - goal_row), abs(col - goal_col))
        near = min(abs(row - goal_row), abs(col - goal_col))
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
            via = node
            if k < 4:
                cand = g_node + w
            else:
                cand = g_node + w * diagonal_factor
                # the two cells beside the diagonal move, when open, may offer a cheaper way in: taking it
                # now saves improving this cell later (both are real paths, so optimality is unaffected)
                side = node + offsets[k] - _D_COL[k]
                if state[side] == generation and g[side] + w < cand:
                    cand = g[side] + w
                    via = side
                side = node + offsets[k] - _D_ROW[k] * width
                if state[side] == generation and g[side] + w < cand:
                    cand = g[side] + w
                    via = side
            if st == generation and cand >= g[nb]:
                continue
            state[nb] = generation
            g[nb] = cand
            parent[nb] = via
            nr = row + _D_ROW[k]
            nc = col + _D_COL[k]
            d_row = abs(nr - goal_row)
            d_col = abs(nc - goal_col)
            nb_far = max(d_row, d_col)
            nb_near = min(d_row, d_col)
            f = cand + heuristic_scale * (nb_far + diag_extra * nb_near)
            if f <= f_min + ROUNDING * f_min or (
                # a move of the cheapest weight straight along the heuristic's path to the goal: f is the
                # node's, exactly (in floating point the sums may differ in the last bits)
                w == heuristic_scale
                and via == node
                and nb_far == far - 1
                and nb_near == (near if k < 4 else near - 1)
            ):
                # f is the queue's minimum: it would be popped next anyway (order among equal f is free);
                # deepest first, so in free space the search runs straight to the goal
                if top == stack.shape[0]:
                    return np.inf, FULL_STACK
                stack[top] = nb
                top += 1
                continue
            bucket = np.int64(f * per_f)
            if bucket <= current:
                if size == heap.shape[0]:
                    return np.inf, FULL_HEAP
                _push(heap, size, f, nb)
                size += 1
                continue
            if free != -1:
                entry = free
                free = int(pool[entry, 3])
            elif used < pool.shape[0]:
                entry = used
                used += 1
            else:
                return np.inf, FULL_POOL
            slot = bucket & (BUCKETS - 1)
            pool[entry, 0] = f
            pool[entry, 1] = cand
            pool[entry, 2] = nb
            pool[entry, 3] = head[slot]
            head[slot] = entry
            in_buckets += 1
    return np.inf, expanded


class QueueStorage:
    """The arrays of :func:`astar`'s queue, kept between searches and doubled when a search fills one."""

    def __init__(self, pool_rows: int = 1 << 14, heap_rows: int = 1 << 12, stack_size: int = 1 << 12) -> None:
        self.pool = np.empty((pool_rows, 4), dtype=np.float64)
        self.heap = np.empty((heap_rows, 2), dtype=np.float64)
        self.stack = np.empty(stack_size, dtype=np.int64)

    def grow(self, full: int) -> None:
        """Doubles the array that ``astar`` reported full (FULL_POOL, FULL_HEAP or FULL_STACK)."""
        if full == FULL_POOL:
            self.pool = np.empty((2 * len(self.pool), 4), dtype=np.float64)
        elif full == FULL_HEAP:
            self.heap = np.empty((2 * len(self.heap), 2), dtype=np.float64)
        elif full == FULL_STACK:
            self.stack = np.empty(2 * len(self.stack), dtype=np.int64)
        else:
            raise ConfigError(f"grow: {full} names no queue array (FULL_POOL, FULL_HEAP or FULL_STACK)")


def search(  # noqa: PLR0917 - the kernel's arguments
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
    storage: QueueStorage,
) -> tuple[float, int, int]:
    """:func:`astar` with ``storage``'s arrays, grown and searched again (2 generations later) until they suffice.

    Returns (cost or inf, expanded cells, the generation of the search that finished: the caller's next
    search must use a larger one, by 2 at least).
    """
    while True:
        cost, expanded = astar(
            costs, width, weights, diagonal_factor, heuristic_scale, start, goal,
            g, parent, state, generation, storage.pool, storage.heap, storage.stack,
        )  # fmt: skip
        if expanded >= 0:
            return float(cost), int(expanded), generation
        storage.grow(int(expanded))
        generation += 2


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
