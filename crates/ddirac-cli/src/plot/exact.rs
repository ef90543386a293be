//! Reading `exact.csv` back (the exact motion beside a run's trajectory, see `crate::exact`), thinned
//! like the trajectory, for the figures to draw under the computed lines.

use std::path::Path;

use super::sample::{Envelope, Stride};
use super::ToolError;

/// A path in a plane: the names of its two coordinates and its points.
pub type PlanePath = ([String; 2], Vec<(f64, f64)>);

/// The exact motion of a run.
#[derive(Debug, Clone, Default)]
pub struct Exact {
    /// Coordinate by coordinate: (name, points (t, value)).
    pub series: Vec<(String, Vec<(f64, f64)>)>,
    /// The path in the plane of the first two coordinates it is known for: their names and the
    /// points (the paper's §7.1 figure of the charged particle).
    pub path: Option<PlanePath>,
}

/// The exact motion of the run in `dir`; empty when the directory has no `exact.csv` (the system
/// has no exact solution).
pub fn read(dir: &Path) -> Result<Exact, ToolError> {
    let path = dir.join(crate::exact::ExactFile::NAME);
    if !path.exists() {
        return Ok(Exact::default());
    }
    let malformed = |why: String| ToolError::malformed(&path, why);
    let open = || {
        let file =
            std::fs::File::open(&path).map_err(|source| ToolError::Read { path: path.clone(), source, help: None })?;
        Ok::<_, ToolError>(csv::Reader::from_reader(file))
    };
    let mut reader = open()?;
    let header = reader.headers().map_err(|e| malformed(e.to_string()))?.clone();
    if header.get(0) != Some("t") {
        return Err(malformed("its first column is not `t`".into()));
    }
    let mut record = csv::ByteRecord::new();
    let mut rows = 0;
    while reader.read_byte_record(&mut record).map_err(|e| malformed(e.to_string()))? {
        rows += 1;
    }
    let mut envelopes: Vec<Envelope> = (1..header.len()).map(|_| Envelope::new(rows)).collect();
    let mut plane = (header.len() >= 3).then(|| Stride::new(rows));
    let mut reader = open()?;
    let mut record = csv::StringRecord::new();
    while reader.read_record(&mut record).map_err(|e| malformed(e.to_string()))? {
        let number = |i: usize| record.get(i).and_then(|s| s.parse::<f64>().ok());
        let t = number(0).ok_or_else(|| malformed(format!("a row without a time: {record:?}")))?;
        for (i, envelope) in envelopes.iter_mut().enumerate() {
            envelope.push(t, number(1 + i));
        }
        if let (Some(plane), Some(x), Some(y)) = (&mut plane, number(1), number(2)) {
            plane.push((x, y));
        }
    }
    let names: Vec<String> = header.iter().skip(1).map(str::to_owned).collect();
    let path = plane.map(|plane| ([names[0].clone(), names[1].clone()], plane.finish()));
    Ok(Exact { series: names.into_iter().zip(envelopes.into_iter().map(Envelope::finish)).collect(), path })
}
