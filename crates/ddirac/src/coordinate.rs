//! Coordinates: each with its name, its kind (real or angle) and its role (shape or group), and the
//! split of a system's coordinates into shape coordinates x ∈ Σ and group coordinates g ∈ G (paper
//! §2.2.1, Q = Σ × G).

/// Whether a coordinate lives on the real line or on the circle S¹ (paper §6).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CoordinateKind {
    /// A coordinate on ℝ.
    Real,
    /// An angle on S¹; the Lagrangian must be 2π-periodic in it.
    Angle,
}

/// Whether a coordinate belongs to the shape space Σ or to the symmetry group G.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// A coordinate x of the shape space Σ = Q/G.
    Shape,
    /// A coordinate g of the group G, translated by the symmetry.
    Group,
}

/// A named coordinate with its kind and role.
///
/// ```
/// use ddirac::{Coordinate, CoordinateKind, Role};
/// let theta = Coordinate::group("theta").angle();
/// assert_eq!(theta.kind, CoordinateKind::Angle);
/// assert_eq!(theta.role, Role::Group);
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Coordinate {
    /// Name used in specs and output columns.
    pub name: String,
    /// Real line or angle.
    pub kind: CoordinateKind,
    /// Shape or group.
    pub role: Role,
}

impl Coordinate {
    /// A real shape coordinate.
    pub fn shape(name: &str) -> Self {
        Self { name: name.to_owned(), kind: CoordinateKind::Real, role: Role::Shape }
    }

    /// A real group coordinate.
    pub fn group(name: &str) -> Self {
        Self { name: name.to_owned(), kind: CoordinateKind::Real, role: Role::Group }
    }

    /// The same coordinate, marked as an angle on S¹.
    pub fn angle(mut self) -> Self {
        self.kind = CoordinateKind::Angle;
        self
    }
}

/// The indices of the shape coordinates x and group coordinates g of a system.
///
/// ```
/// use ddirac::{Coordinate, Split};
/// let split = Split::new(&[Coordinate::group("a"), Coordinate::shape("b"), Coordinate::shape("c")]);
/// assert_eq!(split.shape, vec![1, 2]);
/// assert_eq!(split.group, vec![0]);
/// assert_eq!(split.x(&[7.0, 8.0, 9.0]), vec![8.0, 9.0]);
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Split {
    /// Positions of the shape coordinates, in order.
    pub shape: Vec<usize>,
    /// Positions of the group coordinates, in order.
    pub group: Vec<usize>,
}

impl Split {
    /// Reads the roles of `coordinates`.
    pub fn new(coordinates: &[Coordinate]) -> Self {
        let of = |role| coordinates.iter().enumerate().filter(|(_, c)| c.role == role).map(|(i, _)| i).collect();
        Self { shape: of(Role::Shape), group: of(Role::Group) }
    }

    /// Number of shape coordinates, dim Σ.
    pub fn n_x(&self) -> usize {
        self.shape.len()
    }

    /// Number of group coordinates, dim G.
    pub fn n_g(&self) -> usize {
        self.group.len()
    }

    /// The shape entries of a full vector.
    pub fn x<T: Copy>(&self, full: &[T]) -> Vec<T> {
        self.shape.iter().map(|&i| full[i]).collect()
    }

    /// The group entries of a full vector.
    pub fn g<T: Copy>(&self, full: &[T]) -> Vec<T> {
        self.group.iter().map(|&i| full[i]).collect()
    }

    /// The momentum map J(q, p) = p_g of the translations of the group coordinates (paper
    /// Lemma 2.1), one entry per group coordinate. It does not depend on q; the momenta of the
    /// reduced equations, (w, μ) = λ̂_d(q, p), keep p_g as μ at the same positions, so it applies to
    /// them too.
    ///
    /// ```
    /// use ddirac::{Coordinate, Split};
    /// let split = Split::new(&[Coordinate::shape("r"), Coordinate::group("phi")]);
    /// assert_eq!(split.momentum_map(&[0.5, 1.2]).collect::<Vec<_>>(), vec![1.2]);
    /// ```
    pub fn momentum_map<'a>(&'a self, p: &'a [f64]) -> impl Iterator<Item = f64> + 'a {
        self.group.iter().map(move |&i| p[i])
    }

    /// Assembles a full vector from its shape and group entries.
    pub fn join<T: Copy + Default>(&self, x: &[T], g: &[T]) -> Vec<T> {
        let mut full = vec![T::default(); self.n_x() + self.n_g()];
        self.shape.iter().zip(x).for_each(|(&i, &v)| full[i] = v);
        self.group.iter().zip(g).for_each(|(&i, &v)| full[i] = v);
        full
    }
}
