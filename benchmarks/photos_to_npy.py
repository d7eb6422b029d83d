#!/usr/bin/env python3
"""Decodes a folder of photos into <stem>.npy (uint8 [H, W, 3], RGB) for refit_bench and train_bench
on GPU hosts that have Python's numpy and OpenCV but no codecs vksplat links. Photos with alpha
are composited on --background (as vksplat does for NeRF-synthetic photos), else refused.
usage: photos_to_npy.py IMAGES_DIR OUT_DIR [--background R,G,B]"""
import argparse
import pathlib
import sys

import cv2
import numpy as np

parser = argparse.ArgumentParser()
parser.add_argument("source", type=pathlib.Path)
parser.add_argument("target", type=pathlib.Path)
parser.add_argument("--background", help="R,G,B in [0, 1]: composite RGBA photos on it")
args = parser.parse_args()
args.target.mkdir(parents=True, exist_ok=True)
for path in sorted(args.source.iterdir()):
    image = cv2.imread(str(path), cv2.IMREAD_UNCHANGED)
    if image is None:
        continue
    if image.dtype != np.uint8 or image.ndim != 3 or image.shape[2] not in (3, 4):
        sys.exit(f"{path}: expected an 8-bit RGB or RGBA photo, got {image.dtype} {image.shape}")
    if image.shape[2] == 4:
        if args.background is None:
            sys.exit(f"{path}: has alpha; give --background R,G,B to composite it")
        rgba = cv2.cvtColor(image, cv2.COLOR_BGRA2RGBA).astype(np.float32) / 255.0
        background = np.array([float(c) for c in args.background.split(",")], np.float32)
        alpha = rgba[..., 3:]
        rgb = rgba[..., :3] * alpha + background * (1.0 - alpha)
        np.save(args.target / (path.stem + ".npy"), np.round(rgb * 255.0).astype(np.uint8))
    else:
        np.save(args.target / (path.stem + ".npy"), cv2.cvtColor(image, cv2.COLOR_BGR2RGB))
