//! Reading a run directory back: `summary.json` and the trajectory as `ddirac run` writes them
//! (`trajectory.csv`, or the `npy/<column>.npy` files of a run with `format = ["npy"]`).
//!
//! The trajectory is streamed (a CSV twice: once to count its rows, once to read them), so that
//! figures of long runs are drawn in bounded memory; columns are found by name.

use std::fs::File;
use std::io::{BufReader, Read, Seek, SeekFrom};
use std::path::{Path, PathBuf};

use serde_json::Value;

use super::ToolError;

/// Name of the trajectory file in a run directory.
pub const TRAJECTORY: &str = "trajectory.csv";
/// Name of the summary file in a run directory.
pub const SUMMARY: &str = "summary.json";

/// What the figures need from `summary.json`.
#[derive(Debug, Clone)]
pub struct RunSummary {
    /// The system's name (`double_spherical_pendulum`).
    pub system: String,
    /// The parameters, by name.
    pub parameters: Vec<(String, f64)>,
    /// The coordinate names, in order.
    pub coordinates: Vec<String>,
    /// The angles written wrapped to (−π, π]: `angles` when `output.wrap_angles`, else none.
    pub wrapped: Vec<String>,
    /// One line on the run: steps, step, rule, variant, reduced or not.
    pub description: String,
    /// The scale the momentum map's drift is measured against (`momentum_map.scale`: the larger of
    /// ‖J₀‖∞ and the run's largest momentum), when the summary gives a positive one.
    pub momentum_scale: Option<f64>,
}

impl RunSummary {
    /// Reads `DIR/summary.json`.
    pub fn read(dir: &Path) -> Result<Self, ToolError> {
        let path = dir.join(SUMMARY);
        let text = std::fs::read_to_string(&path).map_err(|source| missing(dir, &path, source))?;
        let json: Value = serde_json::from_str(&text).map_err(|e| ToolError::malformed(&path, e.to_string()))?;
        let bad = |why: &str| ToolError::malformed(&path, why);
        let system = json["system"].as_str().ok_or_else(|| bad("no `system` name"))?.to_owned();
        let coordinates = json["coordinates"]
            .as_array()
            .and_then(|a| a.iter().map(|c| c.as_str().map(str::to_owned)).collect::<Option<Vec<_>>>())
            .filter(|c| !c.is_empty())
            .ok_or_else(|| bad("no list of `coordinates`"))?;
        let parameters = json["parameters"]
            .as_object()
            .map(|o| o.iter().filter_map(|(k, v)| Some((k.clone(), v.as_f64()?))).collect())
            .unwrap_or_default();
        let wrapped = if json["output"]["wrap_angles"].as_bool().unwrap_or(false) {
            let names = json["angles"].as_array().map(|a| a.iter().filter_map(|n| n.as_str()).collect::<Vec<_>>());
            names.unwrap_or_default().into_iter().map(str::to_owned).collect()
        } else {
            vec![]
        };
        let method = &json["method"];
        let text = |v: &Value| v.as_str().unwrap_or("?").to_owned();
        let description = format!(
            "{} steps of h = {}, rule {}, variant {}, {}",
            json["steps"].as_u64().map_or("?".into(), |n| n.to_string()),
            json["step"].as_f64().map_or("?".into(), |h| h.to_string()),
            text(&method["rule"]),
            text(&method["variant"]),
            if method["reduced"].as_bool().unwrap_or(false) { "reduced" } else { "unreduced" },
        );
        let momentum_scale = json["momentum_map"]["scale"].as_f64().filter(|s| s.is_finite() && *s > 0.0);
        Ok(Self { system, parameters, coordinates, wrapped, description, momentum_scale })
    }

    /// Whether the coordinate `name` is an angle written wrapped to (−π, π].
    pub fn is_wrapped(&self, name: &str) -> bool {
        self.wrapped.iter().any(|w| w == name)
    }

    /// The parameter called `name`.
    pub fn parameter(&self, name: &str) -> Option<f64> {
        self.parameters.iter().find(|(n, _)| n == name).map(|(_, v)| *v)
    }
}

