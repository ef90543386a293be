//! The method keys: their names, defaults and rules, shared by a spec's `[method]` table and the
//! Python package's `simulate(..., **method keys)`.
//!
//! | key | value | default |
//! |---|---|---|
//! | `rule` | `left`, `right`, `midpoint`, `trapezoid` | `midpoint` |
//! | `variant` | `plus`, `minus` | `plus` |
//! | `reduced` | reduced equations, group motion reconstructed | false |
//! | `connection` | K = h_(d,Σ): one row per group coordinate, one column per shape coordinate | zeros |
//! | `tolerance` | Newton's tolerance, positive | 1e-12 |
//! | `max_iterations` | Newton's corrections per solve, at least 1 | 50 |
//! | `jacobian` | `reuse` (chord Newton) or `fresh` (classical Newton) | `reuse` |
//! | `derivatives` | `auto`, `compiled`, `dual` | `auto` |
//! | `check_invariance` | test the invariance of L_d before a reduced run | true |
//! | `on_energy_jump` | `warn`, `error`, `ignore` | `warn` |
//! | `energy_jump_threshold` | smallest relative change that may count as a jump, positive | 1e-3 |
//! | `order` | 2, 4, 6, 8 | 2 |
//! | `composition` | `suzuki` (4), `kahan-li` (6, 8), `triple-jump` (4, 6, 8) | by the order |
//! | `atlas` | switch charts of the system's atlas | true |
//! | `sensitivities` | propagate the tangent map d(q_N, p_N)/d(q_0, p_0) | false |
//!
//! The defaults are those of [`ddirac::Method::default`].

use ddirac::composition::{self, Composition};
use ddirac::{
    Connection, Coordinate, Differentiation, EnergyJump, JumpAction, Method, NewtonOptions, Role, Rule, Variant,
};

use super::{finite, KeyError, Spelling};

/// The method keys as a front end read them; `None` for a key not given (its default).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MethodKeys {
    /// `rule`.
    pub rule: Option<String>,
    /// `variant`.
    pub variant: Option<String>,
    /// `reduced`.
    pub reduced: Option<bool>,
    /// `connection`: the rows of K.
    pub connection: Option<Vec<Vec<f64>>>,
    /// `tolerance`.
    pub tolerance: Option<f64>,
    /// `max_iterations`.
    pub max_iterations: Option<i64>,
    /// `jacobian`.
    pub jacobian: Option<String>,
    /// `derivatives`.
    pub derivatives: Option<String>,
    /// `check_invariance`.
    pub check_invariance: Option<bool>,
    /// `on_energy_jump`.
    pub on_energy_jump: Option<String>,
    /// `energy_jump_threshold`.
    pub energy_jump_threshold: Option<f64>,
    /// `order`.
    pub order: Option<i64>,
    /// `composition`.
    pub composition: Option<String>,
    /// `atlas`.
    pub atlas: Option<bool>,
    /// `sensitivities`.
    pub sensitivities: Option<bool>,
}

impl MethodKeys {
    /// Every key of `method`, as a spec would write it to give that method: [`method`] of these keys
    /// is `method` again.
    pub fn of(method: &Method) -> Self {
        MethodKeys {
            rule: Some(method.rule.name().to_owned()),
            variant: Some(method.variant.name().to_owned()),
            reduced: Some(method.reduced),
            connection: method.connection.as_ref().map(Connection::rows),
            tolerance: Some(method.newton.tolerance),
            max_iterations: Some(method.newton.max_iterations as i64),
            jacobian: Some(if method.newton.reuse_jacobian { "reuse" } else { "fresh" }.to_owned()),
            derivatives: Some(method.differentiation.name().to_owned()),
            check_invariance: Some(method.check_invariance),
            on_energy_jump: Some(method.energy_jump.action.name().to_owned()),
            energy_jump_threshold: Some(method.energy_jump.threshold),
            order: Some(i64::from(method.composition.order())),
            composition: Some(method.composition.name().to_owned()),
            atlas: Some(method.atlas),
            sensitivities: Some(method.sensitivities),
        }
    }
}

/// A method key, or a part of the connection's value that a refusal points at.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MethodKey {
    /// `rule`.
    Rule,
    /// `variant`.
    Variant,
    /// `reduced`.
    Reduced,
    /// `connection`, the whole matrix.
    Connection,
    /// Row `i` (from 0) of the connection.
    ConnectionRow(usize),
    /// Entry (row, column) of the connection, from 0.
    ConnectionEntry(usize, usize),
    /// `tolerance`.
    Tolerance,
    /// `max_iterations`.
    MaxIterations,
    /// `jacobian`.
    Jacobian,
    /// `derivatives`.
    Derivatives,
    /// `check_invariance`.
    CheckInvariance,
    /// `on_energy_jump`.
    OnEnergyJump,
    /// `energy_jump_threshold`.
    EnergyJumpThreshold,
    /// `order`.
    Order,
    /// `composition`.
    Composition,
    /// `atlas`.
    Atlas,
    /// `sensitivities`.
    Sensitivities,
}

