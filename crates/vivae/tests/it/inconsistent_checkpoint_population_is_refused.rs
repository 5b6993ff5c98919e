//! A checkpoint that is intact (its checksum matches) but whose population is
//! inconsistent stops `resume` with exit 2 and one line naming the file and
//! what is wrong: the population validates itself as it is read.

use crate::common::*;

#[test]
fn a_checksummed_but_inconsistent_population_is_refused() {
    let dir = scratch("inconsistent-ckpt");
    let config = write_small_config(&dir, 2);
    let run_dir = dir.join("run");
    evolve(&config, &run_dir, &[]);
    let ckpt = run_dir.join("checkpoints/gen-000002.ckpt");
    let good = std::fs::read_to_string(&ckpt).unwrap();
    let (header, body) = good.split_once('\n').unwrap();
    // What the program writes, with the checksum of the current format.
    assert_eq!(good, vivae_lab::rundir::seal_checkpoint(body), "{header}");

    // Each edit keeps the JSON well formed; the checksum is recomputed.
    let edits: [(&str, &str, &str, &str); 3] = [
        // A link to a node that does not exist (the first link of the first genome).
        (
            r#""genomes":[{"nodes":"#,
            r#""to":"#,
            r#""to":9999,"#,
            "missing node",
        ),
        // Counters below the ids in use.
        (
            r#""next_species_id":"#,
            "",
            r#""next_species_id":0,"#,
            "next_species_id",
        ),
        // No genomes at all.
        (r#""genomes":["#, "", r#""genomes":[],"#, "no genomes"),
    ];
    for (anchor, field, replacement, expect) in edits {
        let start = body.find(anchor).expect("anchor in checkpoint");
        let (from, to) = if field.is_empty() {
            // Replace the anchor's whole value (up to its closing bracket or comma).
            let value_start = start + anchor.len();
            let end = if anchor.ends_with('[') {
                matching_bracket(body, value_start - 1) + 2
            } else {
                value_start + body[value_start..].find(',').unwrap() + 1
            };
            (start, end)
        } else {
            let at = start + body[start..].find(field).unwrap();
            let end = at + body[at..].find(',').unwrap() + 1;
            (at, end)
        };
        let edited = format!("{}{}{}", &body[..from], replacement, &body[to..]);
        assert_ne!(edited, body);
        let text = vivae_lab::rundir::seal_checkpoint(&edited);
        std::fs::write(&ckpt, &text).unwrap();
        let out = run(vivae()
            .args(["resume", "-q", "--generations", "3"])
            .arg(&run_dir));
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{expect}: {stderr}");
        assert_eq!(stderr.trim().lines().count(), 1, "{expect}: {stderr}");
        assert!(stderr.contains("gen-000002.ckpt"), "{expect}: {stderr}");
        assert!(stderr.contains(expect), "{expect}: {stderr}");
        assert!(!stderr.contains("panicked"), "{expect}: {stderr}");
    }
    // The untouched checkpoint still resumes.
    std::fs::write(&ckpt, &good).unwrap();
    let out = run(vivae()
        .args(["resume", "-q", "--generations", "3"])
        .arg(&run_dir));
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Index of the bracket closing the one at `open` (JSON without brackets in strings).
fn matching_bracket(text: &str, open: usize) -> usize {
    let mut depth = 0usize;
    for (i, c) in text[open..].char_indices() {
        match c {
            '[' | '{' => depth += 1,
            ']' | '}' => {
                depth -= 1;
                if depth == 0 {
                    return open + i;
                }
            }
            _ => {}
        }
    }
    panic!("unbalanced JSON");
}
