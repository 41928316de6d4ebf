#!/usr/bin/env python3
"""Regenerates docs/gallery/ and docs/gallery.md: castellan on 20 real castle plans and 10 real
elevations from ../shared/data/castle_drawings_pd (public domain; attribution in the page).

    cargo build --release -p castellan && python3 scripts/gallery.py

Every drawing goes through the same commands a user would run (`castellan plan`,
`castellan reconstruct`, `castellan facade`, `castellan gothic`); failures are recorded and
shown with their message, never skipped. Only the standard library is needed.
"""

import json
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DATA = ROOT.parent / "shared" / "data" / "castle_drawings_pd"
OUT = ROOT / "docs" / "gallery"
PAGE = ROOT / "docs" / "gallery.md"
BIN = ROOT / "target" / "release" / "castellan"
DEVSET = ROOT / "crates" / "plan" / "tests" / "data" / "devset.json"

# 21 plans: whole castles of every kind in the collection (Viollet-le-Duc's engravings,
# Lefèvre-Pontalis's and Armitage's plans, Loftie's Tower of London), keeps, a town gate,
# and drawings known to be hard (grey washes, earthworks, hatching). Metres per pixel where
# the scale bar was read by hand. A third element would turn on plan options a user would
# choose for that drawing, both for `castellan plan` and in the project `castellan
# reconstruct` reads (Loftie's White Tower needed `--hatching` until the learned wall ink).
PLANS = [
    ("plans/vld3_coucy_plan_112.png", 0.32),
    ("plans/vld3_pierrefonds_plan_154.png", None),
    ("plans/vld3_sully-sur-loire_plan_164.png", None),
    ("plans/vld3_arques_plan_075.png", None),
    ("plans/vld3_chateau-gaillard_plan_090.png", None),
    ("plans/vld1_vincennes_plan_286.png", None),
    ("plans/vld3_villandraut_plan_143.png", None),
    ("plans/vld3_bonaguil_plan_168.png", None),
    ("plans/vld2_paris-bastille_plan_175.png", None),
    ("plans/vld3_paris-louvre_plan_139.png", None),
    ("plans/vld6_xaintrailles_plan_315.png", None),
    ("plans/vld6_saint-medard-en-jalle_plan_309.png", None),
    ("plans/vld3_chambord_plan_188.png", None),
    ("plans/vld7_carcassonne-porte-narbonnaise_plan_340.png", None),
    ("plans/vld5_arques-donjon_plan_040.png", None),
    ("plans/lefevre_coucy_plan_illus_005.jpg", None),
    ("plans/armitage_pevensey_plan_fig24c.png", None),
    ("plans/armitage_old-sarum_plan_fig30.png", None),
    ("plans/loftie_tower-of-london_plan_plan-01.png", None),
    ("plans/vldannals_roche-pont_plan_fig45.jpg", None),
    ("plans/loftie_tower-of-london-white-tower_plan_plan-02.png", None),
]

