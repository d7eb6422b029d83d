#!/usr/bin/env python3
"""Decodes a folder of photos into <stem>.npy (uint8 [H, W, 3], RGB) for refit_bench on GPU hosts
that have Python's numpy and OpenCV but no codecs vksplat links. Photos with alpha are refused:
composite them first (refit_bench takes the photos as they are).
usage: photos_to_npy.py IMAGES_DIR OUT_DIR"""
import pathlib
import sys

import cv2
import numpy as np

source, target = map(pathlib.Path, sys.argv[1:3])
target.mkdir(parents=True, exist_ok=True)
for path in sorted(source.iterdir()):
    image = cv2.imread(str(path), cv2.IMREAD_UNCHANGED)
    if image is None:
        continue
    if image.ndim != 3 or image.shape[2] != 3:
        sys.exit(f"{path}: expected an 8-bit RGB photo, got shape {image.shape}")
    np.save(target / (path.stem + ".npy"), cv2.cvtColor(image, cv2.COLOR_BGR2RGB))
