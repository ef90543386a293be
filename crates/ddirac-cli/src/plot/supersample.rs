//! Anti-aliased bitmaps: the figure is drawn at k times its size, and each k × k block of pixels is
//! averaged into one pixel of the image written.
//!
//! The bitmap backend of plotters draws lines, markers and polygons without anti-aliasing (only text
//! is blended); averaging k² samples per pixel gives every edge k² + 1 levels of coverage.

use std::path::Path;

use plotters::prelude::*;

use super::{Drawing, ToolError};

/// Samples per pixel along each axis.
pub const FACTOR: u32 = 3;

/// The largest drawing buffer, in bytes, before the factor is lowered (a figure of very many panels).
const MAX_BUFFER: u64 = 400 << 20;

/// The factor for an image of `size` pixels: [`FACTOR`], lowered while the buffer would be too large.
fn factor((w, h): (u32, u32)) -> u32 {
    (1..=FACTOR).rev().find(|k| 3 * u64::from(w * k) * u64::from(h * k) <= MAX_BUFFER).unwrap_or(1)
}

/// Draws `figure` anti-aliased into the PNG file `path` (whose extension picks the encoder); errors
/// name `target`, the file it becomes.
pub fn write_png<D: Drawing>(figure: &D, path: &Path, target: &Path) -> Result<(), ToolError> {
    let (w, h) = figure.size();
    let k = factor((w, h));
    let mut large = vec![0u8; 3 * (w * k) as usize * (h * k) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut large, (w * k, h * k)).into_drawing_area();
        figure.draw(&root, k).map_err(|why| ToolError::write(target, why))?;
    }
    let small = downsample(&large, (w, h), k);
    drop(large);
    let mut backend = BitMapBackend::new(path, (w, h));
    backend.blit_bitmap((0, 0), (w, h), &small).map_err(|e| ToolError::write(target, e.to_string()))?;
    backend.present().map_err(|e| ToolError::write(target, e.to_string()))
}

/// The RGB image of `size` pixels whose pixels are the means of the k × k blocks of `large`.
fn downsample(large: &[u8], (w, h): (u32, u32), k: u32) -> Vec<u8> {
    let (w, h, k) = (w as usize, h as usize, k as usize);
    let row = 3 * w * k;
    let mut small = vec![0u8; 3 * w * h];
    let mut sums = vec![0u32; 3 * w];
    for y in 0..h {
        sums.iter_mut().for_each(|s| *s = 0);
        for line in large[y * k * row..(y + 1) * k * row].chunks_exact(row) {
            for (x, block) in line.chunks_exact(3 * k).enumerate() {
                for pixel in block.chunks_exact(3) {
                    for c in 0..3 {
                        sums[3 * x + c] += u32::from(pixel[c]);
                    }
                }
            }
        }
        let n = (k * k) as u32;
        for (out, sum) in small[3 * w * y..3 * w * (y + 1)].iter_mut().zip(&sums) {
            *out = ((sum + n / 2) / n) as u8;
        }
    }
    small
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_pixel_is_the_mean_of_its_block() {
        // 4 × 2 samples, k = 2: two pixels, one all white, one half black.
        let white = [255u8; 3];
        let black = [0u8; 3];
        let rows = [[white, white, black, white], [white, white, black, white]];
        let large: Vec<u8> = rows.iter().flatten().flatten().copied().collect();
        assert_eq!(downsample(&large, (2, 1), 2), vec![255, 255, 255, 128, 128, 128]);
    }

    #[test]
    fn large_figures_are_drawn_with_fewer_samples() {
        assert_eq!(factor((1200, 700)), FACTOR);
        assert!(factor((1200, 16_000)) < FACTOR);
        assert_eq!(factor((100_000, 100_000)), 1);
    }
}