impl MethodKey {
    /// Every key, in the order of the table above.
    pub const ALL: [MethodKey; 15] = [
        MethodKey::Rule,
        MethodKey::Variant,
        MethodKey::Reduced,
        MethodKey::Connection,
        MethodKey::Tolerance,
        MethodKey::MaxIterations,
        MethodKey::Jacobian,
        MethodKey::Derivatives,
        MethodKey::CheckInvariance,
        MethodKey::OnEnergyJump,
        MethodKey::EnergyJumpThreshold,
        MethodKey::Order,
        MethodKey::Composition,
        MethodKey::Atlas,
        MethodKey::Sensitivities,
    ];

    /// The key's name (`tolerance`); a part of the connection is `connection`.
    pub fn name(self) -> &'static str {
        match self {
            MethodKey::Rule => "rule",
            MethodKey::Variant => "variant",
            MethodKey::Reduced => "reduced",
            MethodKey::Connection | MethodKey::ConnectionRow(_) | MethodKey::ConnectionEntry(..) => "connection",
            MethodKey::Tolerance => "tolerance",
            MethodKey::MaxIterations => "max_iterations",
            MethodKey::Jacobian => "jacobian",
            MethodKey::Derivatives => "derivatives",
            MethodKey::CheckInvariance => "check_invariance",
            MethodKey::OnEnergyJump => "on_energy_jump",
            MethodKey::EnergyJumpThreshold => "energy_jump_threshold",
            MethodKey::Order => "order",
            MethodKey::Composition => "composition",
            MethodKey::Atlas => "atlas",
            MethodKey::Sensitivities => "sensitivities",
        }
    }

    /// The key as `spelling` writes it, in backquotes: `` `method.tolerance` `` or `` `tolerance` ``.
    pub fn spelled(self, spelling: Spelling) -> String {
        match spelling {
            Spelling::Spec => format!("`method.{}`", self.name()),
            Spelling::Argument => format!("`{}`", self.name()),
        }
    }
}

/// The method of `keys`, each key not given at its default; `coordinates` are the system's (the
/// connection's rows and columns follow its group and shape coordinates).
pub fn method(
    keys: &MethodKeys,
    coordinates: &[Coordinate],
    spelling: Spelling,
) -> Result<Method, KeyError<MethodKey>> {
    let key = |k: MethodKey| k.spelled(spelling);
    let defaults = Method::default();
    let rule =
        match &keys.rule {
            Some(r) => Rule::from_name(r).ok_or_else(|| {
                let names: Vec<&str> = Rule::ALL.iter().map(|r| r.name()).collect();
                KeyError::at(MethodKey::Rule, format!("unknown rule `{r}`"), "not a quadrature rule")
                    .with_help(format!("{} is one of: {}", key(MethodKey::Rule), names.join(", ")))
            })?,
            None => defaults.rule,
        };
    let variant = match keys.variant.as_deref() {
        Some("plus") => Variant::Plus,
        Some("minus") => Variant::Minus,
        Some(other) => {
            return Err(KeyError::at(MethodKey::Variant, format!("unknown variant `{other}`"), "not a variant")
                .with_help(format!("{} is `plus` or `minus`", key(MethodKey::Variant))))
        }
        None => defaults.variant,
    };
    let tolerance = match keys.tolerance {
        Some(t) => positive(MethodKey::Tolerance, t, spelling)?,
        None => defaults.newton.tolerance,
    };
    let max_iterations = match keys.max_iterations {
        Some(n) if n >= 1 => n as usize,
        Some(n) => {
            return Err(KeyError::at(
                MethodKey::MaxIterations,
                format!("{} must be at least 1", key(MethodKey::MaxIterations)),
                n.to_string(),
            ))
        }
        None => defaults.newton.max_iterations,
    };
    let reuse_jacobian = match keys.jacobian.as_deref() {
        Some("reuse") => true,
        Some("fresh") => false,
        Some(other) => {
            return Err(KeyError::at(MethodKey::Jacobian, format!("unknown Jacobian policy `{other}`"), "not a policy")
                .with_help(format!(
                    "{} is `reuse` (one Jacobian per step, chord Newton) or `fresh` (classical Newton)",
                    key(MethodKey::Jacobian)
                )))
        }
        None => defaults.newton.reuse_jacobian,
    };
    let differentiation = match &keys.derivatives {
        Some(d) => Differentiation::from_name(d).ok_or_else(|| {
            KeyError::at(MethodKey::Derivatives, format!("unknown derivative evaluation `{d}`"), "not a choice")
                .with_help(format!(
                    "{} is `auto` (compiled when the Lagrangian allows it), `compiled` or `dual`",
                    key(MethodKey::Derivatives)
                ))
        })?,
        None => defaults.differentiation,
    };
    let action = match &keys.on_energy_jump {
        Some(a) => JumpAction::from_name(a).ok_or_else(|| {
            KeyError::at(MethodKey::OnEnergyJump, format!("unknown action `{a}`"), "not an action")
                .with_help(format!("{} is `warn` (default), `error` or `ignore`", key(MethodKey::OnEnergyJump)))
        })?,
        None => defaults.energy_jump.action,
    };
    let threshold = match keys.energy_jump_threshold {
        Some(t) => positive(MethodKey::EnergyJumpThreshold, t, spelling)?,
        None => defaults.energy_jump.threshold,
    };
    let composition = composition_of(keys, spelling)?;
    let connection = match &keys.connection {
        Some(rows) => {
            let rows = connection_rows(rows, coordinates, spelling)?;
            Some(
                Connection::new(&rows)
                    .map_err(|e| KeyError::at(MethodKey::Connection, e.to_string(), "this connection"))?,
            )
        }
        None => None,
    };
    Ok(Method {
        rule,
        variant,
        reduced: keys.reduced.unwrap_or(defaults.reduced),
        connection,
        newton: NewtonOptions { tolerance, max_iterations, reuse_jacobian },
        check_invariance: keys.check_invariance.unwrap_or(defaults.check_invariance),
        differentiation,
        energy_jump: EnergyJump { threshold, action },
        composition,
        atlas: keys.atlas.unwrap_or(defaults.atlas),
        sensitivities: keys.sensitivities.unwrap_or(defaults.sensitivities),
    })
}

