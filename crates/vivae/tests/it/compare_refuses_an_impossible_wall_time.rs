//! `vivae compare` on a `timing.csv` whose seconds add up to more than a real
//! run's (issue 24: 1e307 s made it hang drawing the axes) refuses it at once:
//! exit 2, one line naming the file and the line, nothing written. The limit
//! is 1e9 s (about 32 years) in all, up to each line.

use crate::common::*;

#[test]
fn timing_beyond_1e9_seconds_in_all_is_refused_naming_file_and_line() {
    let dir = scratch("compare-huge-time");
    let config = write_small_config(&dir, 2);
    let run_dir = dir.join("run");
    evolve(&config, &run_dir, &[]);
    let timing = run_dir.join("timing.csv");
    let text = String::from_utf8(read(&run_dir, "timing.csv")).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let with_seconds = |line: &str, seconds: &str| {
        let f: Vec<&str> = line.split(',').collect();
        format!("{},{seconds},{}", f[0], f[2])
    };
    let out = dir.join("cmp.png");
    for (first, second, bad_line) in [
        // Each below the limit, their sum above it (first: today's code drew
        // this, and would hang on the next ones).
        ("6e8", "6e8", 3),
        ("1", "1e307", 3),
        ("1e307", "1", 2),
    ] {
        let forged = format!(
            "{}\n{}\n{}\n",
            lines[0],
            with_seconds(lines[1], first),
            with_seconds(lines[2], second)
        );
        std::fs::write(&timing, forged).unwrap();
        let result = run(vivae().arg("compare").arg(&run_dir).arg("-o").arg(&out));
        let err = String::from_utf8_lossy(&result.stderr);
        assert_eq!(result.status.code(), Some(2), "{err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains("timing.csv"), "{err}");
        assert!(err.contains(&format!("line {bad_line}")), "{err}");
        assert!(!out.exists());
    }
    // Up to the limit is drawn.
    let forged = format!(
        "{}\n{}\n{}\n",
        lines[0],
        with_seconds(lines[1], "5e8"),
        with_seconds(lines[2], "5e8")
    );
    std::fs::write(&timing, forged).unwrap();
    ok(vivae().arg("compare").arg(&run_dir).arg("-o").arg(&out));
    assert!(out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
