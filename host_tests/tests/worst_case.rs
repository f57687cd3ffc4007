//! The visible-surface sweep's worst case (`testkit::staggered`):
//! staggered overlapping faces, each nearer than the last, in the three
//! orders, against the exact reference and in both ways of resolving
//! intersecting spans; and the 1 MB display list of 38,835 of them that
//! `docs/performance.md` ("Worst cases") times (`scanvert-bench --
//! --write-worst DIR` writes the lists).

use embedded_graphics_core::pixelcolor::{Rgb888, RgbColor};
use host_tests::harness3d::{color_of, compare, render3, vertex3};
use scanvert::display_list::{DisplayList, Writer};
use scanvert::visible::sweep::Resolve;
use testkit::reference3d::Poly3;
use testkit::staggered::{staggered, Order, H, W};

const ORDERS: [Order; 3] = [Order::Nearer, Order::Reversed, Order::Farther];

/// Faces of the 1 MB list.
const BIG: usize = 38_835;

/// The display list of `faces`: a black clear, then each face's colour
/// and the face (no clip registers, 25 bytes a face).
fn list(faces: &[Poly3]) -> Vec<u8> {
    let size = 16
        + 4
        + faces
            .iter()
            .map(|p| 4 + 3 + 6 * p.poly.len())
            .sum::<usize>();
    let mut buf = vec![0u8; size];
    let mut w = Writer::new(&mut buf, W, H).expect("frame size");
    w.clear(Rgb888::BLACK).expect("sized");
    for (k, p) in faces.iter().enumerate() {
        w.color(color_of(k)).expect("sized");
        w.poly3(p.poly.iter().copied().map(vertex3))
            .expect("3 vertices");
    }
    w.finish().to_vec()
}

#[test]
fn small_instances_are_exact_in_both_modes() {
    for order in ORDERS {
        let faces = staggered(48, order);
        for mode in [Resolve::Bisect, Resolve::Crossing] {
            let (m, first) = compare(&faces, W, H, mode);
            assert!(m.covered > 0);
            assert_eq!(m.mismatched, 0, "{order:?} {mode:?}: {m:?}, {first:?}");
        }
    }
}

#[test]
fn both_modes_and_both_listings_draw_the_same() {
    let n = 600;
    let nearer = render3(&staggered(n, Order::Nearer), W, H, Resolve::Crossing).0;
    let bisect = render3(&staggered(n, Order::Nearer), W, H, Resolve::Bisect).0;
    assert_eq!(nearer, bisect);
    // Face k of the reversed list is face n − 1 − k.
    let reversed = render3(&staggered(n, Order::Reversed), W, H, Resolve::Crossing).0;
    let back: Vec<_> = reversed.iter().map(|w| w.map(|k| n - 1 - k)).collect();
    assert_eq!(nearer, back);
    // Every face shows: its last row's right end is in front of the rest.
    let mut shown = vec![false; n];
    for k in nearer.iter().flatten() {
        shown[*k] = true;
    }
    assert!(shown.iter().all(|s| *s));
    let farther = render3(&staggered(n, Order::Farther), W, H, Resolve::Crossing).0;
    let bisect = render3(&staggered(n, Order::Farther), W, H, Resolve::Bisect).0;
    assert_eq!(farther, bisect);
}

#[test]
fn the_big_list_is_one_megabyte() {
    let bytes = list(&staggered(BIG, Order::Nearer));
    DisplayList::new_checked(&bytes).expect("valid");
    assert!(bytes.len() <= 1 << 20, "{} bytes", bytes.len());
    assert!(bytes.len() > 900_000, "{} bytes", bytes.len());
}
