#!/usr/bin/env python3
"""Writes gltfpack_sphere.gltf: a float UV sphere (positions, normals, UVs spanning [0, 2] x
[0, 1]) off the origin, with a 2x2 base-colour texture, the input that gltfpack turned into
gltfpack_sphere.glb (tests/scenes/gltf_quantization_test.cpp):

    python3 tests/scenes/data/gen_gltfpack_sphere.py tests/scenes/data/gltfpack_sphere.gltf
    gltfpack -i tests/scenes/data/gltfpack_sphere.gltf -o tests/scenes/data/gltfpack_sphere.glb -c

(gltfpack 1.3.0, npm's `gltfpack` package: KHR_mesh_quantization, EXT_meshopt_compression and
KHR_texture_transform, its defaults.)"""
import base64
import json
import math
import struct
import sys

SEGMENTS, RINGS, RADIUS, CENTRE = 16, 8, 1.5, (0.3, -0.2, 0.5)
PNG = ("iVBORw0KGgoAAAANSUhEUgAAAAIAAAACCAYAAABytg0kAAAAOXRFWHRTb2Z0d2FyZQBNYXRwbG90bGliIHZlcnNp"
       "b24zLjYuMywgaHR0cHM6Ly9tYXRwbG90bGliLm9yZy/P9b71AAAACXBIWXMAAA9hAAAPYQGoP6dpAAAAGklEQVR4"
       "nGPgYmD4f4KB4T+jHAPDfy4GBgYAKOgD+V7N2sAAAAAASUVORK5CYII=")

pos, nrm, uv, idx = [], [], [], []
for r in range(RINGS + 1):
    theta = math.pi * r / RINGS
    for s in range(SEGMENTS + 1):
        phi = 2 * math.pi * s / SEGMENTS
        n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
        nrm.append(n)
        pos.append(tuple(c + RADIUS * d for c, d in zip(CENTRE, n)))
        uv.append((2.0 * s / SEGMENTS, r / RINGS))
for r in range(RINGS):
    for s in range(SEGMENTS):
        a, b = r * (SEGMENTS + 1) + s, (r + 1) * (SEGMENTS + 1) + s
        if r > 0:
            idx += [a, b, a + 1]
        if r < RINGS - 1:
            idx += [a + 1, b, b + 1]

blob = b"".join(struct.pack("<3f", *p) for p in pos)
blob += b"".join(struct.pack("<3f", *n) for n in nrm)
blob += b"".join(struct.pack("<2f", *t) for t in uv)
blob += b"".join(struct.pack("<H", i) for i in idx)
blob += b"\0" * (-len(blob) % 4)
count, p3, p2 = len(pos), 12 * len(pos), 8 * len(pos)
lo = [min(p[i] for p in pos) for i in range(3)]
hi = [max(p[i] for p in pos) for i in range(3)]
gltf = {
    "asset": {"version": "2.0"},
    "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
                                "indices": 3, "material": 0}]}],
    "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                                            "metallicFactor": 0}}],
    "textures": [{"source": 0}],
    "images": [{"uri": "data:image/png;base64," + PNG}],
    "buffers": [{"byteLength": len(blob),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": p3},
                    {"buffer": 0, "byteOffset": p3, "byteLength": p3},
                    {"buffer": 0, "byteOffset": 2 * p3, "byteLength": p2},
                    {"buffer": 0, "byteOffset": 2 * p3 + p2, "byteLength": 2 * len(idx)}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": count,
                   "min": lo, "max": hi},
                  {"bufferView": 1, "componentType": 5126, "type": "VEC3", "count": count},
                  {"bufferView": 2, "componentType": 5126, "type": "VEC2", "count": count},
                  {"bufferView": 3, "componentType": 5123, "type": "SCALAR", "count": len(idx)}],
}
with open(sys.argv[1], "w") as f:
    json.dump(gltf, f, indent=1)
    f.write("\n")
