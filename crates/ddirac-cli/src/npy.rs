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
use std::io::{self, BufWriter, Read, Seek, SeekFrom, Write};
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

/// The header of an array of any shape and element type (`descr`: `<f8`, `<i8`, `|u1`), padded as
/// NumPy pads it: magic, version, length and dict together a multiple of 64 bytes.
pub fn header_nd(descr: &str, shape: &[u64]) -> Vec<u8> {
    let dims: Vec<String> = shape.iter().map(u64::to_string).collect();
    let shape = match dims.len() {
        1 => format!("({},)", dims[0]),
        _ => format!("({})", dims.join(", ")),
    };
    let dict = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
    let total = (10 + dict.len() + 1).div_ceil(64) * 64;
    let mut bytes = vec![b' '; total];
    bytes[..6].copy_from_slice(MAGIC);
    bytes[6..8].copy_from_slice(&[1, 0]);
    bytes[8..10].copy_from_slice(&((total - 10) as u16).to_le_bytes());
    bytes[10..10 + dict.len()].copy_from_slice(dict.as_bytes());
    bytes[total - 1] = b'\n';
    bytes
}

/// Writes a whole array: the header of `shape` and `descr`, then `data` (already in that layout).
pub fn write(path: &Path, descr: &str, shape: &[u64], data: &[u8]) -> io::Result<()> {
    let mut file = BufWriter::new(File::create(path)?);
    file.write_all(&header_nd(descr, shape))?;
    file.write_all(data)?;
    file.into_inner().map_err(|e| e.into_error())?.sync_all()
}

/// f64 values as the bytes of a `<f8` array.
pub fn f64_bytes(values: &[f64]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// An array read back: element type, shape and the data's bytes.
#[derive(Debug, Clone, PartialEq)]
pub struct Array {
    /// `<f8`, `<i8`, `|u1`, …
    pub descr: String,
    /// The shape.
    pub shape: Vec<u64>,
    /// The data, in C order.
    pub data: Vec<u8>,
}

/// The header of an array file: element type, shape and where the data starts.
#[derive(Debug, Clone, PartialEq)]
pub struct Header {
    /// `<f8`, `<i8`, `|u1`, …
    pub descr: String,
    /// The shape.
    pub shape: Vec<u64>,
    /// The offset of the data in the file, bytes.
    pub offset: usize,
}

/// Reads the header of an array of format version 1.0 written by this module (C order), and checks
/// that the file holds exactly the data its shape and element type say: refuses a truncated file.
pub fn read_header(path: &Path) -> io::Result<Header> {
    let mut file = File::open(path)?;
    let length = file.metadata()?.len();
    let mut start = [0u8; 10];
    file.read_exact(&mut start).map_err(|_| invalid("no NPY 1.0 magic"))?;
    let mut dict = vec![0u8; usize::from(u16::from_le_bytes([start[8], start[9]]))];
    file.read_exact(&mut dict).map_err(|_| invalid("short header"))?;
    parse(&start, &dict, length)
}

/// The header of `start` (magic, version and header length: 10 bytes) and `dict` (the header's
/// dict) of a file of `length` bytes.
fn parse(start: &[u8], dict: &[u8], length: u64) -> io::Result<Header> {
    if &start[..6] != MAGIC || start[6] != 1 {
        return Err(invalid("no NPY 1.0 magic"));
    }
    let dict = std::str::from_utf8(dict).map_err(|_| invalid("header not UTF-8"))?;
    let field = |key: &str| dict.split(key).nth(1).ok_or_else(|| invalid(key));
    let descr = field("'descr': '")?.split('\'').next().unwrap_or_default().to_owned();
    if field("'fortran_order': ")?.starts_with("True") {
        return Err(invalid("Fortran order"));
    }
    let shape_text = field("'shape': (")?.split(')').next().unwrap_or_default();
    let shape = shape_text
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().map_err(|_| invalid("shape")))
        .collect::<io::Result<Vec<u64>>>()?;
    let item: u64 = match descr.as_bytes() {
        [b'<' | b'|', _, _, ..] => descr.get(2..).and_then(|size| size.parse().ok()).filter(|&size| size > 0),
        _ => None,
    }
    .ok_or_else(|| invalid(&format!("the element type `{descr}` is not a little-endian type of ddirac")))?;
    let offset = 10 + dict.len();
    let expected = shape.iter().try_fold(item, |n, &d| n.checked_mul(d));
    let data = length.saturating_sub(offset as u64);
    if expected != Some(data) {
        let dims: Vec<String> = shape.iter().map(u64::to_string).collect();
        let wanted = expected.map_or_else(|| "more than 2^64".to_owned(), |n| n.to_string());
        return Err(io::Error::new(
            io::ErrorKind::InvalidData,
            format!(
                "the header's shape ({}) of `{descr}` needs {wanted} bytes of data, but the file holds {data} \
                 (is it truncated?)",
                dims.join(", ")
            ),
        ));
    }
    Ok(Header { descr, shape, offset })
}

