//! OBJ + MTL tests: one group per visible terminal (§7.1.2) in world coordinates, faces in
//! range, one material per used appearance.

use super::*;

#[test]
fn obj_has_one_group_per_visible_terminal_and_faces_in_range() {
    let (obj, _) = obj_of(&castle());
    assert!(obj.lines().any(|l| l == "mtllib castle.mtl"));
    let groups: Vec<&str> = obj.lines().filter_map(|l| l.strip_prefix("g ")).collect();
    assert_eq!(
        groups,
        [
            "Tower_3", "Gate_4", "Brick_5", "Brick_6", "Brick_7", "Brick_8"
        ]
    );
    let vertices = obj.lines().filter(|l| l.starts_with("v ")).count();
    let normals = obj.lines().filter(|l| l.starts_with("vn ")).count();
    assert_eq!((vertices, normals), (6 * 24, 6 * 24));
    let faces: Vec<&str> = obj.lines().filter(|l| l.starts_with("f ")).collect();
    assert_eq!(faces.len(), 6 * 12);
    for f in faces {
        for corner in f[2..].split(' ') {
            let (v, n) = corner.split_once("//").expect("v//vn");
            let (v, n): (usize, usize) = (v.parse().unwrap(), n.parse().unwrap());
            assert!(
                (1..=vertices).contains(&v) && (1..=normals).contains(&n),
                "{f}"
            );
        }
    }
    let mats: Vec<&str> = obj
        .lines()
        .filter_map(|l| l.strip_prefix("usemtl "))
        .collect();
    let plain = ["appearance_0"; 5];
    assert_eq!(
        mats,
        [&["appearance_1"][..], &plain].concat(),
        "equal appearances share"
    );
}

#[test]
fn obj_vertices_are_in_world_coordinates() {
    let (obj, _) = obj_of(&castle());
    // Brick_5 sits at wall (0, 0, -2.5) + (-1, -1, 0); its box spans ±(0.5, 0.25, 0.5).
    let group = obj.split("g Brick_5\n").nth(1).unwrap();
    let xyz: Vec<[f64; 3]> = group
        .lines()
        .take_while(|l| !l.starts_with("g "))
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let v: Vec<f64> = l.split(' ').map(|c| c.parse().unwrap()).collect();
            [v[0], v[1], v[2]]
        })
        .collect();
    let lo = [0, 1, 2].map(|k| xyz.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min));
    let hi = [0, 1, 2].map(|k| xyz.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max));
    assert_eq!((lo, hi), ([-1.5, -1.25, -3.0], [-0.5, -0.75, -2.0]));
}

#[test]
fn mtl_holds_one_material_per_used_appearance() {
    let (_, mtl) = obj_of(&castle());
    assert_eq!(mtl.matches("newmtl ").count(), 2);
    let glass = mtl.split("newmtl appearance_1\n").nth(1).unwrap();
    let glass = glass.split("newmtl").next().unwrap();
    for line in [
        "Kd 0.9 0.1 0.1",
        "d 0.75",
        "Ke 0 0.5 0",
        "Ns 700",
        "map_Kd bricks.png",
    ] {
        assert!(
            glass.lines().any(|l| l == line),
            "missing {line:?} in\n{glass}"
        );
    }
    let plain = mtl.split("newmtl appearance_0\n").nth(1).unwrap();
    assert!(plain.lines().any(|l| l == "d 1") && !plain.contains("map_Kd"));
    assert!(plain.lines().any(|l| l == "Ka 0.16 0.156 0.144"), "{plain}");
}
