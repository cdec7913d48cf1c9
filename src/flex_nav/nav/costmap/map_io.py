"""Read and write maps in ROS map_server format (a YAML file next to a PGM/PNG image).

:func:`load_map` follows ROS 1 map_server's image loader: each pixel's channels are averaged (in
``trinary`` mode, or when the image has no alpha channel, the alpha channel is averaged in too),
``negate`` inverts the grey value, ``occ = (255 - grey) / 255`` and

- ``occ > occupied_thresh`` -> 100, ``occ < free_thresh`` -> 0,
- otherwise ``trinary``: -1; ``scale``: -1 for a fully transparent pixel, else
  ``int(1 + 98 * (occ - free_thresh) / (occupied_thresh - free_thresh))``;
- ``raw``: the (negated) grey value itself; 255 means unknown (-1), other values must be 0..100.

The image's top row is the map's far (+y) edge, so rows are flipped into OccupancyGrid order.

:func:`save_map` writes what ROS 1 map_saver writes: a binary PGM with 0 for occupied
(value >= ``occupied_threshold``), 254 for free (0 <= value <= ``free_threshold``) and 205 for
everything else, plus a YAML with ``negate: 0``, ``occupied_thresh: 0.65``, ``free_thresh: 0.196``
(the thresholds that read the three grey levels back exactly).

Every problem with a file raises :class:`ConfigError` naming the file, the field and the valid choices.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any, Callable, Dict, Sequence, Tuple, Union

import cv2
import numpy as np
import yaml

from flex_nav.exceptions import ConfigError, choices_message
from flex_nav.nav.costmap.grid_map import GridMap

MODES = ("trinary", "scale", "raw")
REQUIRED_FIELDS = ("image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh")
SAVED_OCCUPIED = 0  # PGM grey level map_saver writes for an occupied cell
SAVED_FREE = 254  # ... for a free cell
SAVED_UNKNOWN = 205  # ... for an unknown cell

PathLike = Union[str, Path]
_RAW_BAD = 999  # marks a raw-mode grey value outside 0..100 and 255


def load_map(yaml_path: PathLike) -> GridMap:
    """Load a map_server YAML (and the image it names, relative to the YAML's folder) as a :class:`GridMap`."""
    path = Path(yaml_path)
    meta = _read_yaml(path)
    image_path = Path(meta["image"])
    if not image_path.is_absolute():
        image_path = path.parent / image_path
    pixels = _read_image(image_path, path)
    occupancy = image_to_occupancy(
        pixels,
        negate=meta["negate"],
        occupied_thresh=meta["occupied_thresh"],
        free_thresh=meta["free_thresh"],
        mode=meta["mode"],
        source=str(image_path),
    )
    return GridMap(occupancy, meta["resolution"], meta["origin"])


def image_to_occupancy(
    pixels: np.ndarray,
    *,
    negate: bool,
    occupied_thresh: float,
    free_thresh: float,
    mode: str = "trinary",
    source: str = "<image>",
) -> np.ndarray:
    """Convert image pixels (top row first; grey (H, W) or colour (H, W, C) uint8) to OccupancyGrid values.

    Returns int8 (H, W) with row 0 = the image's BOTTOM row (OccupancyGrid order).
    """
    if mode not in MODES:
        raise ConfigError(choices_message(f"{source}: mode", mode, MODES))
    if pixels.dtype != np.uint8 or pixels.ndim not in (2, 3):
        raise ConfigError(
            f"{source}: image must be 8-bit grey or colour, got dtype {pixels.dtype} shape {pixels.shape}"
        )
    channels = 1 if pixels.ndim == 2 else pixels.shape[2]
    has_alpha = channels in (2, 4)

    def classify(grey: np.ndarray, alpha: np.ndarray) -> np.ndarray:
        # grey: channel average [0..255] as float64; alpha: alpha channel [0..255]
        if negate:
            grey = 255.0 - grey
        if mode == "raw":
            raw = np.trunc(grey).astype(np.int16)
            raw = np.where(raw == 255, -1, raw)
            return np.where(raw > 100, _RAW_BAD, raw).astype(np.int16)
        occ = (255.0 - grey) / 255.0
        out = np.full(grey.shape, -1, dtype=np.int16)
        if mode == "scale":
            ratio = (occ - free_thresh) / (occupied_thresh - free_thresh)
            scaled = np.trunc(1.0 + 98.0 * np.clip(ratio, 0.0, 1.0)).astype(np.int8)
            out = np.where(alpha >= 1.0, scaled, out)
        out[occ > occupied_thresh] = 100
        out[occ < free_thresh] = 0
        return out

    if channels == 1:
        # 256-entry lookup table: the rule depends on the grey value alone.
        levels = np.arange(256, dtype=np.float64)
        table = classify(levels, np.full(256, 255.0))
        grey_u8 = pixels if pixels.ndim == 2 else pixels[:, :, 0]
        result = table[grey_u8]
    else:
        avg_channels = channels if (mode == "trinary" or not has_alpha) else channels - 1
        grey = pixels[:, :, :avg_channels].astype(np.float64).mean(axis=2)
        alpha = pixels[:, :, -1].astype(np.float64) if has_alpha else np.full(grey.shape, 255.0)
        result = classify(grey, alpha)
    if mode == "raw":
        bad = result == _RAW_BAD
        if bad.any():
            found = np.unique(pixels[bad] if pixels.ndim == 2 else pixels[bad][:, 0])[:8].tolist()
            raise ConfigError(f"{source}: mode raw needs grey values 0..100 or 255 (unknown), found {found}")
    return np.ascontiguousarray(np.flipud(result)).astype(np.int8)


def save_map(
    grid: GridMap,
    yaml_path: PathLike,
    *,
    occupied_threshold: int = 65,
    free_threshold: int = 25,
    image_name: str = "",
) -> Path:
    """Write ``grid`` as map_saver does: ``yaml_path`` plus a PGM beside it; returns the image path.

    ``occupied_threshold`` / ``free_threshold`` [0..100] classify cell values into the three grey levels.
    ``image_name`` defaults to the YAML's name with suffix ``.pgm``.
    """
    if not (0 <= free_threshold < occupied_threshold <= 100):
        raise ConfigError(
            f"save_map thresholds must satisfy 0 <= free_threshold < occupied_threshold <= 100, "
            f"got free_threshold={free_threshold!r}, occupied_threshold={occupied_threshold!r}"
        )
    path = Path(yaml_path)
    if not path.parent.is_dir():
        raise ConfigError(f"{path}: folder {path.parent} does not exist")
    name = image_name or path.with_suffix(".pgm").name
    image_path = path.parent / name
    data = grid.occupancy
    pixels = np.full(data.shape, SAVED_UNKNOWN, dtype=np.uint8)
    pixels[data >= occupied_threshold] = SAVED_OCCUPIED
    pixels[(data >= 0) & (data <= free_threshold)] = SAVED_FREE
    pixels = np.flipud(pixels)
    header = f"P5\n# CREATOR: flex_nav map_io {grid.resolution:.3f} m/pix\n{grid.width} {grid.height}\n255\n"
    with open(image_path, "wb") as out:
        out.write(header.encode("ascii"))
        out.write(np.ascontiguousarray(pixels).tobytes())
    ox, oy, yaw = grid.origin
    text = (
        f"image: {name}\n"
        f"resolution: {grid.resolution!r}\n"
        f"origin: [{ox!r}, {oy!r}, {yaw!r}]\n"
        "negate: 0\n"
        "occupied_thresh: 0.65\n"
        "free_thresh: 0.196\n"
    )
    path.write_text(text, encoding="utf-8")
    return image_path


def _read_yaml(path: Path) -> Dict[str, Any]:
    if not path.is_file():
        raise ConfigError(f"map file {path} does not exist")
    try:
        raw = yaml.safe_load(path.read_text(encoding="utf-8"))
    except (yaml.YAMLError, UnicodeDecodeError) as err:
        raise ConfigError(f"{path}: not valid YAML: {err}") from err
    if not isinstance(raw, dict):
        raise ConfigError(
            f"{path}: expected a mapping with fields {', '.join(REQUIRED_FIELDS)}, got {type(raw).__name__}"
        )
    missing = [f for f in REQUIRED_FIELDS if f not in raw]
    if missing:
        raise ConfigError(f"{path}: missing field(s) {', '.join(missing)} (required: {', '.join(REQUIRED_FIELDS)})")
    meta: Dict[str, Any] = {}
    image = raw["image"]
    if not isinstance(image, str) or not image:
        raise ConfigError(f"{path}: field image must be a non-empty file name, got {image!r}")
    meta["image"] = image
    meta["resolution"] = _number(path, "resolution", raw["resolution"], lambda v: v > 0.0, "a number > 0 [m/cell]")
    origin = raw["origin"]
    if not isinstance(origin, (list, tuple)) or len(origin) != 3:
        raise ConfigError(f"{path}: field origin must be [x, y, yaw] ([m], [m], [rad]), got {origin!r}")
    meta["origin"] = _origin(path, origin)
    negate = raw["negate"]
    if isinstance(negate, bool) or negate in (0, 1):
        meta["negate"] = bool(negate)
    else:
        raise ConfigError(choices_message(f"{path}: field negate", negate, (0, 1)))
    meta["occupied_thresh"] = _number(
        path, "occupied_thresh", raw["occupied_thresh"], lambda v: 0.0 <= v <= 1.0, "a number in [0, 1]"
    )
    meta["free_thresh"] = _number(
        path, "free_thresh", raw["free_thresh"], lambda v: 0.0 <= v <= 1.0, "a number in [0, 1]"
    )
    if meta["free_thresh"] >= meta["occupied_thresh"]:
        raise ConfigError(
            f"{path}: field free_thresh ({meta['free_thresh']}) must be below "
            f"occupied_thresh ({meta['occupied_thresh']})"
        )
    mode = raw.get("mode", "trinary")
    if mode not in MODES:
        raise ConfigError(choices_message(f"{path}: field mode", mode, MODES))
    meta["mode"] = mode
    return meta


def _number(path: Path, field: str, value: object, ok: Callable[[float], bool], wanted: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ConfigError(f"{path}: field {field} must be {wanted}, got {value!r}")
    number = float(value)
    if not math.isfinite(number) or not ok(number):
        raise ConfigError(f"{path}: field {field} must be {wanted}, got {value!r}")
    return number


def _origin(path: Path, origin: Sequence[object]) -> Tuple[float, float, float]:
    values = []
    for name, v in zip(("x", "y", "yaw"), origin):
        values.append(_number(path, f"origin.{name}", v, lambda _v: True, "a finite number"))
    return values[0], values[1], values[2]


def _read_image(image_path: Path, yaml_path: Path) -> np.ndarray:
    if not image_path.is_file():
        raise ConfigError(f"{yaml_path}: field image names {image_path}, which does not exist")
    pixels = cv2.imread(str(image_path), cv2.IMREAD_UNCHANGED)
    if pixels is None:
        raise ConfigError(f"{yaml_path}: field image: cannot decode {image_path} (valid: 8-bit PGM or PNG)")
    if pixels.dtype != np.uint8:
        raise ConfigError(f"{yaml_path}: field image: {image_path} has {pixels.dtype} pixels (valid: 8-bit)")
    return pixels