# 10 orthographic elevations. `bbox` outlines the façade to parse, `training` holds the boxes
# a user would draw (elevation pixels), `scale` is metres per pixel from the drawing's own bar.
# `model` reconstructs the elevation with its paired plan when one plan shape is the building
# the elevation shows; `no_model` says why not otherwise.
ELEVATIONS = [
    {
        "file": "elevations/vld9_coucy-tour-angle_elevation_088.png",
        "bbox": [60, 195, 172, 478],
        "scale": 0.126,
        "training": {
            "window": [[112, 160, 118, 176], [137, 160, 142, 172], [87, 338, 90, 356]],
            "wall": [[95, 240, 130, 280], [100, 400, 140, 440], [70, 300, 85, 340]],
            "background": [[180, 100, 220, 140], [5, 150, 30, 240]],
        },
        "model": {
            "plan": "plans/vld3_coucy_plan_112.png",
            "plan_scale": 0.32,
            "facade_point": [116, 330],
            "plan_point": [392, 462],
        },
    },
    {
        "file": "elevations/vld5_arques-donjon_elevation_046.png",
        "bbox": [80, 215, 330, 505],
        "scale": 0.0957,
        "training": {
            "window": [[132, 336, 149, 360], [217, 338, 231, 361], [133, 401, 147, 419]],
            "wall": [[80, 290, 110, 320], [250, 430, 280, 460], [160, 250, 200, 275]],
            "background": [[20, 60, 60, 120], [335, 60, 365, 110], [20, 520, 110, 545]],
        },
        "model": {
            "plan": "plans/vld5_arques-donjon_plan_040.png",
            "plan_scale": 0.0913,
            "facade_point": [205, 400],
            "plan_point": [280, 398],
        },
    },
    {
        "file": "elevations/vld5_chambois-donjon_elevation_052.png",
        "bbox": [50, 270, 192, 500],
        "scale": None,
        "training": {
            "window": [[98, 318, 108, 335], [150, 322, 160, 335], [96, 395, 107, 412]],
            "wall": [[60, 350, 90, 380], [165, 440, 185, 470], [118, 300, 140, 318]],
            "background": [[200, 60, 250, 100], [5, 100, 30, 180]],
        },
        "model": {
            "plan": "plans/vld5_chambois-donjon_plan_051.png",
            "plan_scale": None,
            "facade_point": [120, 420],
            "plan_point": [130, 186],
        },
    },
    {
        "file": "elevations/vld7_poitiers-palais_elevation_015.png",
        "bbox": [45, 215, 315, 520],
        "scale": None,
        "training": {
            "window": [[105, 395, 118, 440], [245, 395, 258, 440], [60, 225, 75, 235]],
            "wall": [[60, 470, 100, 510], [270, 460, 300, 500], [180, 470, 220, 510]],
            "background": [[5, 30, 40, 120], [320, 30, 360, 120]],
        },
        "model": {
            "plan": "plans/vld7_poitiers-palais_plan_013.png",
            "plan_scale": None,
            "facade_point": [180, 400],
            "plan_point": [140, 440],
        },
    },
    {
        "file": "elevations/vld9_vincennes-tour-angle_elevation_111.png",
        "bbox": [150, 120, 305, 525],
        "scale": None,
        "training": {
            "window": [[247, 185, 260, 225], [248, 280, 260, 320], [248, 375, 260, 410]],
            "wall": [[165, 240, 200, 270], [270, 430, 295, 470], [200, 350, 235, 380]],
            "background": [[5, 120, 45, 280], [320, 140, 360, 300]],
        },
        "no_model": "the plan (vld9_vincennes-tour-angle_plan_110) draws the tower twice, as a "
        "roof plan and as a section; the parser finds walls but no tower",
    },
    {
        "file": "elevations/vld7_saint-jean-au-bois-porte_elevation_388_crop.png",
        "bbox": [75, 30, 260, 215],
        "scale": None,
        "training": {
            "window": [[150, 130, 185, 180]],
            "wall": [[85, 100, 120, 130], [210, 100, 245, 130], [100, 185, 140, 210]],
            "background": [[5, 5, 60, 50], [270, 5, 330, 40]],
        },
        "no_model": "the gate's plan (vld7_saint-jean-au-bois-porte_plan_388_crop) is hatched on "
        "one side and the parser finds no closed room for the gate",
    },
    {
        "file": "elevations/vld7_saint-leu-d-esserent-porte_elevation_386_crop.png",
        "bbox": [15, 80, 385, 355],
        "scale": None,
        "training": {
            "window": [[120, 250, 200, 340], [250, 270, 290, 340]],
            "wall": [[50, 110, 90, 140], [320, 240, 350, 290], [150, 150, 200, 180]],
            "background": [[20, 5, 90, 60], [200, 5, 280, 40]],
        },
        "no_model": "the plan (vld7_saint-leu-d-esserent-porte_plan_386_crop) encloses no open "
        "space (§5.2 item 4)",
    },
    {
        "file": "elevations/vld5_rouen-donjon_elevation_075.png",
        "bbox": [28, 260, 160, 530],
        "scale": None,
        "training": {
            "window": [[132, 370, 138, 392], [128, 455, 140, 470], [82, 460, 95, 500]],
            "wall": [[100, 280, 140, 320], [105, 400, 130, 440], [50, 420, 75, 450]],
            "background": [[180, 250, 200, 380], [5, 60, 40, 200]],
        },
        "model": {
            "plan": "plans/vld5_rouen-donjon_plan_074.png",
            "plan_scale": None,
            "facade_point": [95, 400],
            "plan_point": [395, 35],
        },
    },
    {
        "file": "elevations/vld7_carcassonne-porte-narbonnaise_elevation_345.png",
        "bbox": [75, 205, 395, 460],
        "scale": None,
        "training": {
            "window": [[95, 215, 105, 228], [210, 215, 222, 228], [305, 215, 320, 228]],
            "wall": [[100, 330, 140, 370], [330, 350, 370, 390], [150, 260, 190, 290]],
            "background": [[5, 60, 60, 200], [390, 30, 440, 120]],
        },
        "no_model": "the façade spans two towers and the gate between them; no one plan shape "
        "(vld7_carcassonne-porte-narbonnaise_plan_340) is that front",
    },
    {
        "file": "elevations/vld5_pierrefonds-donjon_elevation_093.png",
        "bbox": [150, 210, 350, 400],
        "scale": None,
        "training": {
            "window": [[225, 225, 240, 240], [290, 210, 305, 225]],
            "wall": [[170, 300, 200, 340], [280, 300, 320, 340], [60, 260, 90, 300]],
            "background": [[5, 30, 45, 150], [370, 40, 405, 110]],
        },
        "no_model": "the elevation shows the donjon with its towers in perspective-like depth "
        "and the plan (vld5_pierrefonds-donjon_plan_088) parses the towers but not the donjon "
        "block as one shape",
    },
]


