//! The PNG figures were drawn without anti-aliasing: a curve's pixels were either its full colour
//! or the white background, so that curves were staircases. Anti-aliased, the pixels at a curve's
//! edge take colours between the two.
//!
//! The test reads the PNG of the second mass's path of the double spherical pendulum (a curve in
//! every direction) and counts, among the pixels of the curve's colour, the hard edges: a pixel of
//! the full colour next to a pixel of pure background, left–right or up–down.

use crate::common;

use common::{example, TempDir};

/// The colour of the first series of a panel (the path of the second mass).
const DATA: [u8; 3] = [31, 119, 180];

/// An RGB image: width, height, pixels row by row.
struct Image {
    width: usize,
    height: usize,
    rgb: Vec<[u8; 3]>,
}

impl Image {
    fn read(path: &std::path::Path) -> Self {
        let decoder = png::Decoder::new(std::fs::File::open(path).unwrap());
        let mut reader = decoder.read_info().unwrap();
        let mut buffer = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buffer).unwrap();
        assert_eq!(info.bit_depth, png::BitDepth::Eight);
        let samples = info.color_type.samples();
        let rgb = buffer[..info.buffer_size()].chunks_exact(samples).map(|p| [p[0], p[1], p[2]]).collect();
        Self { width: info.width as usize, height: info.height as usize, rgb }
    }

    fn at(&self, x: usize, y: usize) -> [u8; 3] {
        self.rgb[y * self.width + x]
    }
}

fn background(c: [u8; 3]) -> bool {
    c.iter().all(|&v| v >= 245)
}

fn full(c: [u8; 3]) -> bool {
    c.iter().zip(DATA).all(|(&v, d)| v.abs_diff(d) <= 6)
}

/// A blend of the data colour with white, a of the way from white (estimated from red).
fn blend(c: [u8; 3]) -> Option<f64> {
    let a = (255.0 - f64::from(c[0])) / (255.0 - f64::from(DATA[0]));
    let close = c.iter().zip(DATA).all(|(&v, d)| (f64::from(v) - (255.0 - a * (255.0 - f64::from(d)))).abs() <= 5.0);
    (close && a > 0.1 && a < 0.9).then_some(a)
}

#[test]
fn curves_in_the_png_figures_have_soft_edges() {
    let dir = TempDir::new("antialiased");
    let sets = ["time.steps=2000", "time.duration=20", "output.plots=true"];
    let output = common::run(&example("double_spherical_pendulum.toml"), &sets, &dir);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let image = Image::read(&dir.out().join("second_bob_path.png"));

    let (mut full_pixels, mut blended, mut hard_edges) = (0, 0, 0);
    for y in 0..image.height {
        for x in 0..image.width {
            let c = image.at(x, y);
            full_pixels += usize::from(full(c));
            blended += usize::from(blend(c).is_some());
            let neighbours =
                [(x + 1 < image.width).then(|| image.at(x + 1, y)), (y + 1 < image.height).then(|| image.at(x, y + 1))];
            for d in neighbours.into_iter().flatten() {
                if (full(c) && background(d)) || (background(c) && full(d)) {
                    hard_edges += 1;
                }
            }
        }
    }
    assert!(full_pixels > 200, "the path is not drawn in its colour ({full_pixels} pixels)");
    assert!(blended > full_pixels / 2, "{blended} pixels between the curve's colour and white, {full_pixels} of it");
    assert!(
        hard_edges * 100 <= full_pixels,
        "{hard_edges} hard edges between the curve's colour and white for {full_pixels} pixels of it"
    );
}
