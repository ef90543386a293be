//! What the figures of a rigid body's run read: its `summary.json` ([`RigidSummary`]) and its
//! trajectory (`t`, `R11` … `R33`, `Pi1` … `Pi3`, `energy`, `momentum_x` … `momentum_z`), gathered
//! in one pass ([`RigidData`]).

use std::path::Path;

use serde_json::Value;

use super::data::{TrajectoryFile, SUMMARY};
use super::sample::{Envelope, Stride};
use super::sphere::{unit, Vec3};
use super::ToolError;

/// The system's name in `summary.json`.
pub const RIGID_BODY: &str = "rigid_body";

/// What the figures need from a rigid body's `summary.json`.
pub struct RigidSummary {
    /// The system's name: `rigid_body`, or the name of a rigid system written as text.
    pub name: String,
    /// The principal moments of inertia I1, I2, I3 of the built-in body (none for a system of text,
    /// whose energy need not be ½ Σ Πᵢ²/Iᵢ).
    pub inertia: Option<[f64; 3]>,
    /// Whether |Π| is not conserved: gravity acts on the built-in body (m g |c| ≠ 0), or a system of
    /// text is not invariant under every rotation.
    pub heavy: bool,
    /// `SO(3)`, `vertical` or `none`.
    pub symmetry: String,
    /// The parameters and the run, in one line.
    pub description: String,
}

/// Whether `DIR/summary.json` is that of a rigid system's run: its `attitude` is `SO(3)` (or it is
/// the built-in body's); false if it cannot be read: the ordinary path reports why.
pub fn is_rigid_run(dir: &Path) -> bool {
    let json = std::fs::read_to_string(dir.join(SUMMARY)).ok().and_then(|t| serde_json::from_str::<Value>(&t).ok());
    json.is_some_and(|j| j["attitude"].as_str() == Some("SO(3)") || j["system"].as_str() == Some(RIGID_BODY))
}

impl RigidSummary {
    /// Reads `DIR/summary.json`.
    pub fn read(dir: &Path) -> Result<Self, ToolError> {
        let path = dir.join(SUMMARY);
        let text = std::fs::read_to_string(&path).map_err(|source| ToolError::Read {
            path: path.clone(),
            source,
            help: None,
        })?;
        let json: Value = serde_json::from_str(&text).map_err(|e| ToolError::malformed(&path, e.to_string()))?;
        let name = json["system"].as_str().unwrap_or(RIGID_BODY).to_owned();
        let symmetry = json["symmetry"].as_str().unwrap_or("none").to_owned();
        let (inertia, heavy, body) = if name == RIGID_BODY {
            let parameter = |name: &str| {
                json["parameters"][name]
                    .as_f64()
                    .ok_or_else(|| ToolError::malformed(&path, format!("no parameter `{name}`")))
            };
            let inertia = [parameter("I1")?, parameter("I2")?, parameter("I3")?];
            let (m, g) = (parameter("m")?, parameter("g").unwrap_or(0.0));
            let c = [parameter("c1").unwrap_or(0.0), parameter("c2").unwrap_or(0.0), parameter("c3").unwrap_or(0.0)];
            let heavy = m * g * c.iter().map(|x| x * x).sum::<f64>().sqrt() != 0.0;
            let list = |v: &[f64]| v.iter().map(f64::to_string).collect::<Vec<_>>().join(", ");
            let body = if heavy {
                format!("I = ({}), m = {m}, g = {g}, c = ({})", list(&inertia), list(&c))
            } else {
                format!("I = ({}), free body", list(&inertia))
            };
            (Some(inertia), heavy, body)
        } else {
            (None, symmetry != "SO(3)", format!("symmetry {symmetry}"))
        };
        let method = &json["method"];
        let order = method["order"].as_u64().filter(|&o| o > 2).map_or(String::new(), |o| format!(", order {o}"));
        let description = format!(
            "{body}; {} steps of h = {}, rule {}{order}, {}",
            json["steps"].as_u64().map_or("?".into(), |n| n.to_string()),
            json["step"].as_f64().map_or("?".into(), |h| h.to_string()),
            method["rule"].as_str().unwrap_or("?"),
            if method["reduced"].as_bool().unwrap_or(false) { "reduced by SO(3)" } else { "unreduced" },
        );
        Ok(Self { name, inertia, heavy, symmetry, description })
    }

