#!/usr/bin/env python3
"""Window/door recall and precision of `castellan gothic` against the boxes of CMP Facade DB
(XML) and Paris Art-deco (per-pixel label matrices), by bounding-box IoU >= 0.5.

usage: gothic_eval.py cmp|paris GT_DIR OUT_DIR   (OUT_DIR holds <name>.json from castellan gothic)
Pure Python, no third-party modules.
"""
import json, os, re, sys


def cmp_boxes(xml_path, w, h):
    text = open(xml_path).read()
    boxes = []
    for obj in re.findall(r"<object>(.*?)</object>", text, re.S):
        name = re.search(r"<labelname>\s*(.*?)\s*</labelname>", obj, re.S)
        if name is None or name.group(1) not in ("window", "door"):
            continue
        xs = [float(v) for v in re.findall(r"<x>\s*(.*?)\s*</x>", obj, re.S)]
        ys = [float(v) for v in re.findall(r"<y>\s*(.*?)\s*</y>", obj, re.S)]
        if not xs or not ys:
            continue
        boxes.append((min(xs) * w, min(ys) * h, max(xs) * w, max(ys) * h))
    return boxes


def paris_boxes(txt_path):
    rows = [list(map(int, line.split())) for line in open(txt_path) if line.strip()]
    h, w = len(rows), len(rows[0])
    seen = [[False] * w for _ in range(h)]
    boxes = []
    for y in range(h):
        for x in range(w):
            if seen[y][x] or rows[y][x] not in (0, 3):  # door, window
                continue
            label, stack = rows[y][x], [(x, y)]
            seen[y][x] = True
            x0, y0, x1, y1, n = x, y, x, y, 0
            while stack:
                cx, cy = stack.pop()
                n += 1
                x0, y0, x1, y1 = min(x0, cx), min(y0, cy), max(x1, cx), max(y1, cy)
                for nx, ny in ((cx + 1, cy), (cx - 1, cy), (cx, cy + 1), (cx, cy - 1)):
                    if 0 <= nx < w and 0 <= ny < h and not seen[ny][nx] and rows[ny][nx] == label:
                        seen[ny][nx] = True
                        stack.append((nx, ny))
            if n >= 50:
                boxes.append((x0, y0, x1 + 1, y1 + 1))
    return boxes


def iou(a, b):
    iw = max(0.0, min(a[2], b[2]) - max(a[0], b[0]))
    ih = max(0.0, min(a[3], b[3]) - max(a[1], b[1]))
    inter = iw * ih
    union = (a[2] - a[0]) * (a[3] - a[1]) + (b[2] - b[0]) * (b[3] - b[1]) - inter
    return inter / union if union > 0 else 0.0


def main():
    kind, gt_dir, out_dir = sys.argv[1:4]
    tot_gt = tot_hit = tot_el = tot_good = 0
    for f in sorted(os.listdir(out_dir)):
        if not f.endswith(".json"):
            continue
        name = f[:-5]
        doc = json.load(open(os.path.join(out_dir, f)))
        els = [(e["x0"], e["y0"] - e["h"] - e["v"], e["x0"] + e["w"], e["y0"]) for e in doc["elements"]]
        if kind == "cmp":
            gt = cmp_boxes(os.path.join(gt_dir, name + ".xml"), doc["width"], doc["height"])
        else:
            gt = paris_boxes(os.path.join(gt_dir, name + ".txt"))
        hit = sum(any(iou(g, e) >= 0.5 for e in els) for g in gt)
        good = sum(any(iou(g, e) >= 0.5 for g in gt) for e in els)
        tot_gt, tot_hit, tot_el, tot_good = tot_gt + len(gt), tot_hit + hit, tot_el + len(els), tot_good + good
        print(f"{name}: {len(gt)} windows/doors, {hit} found; {len(els)} elements, {good} on a window/door")
    print(f"TOTAL: recall {tot_hit}/{tot_gt} = {tot_hit / max(tot_gt, 1):.3f}, "
          f"precision {tot_good}/{tot_el} = {tot_good / max(tot_el, 1):.3f}")


if __name__ == "__main__":
    main()
