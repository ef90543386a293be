//! Entries of the initial data set by name: `--set initial.q.phi1=0.3` and the members of an
//! ensemble (`initial.q.<coordinate>`, `initial.p.<coordinate>`, `initial.v.<coordinate>`; for a
//! rigid body also `initial.Pi.<i>` and `initial.Omega.<i>`, i = 1, 2, 3, the components of the body
//! angular momentum and velocity, with its shape coordinates' `q`, `p`, `v`).
//!
//! They are applied to the validated problem, by coordinate name, whether the spec writes its
//! vectors in coordinate order (`q = [0, 1]`) or by name (`q = { x = 0, y = 1 }`), so that a member
//! of an ensemble and `ddirac run --set` with the same values start from the same numbers.
//! An entry of the spec's own momentum vector (`p` or `v`) replaces that entry; the other vector
//! replaces the spec's only when every coordinate's entry is given. For a rigid body `Pi` goes with
//! `p` and `Omega` with `v`: the spec's `Pi` (and `p`) are replaced by velocities only when all three
//! components of `Omega` and every shape coordinate's `v` are given, and the other way round.

use ddirac::rigid::{RigidInitial, RigidProblem};
use ddirac::{InitialMomentum, Problem};

use crate::diagnostics::CliError;

/// Which initial vector an entry belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Vector {
    /// `initial.q`.
    Q,
    /// `initial.p`.
    P,
    /// `initial.v`.
    V,
    /// `initial.Pi` of a rigid body.
    Pi,
    /// `initial.Omega` of a rigid body.
    Omega,
}

impl Vector {
    /// Whether the vector holds momenta (`p`, `Pi`) rather than velocities (`v`, `Omega`); `None` for
    /// `q`.
    fn momenta(self) -> Option<bool> {
        match self {
            Vector::Q => None,
            Vector::P | Vector::Pi => Some(true),
            Vector::V | Vector::Omega => Some(false),
        }
    }

    /// Whether it belongs to the attitude of a rigid body.
    pub fn of_attitude(self) -> bool {
        matches!(self, Vector::Pi | Vector::Omega)
    }
}

/// One entry: `initial.<vector>.<coordinate>`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Entry {
    /// The vector.
    pub vector: Vector,
    /// The coordinate's name.
    pub coordinate: String,
}

impl Entry {
    /// `Some` for a key `initial.q.<name>`, `initial.p.<name>` or `initial.v.<name>` (an error if it
    /// names no coordinate); `None` for any other key.
    pub fn parse(key: &str) -> Option<Result<Self, String>> {
        let rest = key.trim().strip_prefix("initial.")?;
        let (vector, name) = rest.split_once('.')?;
        let vector = match vector.trim() {
            "q" => Vector::Q,
            "p" => Vector::P,
            "v" => Vector::V,
            "Pi" => Vector::Pi,
            "Omega" => Vector::Omega,
            _ => return None,
        };
        let name = name.trim().trim_matches('"');
        if name.is_empty() {
            return Some(Err(format!("`{key}` names no coordinate")));
        }
        if vector.of_attitude() && !matches!(name, "1" | "2" | "3") {
            return Some(Err(format!(
                "`{key}` names no component: the body's vectors have the components 1, 2 and 3 (`initial.{}.1`)",
                rest.split_once('.').map_or("Pi", |(v, _)| v.trim())
            )));
        }
        Some(Ok(Self { vector, coordinate: name.to_owned() }))
    }

    /// The key as `--set` writes it.
    pub fn key(&self) -> String {
        let vector = match self.vector {
            Vector::Q => "q",
            Vector::P => "p",
            Vector::V => "v",
            Vector::Pi => "Pi",
            Vector::Omega => "Omega",
        };
        format!("initial.{vector}.{}", self.coordinate)
    }

    /// The component 0, 1 or 2 of an entry of `Pi` or `Omega`.
    fn component(&self) -> usize {
        self.coordinate.parse::<usize>().map_or(0, |i| i.saturating_sub(1).min(2))
    }
}

