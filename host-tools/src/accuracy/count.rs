//! Instructions per frame, counted exactly by callgrind: the command runs itself under valgrind
//! once per configuration (`accuracy-count LABEL`, a hidden subcommand), and only the call of
//! [`super::config::counted_frame`] is collected.

use std::path::Path;
use std::process::Command;

/// The count of one configuration's M1 frame.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Count {
    /// Instructions of the counted frame.
    pub instructions: u64,
    /// What the frame drew (the child's own line).
    pub note: String,
}

/// Checks that valgrind runs; the error says how to install it.
pub fn check_valgrind() -> Result<String, String> {
    let out = Command::new("valgrind")
        .arg("--version")
        .output()
        .map_err(|e| {
            format!(
                "valgrind is needed to count instructions ({e}); install it (e.g. \
             `apt-get install valgrind`) or pass --no-count to leave the column empty"
            )
        })?;
    Ok(String::from_utf8_lossy(&out.stdout).trim().to_string())
}

/// Runs `exe accuracy-count LABEL` under callgrind and reads the total it collected.
pub fn count(exe: &Path, label: &str, models: &[String], scratch: &Path) -> Result<Count, String> {
    let out_file = scratch.join(format!("callgrind.{label}.out"));
    let mut cmd = Command::new("valgrind");
    cmd.arg("--tool=callgrind")
        .arg("--toggle-collect=*counted_frame*")
        .arg(format!("--callgrind-out-file={}", out_file.display()))
        .arg(exe)
        .arg("accuracy-count")
        .arg(label);
    for m in models {
        cmd.arg("--models").arg(m);
    }
    let run = cmd
        .output()
        .map_err(|e| format!("cannot run valgrind: {e}"))?;
    if !run.status.success() {
        return Err(format!(
            "callgrind run of {label} failed: {}",
            String::from_utf8_lossy(&run.stderr).trim()
        ));
    }
    let text =
        std::fs::read_to_string(&out_file).map_err(|e| format!("{}: {e}", out_file.display()))?;
    let _ = std::fs::remove_file(&out_file);
    let instructions =
        parse_total(&text).ok_or_else(|| format!("no totals in {}", out_file.display()))?;
    Ok(Count {
        instructions,
        note: String::from_utf8_lossy(&run.stdout).trim().to_string(),
    })
}

/// The collected instruction count of a callgrind output file: its `totals:` line, or its
/// `summary:` line (the first number: events are listed with `Ir` first).
pub fn parse_total(text: &str) -> Option<u64> {
    let find = |key: &str| {
        text.lines()
            .find_map(|l| l.strip_prefix(key))
            .and_then(|rest| rest.split_whitespace().next())
            .and_then(|n| n.parse().ok())
    };
    find("totals:").or_else(|| find("summary:"))
}

#[cfg(test)]
mod tests {
    use super::parse_total;

    #[test]
    fn reads_totals_or_summary() {
        assert_eq!(
            parse_total("events: Ir\nfn=x\n1 2\ntotals: 6942538\n"),
            Some(6_942_538)
        );
        assert_eq!(parse_total("events: Ir\nsummary: 12 \n"), Some(12));
        assert_eq!(parse_total("events: Ir\n"), None);
    }
}
