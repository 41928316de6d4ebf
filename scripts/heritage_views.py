#!/usr/bin/env python3
"""Pictures of castellan's heritage files as other tools read them (issue 24, docs/heritage.md).

The CityJSON file is loaded with cjio and drawn by its semantic surfaces (WallSurface,
RoofSurface, Window, ...); the IFC file is loaded with IfcOpenShell, meshed by IfcOpenShell's
own geometry kernel and drawn by entity (IfcWall, IfcRoof, IfcSpace, ...). Nothing of castellan
is used: what is drawn is what those readers make of the files.

    python3 -m venv /tmp/views
    /tmp/views/bin/pip install ifcopenshell==0.9.0.post1 cjio==0.10.1 matplotlib
    castellan demo -o out/demo
    /tmp/views/bin/python scripts/heritage_views.py out/demo docs/heritage
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

SURFACE_COLOURS = {
    "WallSurface": "#c8b9a0",
    "RoofSurface": "#a0453a",
    "GroundSurface": "#6b6b6b",
    "Window": "#3a6ea5",
    "Door": "#6b3e1f",
    "OuterFloorSurface": "#e0d6c0",
    "FloorSurface": "#e0d6c0",
    "OuterCeilingSurface": "#8c7f6a",
    "CeilingSurface": "#8c7f6a",
    "ClosureSurface": "#b0b0b0",
}
ENTITY_COLOURS = {
    "IfcWall": "#c8b9a0",
    "IfcRoof": "#a0453a",
    "IfcSlab": "#e0d6c0",
    "IfcWindow": "#3a6ea5",
    "IfcDoor": "#6b3e1f",
}


def cityjson_polygons(path):
    """(polygon, semantic type) of every surface of the highest LoD of each BuildingPart, from
    the document cjio reads and decompresses (real coordinates)."""
    from cjio import cityjson

    with open(path) as f:
        cm = cityjson.CityJSON(file=f)
    cm.decompress()
    vertices = cm.j["vertices"]
    out = []
    parts = [o for o in cm.j["CityObjects"].values() if o["type"] == "BuildingPart"]
    for co in parts:
        if not co.get("geometry"):
            continue
        geometry = max(co["geometry"], key=lambda g: float(g["lod"]))
        surfaces = geometry["semantics"]["surfaces"]
        values = geometry["semantics"]["values"]
        for solid, solid_values in zip(geometry["boundaries"], values):
            for shell, shell_values in zip(solid, solid_values):
                for surface, value in zip(shell, shell_values):
                    kind = surfaces[value]["type"] if value is not None else "WallSurface"
                    out.append(([tuple(vertices[i]) for i in surface[0]], kind))
    return out, len(parts)


def ifc_triangles(path):
    """(triangle, entity) of every product IfcOpenShell meshes, spaces left out."""
    import ifcopenshell
    import ifcopenshell.geom

    f = ifcopenshell.open(str(path))
    settings = ifcopenshell.geom.settings()
    settings.set("use-world-coords", True)
    out = []
    it = ifcopenshell.geom.iterator(settings, f, include=f.by_type("IfcElement"))
    if it.initialize():
        while True:
            shape = it.get()
            entity = f.by_id(shape.id).is_a()
            v = shape.geometry.verts
            points = [tuple(v[i : i + 3]) for i in range(0, len(v), 3)]
            faces = shape.geometry.faces
            for i in range(0, len(faces), 3):
                out.append(([points[k] for k in faces[i : i + 3]], entity))
            if not it.next():
                break
    counts = {t: len(f.by_type(t)) for t in ["IfcElementAssembly", "IfcWall", "IfcRoof", "IfcSlab", "IfcWindow", "IfcSpace"]}
    return out, counts


def draw(polygons, colours, title, legend, out):
    fig = plt.figure(figsize=(9, 7), dpi=110)
    ax = fig.add_subplot(projection="3d")
    # Painter's order: far first (seen from the south-west, above).
    polygons = sorted(polygons, key=lambda p: sum(x + y for x, y, _ in p[0]) / len(p[0]), reverse=True)
    collection = Poly3DCollection(
        [p for p, _ in polygons],
        facecolors=[colours.get(k, "#999999") for _, k in polygons],
        edgecolors="none",
        linewidths=0,
    )
    ax.add_collection3d(collection)
    xs = [c[0] for p, _ in polygons for c in p]
    ys = [c[1] for p, _ in polygons for c in p]
    zs = [c[2] for p, _ in polygons for c in p]
    span = max(max(xs) - min(xs), max(ys) - min(ys))
    cx, cy = (max(xs) + min(xs)) / 2, (max(ys) + min(ys)) / 2
    ax.set_xlim(cx - span / 2, cx + span / 2)
    ax.set_ylim(cy - span / 2, cy + span / 2)
    ax.set_zlim(min(zs), min(zs) + span * 0.6)
    ax.set_box_aspect((1, 1, 0.6))
    ax.view_init(elev=28, azim=-60)
    ax.set_axis_off()
    ax.set_title(title, fontsize=10)
    ax.legend(handles=[Patch(color=colours[k], label=k) for k in legend], loc="lower left", fontsize=8)
    fig.savefig(out, bbox_inches="tight")
    plt.close(fig)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    src, dst = Path(sys.argv[1]), Path(sys.argv[2])
    dst.mkdir(parents=True, exist_ok=True)
    polygons, parts = cityjson_polygons(src / "model.city.json")
    kinds = sorted({k for _, k in polygons}, key=list(SURFACE_COLOURS).index)
    draw(
        polygons,
        SURFACE_COLOURS,
        f"model.city.json read by cjio: 1 Building, {parts} BuildingParts, {len(polygons)} surfaces by semantic type",
        kinds,
        dst / "cityjson.png",
    )
    triangles, counts = ifc_triangles(src / "model.ifc")
    entities = sorted({k for _, k in triangles}, key=list(ENTITY_COLOURS).index)
    said = ", ".join(f"{n} {t}" for t, n in counts.items())
    draw(
        triangles,
        ENTITY_COLOURS,
        f"model.ifc meshed by IfcOpenShell: {said}",
        entities,
        dst / "ifc.png",
    )
    print(f"wrote {dst / 'cityjson.png'} and {dst / 'ifc.png'}")


if __name__ == "__main__":
    main()
