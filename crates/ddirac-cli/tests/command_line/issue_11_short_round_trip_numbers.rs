//! Tiny numbers were written to trajectory.csv with about 300 characters (`0.000…0001`), huge ones
//! with all their integer digits. Every CSV number is now the shortest string that reads back as
//! the same f64: at most 24 characters, and bit for bit the value of the `.npy` column.

use crate::common;

use common::{ddirac, TempDir};

/// A harmonic oscillator started at `x0` with momentum `p0`.
fn oscillator(dir: &TempDir, x0: &str, p0: &str) -> String {
    dir.file(
        "spec.toml",
        &format!(
            r#"
[system]
shape = ["x"]
lagrangian = "0.5*x_dot^2 - 0.5*x^2"
[time]
steps = 40
duration = 4.0
[initial]
q = [{x0}]
p = [{p0}]
"#
        ),
    )
}

fn npy(path: &std::path::Path) -> Vec<f64> {
    let bytes = std::fs::read(path).unwrap();
    let header = 10 + u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    bytes[header..].chunks_exact(8).map(|c| f64::from_le_bytes(c.try_into().unwrap())).collect()
}

#[test]
fn tiny_and_huge_values_are_short_and_exact() {
    for (x0, p0) in [("1e-300", "-3e-301"), ("2.5e150", "1e149"), ("1e-320", "0.0")] {
        let dir = TempDir::new("numbers");
        let spec = oscillator(&dir, x0, p0);
        let out = dir.out();
        let output = ddirac(&["run", &spec, "--out", out.to_str().unwrap(), "--quiet", "--format", "csv,npy"], &dir.0);
        assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
        let text = std::fs::read_to_string(out.join("trajectory.csv")).unwrap();
        let mut lines = text.lines();
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
        assert_eq!(rows.len(), 41);
        for (j, name) in header.iter().enumerate() {
            let column = npy(&out.join("npy").join(format!("{name}.npy")));
            for (k, row) in rows.iter().enumerate() {
                let field = row[j];
                assert!(field.len() <= 24, "{x0}: {name}[{k}] has {} characters: {field}", field.len());
                if field.is_empty() {
                    assert!(column[k].is_nan());
                } else {
                    let value: f64 = field.parse().unwrap();
                    assert_eq!(value.to_bits(), column[k].to_bits(), "{x0}: {name}[{k}] = {field} ≠ {:e}", column[k]);
                }
            }
        }
        // The values are as tiny or huge as the initial data: x(0) is written as given.
        let x0_written = rows[0][header.iter().position(|h| *h == "x").unwrap()];
        assert_eq!(x0_written.parse::<f64>().unwrap(), x0.parse::<f64>().unwrap());
    }
}