/// A `--set` assignment of an initial entry: the argument as given, the entry and its value.
pub type Assignment = (String, Entry, f64);

/// Splits `--set` assignments into entries of the initial data (with their values) and edits of the
/// spec text, in order; an entry whose key or value is malformed is refused naming its argument.
pub fn split(set: &[String]) -> Result<(Vec<Assignment>, Vec<String>), CliError> {
    let mut entries = vec![];
    let mut edits = vec![];
    for arg in set {
        let entry = arg.split_once('=').and_then(|(key, value)| Some((Entry::parse(key)?, value)));
        match entry {
            Some((entry, value)) => {
                let entry = entry.map_err(|why| CliError::Set { arg: arg.clone(), why })?;
                let value: f64 = value.trim().parse().map_err(|_| CliError::Set {
                    arg: arg.clone(),
                    why: format!("`{}` is not a number", value.trim()),
                })?;
                entries.push((arg.clone(), entry, value));
            }
            None => edits.push(arg.clone()),
        }
    }
    Ok((entries, edits))
}

/// Refuses entries of the body's vectors for a system in coordinates: they belong to a rigid body.
pub fn refuse_attitude(entries: &[Entry]) -> Result<(), String> {
    match entries.iter().find(|e| e.vector.of_attitude()) {
        Some(entry) => Err(format!(
            "`{}` belongs to a rigid body (the components of its body angular momentum or velocity); this system is \
             in coordinates: set `initial.q.<coordinate>`, `initial.p.<coordinate>` or `initial.v.<coordinate>`",
            entry.key()
        )),
        None => Ok(()),
    }
}

/// Refuses entries of both momentum vectors, and entries of the one the spec does not give (p where
/// it gives v, or v where it gives p) unless all `n` of them are given.
pub fn check_kinds(entries: &[Entry], problem: &Problem, n: usize) -> Result<(), String> {
    refuse_attitude(entries)?;
    let momenta = matches!(problem.initial, InitialMomentum::Momentum(_));
    check_families(entries, momenta, n, false)
}

/// [`check_kinds`] for a rigid body with `shape` shape coordinates whose spec starts from momenta
/// (`Pi`) when `momenta`: `Pi` goes with `p`, `Omega` with `v`, and the other family replaces the
/// spec's only when all 3 + `shape` entries are given.
pub fn check_rigid_kinds(entries: &[Entry], momenta: bool, shape: usize) -> Result<(), String> {
    check_families(entries, momenta, shape + 3, true)
}

pub(crate) fn check_families(entries: &[Entry], momenta: bool, n: usize, rigid: bool) -> Result<(), String> {
    let given = |family: bool| entries.iter().any(|e| e.vector.momenta() == Some(family));
    let (p, v) = if rigid { ("Pi` or `initial.p", "Omega` or `initial.v") } else { ("p", "v") };
    if given(true) && given(false) {
        return Err(format!(
            "entries of `initial.{p}` and of `initial.{v}` are given together: a run starts from momenta or \
             from velocities, so give entries of one of them"
        ));
    }
    let (given, other_name) = if momenta { (p, v) } else { (v, p) };
    let count = entries.iter().filter(|e| e.vector.momenta() == Some(!momenta)).count();
    if count > 0 && count < n {
        let all =
            if rigid { format!("all {n} (three of the body, one per shape coordinate)") } else { format!("all {n}") };
        return Err(format!(
            "the spec gives `initial.{given}`; entries of `initial.{other_name}` replace it only when {all} \
             coordinates are given ({count} are): set entries of `initial.{given}` instead"
        ));
    }
    Ok(())
}

