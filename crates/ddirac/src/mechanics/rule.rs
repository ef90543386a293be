//! The quadrature rules that turn a Lagrangian L(q, v) into a discrete Lagrangian L_d(q0, q1)
//! ([`crate::DiscreteLagrangian`]; paper §7).

/// The quadrature rule that turns L(q, v) into L_d(q0, q1).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rule {
    /// h L(q0, (q1 − q0)/h)
    Left,
    /// h L(q1, (q1 − q0)/h)
    Right,
    /// h L((q0 + q1)/2, (q1 − q0)/h)
    Midpoint,
    /// h/2 [L(q0, v) + L(q1, v)], v = (q1 − q0)/h
    Trapezoid,
}

impl Rule {
    /// All rules, in the order of the table above.
    pub const ALL: [Rule; 4] = [Rule::Left, Rule::Right, Rule::Midpoint, Rule::Trapezoid];

    /// The rule's name in specs: `left`, `right`, `midpoint`, `trapezoid`.
    pub fn name(self) -> &'static str {
        match self {
            Rule::Left => "left",
            Rule::Right => "right",
            Rule::Midpoint => "midpoint",
            Rule::Trapezoid => "trapezoid",
        }
    }

    /// Parses a rule name.
    ///
    /// ```
    /// assert_eq!(ddirac::Rule::from_name("midpoint"), Some(ddirac::Rule::Midpoint));
    /// assert_eq!(ddirac::Rule::from_name("simpson"), None);
    /// ```
    pub fn from_name(name: &str) -> Option<Rule> {
        Rule::ALL.into_iter().find(|r| r.name() == name)
    }
}
