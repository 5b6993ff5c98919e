#!/usr/bin/env bash
# Regenerates the reference pages from the code: docs/reference/config.md
# (`vivae config reference`, from the doc comments of the parameter structs)
# and docs/reference/cli.md (`vivae help-reference`, from the command-line
# definitions), and the config key table of any page that embeds it between
# <!-- BEGIN CONFIG REFERENCE --> and <!-- END CONFIG REFERENCE -->.
# A test (`cargo test --release -p vivae --test it reference_docs`) fails
# while any of them differs from what the program generates.
#
#   scripts/update-reference.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --quiet --release -p vivae
vivae="${CARGO_TARGET_DIR:-target}/release/vivae"
mkdir -p docs/reference
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

# Each page is written whole beside its final name, then renamed over it.
write() { # write PAGE COMMAND...
    local page="$1"
    shift
    "$@" > "$page.tmp"
    mv "$page.tmp" "$page"
    echo "$page: updated"
}
write docs/reference/config.md "$vivae" config reference
write docs/reference/cli.md "$vivae" help-reference

"$vivae" config reference --table > "$tmp/table"
grep -rl --include='*.md' -- '<!-- BEGIN CONFIG REFERENCE -->' docs | while read -r page; do
    awk -v table="$tmp/table" '
      /<!-- BEGIN CONFIG REFERENCE -->/ { print; while ((getline line < table) > 0) print line; skip = 1; next }
      /<!-- END CONFIG REFERENCE -->/ { skip = 0 }
      !skip { print }
    ' "$page" > "$page.tmp"
    if cmp -s "$page" "$page.tmp"; then
        rm "$page.tmp"
    else
        mv "$page.tmp" "$page"
        echo "$page: config key table updated"
    fi
done