def run(args, cwd=None):
    """Runs castellan; returns (ok, seconds, the last line of stderr)."""
    ok, secs, msg, _ = run_warned(args, cwd)
    return ok, secs, msg


def run_warned(args, cwd=None):
    """`run`, and what the command warned of (the text after each `warning: `)."""
    t0 = time.perf_counter()
    p = subprocess.run([str(BIN), *map(str, args)], cwd=cwd, capture_output=True, text=True)
    lines = [l for l in p.stderr.splitlines() if l.strip() and not l.lstrip().startswith("[")]
    warned = [l.split("warning: ", 1)[1] for l in lines if "warning: " in l]
    return p.returncode == 0, time.perf_counter() - t0, (lines[-1] if lines else ""), warned


def devset_towers():
    if not DEVSET.is_file():
        return {}
    plans = json.loads(DEVSET.read_text())["plans"]
    return {p["file"]: p.get("towers") for p in plans}


def manifest():
    return {m["file"]: m for m in json.loads((DATA / "manifest.json").read_text())}


def write_project(folder, plan, plan_scale, facade=None, options=()):
    lines = [f'plan = "{plan}"']
    if plan_scale:
        lines.append(f"scale = {plan_scale}")
    lines += [f"{o} = true" for o in options]
    lines.append("seed = 7")
    if facade:
        e, m = facade
        boxes = {k: v for k, v in e["training"].items() if k != "background"}
        cls = ", ".join(f"{k} = {json.dumps(v)}" for k, v in boxes.items())
        lines += ["", "[[facade]]", 'image = "elevation.png"', "rectified = true",
                  f"bbox = {json.dumps(e['bbox'])}"]
        if e["scale"]:
            lines.append(f"scale = {e['scale']}")
        lines += [f"training = {{ classes = {{ {cls} }} }}", "", "[[correspondence]]",
                  'facade = "elevation.png"', f"facade_point = {json.dumps(m['facade_point'])}",
                  f"plan_points = [{json.dumps(m['plan_point'])}]"]
    (folder / "PROJECT.toml").write_text("\n".join(lines) + "\n")


