#!/usr/bin/env bash
# Regenerates the config key table in docs/guide.md (between the BEGIN/END
# CONFIG REFERENCE markers) from `vivae config reference`, i.e. from the doc
# comments of the parameter structs. A unit test fails while the two differ.
#
#   scripts/update-config-reference.sh
set -euo pipefail
cd "$(dirname "$0")/.."
table="$(mktemp)"
out=docs/.guide.md.tmp
trap 'rm -f "$table" "$out"' EXIT
cargo run --quiet --release -p vivae -- config reference > "$table"
awk -v table="$table" '
  /<!-- BEGIN CONFIG REFERENCE -->/ { print; while ((getline line < table) > 0) print line; skip = 1; next }
  /<!-- END CONFIG REFERENCE -->/ { skip = 0 }
  !skip { print }
' docs/guide.md > "$out"
mv "$out" docs/guide.md
echo "docs/guide.md: config reference updated"
