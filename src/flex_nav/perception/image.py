"""A ``sensor_msgs/Image``-like buffer -> an RGB ``uint8`` array (height, width, 3), or a depth image
[m] float32 (height, width), without cv_bridge.

Colour: only 8-bit encodings are accepted; depth: REP 118's ``32FC1`` [m] and ``16UC1`` [mm] (0 = no
return). Each row may be padded (``step`` >= width * bytes per pixel). The colour result is a view into
the buffer where no channel reordering is needed (``rgb8`` without padding), so the caller must not
keep it past the buffer's lifetime if the buffer is reused.
"""

from __future__ import annotations

from typing import Dict, Union

import numpy as np

from flex_nav.exceptions import ConfigError, choices_message

CHANNELS: Dict[str, int] = {"rgb8": 3, "bgr8": 3, "rgba8": 4, "bgra8": 4, "mono8": 1}
ENCODINGS = tuple(CHANNELS)

Buffer = Union[bytes, bytearray, memoryview, np.ndarray]


def to_rgb(data: Buffer, width: int, height: int, encoding: str, step: int = 0) -> np.ndarray:
    """RGB uint8 (height, width, 3) from raw image bytes; ``step`` [bytes per row], 0 = packed.

    Raises :class:`ConfigError` (a ValueError) naming the problem for an unsupported encoding, a
    non-positive size, a step shorter than a row or a buffer shorter than ``step * height``.
    """
    channels = CHANNELS.get(encoding)
    if channels is None:
        raise ConfigError(choices_message("image encoding", encoding, ENCODINGS))
    pixels = _rows(data, width, height, channels, step, what="image").reshape(height, width, channels)
    if encoding == "rgb8":
        return pixels
    if encoding == "mono8":
        return np.repeat(pixels, 3, axis=2)
    if encoding == "rgba8":
        return pixels[:, :, :3]
    return pixels[:, :, 2::-1]  # bgr8 / bgra8: B, G, R -> R, G, B


DEPTH_ENCODINGS: Dict[str, str] = {"32FC1": "f4", "16UC1": "u2"}  # numpy type (byte order added from the message)


def to_depth(data: Buffer, width: int, height: int, encoding: str, step: int = 0, *,
             bigendian: bool = False) -> np.ndarray:
    """Depth [m] float32 (height, width) from a REP 118 depth image: ``32FC1`` in metres or ``16UC1`` in
    millimetres (0 = no return, kept as 0: :func:`flex_nav.perception.preprocess.depth_patch` treats it as
    missing). ConfigError names an unsupported encoding, a bad size, step or buffer length (:func:`_rows`)."""
    kind = DEPTH_ENCODINGS.get(encoding)
    if kind is None:
        raise ConfigError(choices_message("depth image encoding", encoding, tuple(DEPTH_ENCODINGS)))
    dtype = np.dtype(kind).newbyteorder(">" if bigendian else "<")
    if step % dtype.itemsize:
        raise ConfigError(f"depth image step {step} is not a multiple of the {dtype.itemsize} bytes of a pixel")
    rows = _rows(data, width, height, dtype.itemsize, step, what="depth image")
    values = np.ascontiguousarray(rows).view(dtype).reshape(height, width)
    if encoding == "16UC1":
        return values.astype(np.float32) * np.float32(0.001)
    return values.astype(np.float32)


def _rows(data: Buffer, width: int, height: int, pixel_bytes: int, step: int, *, what: str) -> np.ndarray:
    """The (height, width * pixel_bytes) uint8 rows of an image buffer without row padding; ``step`` [bytes
    per row], 0 = packed. ConfigError names ``what`` and a non-positive size, a step shorter than a row,
    non-byte data or a buffer shorter than ``step * height``."""
    if width <= 0 or height <= 0:
        raise ConfigError(f"{what} size {width}x{height} must be positive")
    row = width * pixel_bytes
    step = row if step == 0 else step
    if step < row:
        raise ConfigError(f"{what} step {step} is shorter than a row ({width} px x {pixel_bytes} bytes = {row})")
    flat = np.frombuffer(data, dtype=np.uint8) if not isinstance(data, np.ndarray) else data.reshape(-1)
    if flat.dtype != np.uint8:
        raise ConfigError(f"{what} data must be uint8 bytes, got {flat.dtype}")
    if flat.size < step * height:
        raise ConfigError(f"{what} data has {flat.size} bytes, {step} x {height} = {step * height} expected")
    return flat[: step * height].reshape(height, step)[:, :row]
