//! The initial data: q0 and exactly one of p0 (momenta) and v0 (velocities), each with one finite
//! entry per coordinate, in the coordinate order or by coordinate name — a spec's `[initial]` table
//! (`q = [0, 1]`, `p = { x = 0, theta = 1 }`) and the Python package's `q0`, `p0`, `v0`.

use ddirac::InitialMomentum;

use super::{finite, KeyError, Spelling};

/// One number per coordinate, as given.
#[derive(Debug, Clone, PartialEq)]
pub enum Values {
    /// In the coordinate order.
    InOrder(Vec<f64>),
    /// By coordinate name, in the order written.
    ByName(Vec<(String, f64)>),
}

/// Which vector of the initial data.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Which {
    /// q0.
    Q,
    /// p0.
    P,
    /// v0.
    V,
}

impl Which {
    /// The vector as `spelling` writes it, in backquotes: `` `initial.q` `` or `` `q0` ``.
    pub fn spelled(self, spelling: Spelling) -> String {
        let letter = match self {
            Which::Q => "q",
            Which::P => "p",
            Which::V => "v",
        };
        match spelling {
            Spelling::Spec => format!("`initial.{letter}`"),
            Spelling::Argument => format!("`{letter}0`"),
        }
    }
}

/// What a refusal of the initial data points at.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InitialKey {
    /// The initial data as a whole (`[initial]`).
    Table,
    /// One vector.
    Vector(Which),
    /// The `i`-th value given of a vector (from 0; for one given by name, its `i`-th name's value).
    Entry(Which, usize),
    /// The `i`-th name given in a vector by name.
    Name(Which, usize),
}

/// A vector with one finite entry per coordinate of `names`, in their order.
pub fn vector(
    values: &Values,
    which: Which,
    names: &[&str],
    spelling: Spelling,
) -> Result<Vec<f64>, KeyError<InitialKey>> {
    let key = which.spelled(spelling);
    match values {
        Values::InOrder(list) => {
            if list.len() != names.len() {
                return Err(KeyError::at(
                    InitialKey::Vector(which),
                    format!("{key} has {} entries, but the system has {} coordinates", list.len(), names.len()),
                    format!("expected {} entries", names.len()),
                )
                .with_help(format!("give one entry per coordinate, in order: {}", names.join(", "))));
            }
            list.iter()
                .zip(names)
                .enumerate()
                .map(|(i, (&v, name))| finite(InitialKey::Entry(which, i), v, &format!("{key} entry for `{name}`")))
                .collect()
        }
        Values::ByName(entries) => {
            if let Some(i) = entries.iter().position(|(n, _)| !names.contains(&n.as_str())) {
                return Err(KeyError::at(
                    InitialKey::Name(which, i),
                    format!("{key} gives a value for `{}`, which is not a coordinate", entries[i].0),
                    "not a coordinate",
                )
                .with_help(format!("the coordinates are: {}", names.join(", "))));
            }
            if let Some((i, (name, _))) =
                entries.iter().enumerate().find(|(i, (n, _))| entries[..*i].iter().any(|(m, _)| m == n))
            {
                return Err(KeyError::at(
                    InitialKey::Name(which, i),
                    format!("{key} gives coordinate `{name}` twice"),
                    "given before",
                ));
            }
            let missing: Vec<&str> = names.iter().copied().filter(|n| !entries.iter().any(|(e, _)| e == n)).collect();
            if !missing.is_empty() {
                return Err(KeyError::at(
                    InitialKey::Vector(which),
                    format!("{key} has no value for {}", quoted(&missing)),
                    format!("missing {}", quoted(&missing)),
                )
                .with_help(format!("give one value per coordinate: {}", names.join(", "))));
            }
            names
                .iter()
                .map(|name| {
                    let i = entries.iter().position(|(n, _)| n == name).expect("checked above");
                    finite(InitialKey::Entry(which, i), entries[i].1, &format!("{key} entry for `{name}`"))
                })
                .collect()
        }
    }
}

/// q0 and exactly one of p0 and v0, each with one finite entry per coordinate of `names`.
pub fn initial(
    q: &Values,
    p: Option<&Values>,
    v: Option<&Values>,
    names: &[&str],
    spelling: Spelling,
) -> Result<(Vec<f64>, InitialMomentum), KeyError<InitialKey>> {
    let q0 = vector(q, Which::Q, names, spelling)?;
    let (table, [p_key, v_key]) = match spelling {
        Spelling::Spec => ("`[initial]`", ["`p`", "`v`"]),
        Spelling::Argument => ("the initial data", ["`p0`", "`v0`"]),
    };
    let momentum = match (p, v) {
        (Some(p), None) => InitialMomentum::Momentum(vector(p, Which::P, names, spelling)?),
        (None, Some(v)) => InitialMomentum::Velocity(vector(v, Which::V, names, spelling)?),
        (None, None) => {
            let help = match spelling {
                Spelling::Spec => "give the initial momenta as `p = [...]` or the initial velocities as `v = [...]`",
                Spelling::Argument => "give the initial momenta as `p0` or the initial velocities as `v0`",
            };
            return Err(KeyError::at(InitialKey::Table, format!("{table} needs {p_key} or {v_key}"), "this table")
                .with_help(help));
        }
        (Some(_), Some(_)) => {
            let labels = [Which::P, Which::V].map(|w| (InitialKey::Vector(w), "given here".to_owned())).to_vec();
            return Err(KeyError::of(format!("{table} takes {p_key} or {v_key}, not both"), labels).with_help(
                format!("remove one of them: {p_key} are momenta, {v_key} velocities mapped to momenta by ∂L/∂v"),
            ));
        }
    };
    Ok((q0, momentum))
}

fn quoted(names: &[&str]) -> String {
    names.iter().map(|n| format!("`{n}`")).collect::<Vec<_>>().join(", ")
}