fn invalid(why: &str) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidData, format!("not a .npy file of ddirac: {why}"))
}

/// Reads an array of format version 1.0 written by this module (C order); refuses a file whose data
/// is not exactly as long as the header's shape and element type say (a truncated file, say).
pub fn read(path: &Path) -> io::Result<Array> {
    let bytes = std::fs::read(path)?;
    if bytes.len() < 10 {
        return Err(invalid("no NPY 1.0 magic"));
    }
    let end = 10 + usize::from(u16::from_le_bytes([bytes[8], bytes[9]]));
    let dict = bytes.get(10..end).ok_or_else(|| invalid("short header"))?;
    let Header { descr, shape, offset } = parse(&bytes[..10], dict, bytes.len() as u64)?;
    Ok(Array { descr, shape, data: bytes[offset..].to_vec() })
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

    #[test]
    fn arrays_of_any_shape_read_back_as_written() {
        let dir = std::env::temp_dir().join(format!("ddirac-npy-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        for (descr, shape) in [("<f8", vec![3u64]), ("<f8", vec![2, 3, 4]), ("|u1", vec![u64::MAX, 1, u64::MAX])] {
            let header = header_nd(descr, &shape);
            assert_eq!(header.len() % 64, 0);
            assert_eq!(*header.last().unwrap(), b'\n');
            let path = dir.join("a.npy");
            if shape[0] == u64::MAX {
                // A header can name more data than any file holds: reading it is refused.
                write(&path, descr, &shape, &[]).unwrap();
                assert!(read(&path).is_err());
                continue;
            }
            let data: Vec<u8> = (0..shape.iter().product::<u64>() * 8).map(|b| b as u8).collect();
            write(&path, descr, &shape, &data).unwrap();
            assert_eq!(read(&path).unwrap(), Array { descr: descr.into(), shape, data });
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn data_shorter_or_longer_than_the_shape_says_is_refused() {
        let dir = std::env::temp_dir().join(format!("ddirac-npy-length-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("a.npy");
        for (descr, size) in [("<f8", 8), ("|u1", 1), ("<i8", 8)] {
            let whole = vec![7u8; 6 * size];
            write(&path, descr, &[2, 3], &whole).unwrap();
            assert_eq!(read(&path).unwrap().data, whole);
            assert_eq!(read_header(&path).unwrap().shape, [2, 3]);
            for len in [0, 6 * size - 1, 6 * size + 1] {
                write(&path, descr, &[2, 3], &vec![7u8; len]).unwrap();
                let error = read(&path).unwrap_err();
                assert_eq!(error.kind(), io::ErrorKind::InvalidData, "{descr}, {len} bytes");
                assert!(error.to_string().contains(&format!("needs {} bytes", 6 * size)), "{error}");
                assert_eq!(read_header(&path).unwrap_err().to_string(), error.to_string());
            }
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
