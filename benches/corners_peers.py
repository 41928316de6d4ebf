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

With --speed-table FILE.md (and --castellan BIN) it instead times, image by image and
interleaved so both see the same machine load, OpenCV Harris (cornerHarris + 3x3 non-maximum
suppression, one thread) against `BIN corners IMAGE` run with RAYON_NUM_THREADS=1 (the detection
time it prints, which excludes decoding and writing), --repeat times each, and writes a
per-image table of the fastest run of each and their ratio (on a shared machine the fastest
run is the one least disturbed by other work). --castellan-before BIN times an older build in
the same loop (Harris, BIN, the older build for each run) and adds its columns.

Setup (never inside the repository):
    python3 -m venv /tmp/cv-venv && /tmp/cv-venv/bin/pip install -r benches/requirements.txt
    /tmp/cv-venv/bin/python benches/corners_peers.py ../shared/data/oxford_affine -o /tmp/peers \
        --castellan target/release/castellan --eval-out /tmp/corners-eval
    /tmp/cv-venv/bin/python benches/corners_peers.py ../shared/data/oxford_affine -o /tmp/peers \
        --castellan target/release/castellan --speed-table /tmp/corners-speed.md --repeat 5
"""

import argparse
import json
import os
import re
import tempfile
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


def castellan_ms(binary, image, scratch):
    """Detection time printed by `castellan corners` on one thread."""
    env = dict(os.environ, RAYON_NUM_THREADS="1")
    out = subprocess.run([str(binary), "corners", str(image), "-o", str(scratch)],
                         env=env, check=True, capture_output=True, text=True)
    m = re.search(r"([0-9.]+) ms;", out.stderr)
    if not m:
        sys.exit(f"{binary}: unexpected output {out.stderr!r}")
    return float(m.group(1))


def speed_table(folders, binary, repeat, path, before=None):
    """Per-image best times of Harris and castellan, interleaved, and their ratio; with
    `before` (an older castellan binary) that one too, in the same loop."""
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        scratch = Path(tmp) / "corners.json"
        for folder in folders:
            for p in images(folder):
                g = np.float32(cv2.imread(str(p), cv2.IMREAD_GRAYSCALE))
                h_ms, c_ms, b_ms = [], [], []
                for _ in range(repeat):
                    t0 = time.perf_counter()
                    harris(g)
                    h_ms.append((time.perf_counter() - t0) * 1e3)
                    c_ms.append(castellan_ms(binary, p, scratch))
                    if before:
                        b_ms.append(castellan_ms(before, p, scratch))
                h, c = min(h_ms), min(c_ms)
                b = min(b_ms) if before else float("nan")
                rows.append((folder.name, p.name, g.shape[1], g.shape[0], c, h, c / h, b, b / h))
                print(f"{folder.name}/{p.name}: IPFIT {c:.1f} ms, Harris {h:.1f} ms, "
                      f"ratio {c / h:.2f}" + (f", before {b:.1f} ms" if before else ""),
                      file=sys.stderr)
    ratios = [r[6] for r in rows]
    load = os.getloadavg()[0]
    md = [f"Per image, fastest of {repeat} interleaved runs, one thread each; "
          f"load average at the end {load:.1f} on {os.cpu_count()} cores.", ""]
    if before:
        md += ["| image | size | IPFIT ms | Harris ms | ratio | IPFIT before ms | ratio before |",
               "| --- | --- | ---: | ---: | ---: | ---: | ---: |"]
        md += [f"| {s}/{n} | {w}×{h} | {c:.1f} | {hm:.1f} | {r:.1f}× | {b:.1f} | {rb:.1f}× |"
               for s, n, w, h, c, hm, r, b, rb in rows]
    else:
        md += ["| image | size | IPFIT ms | Harris ms | ratio |",
               "| --- | --- | ---: | ---: | ---: |"]
        md += [f"| {s}/{n} | {w}×{h} | {c:.1f} | {hm:.1f} | {r:.1f}× |"
               for s, n, w, h, c, hm, r, _, _ in rows]
    total = lambda k: sum(r[k] for r in rows)
    md += ["", f"Median ratio {statistics.median(ratios):.1f}× "
               f"(range {min(ratios):.1f}–{max(ratios):.1f}× over {len(rows)} images; "
               f"total {total(4) / 1e3:.2f} s against {total(5) / 1e3:.2f} s, "
               f"{total(4) / total(5):.1f}×)."]
    if before:
        rb = [r[8] for r in rows]
        md[-1] += (f" Before: median {statistics.median(rb):.1f}× "
                   f"(range {min(rb):.1f}–{max(rb):.1f}×; total {total(7) / 1e3:.2f} s, "
                   f"{total(7) / total(5):.1f}×); after / before time: median "
                   f"{statistics.median(r[4] / r[7] for r in rows):.2f}.")
    path.write_text("\n".join(md) + "\n")
    print(f"written to {path}", file=sys.stderr)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("data", type=Path, help="folder holding the sequence folders")
    ap.add_argument("-o", "--out", type=Path, required=True, help="folder for <sequence>.json")
    ap.add_argument("--sequences", nargs="*", default=SEQUENCES)
    ap.add_argument("--repeat", type=int, default=3, help="timing runs per image (median)")
    ap.add_argument("--castellan", type=Path, help="castellan binary: also run corners-eval")
    ap.add_argument("--eval-out", type=Path, default=Path("corners-eval"))
    ap.add_argument("--overlays", type=float, help="passed to corners-eval --overlays")
    ap.add_argument("--speed-table", type=Path,
                    help="only time Harris against `castellan corners` per image (Markdown)")
    ap.add_argument("--castellan-before", type=Path,
                    help="with --speed-table: also time this older castellan binary, interleaved")
    args = ap.parse_args()
    cv2.setNumThreads(1)
    if args.speed_table:
        if not args.castellan:
            sys.exit("--speed-table needs --castellan BIN")
        speed_table([args.data / s for s in args.sequences], args.castellan, args.repeat,
                    args.speed_table, args.castellan_before)
        return
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