fn missing(dir: &Path, path: &Path, source: std::io::Error) -> ToolError {
    let help = (source.kind() == std::io::ErrorKind::NotFound).then(|| {
        format!(
            "`{}` should be the output directory of `ddirac run` (holding {TRAJECTORY} and {SUMMARY})",
            dir.display()
        )
    });
    ToolError::Read { path: path.to_owned(), source, help }
}

/// One row of the trajectory, with the columns the figures use.
#[derive(Debug)]
pub struct RowView<'a> {
    /// Time.
    pub t: f64,
    /// Coordinates, in the summary's order.
    pub q: &'a [f64],
    /// H(q, p).
    pub energy: Option<f64>,
    /// L_d(q_k, q_{k+1}); missing on the last row.
    pub discrete_energy: Option<f64>,
    /// The momentum map, one entry per group coordinate.
    pub momentum: &'a [f64],
}

/// Where the trajectory's columns are read from.
#[derive(Debug)]
enum Source {
    /// `trajectory.csv`, with the position of each wanted column (`None`: absent).
    Csv { path: PathBuf, index: Vec<Option<usize>> },
    /// `npy/<column>.npy`, with the file of each wanted column (`None`: absent).
    Npy { files: Vec<Option<PathBuf>> },
}

/// The trajectory of a run directory: `trajectory.csv`, or else the `npy/` columns.
#[derive(Debug)]
pub struct TrajectoryFile {
    /// The file (CSV) or directory (`.npy` columns) read.
    pub path: PathBuf,
    source: Source,
    n_q: usize,
    /// Names of the group coordinates, from the `momentum_<name>` columns.
    pub group: Vec<String>,
    /// Number of rows.
    pub rows: usize,
}

/// The wanted columns, in the order rows are decoded: t, q…, energy, discrete_energy, momentum….
fn wanted(coordinates: &[String], group: &[String]) -> Vec<String> {
    std::iter::once("t".to_owned())
        .chain(coordinates.iter().cloned())
        .chain(["energy".to_owned(), "discrete_energy".to_owned()])
        .chain(group.iter().map(|g| format!("momentum_{g}")))
        .collect()
}

impl TrajectoryFile {
    /// Opens the trajectory of the run in `dir` (`trajectory.csv`, or else `npy/*.npy`), finds the
    /// columns of `coordinates` and counts the rows.
    pub fn open(dir: &Path, coordinates: &[String]) -> Result<Self, ToolError> {
        let csv = dir.join(TRAJECTORY);
        let npy = dir.join("npy");
        if !csv.exists() && npy.join("t.npy").exists() {
            return Self::open_npy(&npy, coordinates);
        }
        let mut reader = Self::csv_reader(dir, &csv)?;
        let header = reader.headers().map_err(|e| ToolError::malformed(&csv, e.to_string()))?.clone();
        let group: Vec<String> = header.iter().filter_map(|h| h.strip_prefix("momentum_")).map(str::to_owned).collect();
        let index: Vec<Option<usize>> =
            wanted(coordinates, &group).iter().map(|name| header.iter().position(|h| h == name)).collect();
        let mut record = csv::ByteRecord::new();
        let mut rows = 0;
        while reader.read_byte_record(&mut record).map_err(|e| ToolError::malformed(&csv, e.to_string()))? {
            rows += 1;
        }
        let file =
            Self { path: csv.clone(), source: Source::Csv { path: csv, index }, n_q: coordinates.len(), group, rows };
        file.check(coordinates)
    }

    fn open_npy(npy: &Path, coordinates: &[String]) -> Result<Self, ToolError> {
        let mut group = vec![];
        let entries =
            std::fs::read_dir(npy).map_err(|source| ToolError::Read { path: npy.to_owned(), source, help: None })?;
        for entry in entries.flatten() {
            let name = entry.file_name().to_string_lossy().into_owned();
            if let Some(g) = name.strip_prefix("momentum_").and_then(|n| n.strip_suffix(".npy")) {
                group.push(g.to_owned());
            }
        }
        // The momentum columns follow the coordinate order, as in the CSV header (and the names'
        // order where they are not coordinates: `x`, `y`, `z` of a rigid body).
        group.sort_by(|a, b| {
            let at = |g: &String| coordinates.iter().position(|c| c == g);
            at(a).cmp(&at(b)).then_with(|| a.cmp(b))
        });
        let files: Vec<Option<PathBuf>> = wanted(coordinates, &group)
            .iter()
            .map(|name| Some(npy.join(format!("{name}.npy"))).filter(|p| p.exists()))
            .collect();
        let rows = match &files[0] {
            Some(t) => npy_header(t)?.1,
            None => 0,
        };
        let file = Self { path: npy.to_owned(), source: Source::Npy { files }, n_q: coordinates.len(), group, rows };
        file.check(coordinates)
    }

