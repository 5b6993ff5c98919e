//! A test that needs `../shared/vivae-scenarios` (absent from a clone from the
//! web) skips with a printed note, unless `VIVAE_REQUIRE_SHARED=1` (CI).

use crate::common::corpus_at;

#[test]
fn a_missing_corpus_is_skipped_with_a_note_by_default() {
    let missing = std::env::temp_dir().join("vivae-no-such-corpus-dir");
    assert_eq!(corpus_at(&missing, false), None);
}

#[test]
#[should_panic(expected = "VIVAE_REQUIRE_SHARED=1 requires it")]
fn a_missing_corpus_fails_when_required() {
    let missing = std::env::temp_dir().join("vivae-no-such-corpus-dir");
    corpus_at(&missing, true);
}
