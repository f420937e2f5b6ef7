#!/bin/sh
# tools_list.t — tools/tools.txt is the one list of the tools and the files
# they bake (bake.mk and tools/install.sh read it); what cannot read it is
# checked here against it:
#   every program built in GB_BIN has its line (install.sh's man page NAME)
#   every bake step (a suffix, not -) has a rule in bake.mk writing
#     NAME.SUFFIX and a job in tools/slurm_bake.sh (submit STEP ... PREFIX.SUFFIX)
# Prints TAP.
#
# GB_BIN: the folder of the tools (default build/bin); GB_ROOT: the repository.

. "$(dirname "$0")/tap.sh"

list=$GB_ROOT/tools/tools.txt
listed() {
    awk -v name="$1" '!/^#/ && $1 == name { found = 1 } END { exit !found }' "$list"
}

for program in "$GB_BIN"/*; do
    [ -x "$program" ] || continue
    name=$(basename "$program")
    listed "$name"
    ok $? "$name, built, has its line in tools/tools.txt"
done

awk '!/^#/ && NF && $2 != "-" { print $1, $2 }' "$list" >"$dir/steps"
ok "$([ -s "$dir/steps" ]; echo $?)" "tools/tools.txt lists bake steps"
while read -r name suffix; do
    grep -Fq "\$(2)$suffix" "$GB_ROOT/bake.mk" &&
        grep -Eq "^\\\$\\(2\\)$(echo "$suffix" | sed 's/\./\\./g')( |:)" "$GB_ROOT/bake.mk"
    ok $? "bake.mk has a rule writing NAME$suffix ($name)"
    grep -Eq "submit $name( |\$).*\\\$PREFIX$(echo "$suffix" | sed 's/\./\\./g')" \
        "$GB_ROOT/tools/slurm_bake.sh"
    ok $? "tools/slurm_bake.sh submits $name for PREFIX$suffix"
done <"$dir/steps"

tap_done