def project_with_plan(tmp, stem, plan_src):
    """A fresh project folder for `stem` holding a copy of the plan; returns it and the plan's name."""
    proj = tmp / f"{stem}-project"
    proj.mkdir()
    plan = "plan" + plan_src.suffix
    shutil.copy(plan_src, proj / plan)
    return proj, plan


def reconstruct(proj, dst, row):
    """`castellan reconstruct` on the project; the rendered model goes to dst/model.png and the
    outcome into row. Returns the output folder, or None when it failed."""
    ok, _, msg = run(["reconstruct", proj / "PROJECT.toml", "-o", proj / "out"])
    row["model_ok"], row["model_msg"] = ok, msg
    if not ok:
        return None
    shutil.copy(proj / "out" / "preview.png", dst / "model.png")
    return proj / "out"


def gallery_plan(path, scale, options, info, towers_drawn, tmp):
    stem = Path(path).stem
    dst = OUT / "plans" / stem
    dst.mkdir(parents=True, exist_ok=True)
    src = DATA / path
    shutil.copy(src, dst / ("input" + src.suffix))
    ok, secs, msg = run(["plan", src, "-o", tmp / f"{stem}.json", "--overlay",
                         dst / "labels.png", "--walls", dst / "ink.png", "--svg", dst / "walls.svg",
                         *[f"--{o}" for o in options]])
    row = {"stem": stem, "input": "input" + src.suffix, "ok": ok, "secs": secs, "msg": msg,
           "options": [f"--{o}" for o in options],
           "castle": info.get("castle", stem), "book": info.get("book", ""),
           "author": info.get("author", ""), "towers_drawn": towers_drawn}
    if ok:
        plan = json.loads((tmp / f"{stem}.json").read_text())
        row.update(faces=len(plan["faces"]), towers=plan["towers"],
                   warnings=plan.get("warnings", []), scale_bar=plan.get("scale_bar"))
        proj, plan_name = project_with_plan(tmp, stem, src)
        write_project(proj, plan_name, scale, options=options)
        out = reconstruct(proj, dst, row)
        if out:
            row["terminals"] = json.loads((out / "stats.json").read_text()).get("terminals")
    return row


def gallery_elevation(e, info, tmp):
    src = DATA / e["file"]
    stem = src.stem
    dst = OUT / "elevations" / stem
    dst.mkdir(parents=True, exist_ok=True)
    shutil.copy(src, dst / ("input" + src.suffix))
    training = tmp / f"{stem}.training.json"
    training.write_text(json.dumps({"classes": e["training"]}))
    row = {"stem": stem, "input": "input" + src.suffix, "castle": info.get("castle", stem),
           "book": info.get("book", ""), "author": info.get("author", "")}
    # The default classifier (filter bank + random forest) and the text's GMM (§3.1.3–3.1.4),
    # each with its probability map before the search, so the two can be judged side by side.
    for classifier, suffix in (("forest", ""), ("gmm", "_gmm")):
        ok, secs, msg, warned = run_warned(
            ["facade", src, "--training", training, "-o", tmp / f"{stem}{suffix}.facade.json",
             "--classifier", classifier, "--overlay", dst / f"facade{suffix}.png",
             "--probabilities", dst / f"pixels{suffix}.png"])
        row.update({f"facade{suffix}_ok": ok, f"facade{suffix}_secs": secs,
                    f"facade{suffix}_msg": msg, f"facade{suffix}_warnings": warned})
        if ok:
            f = json.loads((tmp / f"{stem}{suffix}.facade.json").read_text())
            row[f"facades{suffix}"] = len(f["facades"])
            row[f"floors{suffix}"] = sum(len(x["floors"]) for x in f["facades"])
            row[f"windows{suffix}"] = sum(len(fl["windows"]) for x in f["facades"]
                                          for fl in x["floors"])
    ok, secs, msg = run(["gothic", src, "-o", tmp / f"{stem}.gothic.json", "--overlay",
                         dst / "gothic.png", "--masonry", tmp / f"{stem}.masonry.png"])
    row.update(gothic_ok=ok, gothic_secs=secs, gothic_msg=msg)
    if ok:
        g = json.loads((tmp / f"{stem}.gothic.json").read_text())
        row["elements"] = len(g.get("elements", []))
        row["groups"] = len(g.get("groups", []))
    m = e.get("model")
    if m:
        proj, plan_name = project_with_plan(tmp, stem, DATA / m["plan"])
        shutil.copy(src, proj / "elevation.png")
        write_project(proj, plan_name, m["plan_scale"], (e, m))
        out = reconstruct(proj, dst, row)
        if out:
            shutil.copy(out / "overlays" / "elevation_facade.png", dst / "facade_in_outline.png")
            est = json.loads((out / "estimate.json").read_text())
            mapped = [s for s in est["structures"] if s["facades"]]
            if mapped:
                s = mapped[0]
                row["mapped"] = f"{s['id']} ({s['label']}), height {s['height']:.1f} {est['units']}"
    else:
        row["model_ok"], row["model_msg"] = False, e["no_model"]
    return row


