//! What each member's state is written as: the columns of `final.csv`, the `final_<part>` arrays and
//! the trajectory arrays `<part>`, for a system in coordinates (q, p) or a rigid body (R, Π, and q, p
//! of its shape coordinates when it has any).

/// The parts of a member's state.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Layout {
    /// The coordinates (of a rigid body: its shape coordinates).
    pub coordinates: Vec<String>,
    /// Whether the state holds a rigid body's attitude R and body angular momentum Π.
    pub attitude: bool,
}

/// One part of the state: its name (`final_<name>.npy`, `<name>.npy`) and the shape of one value.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Part {
    /// `q`, `p`, `R` or `Pi`.
    pub name: &'static str,
    /// The shape of one member's (or one row's) value: `[n]`, `[3, 3]` or `[3]`.
    pub shape: Vec<usize>,
}

impl Part {
    /// The number of values.
    pub fn width(&self) -> usize {
        self.shape.iter().product()
    }
}

impl Layout {
    /// The parts, in the order of `final.csv`'s columns: R and Π of a rigid body, then q and p (for a
    /// rigid body only when it has shape coordinates).
    pub fn parts(&self) -> Vec<Part> {
        let n = self.coordinates.len();
        let mut parts = vec![];
        if self.attitude {
            parts.push(Part { name: "R", shape: vec![3, 3] });
            parts.push(Part { name: "Pi", shape: vec![3] });
        }
        if !self.attitude || n > 0 {
            parts.push(Part { name: "q", shape: vec![n] });
            parts.push(Part { name: "p", shape: vec![n] });
        }
        parts
    }

    /// The number of values of one state.
    pub fn width(&self) -> usize {
        self.parts().iter().map(Part::width).sum()
    }

    /// The columns of `final.csv` after `member` and `status`: `R11` … `R33`, `Pi1` … `Pi3` of a rigid
    /// body, then the coordinates and `p_<coordinate>`.
    pub fn columns(&self) -> Vec<String> {
        let mut columns = vec![];
        if self.attitude {
            columns.extend((0..9).map(|k| format!("R{}{}", k / 3 + 1, k % 3 + 1)));
            columns.extend((1..=3).map(|i| format!("Pi{i}")));
        }
        columns.extend(self.coordinates.iter().cloned());
        columns.extend(self.coordinates.iter().map(|c| format!("p_{c}")));
        columns
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_columns_follow_the_parts() {
        let names = |l: &Layout| l.parts().iter().map(|p| p.name).collect::<Vec<_>>();
        let coordinates = Layout { coordinates: vec!["x".into(), "y".into()], attitude: false };
        assert_eq!(names(&coordinates), ["q", "p"]);
        assert_eq!(coordinates.columns(), ["x", "y", "p_x", "p_y"]);
        assert_eq!(coordinates.width(), 4);
        let free = Layout { coordinates: vec![], attitude: true };
        assert_eq!(names(&free), ["R", "Pi"]);
        assert_eq!(free.columns().len(), free.width());
        assert_eq!(free.columns()[..2], ["R11", "R12"]);
        assert_eq!(free.columns()[11], "Pi3");
        let rotor = Layout { coordinates: vec!["a".into()], attitude: true };
        assert_eq!(names(&rotor), ["R", "Pi", "q", "p"]);
        assert_eq!(rotor.columns()[12..], ["a", "p_a"]);
        assert_eq!(rotor.width(), 14);
    }
}
