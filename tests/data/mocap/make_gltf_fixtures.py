#!/usr/bin/env python3
"""Writes the small glTF 2.0 fixtures of tests/mocap/gltf_reader_test.cpp (run from anywhere;
the files are committed, rerun only to change them). Every number is chosen so the expected joint
positions can be worked by hand; the test says how."""
import base64
import json
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def data_uri(blob):
    return "data:application/octet-stream;base64," + base64.b64encode(blob).decode()


class Buffer:
    """One buffer; every accessor gets its own tightly packed buffer view."""

    def __init__(self):
        self.blob = b""
        self.views = []
        self.accessors = []

    def add(self, fmt, values, component_type, type_name, normalized=False):
        while len(self.blob) % 4:
            self.blob += b"\0"
        data = struct.pack("<" + fmt * len(values), *values)
        self.views.append({"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(data)})
        self.blob += data
        count = len(values) // {"SCALAR": 1, "VEC3": 3, "VEC4": 4}[type_name]
        accessor = {"bufferView": len(self.views) - 1, "componentType": component_type, "count": count, "type": type_name}
        if normalized:
            accessor["normalized"] = True
        self.accessors.append(accessor)
        return len(self.accessors) - 1

    def floats(self, values, type_name):
        return self.add("f", values, 5126, type_name)


def gltf(nodes, buffer, samplers, channels, skins=None, uri=None):
    doc = {"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": nodes,
           "buffers": [{"byteLength": len(buffer.blob)}], "bufferViews": buffer.views, "accessors": buffer.accessors,
           "animations": [{"samplers": samplers, "channels": channels}]}
    if uri is not None:
        doc["buffers"][0]["uri"] = uri
    if skins:
        doc["skins"] = skins
    return doc


def linear_step_skin():
    # root (0,1,0) -> arm (1,0,0) -> hand (2,0,0); a mesh node carries the skin and stays off the skeleton.
    b = Buffer()
    times = b.floats([0.0, 1.0], "SCALAR")
    turn = b.floats([0, 0, 0, 1, 0, 0, 0.7071067811865476, 0.7071067811865476], "VEC4")  # 0 -> 90 deg about z
    step_times = b.floats([0.0, 0.5], "SCALAR")
    lift = b.floats([0, 1, 0, 0, 2, 0], "VEC3")
    nodes = [{"name": "root", "translation": [0, 1, 0], "children": [1, 3]},
             {"name": "arm", "translation": [1, 0, 0], "children": [2]},
             {"name": "hand", "translation": [2, 0, 0]},
             {"name": "mesh", "skin": 0}]
    samplers = [{"input": times, "output": turn, "interpolation": "LINEAR"},
                {"input": step_times, "output": lift, "interpolation": "STEP"}]
    channels = [{"sampler": 0, "target": {"node": 1, "path": "rotation"}},
                {"sampler": 1, "target": {"node": 0, "path": "translation"}}]
    return gltf(nodes, b, samplers, channels, skins=[{"joints": [0, 1, 2]}], uri=data_uri(b.blob)), None


def cubic_matrix():
    # base: matrix T(0,0,5) Rz(90) S(2); bone under it slides along x by a CUBICSPLINE over 2 s.
    b = Buffer()
    times = b.floats([0.0, 2.0], "SCALAR")
    # per key: in-tangent, value, out-tangent
    slide = b.floats([0, 0, 0, 0, 0, 0, 3, 0, 0,
                      0, 0, 0, 1, 0, 0, 0, 0, 0], "VEC3")
    nodes = [{"name": "base", "matrix": [0, 2, 0, 0, -2, 0, 0, 0, 0, 0, 2, 0, 0, 0, 5, 1], "children": [1]},
             {"name": "bone", "children": [2]},
             {"name": "unanimated_leaf", "translation": [0, 1, 0]}]
    samplers = [{"input": times, "output": slide, "interpolation": "CUBICSPLINE"}]
    channels = [{"sampler": 0, "target": {"node": 1, "path": "translation"}}]
    # The buffer lives in a .bin file next to the .gltf.
    return gltf(nodes, b, samplers, channels, uri="gltf_cubic_matrix.bin"), ("gltf_cubic_matrix.bin", b.blob)


def short_rotation_glb():
    # spin turns from -identity (w = -32768 -> -1) to 90 deg about y, as normalized shorts; tip at (0,0,1).
    b = Buffer()
    times = b.floats([0.0, 1.0], "SCALAR")
    turn = b.add("h", [0, 0, 0, -32768, 0, 23170, 0, 23170], 5122, "VEC4", normalized=True)
    nodes = [{"name": "spin", "children": [1]}, {"name": "tip", "translation": [0, 0, 1]}]
    samplers = [{"input": times, "output": turn}]
    channels = [{"sampler": 0, "target": {"node": 0, "path": "rotation"}}]
    return gltf(nodes, b, samplers, channels, skins=[{"joints": [0, 1]}]), b.blob


def sparse_translation():
    # slider's translation keys come from a sparse accessor with no buffer view: zeros, then
    # element 1 replaced by (4,0,0); end sits at (0,1,0) under it. Indices are UNSIGNED_SHORT.
    b = Buffer()
    times = b.floats([0.0, 1.0], "SCALAR")
    b.add("H", [1, 0], 5123, "SCALAR")  # indices (padded to 4 bytes); its accessor goes unused
    index_view = len(b.views) - 1
    b.floats([4, 0, 0], "VEC3")
    value_view = len(b.views) - 1
    b.accessors.append({"componentType": 5126, "count": 2, "type": "VEC3",
                        "sparse": {"count": 1, "indices": {"bufferView": index_view, "componentType": 5123},
                                   "values": {"bufferView": value_view}}})
    slide = len(b.accessors) - 1
    nodes = [{"name": "slider", "children": [1]}, {"name": "end", "translation": [0, 1, 0]}]
    samplers = [{"input": times, "output": slide}]
    channels = [{"sampler": 0, "target": {"node": 0, "path": "translation"}}]
    return gltf(nodes, b, samplers, channels, skins=[{"joints": [0, 1]}], uri=data_uri(b.blob))


def glb(doc, blob):
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    blob += b"\0" * (-len(blob) % 4)
    body = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(blob), 0x004E4942) + blob
    return struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body


def main():
    doc, _ = linear_step_skin()
    with open(os.path.join(HERE, "gltf_linear_step_skin.gltf"), "w") as f:
        json.dump(doc, f, indent=1)
    doc, (bin_name, blob) = cubic_matrix()
    with open(os.path.join(HERE, "gltf_cubic_matrix.gltf"), "w") as f:
        json.dump(doc, f, indent=1)
    with open(os.path.join(HERE, bin_name), "wb") as f:
        f.write(blob)
    with open(os.path.join(HERE, "gltf_sparse.gltf"), "w") as f:
        json.dump(sparse_translation(), f, indent=1)
    doc, blob = short_rotation_glb()
    with open(os.path.join(HERE, "gltf_short_rotation.glb"), "wb") as f:
        f.write(glb(doc, blob))


if __name__ == "__main__":
    main()