/// Sets `entries` (with their `values`) in `problem`, whose coordinates are `names`.
pub fn apply(problem: &mut Problem, names: &[String], entries: &[Entry], values: &[f64]) -> Result<(), String> {
    check_kinds(entries, problem, names.len())?;
    let index = |entry: &Entry| {
        names.iter().position(|n| *n == entry.coordinate).ok_or_else(|| {
            format!("`{}` is not a coordinate; the coordinates are {}", entry.coordinate, names.join(", "))
        })
    };
    // A complete vector of the other kind replaces the spec's.
    let switch = |vector: Vector| entries.iter().any(|e| e.vector == vector);
    match &problem.initial {
        InitialMomentum::Momentum(_) if switch(Vector::V) => {
            problem.initial = InitialMomentum::Velocity(vec![f64::NAN; names.len()]);
        }
        InitialMomentum::Velocity(_) if switch(Vector::P) => {
            problem.initial = InitialMomentum::Momentum(vec![f64::NAN; names.len()]);
        }
        _ => {}
    }
    for (entry, &value) in entries.iter().zip(values) {
        if !value.is_finite() {
            return Err(format!("`{}` = {value} is not a finite number", entry.key()));
        }
        let i = index(entry)?;
        let slot = match (entry.vector, &mut problem.initial) {
            (Vector::Q, _) => &mut problem.q0[i],
            (Vector::P, InitialMomentum::Momentum(p)) => &mut p[i],
            (Vector::V, InitialMomentum::Velocity(v)) => &mut v[i],
            _ => unreachable!("the vector kind was switched above"),
        };
        *slot = value;
    }
    Ok(())
}