    /// The names of the columns of the trajectory in `dir` (the header of `trajectory.csv`, or else
    /// the `npy/<column>.npy` files), and the file or directory they were read from.
    pub fn column_names(dir: &Path) -> Result<(PathBuf, Vec<String>), ToolError> {
        let csv = dir.join(TRAJECTORY);
        let npy = dir.join("npy");
        if !csv.exists() && npy.join("t.npy").exists() {
            let entries =
                std::fs::read_dir(&npy).map_err(|source| ToolError::Read { path: npy.clone(), source, help: None })?;
            let names = entries
                .flatten()
                .filter_map(|e| e.file_name().to_string_lossy().strip_suffix(".npy").map(str::to_owned))
                .collect();
            return Ok((npy, names));
        }
        let mut reader = Self::csv_reader(dir, &csv)?;
        let header = reader.headers().map_err(|e| ToolError::malformed(&csv, e.to_string()))?;
        let names = header.iter().map(str::to_owned).collect();
        Ok((csv, names))
    }

    /// Refuses a trajectory without time, without a coordinate, or without rows.
    fn check(self, coordinates: &[String]) -> Result<Self, ToolError> {
        let present = |i: usize| match &self.source {
            Source::Csv { index, .. } => index[i].is_some(),
            Source::Npy { files } => files[i].is_some(),
        };
        if !present(0) {
            return Err(ToolError::malformed(&self.path, "no column `t`"));
        }
        if let Some(c) = coordinates.iter().enumerate().find(|(i, _)| !present(1 + i)).map(|(_, c)| c) {
            return Err(ToolError::malformed(&self.path, format!("no column for coordinate `{c}`")));
        }
        if self.rows == 0 {
            return Err(ToolError::malformed(&self.path, "it has no rows"));
        }
        Ok(self)
    }

    fn csv_reader(dir: &Path, path: &Path) -> Result<csv::Reader<File>, ToolError> {
        let file = File::open(path).map_err(|source| missing(dir, path, source))?;
        Ok(csv::Reader::from_reader(file))
    }

    /// A reader of the rows, from the first.
    pub fn rows(&self) -> Result<RowReader<'_>, ToolError> {
        let inner = match &self.source {
            Source::Csv { path, .. } => {
                Inner::Csv(Self::csv_reader(path.parent().unwrap_or(Path::new(".")), path)?, csv::StringRecord::new())
            }
            Source::Npy { files } => Inner::Npy(
                files
                    .iter()
                    .map(|f| f.as_ref().map(|path| npy_reader(path, self.rows)).transpose())
                    .collect::<Result<_, _>>()?,
            ),
        };
        Ok(RowReader {
            file: self,
            inner,
            values: vec![],
            q: vec![0.0; self.n_q],
            momentum: vec![0.0; self.group.len()],
            row: 0,
        })
    }

    /// Calls `visit` on every row, in order.
    pub fn for_each(&self, mut visit: impl FnMut(&RowView<'_>)) -> Result<(), ToolError> {
        let mut rows = self.rows()?;
        while let Some(row) = rows.next()? {
            visit(&row);
        }
        Ok(())
    }
}

enum Inner {
    Csv(csv::Reader<File>, csv::StringRecord),
    Npy(Vec<Option<(PathBuf, BufReader<File>)>>),
}

/// Reads a trajectory row by row.
pub struct RowReader<'a> {
    file: &'a TrajectoryFile,
    inner: Inner,
    values: Vec<Option<f64>>,
    q: Vec<f64>,
    momentum: Vec<f64>,
    row: usize,
}

