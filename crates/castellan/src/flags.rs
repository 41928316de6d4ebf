//! The value checks of the commands' flags, one home for each rule (issue 20): a flag's
//! `value_parser` names one of these, so every command refuses the same bad numbers with the
//! same words. Ranges that are also PROJECT.toml rules come from the libraries
//! (`plan::scale::METRES_PER_PIXEL`, `plan::scale::SCALE_BAR_METRES`).

use std::ops::RangeInclusive;

/// Any finite number.
pub fn finite(s: &str) -> Result<f64, String> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("'{s}' is not a number"))?;
    if !v.is_finite() {
        return Err(format!("'{s}' is not a finite number"));
    }
    Ok(v)
}

/// A finite number above 0.
pub fn positive(s: &str) -> Result<f64, String> {
    let v = finite(s)?;
    if v <= 0.0 {
        return Err(format!("'{s}' must be positive"));
    }
    Ok(v)
}

/// A finite number, 0 or above.
pub fn nonnegative(s: &str) -> Result<f64, String> {
    let v = finite(s)?;
    if v < 0.0 {
        return Err(format!("'{s}' must not be negative"));
    }
    Ok(v)
}

/// A fraction from 0 to 1.
pub fn fraction(s: &str) -> Result<f64, String> {
    let v = finite(s)?;
    if !(0.0..=1.0).contains(&v) {
        return Err(format!("the fraction must be between 0 and 1, found '{s}'"));
    }
    Ok(v)
}

/// A drawing scale in metres per pixel, within the plausible range of every scale a user gives.
pub fn metres_per_pixel(s: &str) -> Result<f64, String> {
    within(
        s,
        &plan::scale::METRES_PER_PIXEL,
        "scale in metres per pixel",
    )
}

/// The length in metres of a drawn scale bar.
pub fn scale_bar_metres(s: &str) -> Result<f64, String> {
    within(
        s,
        &plan::scale::SCALE_BAR_METRES,
        "scale-bar length in metres",
    )
}

fn within(s: &str, range: &RangeInclusive<f64>, unit: &str) -> Result<f64, String> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("'{s}' is not a number"))?;
    plan::scale::check_range(v, range, unit)?;
    Ok(v)
}

/// The per-pixel classifier of the façade stages (§3.1.3–3.1.4): `forest` (the default, a
/// filter bank and random forest, issue 21) or `gmm` (the text's Gaussian mixtures).
pub fn classifier(s: &str) -> Result<facade::classify::Method, String> {
    serde_json::from_value(serde_json::Value::String(s.trim().to_string())).map_err(|_| {
        format!(
            "'{s}' is not a classifier: use forest (the default) or gmm (§3.1.3–3.1.4's mixtures)"
        )
    })
}

/// How the plan's walls are read (ch. 5): `learned` (the default, the learned wall ink of
/// issue 26), `network` (the wall-ink network, issue 26) or `rules` (§5.1.2's threshold with
/// the hand-tuned clean-up of issue 11).
pub fn ink(s: &str) -> Result<plan::ink::InkMethod, String> {
    serde_json::from_value(serde_json::Value::String(s.trim().to_string())).map_err(|_| {
        format!("'{s}' is not a way to read walls: use learned (the default), network or rules")
    })
}

/// An odd window side from 3 to 101 pixels (§2.1.1's W × W neighbourhood).
pub fn odd_window(s: &str) -> Result<usize, String> {
    let w: usize = s
        .trim()
        .parse()
        .map_err(|_| format!("'{s}' is not a whole number"))?;
    if w < 3 || w.is_multiple_of(2) || w > 101 {
        return Err(format!("the window must be odd, from 3 to 101 (found {w})"));
    }
    Ok(w)
}

/// What each command's flag tests parse with: one command's flags alone, without the command
/// tree (`cli.rs` names every command; the commands' tests need not know it).
#[cfg(test)]
pub mod testing {
    use clap::{Args, Parser};

    #[derive(Parser)]
    struct One<A: Args> {
        #[command(flatten)]
        args: A,
    }

    /// `argv`: the command's arguments, after `castellan COMMAND`.
    pub fn parse<A: Args>(argv: &[&str]) -> Result<A, clap::Error> {
        One::<A>::try_parse_from(std::iter::once("castellan").chain(argv.iter().copied()))
            .map(|one| one.args)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_must_be_finite() {
        assert_eq!(finite(" -2.5 "), Ok(-2.5));
        assert_eq!(finite("x"), Err("'x' is not a number".into()));
        assert_eq!(finite("inf"), Err("'inf' is not a finite number".into()));
        assert!(finite("NaN").is_err());
    }

    #[test]
    fn signs_are_checked() {
        assert_eq!(positive("0.1"), Ok(0.1));
        assert_eq!(positive("0"), Err("'0' must be positive".into()));
        assert_eq!(nonnegative("0"), Ok(0.0));
        assert_eq!(nonnegative("-1"), Err("'-1' must not be negative".into()));
    }

    #[test]
    fn fractions_lie_between_0_and_1() {
        assert_eq!(fraction("0"), Ok(0.0));
        assert_eq!(fraction("1"), Ok(1.0));
        assert!(fraction("1.01").is_err());
        assert!(fraction("nan").is_err());
    }

    #[test]
    fn scales_use_the_library_ranges() {
        assert_eq!(metres_per_pixel("0.05"), Ok(0.05));
        let e = metres_per_pixel("1e300").unwrap_err();
        assert!(
            e.contains("not a plausible scale in metres per pixel"),
            "{e}"
        );
        assert!(metres_per_pixel("1e-9").is_err());
        assert_eq!(scale_bar_metres("30"), Ok(30.0));
        assert!(scale_bar_metres("0").is_err());
    }

    #[test]
    fn windows_are_odd_and_bounded() {
        assert_eq!(odd_window("7"), Ok(7));
        assert!(odd_window("8").is_err());
        assert!(odd_window("1").is_err());
        assert!(odd_window("103").is_err());
        assert!(odd_window("seven").is_err());
    }
}
