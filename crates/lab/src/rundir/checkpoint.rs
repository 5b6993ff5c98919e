//! Checkpoint files: their sealed format (a header line with a checksum of
//! the body), the newest one, pruning. What a checkpoint's body holds (the
//! search and the task's progress) is the run's ([`crate::run`]).

use std::sync::atomic::{AtomicUsize, Ordering};

use super::*;

/// The header of the first checkpoint format: its checksum is [`fnv1a`] of the body.
const CHECKPOINT_MAGIC_V1: &str = "vivae-checkpoint v1";

/// The header of checkpoints written now: its checksum is [`fnv1a_words`]
/// of the body (the body is the same JSON as in v1).
pub(crate) const CHECKPOINT_MAGIC: &str = "vivae-checkpoint v2";

/// FNV-1a over the body's 8-byte little-endian words (the last one padded
/// with zeros), then its length: the checksum of a v2 checkpoint.
///
/// A checkpoint after every generation hashed a megabyte each time, and
/// FNV-1a over bytes is one multiply per byte in a dependent chain (1.3 ms
/// a checkpoint of the default run); over words it is an eighth of that.
/// Each step is a bijection of the running hash, so a change of any one
/// word always changes the checksum, as with bytes.
pub fn fnv1a_words(bytes: &[u8]) -> u64 {
    const PRIME: u64 = 0x0100_0000_01b3;
    let mut chunks = bytes.chunks_exact(8);
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for c in &mut chunks {
        let w = u64::from_le_bytes(c.try_into().expect("8 bytes"));
        h = (h ^ w).wrapping_mul(PRIME);
    }
    let rest = chunks.remainder();
    if !rest.is_empty() {
        let mut last = [0u8; 8];
        last[..rest.len()].copy_from_slice(rest);
        h = (h ^ u64::from_le_bytes(last)).wrapping_mul(PRIME);
    }
    (h ^ bytes.len() as u64).wrapping_mul(PRIME)
}

/// `body` (a checkpoint's JSON) behind the header of the current format:
/// the bytes of a checkpoint file (for tests and tools that edit one).
pub fn seal_checkpoint(body: &str) -> String {
    header(fnv1a_words(body.as_bytes())) + body
}

/// The header line of a current-format checkpoint whose body hashes to
/// `checksum` (always the same length: the checksum has 16 digits).
pub(crate) fn header(checksum: u64) -> String {
    format!("{CHECKPOINT_MAGIC} {checksum:016x}\n")
}

/// The bytes of a checkpoint whose body `write_body` writes, behind the
/// header of the current format.
pub(crate) fn seal_with(write_body: impl FnOnce(&mut Vec<u8>) -> Result<()>) -> Result<Vec<u8>> {
    // The header's checksum is filled in once the body is written after
    // it: the body is neither copied nor reallocated for the header.
    // The last checkpoint's size: the next one is about as large.
    static LAST_LEN: AtomicUsize = AtomicUsize::new(0);
    let placeholder = header(0);
    let mut out =
        Vec::with_capacity(LAST_LEN.load(Ordering::Relaxed).max(placeholder.len()) + 4096);
    out.extend_from_slice(placeholder.as_bytes());
    write_body(&mut out)?;
    let sealed = header(fnv1a_words(&out[placeholder.len()..]));
    out[..placeholder.len()].copy_from_slice(sealed.as_bytes());
    LAST_LEN.store(out.len(), Ordering::Relaxed);
    Ok(out)
}

/// The body of checkpoint `text` (either format), its checksum checked;
/// errors name `path`.
pub(crate) fn unseal<'a>(text: &'a str, path: &Path) -> Result<&'a str> {
    let bad = |why: &str| Error::Checkpoint {
        path: path.to_path_buf(),
        reason: why.to_string(),
    };
    let (header, body) = text
        .split_once('\n')
        .ok_or_else(|| bad("not a vivae checkpoint (no header line)"))?;
    // Checkpoints of either format resume: only the checksum differs.
    let (checksum, hash): (&str, fn(&[u8]) -> u64) =
        if let Some(c) = header.strip_prefix(CHECKPOINT_MAGIC) {
            (c, fnv1a_words)
        } else if let Some(c) = header.strip_prefix(CHECKPOINT_MAGIC_V1) {
            (c, fnv1a)
        } else {
            return Err(bad("not a vivae checkpoint (bad header)"));
        };
    let expected = u64::from_str_radix(checksum.trim(), 16)
        .map_err(|_| bad("not a vivae checkpoint (bad checksum field)"))?;
    if hash(body.as_bytes()) != expected {
        return Err(bad("corrupt or truncated checkpoint (checksum mismatch)"));
    }
    Ok(body)
}

/// Path of the newest checkpoint in a run directory.
pub fn latest_checkpoint(run_dir: &Path) -> Result<PathBuf> {
    let dir = run_dir.join(files::CHECKPOINTS);
    let entries = fs::read_dir(&dir).map_err(|e| Error::Checkpoint {
        path: run_dir.to_path_buf(),
        reason: format!(
            "not a vivae run directory ({}: {})",
            files::CHECKPOINTS,
            crate::io::io_reason(&e)
        ),
    })?;
    checkpoint_names(entries)
        .pop()
        .map(|n| dir.join(n))
        .ok_or_else(|| Error::Checkpoint {
            path: dir.clone(),
            reason: "no checkpoint to resume from".into(),
        })
}

/// Writes checkpoint `bytes` of generation `done` into the run directory
/// `dir` (atomically) and prunes all but the newest `keep` checkpoints.
pub(crate) fn write_checkpoint_bytes(
    dir: &Path,
    done: u32,
    keep: usize,
    bytes: &[u8],
) -> Result<()> {
    let dir = dir.join(files::CHECKPOINTS);
    let path = dir.join(format!("gen-{done:06}.ckpt"));
    write_atomic(&path, bytes)?;
    prune_checkpoints(&dir, keep)
}

/// Checkpoint file names in a listing, oldest first (names sort by generation).
pub(crate) fn checkpoint_names(entries: fs::ReadDir) -> Vec<String> {
    let mut names: Vec<String> = entries
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("gen-") && n.ends_with(".ckpt"))
        .collect();
    names.sort();
    names
}

pub(crate) fn prune_checkpoints(dir: &Path, keep: usize) -> Result<()> {
    let names = checkpoint_names(fs::read_dir(dir).map_err(Error::io("list", dir))?);
    let excess = names.len().saturating_sub(keep);
    for n in &names[..excess] {
        let path = dir.join(n);
        fs::remove_file(&path).map_err(Error::io("prune", path))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_word_checksum_sees_every_byte_and_the_length() {
        let body = b"{\"config\":{\"seed\":1},\"rest\":[1,2,3]}".to_vec();
        let h = fnv1a_words(&body);
        for i in 0..body.len() {
            for bit in 0..8 {
                let mut b = body.clone();
                b[i] ^= 1 << bit;
                assert_ne!(fnv1a_words(&b), h, "byte {i} bit {bit}");
            }
        }
        // Dropping trailing zeros changes the length, and so the checksum.
        assert_ne!(fnv1a_words(&[1, 0, 0]), fnv1a_words(&[1]));
        assert_ne!(fnv1a_words(&[]), fnv1a_words(&[0]));
    }
}
