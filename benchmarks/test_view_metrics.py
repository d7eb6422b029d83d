#!/usr/bin/env python3
"""PSNR and SSIM of train_bench's test-view renders (float32 [H, W, 3] .npy) against the photos
(uint8 [H, W, 3] .npy of the same stem), SSIM as the reference trainer computes it
(utils/loss_utils.py: 11x11 Gaussian window, sigma 1.5, zero padding, C1 = 0.01^2, C2 = 0.03^2,
the mean of the SSIM map over pixels and channels). numpy only.
usage: test_view_metrics.py RENDERS_DIR PHOTOS_DIR"""
import pathlib
import sys

import numpy as np


def blur(image, window):
    """Separable 'same' convolution with zero padding, as conv2d(padding=5) does."""
    half = len(window) // 2
    for axis in (0, 1):
        padded = np.pad(image, [(half, half) if a == axis else (0, 0) for a in range(image.ndim)])
        size = image.shape[axis]
        image = sum(w * np.take(padded, np.arange(k, k + size), axis=axis) for k, w in enumerate(window))
    return image


def ssim(a, b):
    x = np.arange(11) - 5
    window = np.exp(-x**2 / (2 * 1.5**2))
    window /= window.sum()
    mu_a, mu_b = blur(a, window), blur(b, window)
    var_a = blur(a * a, window) - mu_a**2
    var_b = blur(b * b, window) - mu_b**2
    cov = blur(a * b, window) - mu_a * mu_b
    c1, c2 = 0.01**2, 0.03**2
    return float(np.mean(((2 * mu_a * mu_b + c1) * (2 * cov + c2)) / ((mu_a**2 + mu_b**2 + c1) * (var_a + var_b + c2))))


renders, photos = map(pathlib.Path, sys.argv[1:3])
psnrs, ssims = [], []
for path in sorted(renders.glob("*.npy")):
    render = np.load(path).astype(np.float64)
    photo = np.load(photos / path.name).astype(np.float64) / 255.0
    mse = np.mean((render - photo) ** 2)
    psnrs.append(10 * np.log10(1.0 / mse))
    ssims.append(ssim(render, photo))
print(f"{len(psnrs)} test views: PSNR {np.mean(psnrs):.3f} dB, SSIM {np.mean(ssims):.4f}")
