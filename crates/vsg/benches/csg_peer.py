"""Times the solids of benches/csg.rs in Python manifold3d and prints the ratio to boolmesh.

Runs `cargo bench -p vsg --bench csg` first (unless --no-cargo), then the same Booleans in
manifold3d on the same machine, and reads criterion's estimates from target/criterion.
    python3 crates/vsg/benches/csg_peer.py   (with manifold3d installed, see requirements.txt)
"""

import json
import pathlib
import statistics
import subprocess
import sys
import time

from manifold3d import Manifold, OpType, set_circular_segments

ROOT = pathlib.Path(__file__).resolve().parents[3]
SEGMENTS = 64


def wall_and_windows():
    wall = Manifold.cube((20, 10, 1), center=True)
    windows = [
        Manifold.cube((1, 0.6, 2), center=True).translate((-9 + 2 * c, -4.5 + r, 0))
        for r in range(10)
        for c in range(10)
    ]
    return wall, windows


def ring():
    # Cylinders along y, as VSG's (manifold3d's run along z; the Boolean does not care).
    outer = Manifold.cylinder(1.0, 2.0, circular_segments=SEGMENTS, center=True)
    inner = Manifold.cylinder(2.0, 1.5, circular_segments=SEGMENTS, center=True)
    return outer, [inner]


def timed(build, repeats=20):
    first, rest = build()
    samples = []
    volume = None
    for _ in range(repeats):
        t = time.perf_counter()
        # Same algorithm as the Rust side: union the cutters, subtract once; num_tri() forces
        # manifold3d's lazy evaluation.
        result = first - Manifold.batch_boolean(rest, OpType.Add)
        result.num_tri()
        samples.append(time.perf_counter() - t)
        volume = result.volume()
    return statistics.median(samples), volume


def criterion_ms(name):
    path = ROOT / "target" / "criterion" / "csg" / name / "new" / "estimates.json"
    return json.loads(path.read_text())["median"]["point_estimate"] / 1e6


def main():
    if "--no-cargo" not in sys.argv:
        subprocess.run(
            ["cargo", "bench", "-p", "vsg", "--bench", "csg"], cwd=ROOT, check=True
        )
    set_circular_segments(SEGMENTS)
    cases = [
        ("wall minus 100 windows", "wall minus 100 windows", wall_and_windows),
        ("cylinder minus cylinder", "cylinder minus cylinder", ring),
    ]
    print(f"{'case':28} {'boolmesh ms':>12} {'manifold3d ms':>14} {'ratio':>7} {'volume':>10}")
    for label, bench, build in cases:
        peer, volume = timed(build)
        ours = criterion_ms(bench)
        print(f"{label:28} {ours:12.3f} {peer * 1e3:14.3f} {ours / (peer * 1e3):7.2f} {volume:10.4f}")


if __name__ == "__main__":
    main()