/// A finite positive value of `key`.
fn positive(key: MethodKey, value: f64, spelling: Spelling) -> Result<f64, KeyError<MethodKey>> {
    let v = finite(key, value, &key.spelled(spelling))?;
    if v > 0.0 {
        Ok(v)
    } else {
        Err(KeyError::at(key, format!("{} must be positive", key.spelled(spelling)), format!("{v}")))
    }
}

/// `order` and `composition`: the composition of a step.
fn composition_of(keys: &MethodKeys, spelling: Spelling) -> Result<Composition, KeyError<MethodKey>> {
    let order = match keys.order {
        Some(o) => match u8::try_from(o) {
            Ok(order) if composition::ORDERS.contains(&order) => Some(order),
            _ => {
                return Err(KeyError::at(MethodKey::Order, format!("there is no method of order {o}"), "not an order")
                    .with_help(format!(
                        "{} is 2 (the basic step), 4, 6 or 8 (compositions of it)",
                        MethodKey::Order.spelled(spelling)
                    )))
            }
        },
        None => None,
    };
    Composition::select(order, keys.composition.as_deref()).map_err(|why| {
        // Without a composition key, the refusal is the order's.
        let key = if keys.composition.is_some() { MethodKey::Composition } else { MethodKey::Order };
        KeyError::at(key, why, "this composition").with_help(format!(
            "{} is `suzuki` (order 4), `kahan-li` (orders 6, 8) or `triple-jump` (orders 4, 6, 8)",
            MethodKey::Composition.spelled(spelling)
        ))
    })
}

/// K's rows, checked against the system: one row per group coordinate, one finite entry per shape
/// coordinate.
fn connection_rows(
    rows: &[Vec<f64>],
    coordinates: &[Coordinate],
    spelling: Spelling,
) -> Result<Vec<Vec<f64>>, KeyError<MethodKey>> {
    let key = MethodKey::Connection.spelled(spelling);
    let of = |role| coordinates.iter().filter(|c| c.role == role).map(|c| c.name.as_str()).collect::<Vec<_>>();
    let (shape, group) = (of(Role::Shape), of(Role::Group));
    let expected = format!(
        "K = h_(d,Σ) has one row per group coordinate ({}) and one column per shape coordinate ({}): {} × {}",
        group.join(", "),
        shape.join(", "),
        group.len(),
        shape.len()
    );
    if rows.len() != group.len() {
        return Err(KeyError::at(
            MethodKey::Connection,
            format!("{key} has {} rows, expected {}", rows.len(), group.len()),
            "wrong number of rows",
        )
        .with_help(expected));
    }
    for (j, row) in rows.iter().enumerate() {
        if row.len() != shape.len() {
            return Err(KeyError::at(
                MethodKey::ConnectionRow(j),
                format!("row {} of {key} has {} entries, expected {}", j + 1, row.len(), shape.len()),
                format!("row for `{}`", group[j]),
            )
            .with_help(expected));
        }
        for (i, &x) in row.iter().enumerate() {
            finite(MethodKey::ConnectionEntry(j, i), x, &format!("an entry of {key}"))?;
        }
    }
    Ok(rows.to_vec())
}
