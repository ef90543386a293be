//! Entries of the initial data set by name: `--set initial.q.phi1=0.3` and the members of an
//! ensemble (`initial.q.<coordinate>`, `initial.p.<coordinate>`, `initial.v.<coordinate>`).
//!
//! They are applied to the validated problem, by coordinate name, whether the spec writes its
//! vectors in coordinate order (`q = [0, 1]`) or by name (`q = { x = 0, y = 1 }`), so that a member
//! of an ensemble and `ddirac run --set` with the same values start from the same numbers.
//! An entry of the spec's own momentum vector (`p` or `v`) replaces that entry; the other vector
//! replaces the spec's only when every coordinate's entry is given.

use ddirac::{InitialMomentum, Problem};

/// Which initial vector an entry belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Vector {
    /// `initial.q`.
    Q,
    /// `initial.p`.
    P,
    /// `initial.v`.
    V,
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
            _ => return None,
        };
        let name = name.trim().trim_matches('"');
        if name.is_empty() {
            return Some(Err(format!("`{key}` names no coordinate")));
        }
        Some(Ok(Self { vector, coordinate: name.to_owned() }))
    }

    /// The key as `--set` writes it.
    pub fn key(&self) -> String {
        let vector = match self.vector {
            Vector::Q => "q",
            Vector::P => "p",
            Vector::V => "v",
        };
        format!("initial.{vector}.{}", self.coordinate)
    }
}

/// Refuses entries of both momentum vectors, and entries of the one the spec does not give (p where
/// it gives v, or v where it gives p) unless all `n` of them are given.
pub fn check_kinds(entries: &[Entry], problem: &Problem, n: usize) -> Result<(), String> {
    let given = |vector: Vector| entries.iter().any(|e| e.vector == vector);
    if given(Vector::P) && given(Vector::V) {
        return Err("entries of `initial.p` and of `initial.v` are given together: a run starts from momenta or \
                    from velocities, so give entries of one of them"
            .into());
    }
    let (given, other, other_name) = match problem.initial {
        InitialMomentum::Momentum(_) => ("p", Vector::V, "v"),
        InitialMomentum::Velocity(_) => ("v", Vector::P, "p"),
    };
    let count = entries.iter().filter(|e| e.vector == other).count();
    if count > 0 && count < n {
        return Err(format!(
            "the spec gives `initial.{given}`; entries of `initial.{other_name}` replace it only when all {n} \
             coordinates are given ({count} are): set `initial.{given}.<coordinate>` instead"
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
}
