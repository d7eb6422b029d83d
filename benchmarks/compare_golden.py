#!/usr/bin/env python3
"""Compares renders saved by `vksplat bench --save-npy` (float32 H x W x 3 .npy) with golden PNGs.

Used on GPU hosts, where the library is built without image codecs: numpy and OpenCV's Python
package read both sides. Prints PSNR of the 8-bit quantised render against the golden image and
the fraction of 8-bit values within 2/255, per view.

usage: compare_golden.py RENDER_DIR GOLDEN_DIR VIEW [VIEW ...]
"""
import sys

import cv2
import numpy as np


def main():
    render_dir, golden_dir, views = sys.argv[1], sys.argv[2], [int(v) for v in sys.argv[3:]]
    for view in views:
        render = np.load(f"{render_dir}/view_{view:04d}.npy")
        ours = np.round(np.clip(render, 0.0, 1.0) * 255.0)
        golden = cv2.imread(f"{golden_dir}/{view:05d}.png", cv2.IMREAD_COLOR)[:, :, ::-1].astype(np.float64)
        diff = np.abs(ours - golden)
        mse = np.mean((diff / 255.0) ** 2)
        psnr = float("inf") if mse == 0 else 10.0 * np.log10(1.0 / mse)
        within = np.mean(diff <= 2.0)
        print(f"golden view {view}: PSNR {psnr:.2f} dB, {100.0 * within:.4f}% of values within 2/255, "
              f"max error {diff.max() / 255.0:.4f}")


if __name__ == "__main__":
    main()
