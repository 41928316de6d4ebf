//! The real development set (issue 23): `data/gothic_devset/annotations.json` is well formed,
//! and the metrics of `examples/gothic_devset.rs` (IoU matching, recall/precision, nesting)
//! give known answers. No estimation runs here: the evaluation itself is the example.

#[path = "../examples/gothic_devset.rs"]
#[allow(dead_code)]
mod devset;

use devset::{GtElement, HeadKind, ImageKind, Predicted, Role, iou, match_greedy, score};

const OPENING: Role = Role::Opening;
const ENCLOSING: Role = Role::Enclosing;

fn gt(bbox: [f64; 4], role: Role, parent: Option<usize>, difficult: bool) -> GtElement {
    GtElement {
        bbox,
        kind: HeadKind::Round,
        role,
        parent,
        difficult,
    }
}

fn pred(bbox: [f64; 4], parent: Option<usize>) -> Predicted {
    Predicted { bbox, parent }
}

#[test]
fn annotations_are_well_formed() {
    let path = devset::annotations_path();
    let ann = devset::read_annotations(&path).unwrap();
    let elevations = ann
        .iter()
        .filter(|a| a.kind == ImageKind::Elevation)
        .count();
    let photos = ann.iter().filter(|a| a.kind == ImageKind::Photo).count();
    assert!(elevations >= 10, "{elevations} elevations, need ≥ 10");
    assert!(photos >= 10, "{photos} photos, need ≥ 10");
    assert_eq!(elevations + photos, ann.len(), "kind is elevation or photo");
    let mut files = std::collections::HashSet::new();
    for a in &ann {
        let f = &a.file;
        assert!(files.insert(f.clone()), "{f} annotated twice");
        assert!(
            f.starts_with("elevations/"),
            "{f}: relative to castle_drawings_pd"
        );
        assert_eq!(
            a.kind == ImageKind::Photo,
            f.contains("_photo_"),
            "{f}: kind {:?}",
            a.kind
        );
        assert!(
            !a.book.is_empty() && !a.author.is_empty() && !a.source.is_empty(),
            "{f}"
        );
        assert!(
            a.elements.iter().any(|e| !e.difficult),
            "{f}: no element that counts"
        );
        for (i, e) in a.elements.iter().enumerate() {
            let [x0, y0, x1, y1] = e.bbox;
            assert!(
                0.0 <= x0 && x0 < x1 && x1 <= a.width as f64,
                "{f} #{i}: x {x0}..{x1} outside 0..{}",
                a.width
            );
            assert!(
                0.0 <= y0 && y0 < y1 && y1 <= a.height as f64,
                "{f} #{i}: y {y0}..{y1} outside 0..{}",
                a.height
            );
            if let Some(p) = e.parent {
                assert!(p < a.elements.len() && p != i, "{f} #{i}: parent {p}");
                let q = &a.elements[p];
                assert_eq!(
                    q.role,
                    Role::Enclosing,
                    "{f} #{i}: parent {p} is not enclosing"
                );
                let b = q.bbox;
                assert!(
                    b[0] <= x0 && b[1] <= y0 && x1 <= b[2] && y1 <= b[3],
                    "{f} #{i}: {:?} not inside its parent {p} {:?}",
                    e.bbox,
                    b
                );
            }
        }
    }
    // Image sizes against the real files, when they are here.
    let root = devset::images_root();
    if !root.is_dir() {
        eprintln!(
            "gothic_devset: {} is absent; image sizes not checked against the files",
            root.display()
        );
        return;
    }
    for a in &ann {
        let path = root.join(&a.file);
        let (w, h) =
            image::image_dimensions(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert_eq!((w, h), (a.width, a.height), "{}", a.file);
    }
}

#[test]
fn iou_known_values() {
    let a = [0.0, 0.0, 10.0, 10.0];
    assert_eq!(iou(a, a), 1.0);
    assert_eq!(iou(a, [10.0, 0.0, 20.0, 10.0]), 0.0); // touching
    assert_eq!(iou(a, [20.0, 20.0, 30.0, 30.0]), 0.0);
    // Half overlap: 50 / 150.
    assert!((iou(a, [5.0, 0.0, 15.0, 10.0]) - 1.0 / 3.0).abs() < 1e-12);
    // Contained: 25 / 100.
    assert!((iou(a, [0.0, 0.0, 5.0, 5.0]) - 0.25).abs() < 1e-12);
    // Symmetric.
    let b = [2.0, 3.0, 12.0, 9.0];
    assert_eq!(iou(a, b), iou(b, a));
}

#[test]
fn matching_is_greedy_one_to_one() {
    let g = [
        ([0.0, 0.0, 10.0, 10.0], false),
        ([1.0, 0.0, 11.0, 10.0], false),
    ];
    // p0 overlaps g0 at 0.9 and g1 at 81/109; p1 overlaps g1 at 1.0 and g0 at 90/110.
    let p = [[0.0, 0.0, 10.0, 9.0], [1.0, 0.0, 11.0, 10.0]];
    assert_eq!(match_greedy(&g, &p), vec![Some(0), Some(1)]);
    // Two predictions on one box: the better one matches, the other is a false positive.
    let g = [([0.0, 0.0, 10.0, 10.0], false)];
    let p = [[0.0, 0.0, 10.0, 8.0], [0.0, 0.0, 10.0, 9.5]];
    assert_eq!(match_greedy(&g, &p), vec![None, Some(0)]);
    // Below the threshold: no match (IoU 1/3).
    let p = [[5.0, 0.0, 15.0, 10.0]];
    assert_eq!(match_greedy(&g, &p), vec![None]);
    // Exactly 0.5 matches (IoU 50/100).
    let p = [[0.0, 0.0, 10.0, 5.0]];
    assert_eq!(match_greedy(&g, &p), vec![Some(0)]);
}

#[test]
fn difficult_boxes_do_not_take_predictions_from_boxes_that_count() {
    // The prediction overlaps the difficult box better (1.0) than the counted one (0.9): the
    // counted one still gets it.
    let g = [
        ([0.0, 0.0, 10.0, 9.0], false),
        ([0.0, 0.0, 10.0, 10.0], true),
    ];
    let p = [[0.0, 0.0, 10.0, 10.0]];
    assert_eq!(match_greedy(&g, &p), vec![Some(0)]);
    // A second prediction then goes to the difficult box.
    let p = [[0.0, 0.0, 10.0, 10.0], [0.0, 0.0, 10.0, 10.0]];
    assert_eq!(match_greedy(&g, &p), vec![Some(0), Some(1)]);
}

#[test]
fn recall_precision_known_answer() {
    // 3 counted boxes and 1 difficult one; 4 predictions: 2 on counted boxes, 1 on the
    // difficult box, 1 on nothing.
    let g = vec![
        gt([0.0, 0.0, 10.0, 10.0], OPENING, None, false),
        gt([20.0, 0.0, 30.0, 10.0], OPENING, None, false),
        gt([40.0, 0.0, 50.0, 10.0], OPENING, None, false),
        gt([60.0, 0.0, 70.0, 10.0], OPENING, None, true),
    ];
    let p = vec![
        pred([0.0, 0.0, 10.0, 10.0], None),
        pred([21.0, 0.0, 31.0, 10.0], None),
        pred([60.0, 0.0, 70.0, 10.0], None),
        pred([100.0, 0.0, 110.0, 10.0], None),
    ];
    let s = score(&g, &p);
    assert_eq!((s.gt, s.pred, s.pred_on_difficult, s.matched), (3, 4, 1, 2));
    // The third counted box meets no prediction; the first two are overlapped.
    assert_eq!(s.untouched, 1);
    assert!((s.recall().unwrap() - 2.0 / 3.0).abs() < 1e-12);
    assert!((s.precision().unwrap() - 2.0 / 3.0).abs() < 1e-12);
    assert_eq!(s.nesting(), None);
    // Nothing predicted: recall 0, precision undefined.
    let s = score(&g, &[]);
    assert_eq!((s.recall(), s.untouched), (Some(0.0), 3));
    assert_eq!(s.precision(), None);
}

#[test]
fn nesting_known_answer() {
    // Two bays: arch 0 with windows 1, 2; arch 3 with window 4.
    let g = vec![
        gt([0.0, 0.0, 40.0, 40.0], ENCLOSING, None, false),
        gt([5.0, 10.0, 15.0, 35.0], OPENING, Some(0), false),
        gt([25.0, 10.0, 35.0, 35.0], OPENING, Some(0), false),
        gt([50.0, 0.0, 90.0, 40.0], ENCLOSING, None, false),
        gt([60.0, 10.0, 80.0, 35.0], OPENING, Some(3), false),
    ];
    // Predictions in another order: p0 = window 2 (parent p3, right), p1 = window 1 (no
    // parent, wrong), p2 = window 4 (parent p3 = arch 0's match, wrong: its arch was not
    // found), p3 = arch 0.
    let p = vec![
        pred([25.0, 10.0, 35.0, 35.0], Some(3)),
        pred([5.0, 10.0, 15.0, 35.0], None),
        pred([60.0, 10.0, 80.0, 35.0], Some(3)),
        pred([0.0, 0.0, 40.0, 40.0], None),
    ];
    let s = score(&g, &p);
    assert_eq!((s.matched, s.nested, s.nested_right), (4, 3, 1));
    assert!((s.nesting().unwrap() - 1.0 / 3.0).abs() < 1e-12);
    // All right.
    let p = vec![
        pred([0.0, 0.0, 40.0, 40.0], None),
        pred([5.0, 10.0, 15.0, 35.0], Some(0)),
        pred([25.0, 10.0, 35.0, 35.0], Some(0)),
        pred([50.0, 0.0, 90.0, 40.0], None),
        pred([60.0, 10.0, 80.0, 35.0], Some(3)),
    ];
    let s = score(&g, &p);
    assert_eq!((s.matched, s.nested, s.nested_right), (5, 3, 3));
    // A difficult child is not counted for nesting.
    let mut g2 = g.clone();
    g2[4].difficult = true;
    let s = score(&g2, &p);
    assert_eq!((s.gt, s.matched, s.nested, s.nested_right), (4, 4, 2, 2));
}

#[test]
fn an_unknown_kind_or_role_is_refused() {
    let entry = |kind: &str, role: &str| {
        format!(
            r#"[{{"file": "elevations/x.png", "kind": "{kind}", "castle": "c", "view": null, "width": 10, "height": 10, "book": "b", "author": "a", "source": "s",
                "elements": [{{"box": [0, 0, 5, 5], "kind": "pointed", "role": "{role}", "parent": null}}]}}]"#
        )
    };
    let parse = |text: String| serde_json::from_str::<Vec<devset::Annotated>>(&text);
    assert!(parse(entry("elevation", "opening")).is_ok());
    assert!(parse(entry("sketch", "opening")).is_err());
    assert!(parse(entry("photo", "window")).is_err());
}