impl RowReader<'_> {
    /// The next row, or `None` after the last.
    #[allow(clippy::should_implement_trait)] // a lending reader: the row borrows the reader
    pub fn next(&mut self) -> Result<Option<RowView<'_>>, ToolError> {
        let path = &self.file.path;
        self.values.clear();
        match &mut self.inner {
            Inner::Csv(reader, record) => {
                if !reader.read_record(record).map_err(|e| ToolError::malformed(path, e.to_string()))? {
                    return Ok(None);
                }
                self.row += 1;
                let Source::Csv { index, .. } = &self.file.source else { unreachable!("a CSV reader reads a CSV") };
                for i in index {
                    let text = i.and_then(|i| record.get(i)).unwrap_or("").trim();
                    self.values.push(if text.is_empty() {
                        None
                    } else {
                        Some(text.parse().map_err(|_| {
                            ToolError::malformed(path, format!("row {}: `{text}` is not a number", self.row))
                        })?)
                    });
                }
            }
            Inner::Npy(readers) => {
                if self.row == self.file.rows {
                    return Ok(None);
                }
                self.row += 1;
                let mut bytes = [0u8; 8];
                for reader in readers {
                    self.values.push(match reader {
                        Some((path, r)) => {
                            r.read_exact(&mut bytes).map_err(|e| ToolError::malformed(&*path, e.to_string()))?;
                            Some(f64::from_le_bytes(bytes))
                        }
                        None => None,
                    });
                }
            }
        }
        let (n_q, row, values) = (self.file.n_q, self.row, &self.values);
        let required =
            |v: Option<f64>| v.ok_or_else(|| ToolError::malformed(path, format!("row {row}: a value is missing")));
        for (slot, v) in self.q.iter_mut().zip(&values[1..=n_q]) {
            *slot = required(*v)?;
        }
        for (slot, v) in self.momentum.iter_mut().zip(&values[n_q + 3..]) {
            *slot = required(*v)?;
        }
        Ok(Some(RowView {
            t: required(values[0])?,
            q: &self.q,
            energy: values[n_q + 1],
            discrete_energy: values[n_q + 2].filter(|v| !v.is_nan()),
            momentum: &self.momentum,
        }))
    }
}

/// The offset of the data and the length of a 1-d little-endian f64 `.npy` array.
fn npy_header(path: &Path) -> Result<(usize, usize), ToolError> {
    let bad = |why: &str| ToolError::malformed(path, why);
    let mut file = File::open(path).map_err(|source| ToolError::Read { path: path.to_owned(), source, help: None })?;
    let mut start = [0u8; 12];
    file.read_exact(&mut start).map_err(|_| bad("too short for a .npy file"))?;
    if &start[..6] != b"\x93NUMPY" {
        return Err(bad("not a .npy file"));
    }
    let (length, offset) = match start[6] {
        1 => (u16::from_le_bytes([start[8], start[9]]) as usize, 10),
        2 | 3 => (u32::from_le_bytes([start[8], start[9], start[10], start[11]]) as usize, 12),
        v => return Err(bad(&format!("unknown .npy version {v}"))),
    };
    let mut header = vec![0u8; offset + length];
    file.seek(SeekFrom::Start(0)).and_then(|_| file.read_exact(&mut header)).map_err(|_| bad("truncated header"))?;
    let header = String::from_utf8_lossy(&header[offset..]);
    if !header.contains("'<f8'") || header.contains("'fortran_order': True") {
        return Err(bad("not an array of little-endian f64"));
    }
    let shape =
        header.split("'shape':").nth(1).and_then(|s| s.split(['(', ')']).nth(1)).ok_or_else(|| bad("no shape"))?;
    let rows = shape.trim().trim_end_matches(',').trim().parse().map_err(|_| bad("not a 1-d array"))?;
    Ok((offset + length, rows))
}

/// A reader at the data of a `.npy` column that must hold `rows` values.
fn npy_reader(path: &Path, rows: usize) -> Result<(PathBuf, BufReader<File>), ToolError> {
    let (offset, found) = npy_header(path)?;
    if found != rows {
        return Err(ToolError::malformed(path, format!("{found} rows, but `t.npy` has {rows}")));
    }
    let mut file = File::open(path).map_err(|source| ToolError::Read { path: path.to_owned(), source, help: None })?;
    file.seek(SeekFrom::Start(offset as u64)).map_err(|source| ToolError::Read {
        path: path.to_owned(),
        source,
        help: None,
    })?;
    Ok((path.to_owned(), BufReader::new(file)))
}
