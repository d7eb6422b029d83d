#!/usr/bin/env python3
"""Reference PSNR and SSIM values for tests/eval/metrics_test.cpp, computed with scikit-image.

Run with Debian 12's packages (python3-skimage 0.19.3, python3-numpy 1.24.2):
    /usr/bin/python3 tests/eval/reference_values.py
and paste the printed numbers into metrics_test.cpp if the test images ever change.

The test images are built here exactly as make_test_image() in metrics_test.cpp builds them:
plain double arithmetic in the same order (Python floats are IEEE doubles), rounded to float32
once per value, with pseudo-random values from the same 32-bit LCG.
"""
import numpy as np
from skimage.metrics import peak_signal_noise_ratio, structural_similarity


class Lcg:
    """Numerical Recipes' 32-bit LCG; next() gives a double in [0, 1) with 24 random bits."""

    def __init__(self, seed):
        self.state = seed & 0xFFFFFFFF

    def next(self):
        self.state = (self.state * 1664525 + 1013904223) & 0xFFFFFFFF
        return (self.state >> 8) / 16777216.0


def make_test_image(width, height, channels, seed, variant):
    """variant 0: the 'reference' image; variant 1: a distorted copy of it (same seed)."""
    noise = Lcg(seed)
    distortion = Lcg(seed + 1)
    img = np.empty((height, width, channels), dtype=np.float32)
    for y in range(height):
        for x in range(width):
            u = x / (width - 1)
            v = y / (height - 1)
            for c in range(channels):
                value = 0.5 * u + 0.3 * v * v + 0.1 * c + 0.3 * (noise.next() - 0.5)
                d = distortion.next()
                if variant == 1:
                    value = value + 0.15 * (d - 0.5) + 0.08 * u * v - 0.05
                img[y, x, c] = np.float32(value)
    return img


def compare(width, height, channels, seed):
    a = np.clip(make_test_image(width, height, channels, seed, 0), 0.0, 1.0).astype(np.float64)
    b = np.clip(make_test_image(width, height, channels, seed, 1), 0.0, 1.0).astype(np.float64)
    psnr = peak_signal_noise_ratio(a, b, data_range=1.0)
    if channels == 1:
        a, b, channel_axis = a[:, :, 0], b[:, :, 0], None
    else:
        channel_axis = 2
    ssim = structural_similarity(a, b, channel_axis=channel_axis, data_range=1.0,
                                 gaussian_weights=True, sigma=1.5, use_sample_covariance=False)
    print(f"{width} x {height} x {channels}, seed {seed}: psnr {psnr:.17g}  ssim {ssim:.17g}")


if __name__ == "__main__":
    compare(37, 29, 3, 12345)
    compare(64, 48, 3, 777)
    compare(23, 17, 1, 4242)
    compare(11, 11, 3, 99)
