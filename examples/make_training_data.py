#!/usr/bin/python3
"""Training pairs for a learned denoiser, from ssrt's Python module.

For each frame of a short sequence (a scene's still camera, or a shot's camera path) it
writes one .npz holding
    noisy      the frame's colour with the denoiser off (1 ray per pixel for SSR and SSGI)
    guides     albedo, normal, viewZ, roughness, metallic and motion: the G-buffer
    reference  the Embree reference of all the light (--spp rays per pixel, every bounce)
each as float32 arrays of shape (channels, height, width), and prints the relMSE of the noisy
colour against the reference. The frames carry one history from each to the next, so the
motion vectors and the denoiser's history (were it on) are what a renderer would have.

Run with the module on PYTHONPATH (build/python in a build tree), for example:
    PYTHONPATH=build/python examples/make_training_data.py --scene cornell --frames 4 --out data
"""

import argparse
from pathlib import Path

import numpy as np

import ssrt

GUIDES = ["albedo.R", "albedo.G", "albedo.B", "normal.X", "normal.Y", "normal.Z", "viewZ",
          "roughness", "metallic", "motion.X", "motion.Y"]


def stack(planes, names):
    return np.stack([np.asarray(planes[n]) for n in names])  # a copy: the file keeps its own


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scene", default="cornell", help="a built-in scene or a .gltf/.glb file")
    p.add_argument("--shot", help="a shot file (its scene, settings and camera path)")
    p.add_argument("--frames", type=int, default=4)
    p.add_argument("--width", type=int, default=320)
    p.add_argument("--height", type=int, default=180)
    p.add_argument("--spp", type=int, default=64, help="the reference's rays per pixel")
    p.add_argument("--out", type=Path, default=Path("training_data"))
    args = p.parse_args()

    if args.shot:
        shot = ssrt.Shot(args.shot)
        scene, settings = shot.scene, shot.settings
    else:
        scene, settings = ssrt.Scene(args.scene), ssrt.RenderSettings()
    settings = settings.replace(width=args.width, height=args.height, denoise=False)
    args.out.mkdir(parents=True, exist_ok=True)
    for i, frame in enumerate(ssrt.Renderer(settings).sequence(scene, args.frames)):
        truth = ssrt.compare(frame, spp=args.spp)
        path = args.out / f"frame_{i:04d}.npz"
        np.savez(path, noisy=stack(frame.planes(), ["color.R", "color.G", "color.B"]),
                 guides=stack(frame.planes(), GUIDES),
                 reference=stack(truth["reference"], ["ref.color.R", "ref.color.G", "ref.color.B"]))
        print(f"{path}: frame {frame.index}, noisy relMSE {truth['color']['rel_mse']:.4g}")


if __name__ == "__main__":
    main()