/// Sets `entries` (with their `values`) in the rigid `problem` whose shape coordinates are `shape`.
pub fn apply_rigid(
    problem: &mut RigidProblem,
    shape: &[String],
    entries: &[Entry],
    values: &[f64],
) -> Result<(), String> {
    let momenta = matches!(problem.initial, RigidInitial::Momentum { .. });
    check_rigid_kinds(entries, momenta, shape.len())?;
    let index = |entry: &Entry| {
        shape.iter().position(|n| *n == entry.coordinate).ok_or_else(|| match shape.len() {
            0 => format!(
                "`{}` names a shape coordinate, and this body has none: set `initial.Pi.<i>` or `initial.Omega.<i>`",
                entry.key()
            ),
            _ => format!("`{}` is not a shape coordinate; they are {}", entry.coordinate, shape.join(", ")),
        })
    };
    let switch = |family: bool| entries.iter().any(|e| e.vector.momenta() == Some(family));
    let nan = vec![f64::NAN; shape.len()];
    match &problem.initial {
        RigidInitial::Momentum { .. } if switch(false) => {
            problem.initial = RigidInitial::Velocity { omega: [f64::NAN; 3], v: nan };
        }
        RigidInitial::Velocity { .. } if switch(true) => {
            problem.initial = RigidInitial::Momentum { pi: [f64::NAN; 3], p: nan };
        }
        _ => {}
    }
    for (entry, &value) in entries.iter().zip(values) {
        if !value.is_finite() {
            return Err(format!("`{}` = {value} is not a finite number", entry.key()));
        }
        let slot = match (entry.vector, &mut problem.initial) {
            (Vector::Pi, RigidInitial::Momentum { pi, .. }) => &mut pi[entry.component()],
            (Vector::Omega, RigidInitial::Velocity { omega, .. }) => &mut omega[entry.component()],
            (Vector::Q, _) => &mut problem.s0[index(entry)?],
            (Vector::P, RigidInitial::Momentum { p, .. }) => &mut p[index(entry)?],
            (Vector::V, RigidInitial::Velocity { v, .. }) => &mut v[index(entry)?],
            _ => unreachable!("the vector kind was switched above"),
        };
        *slot = value;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn problem() -> Problem {
        Problem::new(0.1, 10, vec![0.0, 1.0], InitialMomentum::Momentum(vec![2.0, 3.0]))
    }

    fn names() -> Vec<String> {
        vec!["x".into(), "y".into()]
    }

    fn entry(key: &str) -> Entry {
        Entry::parse(key).unwrap().unwrap()
    }

    #[test]
    fn entries_are_set_by_name_and_others_keep_their_values() {
        let mut p = problem();
        apply(&mut p, &names(), &[entry("initial.q.y"), entry("initial.p.x")], &[5.0, 7.0]).unwrap();
        assert_eq!(p.q0, [0.0, 5.0]);
        assert_eq!(p.initial, InitialMomentum::Momentum(vec![7.0, 3.0]));
        assert!(Entry::parse("parameters.m").is_none());
        assert!(Entry::parse("initial.w.x").is_none());
    }

    #[test]
    fn the_other_momentum_vector_replaces_the_spec_s_only_when_complete() {
        let mut p = problem();
        let why = apply(&mut p, &names(), &[entry("initial.v.x")], &[1.0]).unwrap_err();
        assert!(why.contains("all 2 coordinates"), "{why}");
        apply(&mut p, &names(), &[entry("initial.v.x"), entry("initial.v.y")], &[1.0, 2.0]).unwrap();
        assert_eq!(p.initial, InitialMomentum::Velocity(vec![1.0, 2.0]));
    }

    #[test]
    fn momenta_and_velocities_together_are_refused() {
        let mut p = problem();
        let entries = [entry("initial.v.x"), entry("initial.v.y"), entry("initial.p.x")];
        let why = apply(&mut p, &names(), &entries, &[1.0, 2.0, 3.0]).unwrap_err();
        assert!(why.contains("`initial.p` and of `initial.v` are given together"), "{why}");
    }

    #[test]
    fn unknown_coordinates_and_non_finite_values_are_refused() {
        let mut p = problem();
        assert!(apply(&mut p, &names(), &[entry("initial.q.z")], &[1.0]).unwrap_err().contains("coordinates are x, y"));
        assert!(apply(&mut p, &names(), &[entry("initial.q.x")], &[f64::NAN]).unwrap_err().contains("finite"));
    }

    fn rigid() -> RigidProblem {
        let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let mut problem =
            RigidProblem::new(0.1, 10, identity, RigidInitial::Momentum { pi: [1.0, 2.0, 3.0], p: vec![4.0] });
        problem.s0 = vec![0.5];
        problem
    }

    #[test]
    fn a_rigid_body_s_entries_set_its_components_and_shape() {
        let mut p = rigid();
        let shape = ["a".to_owned()];
        apply_rigid(&mut p, &shape, &[entry("initial.Pi.2"), entry("initial.q.a")], &[7.0, 8.0]).unwrap();
        assert_eq!(p.initial, RigidInitial::Momentum { pi: [1.0, 7.0, 3.0], p: vec![4.0] });
        assert_eq!(p.s0, [8.0]);
        let why = apply_rigid(&mut p, &shape, &[entry("initial.Omega.1")], &[1.0]).unwrap_err();
        assert!(why.contains("all 4 (three of the body"), "{why}");
        let all = ["initial.Omega.1", "initial.Omega.2", "initial.Omega.3", "initial.v.a"].map(entry);
        apply_rigid(&mut p, &shape, &all, &[1.0, 2.0, 3.0, 4.0]).unwrap();
        assert_eq!(p.initial, RigidInitial::Velocity { omega: [1.0, 2.0, 3.0], v: vec![4.0] });
        let why = apply_rigid(&mut p, &shape, &[entry("initial.q.b")], &[1.0]).unwrap_err();
        assert!(why.contains("not a shape coordinate; they are a"), "{why}");
        let why = apply_rigid(&mut p, &[], &[entry("initial.q.a")], &[1.0]).unwrap_err();
        assert!(why.contains("this body has none"), "{why}");
        assert!(Entry::parse("initial.Pi.4").unwrap().unwrap_err().contains("components 1, 2 and 3"));
        assert!(Entry::parse("initial.Omega.x").unwrap().unwrap_err().contains("components 1, 2 and 3"));
        let mut q = problem();
        assert!(apply(&mut q, &names(), &[entry("initial.Pi.1")], &[1.0]).unwrap_err().contains("belongs to a rigid"));
    }
}
