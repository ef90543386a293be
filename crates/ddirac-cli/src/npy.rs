//! NumPy `.npy` files of one little-endian f64 column each, streamed to disk.
//!
//! Format version 1.0: the magic `\x93NUMPY`, the version bytes `1, 0`, the header length as a
//! little-endian u16, then the header — a Python dict literal
//! `{'descr': '<f8', 'fortran_order': False, 'shape': (N,), }` padded with spaces and ended by `\n`
//! so that magic, length and header together take a multiple of 64 bytes — and then the N values.
//!
//! The number of rows is not known until the run ends, so the header is first written for 0 rows,
//! padded to the length it has for the largest row count (20 digits), the values are appended as
//! they come, and [`Column::finish`] rewrites the header in place with the final count. Every header
//! of this module has the same length [`HEADER_LEN`], so the rewrite never moves the data. (NumPy's
//! own writer pads its headers in the same way so that files can grow along one axis.)
//!
//! Written by hand rather than with a crate: the format of a 1-d f64 array is these few lines, and
//! the file stays under the control of the caller's staging (temporary name, rename on success).

use std::fs::File;
use std::io::{self, BufWriter, Seek, SeekFrom, Write};
use std::path::Path;

/// Length of the magic, version, header length and header, in bytes: the smallest multiple of 64
/// that holds the header for `u64::MAX` rows.
pub const HEADER_LEN: usize = 128;

const MAGIC: &[u8; 6] = b"\x93NUMPY";

/// The first [`HEADER_LEN`] bytes of a 1-d little-endian f64 array of `rows` values.
pub fn header(rows: u64) -> [u8; HEADER_LEN] {
    let dict = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': ({rows},), }}");
    let mut bytes = [b' '; HEADER_LEN];
    bytes[..6].copy_from_slice(MAGIC);
    bytes[6..8].copy_from_slice(&[1, 0]);
    bytes[8..10].copy_from_slice(&((HEADER_LEN - 10) as u16).to_le_bytes());
    // 20 digits for u64::MAX: the dict always fits with room for the final newline.
    bytes[10..10 + dict.len()].copy_from_slice(dict.as_bytes());
    bytes[HEADER_LEN - 1] = b'\n';
    bytes
}

/// One `.npy` file being written: header for 0 rows, then the values as they are pushed.
#[derive(Debug)]
pub struct Column {
    file: BufWriter<File>,
    rows: u64,
}

impl Column {
    /// Creates (or truncates) `path` and writes a header for 0 rows.
    pub fn create(path: &Path) -> io::Result<Self> {
        let mut file = BufWriter::new(File::create(path)?);
        file.write_all(&header(0))?;
        Ok(Self { file, rows: 0 })
    }

    /// Appends one value.
    pub fn push(&mut self, value: f64) -> io::Result<()> {
        self.file.write_all(&value.to_le_bytes())?;
        self.rows += 1;
        Ok(())
    }

    /// Writes the final row count into the header and syncs the file.
    pub fn finish(self) -> io::Result<()> {
        let mut file = self.file.into_inner().map_err(|e| e.into_error())?;
        file.seek(SeekFrom::Start(0))?;
        file.write_all(&header(self.rows))?;
        file.sync_all()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_is_64_byte_aligned_and_holds_the_largest_count() {
        for rows in [0, 1, 12345, u64::MAX] {
            let h = header(rows);
            assert_eq!(HEADER_LEN % 64, 0);
            assert_eq!(&h[..8], b"\x93NUMPY\x01\x00");
            assert_eq!(u16::from_le_bytes([h[8], h[9]]) as usize + 10, HEADER_LEN);
            let text = std::str::from_utf8(&h[10..]).unwrap();
            let expected = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': ({rows},), }}");
            assert_eq!(text.trim_end_matches([' ', '\n']), expected);
            assert!(text.ends_with('\n'));
        }
        // The dict for u64::MAX leaves a padding space before the newline.
        assert_eq!(header(u64::MAX)[HEADER_LEN - 2], b' ');
    }
}
