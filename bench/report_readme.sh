#!/bin/sh
# report_readme.sh TABLE FILE [NAME] — puts TABLE (one of make report's
# readme-*.md) into FILE (make readme-figures: docs/figures.md) between the
# lines <!-- NAME:begin --> and <!-- NAME:end --> (NAME: report by
# default), replacing what was there. FILE is left as it was if a marker is
# missing or TABLE is empty.
set -e
table=$1 readme=$2 name=${3:-report}
begin="<!-- $name:begin -->" end="<!-- $name:end -->"
grep -qx -- "$begin" "$readme" && grep -qx -- "$end" "$readme" || {
    echo "report_readme.sh: $readme: no $begin / $end lines" >&2; exit 1; }
[ -s "$table" ] || { echo "report_readme.sh: $table is empty: $readme left as it was" >&2; exit 0; }
awk -v table="$table" -v begin="$begin" -v end="$end" '
    $0 == begin { print; while ((getline line < table) > 0) print line; skip = 1; next }
    $0 == end { skip = 0 }
    !skip' "$readme" >"$readme.report.tmp"
mv "$readme.report.tmp" "$readme"
echo "report_readme.sh: $readme: $name table from $table"
