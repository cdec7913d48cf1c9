"""Integer ray tracing on a grid (Bresenham), compiled with numba.

costmap_2d clears free space by walking every cell on the line from the sensor cell to the end cell,
both included; the same cell sequence is produced here (optionally without the end cell, see
:func:`set_rays`). A ray stops where it leaves the grid.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, nogil=True)
def set_rays(  # noqa: PLR0917 - a compiled kernel takes plain positional arguments
    grid: np.ndarray, row0: int, col0: int, end_rows: np.ndarray, end_cols: np.ndarray, value: int,
    skip_end: np.ndarray,
) -> int:  # pragma: no cover - compiled
    """Set every cell on the lines (row0, col0) -> (end_rows[i], end_cols[i]) to ``value``; returns cells set.

    ``grid`` is uint8 (H, W); ``skip_end`` (bool per line): leave that line's end cell alone. Nothing is done
    when the start cell is outside the grid.
    """
    height, width = grid.shape
    if row0 < 0 or row0 >= height or col0 < 0 or col0 >= width:
        return 0
    count = 0
    for i in range(end_rows.shape[0]):
        d_row = end_rows[i] - row0
        d_col = end_cols[i] - col0
        step_row = 1 if d_row >= 0 else -1
        step_col = 1 if d_col >= 0 else -1
        abs_row = abs(d_row)
        abs_col = abs(d_col)
        row = row0
        col = col0
        if abs_col >= abs_row:
            error = abs_col // 2
            for _ in range(abs_col + 1 - int(skip_end[i])):
                if row < 0 or row >= height or col < 0 or col >= width:
                    break
                grid[row, col] = value
                count += 1
                col += step_col
                error += abs_row
                if error >= abs_col:
                    row += step_row
                    error -= abs_col
        else:
            error = abs_row // 2
            for _ in range(abs_row + 1 - int(skip_end[i])):
                if row < 0 or row >= height or col < 0 or col >= width:
                    break
                grid[row, col] = value
                count += 1
                row += step_row
                error += abs_col
                if error >= abs_row:
                    col += step_col
                    error -= abs_row
    return count


def line_cells(row0: int, col0: int, row1: int, col1: int) -> np.ndarray:
    """The (row, col) cells of the Bresenham line between two cells, both included, as an (N, 2) int array."""
    rows, cols = [row0], [col0]
    d_row, d_col = row1 - row0, col1 - col0
    step_row = 1 if d_row >= 0 else -1
    step_col = 1 if d_col >= 0 else -1
    abs_row, abs_col = abs(d_row), abs(d_col)
    row, col = row0, col0
    major, minor = (abs_col, abs_row) if abs_col >= abs_row else (abs_row, abs_col)
    error = major // 2
    for _ in range(major):
        if abs_col >= abs_row:
            col += step_col
        else:
            row += step_row
        error += minor
        if error >= major:
            if abs_col >= abs_row:
                row += step_row
            else:
                col += step_col
            error -= major
        rows.append(row)
        cols.append(col)
    return np.stack([np.array(rows), np.array(cols)], axis=1)
