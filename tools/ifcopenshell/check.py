#!/usr/bin/env python3
"""Reads an IFC file with IfcOpenShell and prints a JSON report for castellan's tests
(crates/vsg/tests/ifc.rs):

    tools/ifcopenshell/.venv/bin/python tools/ifcopenshell/check.py FILE [--express]

- "schema": the file's schema as IfcOpenShell reads it;
- "counts": instances by entity type;
- "errors": what ifcopenshell.validate reports (schema: types, cardinalities, inverses,
  enumerations; with --express also the EXPRESS WHERE rules);
- "products": per IfcElement, IfcElementAssembly and IfcSpace: its type, name, the NetVolume
  of its quantity sets (the file's claim) and the volume IfcOpenShell computes from its
  geometry (an assembly: the sum over the elements it aggregates);
- "map": the IfcMapConversion's numbers, if any;
- "duplicate_guids": GlobalIds that more than one IfcRoot instance has.
"""

import collections
import json
import sys

import ifcopenshell
import ifcopenshell.geom
import ifcopenshell.util.element
import ifcopenshell.util.shape
import ifcopenshell.validate


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    if len(args) != 1:
        sys.exit("usage: check.py FILE [--express]")
    f = ifcopenshell.open(args[0])
    logger = ifcopenshell.validate.json_logger()
    ifcopenshell.validate.validate(f, logger, express_rules="--express" in sys.argv)
    counts = collections.Counter(e.is_a() for e in f)

    settings = ifcopenshell.geom.settings()
    geometric = {}
    for e in f.by_type("IfcProduct"):
        if e.Representation is None or not (e.is_a("IfcSpace") or e.is_a("IfcElement")):
            continue
        shape = ifcopenshell.geom.create_shape(settings, e)
        geometric[e.id()] = ifcopenshell.util.shape.get_volume(shape.geometry)

    products = []
    for e in f.by_type("IfcElement") + f.by_type("IfcSpace"):
        quantities = ifcopenshell.util.element.get_psets(e, qtos_only=True)
        claimed = {k: v for q in quantities.values() for k, v in q.items() if k != "id"}
        if e.is_a("IfcElementAssembly"):
            parts = ifcopenshell.util.element.get_decomposition(e)
            volume = sum(geometric.get(p.id(), 0.0) for p in parts)
        else:
            volume = geometric.get(e.id())
        products.append(
            {
                "type": e.is_a(),
                "name": e.Name,
                "guid": e.GlobalId,
                "net_volume": claimed.get("NetVolume"),
                "net_weight": claimed.get("NetWeight"),
                "geometry_volume": volume,
                "psets": {
                    k: {p: v for p, v in ps.items() if p != "id"}
                    for k, ps in ifcopenshell.util.element.get_psets(e, psets_only=True).items()
                },
            }
        )

    guids = collections.Counter(e.GlobalId for e in f.by_type("IfcRoot"))
    duplicates = sorted(g for g, n in guids.items() if n > 1)

    conversion = None
    for m in f.by_type("IfcMapConversion"):
        conversion = {
            "crs": m.TargetCRS.Name,
            "eastings": m.Eastings,
            "northings": m.Northings,
            "height": m.OrthogonalHeight,
            "x_axis": [m.XAxisAbscissa, m.XAxisOrdinate],
            "scale": m.Scale,
        }

    print(
        json.dumps(
            {
                "schema": f.schema,
                "counts": dict(sorted(counts.items())),
                "errors": [str(s) for s in logger.statements],
                "products": products,
                "map": conversion,
                "duplicate_guids": duplicates,
            },
            indent=1,
            default=str,
        )
    )


if __name__ == "__main__":
    main()
