#!/usr/bin/env python3
"""Peer corner detectors for `castellan corners-eval` (dissertation §2.2, figure 2.4).

Runs OpenCV's Harris (cornerHarris + 3x3 non-maximum suppression), Shi-Tomasi
(goodFeaturesToTrack), FAST and SIFT (DoG) on every image of Oxford-style sequences and writes,
per sequence, PEERS/<sequence>.json:

    {"sequence": "graf", "images": ["img1.ppm", ...],
     "detectors": {"Harris": [[[x, y], ...] per image], ...},
     "time_ms": {"Harris": [ms per image], ...}}

Coordinates are pixels with centres at integers (x right, y down), as castellan's. All
detectors run on one thread (cv2.setNumThreads(1)); each time is the median of --repeat runs
and excludes reading the image. With --castellan BIN the script then runs
`BIN corners-eval ... --peers PEERS --threads 1`, so IPFIT and the peers are timed in the same
run on the same images, and the repeatability of every detector is computed by the same Rust
code.

Setup (never inside the repository):
    python3 -m venv /tmp/cv-venv && /tmp/cv-venv/bin/pip install -r benches/requirements.txt
    /tmp/cv-venv/bin/python benches/corners_peers.py ../shared/data/oxford_affine -o /tmp/peers \
        --castellan target/release/castellan --eval-out /tmp/corners-eval
"""

import argparse
import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

import cv2
import numpy as np

SEQUENCES = ["bark", "bikes", "boat", "graf", "leuven", "trees", "ubc", "wall"]


def harris(gray):
    """cornerHarris (blockSize 3, Sobel 3, k 0.04) + 3x3 non-maximum suppression, kept above
    1% of the strongest response (the usual OpenCV recipe)."""
    r = cv2.cornerHarris(gray, 3, 3, 0.04)
    peaks = (r == cv2.dilate(r, None)) & (r > 0.01 * r.max())
    ys, xs = np.nonzero(peaks)
    return np.stack([xs, ys], axis=1).astype(float)


def shi_tomasi(gray):
    pts = cv2.goodFeaturesToTrack(gray, maxCorners=0, qualityLevel=0.01, minDistance=5)
    return np.zeros((0, 2)) if pts is None else pts.reshape(-1, 2).astype(float)


FAST = cv2.FastFeatureDetector_create(threshold=20, nonmaxSuppression=True)
SIFT = cv2.SIFT_create()


def fast(gray):
    return np.array([k.pt for k in FAST.detect(gray, None)], dtype=float).reshape(-1, 2)


def sift(gray):
    return np.array([k.pt for k in SIFT.detect(gray, None)], dtype=float).reshape(-1, 2)


DETECTORS = {"Harris": harris, "Shi-Tomasi": shi_tomasi, "FAST": fast, "SIFT": sift}


def images(folder):
    out = []
    k = 1
    while True:
        found = [folder / f"img{k}.{e}" for e in ("ppm", "pgm", "png", "jpg")]
        found = [p for p in found if p.is_file()]
        if not found:
            return out
        out.append(found[0])
        k += 1


def run_sequence(folder, repeat):
    paths = images(folder)
    if len(paths) < 2:
        sys.exit(f"{folder}: expected img1, img2, ...")
    result = {"sequence": folder.name, "images": [p.name for p in paths],
              "detectors": {}, "time_ms": {}}
    grays = []
    for p in paths:
        g = cv2.imread(str(p), cv2.IMREAD_GRAYSCALE)
        if g is None:
            sys.exit(f"{p}: not a readable image")
        grays.append(g)
    for name, fn in DETECTORS.items():
        pts, times = [], []
        for g in grays:
            src = np.float32(g) if name == "Harris" else g
            runs = []
            for _ in range(repeat):
                t0 = time.perf_counter()
                p = fn(src)
                runs.append((time.perf_counter() - t0) * 1e3)
            pts.append([[float(x), float(y)] for x, y in p])
            times.append(statistics.median(runs))
        result["detectors"][name] = pts
        result["time_ms"][name] = times
    return result


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("data", type=Path, help="folder holding the sequence folders")
    ap.add_argument("-o", "--out", type=Path, required=True, help="folder for <sequence>.json")
    ap.add_argument("--sequences", nargs="*", default=SEQUENCES)
    ap.add_argument("--repeat", type=int, default=3, help="timing runs per image (median)")
    ap.add_argument("--castellan", type=Path, help="castellan binary: also run corners-eval")
    ap.add_argument("--eval-out", type=Path, default=Path("corners-eval"))
    ap.add_argument("--overlays", type=float, help="passed to corners-eval --overlays")
    args = ap.parse_args()
    cv2.setNumThreads(1)
    args.out.mkdir(parents=True, exist_ok=True)
    folders = [args.data / s for s in args.sequences]
    for f in folders:
        res = run_sequence(f, args.repeat)
        (args.out / f"{f.name}.json").write_text(json.dumps(res))
        n = [len(p) for p in res["detectors"]["Harris"]]
        print(f"{f.name}: Harris {statistics.mean(n):.0f}/image, "
              f"{statistics.mean(res['time_ms']['Harris']):.1f} ms/image", file=sys.stderr)
    if args.castellan:
        cmd = [str(args.castellan), "corners-eval", *map(str, folders), "-o", str(args.eval_out),
               "--peers", str(args.out), "--threads", "1"]
        if args.overlays:
            cmd += ["--overlays", str(args.overlays)]
        subprocess.run(cmd, check=True)


if __name__ == "__main__":
    main()
