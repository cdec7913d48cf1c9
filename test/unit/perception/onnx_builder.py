"""Tiny ONNX models written straight to protobuf bytes, for tests (no ``onnx`` package needed).

Only the fields the tests use are encoded (field numbers from onnx.proto: ModelProto, GraphProto,
NodeProto, AttributeProto, TensorProto, ValueInfoProto/TypeProto). onnxruntime itself checks the result.
"""

from __future__ import annotations

import struct
from pathlib import Path
from typing import Dict, Optional, Sequence, Tuple, Union

import numpy as np

FLOAT, INT64 = 1, 7  # TensorProto.DataType
ATTR_FLOAT, ATTR_INT, ATTR_TENSOR, ATTR_INTS = 1, 2, 4, 7  # AttributeProto.AttributeType
Dim = Union[int, str]


def _varint(value: int) -> bytes:
    value &= (1 << 64) - 1  # negative int64 as two's complement
    out = bytearray()
    while True:
        byte = value & 0x7F
        value >>= 7
        if value:
            out.append(byte | 0x80)
        else:
            out.append(byte)
            return bytes(out)


def _key(field: int, wire: int) -> bytes:
    return _varint(field << 3 | wire)


def _bytes(field: int, payload: bytes) -> bytes:
    return _key(field, 2) + _varint(len(payload)) + payload


def _str(field: int, text: str) -> bytes:
    return _bytes(field, text.encode())


def _int(field: int, value: int) -> bytes:
    return _key(field, 0) + _varint(value)


def tensor(name: str, array: np.ndarray) -> bytes:
    """TensorProto: dims (1), data_type (2), name (8), raw_data (9, little endian)."""
    array = np.ascontiguousarray(array)
    dtype = {np.dtype(np.float32): FLOAT, np.dtype(np.int64): INT64}[array.dtype]
    out = b"".join(_int(1, d) for d in array.shape) + _int(2, dtype) + _str(8, name)
    return out + _bytes(9, array.astype(array.dtype.newbyteorder("<")).tobytes())


def attribute(name: str, value: Union[int, float, np.ndarray, Sequence[int]]) -> bytes:
    """AttributeProto: name (1), f (2), i (3), t (5), ints (8), type (20)."""
    if isinstance(value, np.ndarray):
        return _str(1, name) + _bytes(5, tensor("", value)) + _int(20, ATTR_TENSOR)
    if isinstance(value, float):
        return _str(1, name) + _key(2, 5) + struct.pack("<f", value) + _int(20, ATTR_FLOAT)
    if isinstance(value, int):
        return _str(1, name) + _int(3, value) + _int(20, ATTR_INT)
    return _str(1, name) + b"".join(_int(8, v) for v in value) + _int(20, ATTR_INTS)


def node(op: str, inputs: Sequence[str], outputs: Sequence[str], **attrs: object) -> bytes:
    """NodeProto: input (1), output (2), name (3), op_type (4), attribute (5)."""
    out = b"".join(_str(1, i) for i in inputs) + b"".join(_str(2, o) for o in outputs)
    out += _str(3, f"{op}_{outputs[0]}") + _str(4, op)
    return out + b"".join(_bytes(5, attribute(k, v)) for k, v in attrs.items())  # type: ignore[arg-type]


def value_info(name: str, shape: Sequence[Dim], elem_type: int = FLOAT) -> bytes:
    """ValueInfoProto name (1), type (2) -> TypeProto.tensor_type (1) -> elem_type (1), shape (2) -> dim (1)."""
    dims = b"".join(_bytes(1, _int(1, d) if isinstance(d, int) else _str(2, d)) for d in shape)
    tensor_type = _int(1, elem_type) + _bytes(2, dims)
    return _str(1, name) + _bytes(2, _bytes(1, tensor_type))


def model(
    nodes: Sequence[bytes],
    inputs: Sequence[Tuple[str, Sequence[Dim]]],
    outputs: Sequence[Tuple[str, Sequence[Dim]]],
    initializers: Optional[Dict[str, np.ndarray]] = None,
    metadata: Optional[Dict[str, str]] = None,
    opset: int = 17,
) -> bytes:
    """ModelProto: ir_version (1), producer_name (2), graph (7), opset_import (8), metadata_props (14)."""
    graph = b"".join(_bytes(1, n) for n in nodes) + _str(2, "test_graph")
    graph += b"".join(_bytes(5, tensor(k, v)) for k, v in (initializers or {}).items())
    graph += b"".join(_bytes(11, value_info(n, s)) for n, s in inputs)
    graph += b"".join(_bytes(12, value_info(n, s)) for n, s in outputs)
    out = _int(1, 8) + _str(2, "flex_nav_tests") + _bytes(7, graph) + _bytes(8, _str(1, "") + _int(2, opset))
    return out + b"".join(_bytes(14, _str(1, k) + _str(2, v)) for k, v in (metadata or {}).items())


def constant_output_model(
    path: Path,
    value: np.ndarray,
    input_shape: Sequence[Dim] = (1, 3, 64, 64),
    metadata: Optional[Dict[str, str]] = None,
    input_name: str = "images",
    output_name: str = "output0",
) -> Path:
    """A model whose one output is ``value`` whatever the image (the image is read: + 0 * its mean)."""
    nodes = [
        node("ReduceMean", ["images_in"], ["mean"], keepdims=0),
        node("Mul", ["mean", "zero"], ["nothing"]),
        node("Add", ["value", "nothing"], [output_name]),
        node("Identity", [input_name], ["images_in"]),
    ]
    data = model(
        [nodes[3], *nodes[:3]],
        inputs=[(input_name, input_shape)],
        outputs=[(output_name, value.shape)],
        initializers={"value": value.astype(np.float32), "zero": np.zeros((), dtype=np.float32)},
        metadata=metadata,
    )
    path.write_bytes(data)
    return path


def mean_colour_classifier(path: Path, weights: np.ndarray, size: Tuple[int, int] = (8, 8),
                           softmax: bool = True) -> Path:
    """image (N, C, H, W) -> GlobalAveragePool -> Flatten -> MatMul(weights C x K) [-> Softmax]; C = weights' rows
    (3: RGB, 4: RGB + depth)."""
    channels, k = weights.shape
    nodes = [
        node("GlobalAveragePool", ["image"], ["pooled"]),
        node("Flatten", ["pooled"], ["flat"], axis=1),
        node("MatMul", ["flat", "weights"], ["scores" if softmax else "logits"]),
    ]
    if softmax:
        nodes.append(node("Softmax", ["scores"], ["probabilities"], axis=1))
    out_name = "probabilities" if softmax else "logits"
    data = model(nodes, inputs=[("image", ("batch", channels, size[1], size[0]))], outputs=[(out_name, ("batch", k))],
                 initializers={"weights": weights.astype(np.float32)})
    path.write_bytes(data)
    return path
