//! The retina task's images (`vivae_neat::benchmarks::retina`): `01`
//! pixels are 0 and 1 as before, `pm3` pixels are −3 and +3 (AHNI's
//! reproduction) with the same labels, and both placements put the eight
//! pixels at distinct positions with the left half at x < 0.

use vivae_neat::benchmarks::retina::{LEFT_OBJECTS, Pixels, Placement, RIGHT_OBJECTS, images};

#[test]
fn zero_one_pixels_are_the_bits_of_the_image() {
    let got = images(Pixels::ZeroOne);
    assert_eq!(got.len(), 256);
    for (image, (x, labels)) in got.iter().enumerate() {
        // Input i is bit 7 - i of the image byte (left half in the high nibble).
        for (i, &v) in x.iter().enumerate() {
            assert_eq!(
                v,
                ((image >> (7 - i)) & 1) as f64,
                "image {image} pixel {i}"
            );
        }
        let (left, right) = ((image >> 4) as u8, (image & 0xf) as u8);
        assert_eq!(
            *labels,
            [LEFT_OBJECTS.contains(&left), RIGHT_OBJECTS.contains(&right)]
        );
    }
    // 8 of the 16 patterns of each half are objects.
    let objects = |side: usize| got.iter().filter(|(_, l)| l[side]).count();
    assert_eq!((objects(0), objects(1)), (128, 128));
}

#[test]
fn plus_minus_three_pixels_are_minus_three_off_and_three_on_with_the_same_labels() {
    let zero_one = images(Pixels::ZeroOne);
    let pm3 = images(Pixels::PlusMinusThree);
    for ((x01, l01), (x3, l3)) in zero_one.iter().zip(&pm3) {
        assert_eq!(l01, l3);
        for (&a, &b) in x01.iter().zip(x3) {
            assert_eq!(b, if a == 1.0 { 3.0 } else { -3.0 });
        }
    }
}

#[test]
fn pixel_and_placement_names_parse_and_others_are_one_line_errors() {
    assert_eq!(Pixels::parse("01"), Ok(Pixels::ZeroOne));
    assert_eq!(Pixels::parse("pm3"), Ok(Pixels::PlusMinusThree));
    assert_eq!(Placement::parse("line"), Ok(Placement::Line));
    assert_eq!(Placement::parse("grid"), Ok(Placement::Grid));
    let e = Pixels::parse("pm1").unwrap_err();
    assert!(e.contains("pm1") && !e.contains('\n'), "{e}");
    let e = Placement::parse("cube").unwrap_err();
    assert!(e.contains("cube") && !e.contains('\n'), "{e}");
}

#[test]
fn placements_put_distinct_pixels_with_the_left_half_at_negative_x() {
    for placement in [Placement::Line, Placement::Grid] {
        let p = placement.inputs();
        assert_eq!(p.len(), 8);
        for i in 0..8 {
            assert_eq!(p[i][0] < 0.0, i < 4, "{placement:?} pixel {i}");
            for j in 0..i {
                assert_ne!(p[i], p[j], "{placement:?} pixels {j} and {i}");
            }
        }
    }
    // The line is the placement used before the option existed.
    let line: Vec<[f64; 2]> = (0..8)
        .map(|i| [-1.0 + 2.0 * f64::from(i) / 7.0, -1.0])
        .collect();
    assert_eq!(Placement::Line.inputs(), line);
    // In the grid, top-left sits above bottom-left in the same column.
    let g = Placement::Grid.inputs();
    assert_eq!(g[0][0], g[2][0]);
    assert!(g[0][1] > g[2][1]);
}