def page(plans, elevations, elapsed):
    out = ["# Gallery: castellan on real castle drawings", "",
           "Regenerated by `python3 scripts/gallery.py` (after `cargo build --release -p castellan`)",
           f"from `../shared/data/castle_drawings_pd/`: {len(plans)} plans and {len(elevations)} elevations, every one through",
           "the same commands a user runs. Failures are listed with castellan's own message.",
           f"The whole run took {elapsed:.0f} s on the development machine.", "",
           "All drawings are in the public domain (authors died more than 70 years ago; scans",
           "from Project Gutenberg editions mirrored by GITenberg, and from archive.org); each row",
           "names its book and author.", "", "## Plans", "",
           "Each plan: the input, the walls as read (`castellan plan --walls`: red wall over the",
           "drawing in grey; the learned wall ink, issue 26), `castellan plan --overlay` (colours by label, key in",
           "[formats.md](formats.md#pictures-and-their-keys); a scale bar found on the sheet is framed in magenta — whether it",
           "is the bar is for the reader to judge), the vectorised walls (`--svg`), and the model `castellan reconstruct`",
           "builds from the plan alone (class heights of §5.3; library towers, keep and walls).", "",
           "| drawing | result | input | walls read | labels | walls (SVG) | model |",
           "| --- | --- | --- | --- | --- | --- | --- |"]
    for r in plans:
        d = f"gallery/plans/{r['stem']}"
        who = f"**{r['castle']}**<br>{r['author']}, *{r['book']}*<br>`{r['stem']}`"
        if r["ok"]:
            drawn = r["towers_drawn"]
            towers = f"{r['towers']} towers" + (f" (drawn: {drawn})" if drawn is not None else "")
            res = f"{r['faces']} faces, {towers}, {r['secs']:.1f} s"
            if r.get("options"):
                res += "<br>run with " + " ".join(f"`{o}`" for o in r["options"])
            bar = r.get("scale_bar")
            res += (f"<br>scale bar found: {bar['length_px']} px at ({bar['x0']}, {bar['y0']}), "
                    "framed in magenta") if bar else "<br>no scale bar found"
            if r["warnings"]:
                res += "<br>⚠ " + "<br>⚠ ".join(r["warnings"])
            if not r.get("model_ok"):
                res += f"<br>model failed: {r.get('model_msg', '')}"
        else:
            res = f"**failed**: {r['msg']}"
        img = lambda n: f"![]({d}/{n})" if (OUT / "plans" / r["stem"] / n).is_file() else "—"
        out.append(f"| {who} | {res} | {img(r['input'])} | {img('ink.png')} | {img('labels.png')} | "
                   f"{img('walls.svg')} | {img('model.png')} |")
    out += ["", "## Elevations", "",
            "Each orthographic elevation through the rectangular façade stage (`castellan facade`",
            "with the training boxes in scripts/gallery.py; windows green, wall magenta,",
            "background red, floors and façades outlined): first the pixel classifier's class",
            "probabilities (`--probabilities`, blended where unsure), then the façade tree — with",
            "the default classifier (filter bank + random forest, issue 21) and with the",
            "dissertation's GMM (`--classifier gmm`, §3.1.3–3.1.4) —",
            "and the Gothic stage (`castellan gothic`: arches and rectangles,",
            "groups, nesting). Where one plan shape is the building drawn, the elevation is",
            "reconstructed with its paired plan (`[[facade]]` with the façade's outline `bbox`;",
            "the model cell also shows the façade search inside that outline);",
            "otherwise the row says why not.", "",
            "| drawing | façade stage | Gothic stage | input | probabilities (forest) | façade (forest) | "
            "probabilities (GMM) | façade (GMM) | Gothic | model |",
            "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in elevations:
        d = f"gallery/elevations/{r['stem']}"
        who = f"**{r['castle']}**<br>{r['author']}, *{r['book']}*<br>`{r['stem']}`"
        def fac_cell(suffix, name):
            if not r[f"facade{suffix}_ok"]:
                return f"{name}: **failed**: {r[f'facade{suffix}_msg']}"
            # What `castellan facade` doubts in its model (facade::plausibility, issue 21).
            warned = "".join(f"<br>⚠ {w}" for w in r.get(f"facade{suffix}_warnings", []))
            return (f"{name}: {r[f'facades{suffix}']} façades, {r[f'floors{suffix}']} floors, "
                    f"{r[f'windows{suffix}']} windows, {r[f'facade{suffix}_secs']:.1f} s{warned}")
        fac = fac_cell("", "forest") + "<br>" + fac_cell("_gmm", "GMM")
        got = (f"{r['elements']} elements, {r['groups']} groups, {r['gothic_secs']:.1f} s"
               if r["gothic_ok"] else f"**failed**: {r['gothic_msg']}")
        img = lambda n: f"![]({d}/{n})" if (OUT / "elevations" / r["stem"] / n).is_file() else "—"
        model = (f"{img('model.png')}<br>{r.get('mapped', '')}<br>façade search inside the outline:"
                 f"<br>{img('facade_in_outline.png')}" if r.get("model_ok")
                 else f"no model: {r.get('model_msg', '')}")
        out.append(f"| {who} | {fac} | {got} | {img(r['input'])} | {img('pixels.png')} | "
                   f"{img('facade.png')} | {img('pixels_gmm.png')} | {img('facade_gmm.png')} | "
                   f"{img('gothic.png')} | {model} |")
    return "\n".join(out) + "\n"


def main():
    if not DATA.is_dir():
        sys.exit(f"{DATA} is missing: the gallery is built from the shared castle drawings")
    if not BIN.is_file():
        sys.exit(f"{BIN} is missing: run `cargo build --release -p castellan` first")
    t0 = time.perf_counter()
    shutil.rmtree(OUT, ignore_errors=True)
    info = manifest()
    drawn = devset_towers()
    with tempfile.TemporaryDirectory() as t:
        tmp = Path(t)
        plans = []
        for i, (path, scale, *options) in enumerate(PLANS):
            print(f"[{i + 1}/{len(PLANS)}] {path}", file=sys.stderr)
            options = options[0] if options else []
            plans.append(gallery_plan(path, scale, options, info.get(path, {}),
                                      drawn.get(path), tmp))
        elevations = []
        for i, e in enumerate(ELEVATIONS):
            print(f"[{i + 1}/{len(ELEVATIONS)}] {e['file']}", file=sys.stderr)
            elevations.append(gallery_elevation(e, info.get(e["file"], {}), tmp))
    extra = (ROOT / "docs" / "gallery-notes.md")
    text = page(plans, elevations, time.perf_counter() - t0)
    if extra.is_file():
        text += "\n" + extra.read_text()
    PAGE.write_text(text)
    (OUT / "summary.json").write_text(json.dumps({"plans": plans, "elevations": elevations},
                                                 indent=1, default=str))
    print(f"wrote {PAGE} and {OUT}", file=sys.stderr)


if __name__ == "__main__":
    main()