    /// The indices of the components of R Π its symmetry conserves.
    /// The components of R Π the symmetry conserves.
    pub fn conserved(&self) -> &'static [usize] {
        match self.symmetry.as_str() {
            "SO(3)" => &[0, 1, 2],
            "vertical" => &[2],
            _ => &[],
        }
    }
}

/// Everything the figures take from the trajectory, gathered in one pass.
pub struct RigidData {
    /// Π/|Π| (Π/|Π₀| where |Π| is conserved: the same to round-off).
    pub pi: Stride<Vec3>,
    /// Π at the first row.
    pub pi0: Vec3,
    /// The mean of Π/|Π| over the rows.
    pub mean: Vec3,
    /// R e₁, R e₂, R e₃.
    pub axes: [Stride<Vec3>; 3],
    /// R Π at the first row.
    pub momentum0: Vec3,
    /// (E − E₀)/|E₀| against t.
    pub energy: Envelope,
    /// E₀, where the energy is reported.
    pub energy0: Option<f64>,
    /// R Π − R₀ Π₀ against t, by component.
    pub momentum: [Envelope; 3],
    /// |Π|/|Π₀| − 1 against t.
    pub casimir: Envelope,
}

/// The attitude and body momentum columns, in the order a row's `q` holds them.
fn columns() -> Vec<String> {
    let attitude = (1..=3).flat_map(|i| (1..=3).map(move |j| format!("R{i}{j}")));
    attitude.chain((1..=3).map(|i| format!("Pi{i}"))).collect()
}

/// The trajectory of the run in `dir`, read in one pass.
pub fn gather(dir: &Path) -> Result<RigidData, ToolError> {
    let names = columns();
    let (path, present) = TrajectoryFile::column_names(dir)?;
    let momentum = ["momentum_x", "momentum_y", "momentum_z"].map(str::to_owned);
    if let Some(missing) = names.iter().chain(&momentum).find(|n| !present.contains(n)) {
        let why = format!(
            "no column `{missing}` (the trajectory of a rigid body has the columns t, R11 … R33, the attitude \
             from body to space, Pi1 … Pi3, the body angular momentum, energy and momentum_x … momentum_z)"
        );
        return Err(ToolError::malformed(path, why));
    }
    let trajectory = TrajectoryFile::open(dir, &names)?;
    let rows = trajectory.rows;
    let mut data = RigidData {
        pi: Stride::new(rows),
        pi0: [0.0; 3],
        mean: [0.0; 3],
        axes: std::array::from_fn(|_| Stride::new(rows)),
        momentum0: [f64::NAN; 3],
        energy: Envelope::new(rows),
        energy0: None,
        momentum: std::array::from_fn(|_| Envelope::new(rows)),
        casimir: Envelope::new(rows),
    };
    let mut first = true;
    trajectory.for_each(|row| {
        let (r, pi) = (&row.q[..9], [row.q[9], row.q[10], row.q[11]]);
        let momentum = [row.momentum[0], row.momentum[1], row.momentum[2]];
        if first {
            (data.pi0, data.momentum0, first) = (pi, momentum, false);
        }
        let size = pi.iter().map(|x| x * x).sum::<f64>().sqrt();
        let direction = unit(pi);
        data.pi.push(direction);
        data.mean = std::array::from_fn(|i| data.mean[i] + direction[i] / rows as f64);
        for (j, axis) in data.axes.iter_mut().enumerate() {
            axis.push([r[j], r[3 + j], r[6 + j]]);
        }
        if let Some(e) = row.energy {
            let e0 = *data.energy0.get_or_insert(e);
            data.energy.push(row.t, Some(if e0 == 0.0 { e - e0 } else { (e - e0) / e0.abs() }));
        }
        for (i, envelope) in data.momentum.iter_mut().enumerate() {
            envelope.push(row.t, Some(momentum[i] - data.momentum0[i]));
        }
        let size0 = data.pi0.iter().map(|x| x * x).sum::<f64>().sqrt();
        data.casimir.push(row.t, Some(size / size0 - 1.0));
    })?;
    Ok(data)
}
