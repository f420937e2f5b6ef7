#!/bin/sh
# report_readme.sh TABLE README — puts TABLE (make report's readme-table.md)
# into README between the lines <!-- report:begin --> and <!-- report:end -->,
# replacing what was there; README is left as it was if a marker is missing.
set -e
table=$1 readme=$2
grep -q '^<!-- report:begin -->$' "$readme" && grep -q '^<!-- report:end -->$' "$readme" || {
    echo "report_readme.sh: $readme: no <!-- report:begin --> / <!-- report:end --> lines" >&2; exit 1; }
awk -v table="$table" '
    $0 == "<!-- report:begin -->" { print; while ((getline line < table) > 0) print line; skip = 1; next }
    $0 == "<!-- report:end -->" { skip = 0 }
    !skip' "$readme" >"$readme.report.tmp"
mv "$readme.report.tmp" "$readme"
echo "report_readme.sh: $readme: table from $table"
