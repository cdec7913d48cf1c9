"""onnxruntime sessions for the perception models: CPU only, one intra-op and one inter-op thread.

One thread keeps the classifier's cost predictable on a robot computer shared with navigation (the
target is <= 5 ms per frame on one thread, see ``bench/bench_classifier.py``). Loading errors become
:class:`ConfigError` naming the file, so a node with a bad model path stops at start with that name.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, List, Optional, Tuple, Union

import onnxruntime as ort

from flex_nav.exceptions import ConfigError

Dim = Union[int, str, None]


def make_session(path: Union[str, Path], what: str = "model") -> Any:
    """An ``onnxruntime.InferenceSession`` on the CPU with 1 + 1 threads; ConfigError names ``what`` and ``path``."""
    file = Path(path)
    if not file.is_file():
        raise ConfigError(f"{what} {str(path)!r} does not exist (or is not a file)")
    options = ort.SessionOptions()
    options.intra_op_num_threads = 1
    options.inter_op_num_threads = 1
    options.execution_mode = ort.ExecutionMode.ORT_SEQUENTIAL
    options.graph_optimization_level = ort.GraphOptimizationLevel.ORT_ENABLE_ALL
    options.log_severity_level = 3  # errors only
    try:
        return ort.InferenceSession(str(file), sess_options=options, providers=["CPUExecutionProvider"])
    except Exception as err:  # onnxruntime raises its own (pybind) exception types
        raise ConfigError(f"{what} {str(path)!r} is not a loadable ONNX model: {err}") from err


def image_input(session: Any, what: str = "model", channels: int = 3) -> Tuple[str, List[Dim]]:
    """Name and shape of the model's single 4-D image input (N, ``channels``, H, W); ConfigError otherwise."""
    inputs = session.get_inputs()
    if len(inputs) != 1:
        raise ConfigError(f"{what} must have one input (an N x {channels} x H x W image), it has {len(inputs)}: "
                          f"{[i.name for i in inputs]}")
    shape = list(inputs[0].shape)
    if len(shape) != 4 or (shape[1] not in (channels, None) and not isinstance(shape[1], str)):
        kind = {3: " (RGB)", 4: " (RGB + depth)"}.get(channels, "")
        raise ConfigError(f"{what} input {inputs[0].name!r} has shape {shape}; N x {channels} x H x W{kind} "
                          "expected")
    if "float" not in inputs[0].type:
        raise ConfigError(f"{what} input {inputs[0].name!r} is {inputs[0].type}; a float tensor expected")
    return str(inputs[0].name), shape


def static_size(shape: List[Dim]) -> Optional[Tuple[int, int]]:
    """(width, height) [px] of an NCHW input shape, or None if either is dynamic."""
    h, w = shape[2], shape[3]
    return (w, h) if isinstance(w, int) and isinstance(h, int) and w > 0 and h > 0 else None


def metadata(session: Any) -> dict:
    """The model's custom metadata (key -> string), e.g. ultralytics' ``names`` and ``imgsz``."""
    return dict(session.get_modelmeta().custom_metadata_map)
