# glsl.awk — a GLSL file as a C string literal, the Makefile's shader rule:
#   awk -f tools/glsl.awk -v target=OUT.inc -v depfile=OUT.d FILE.glsl >OUT.inc
# Each line becomes "LINE\n". A line #include "PATH" becomes PATH's lines,
# recursively (PATH from the top of the repository, where make runs). //
# comments and the lines they leave blank are left out: the driver gets the
# code alone. depfile gets the rule "target: every file read" and an empty
# rule for each included one (as cc -MP writes), so that deleting one does
# not stop make.
function emit(file, from,    line, path, status) {
    while ((status = (getline line < file)) > 0) {
        if (line ~ /^#include "[^"]*"[ \t]*$/) {
            path = line
            sub(/^#include "/, "", path)
            sub(/".*$/, "", path)
            included = included " " path
            emit(path, file)
            continue
        }
        sub(/[ \t]*\/\/.*$/, "", line)
        if (line ~ /^[ \t]*$/)
            continue
        gsub(/[\\"]/, "\\\\&", line)
        print "\"" line "\\n\""
    }
    if (status < 0) {
        print "glsl.awk: " file ": cannot read it" (from ? " (included by " from ")" : "") \
            >"/dev/stderr"
        exit 1
    }
    close(file)
}
BEGIN {
    emit(ARGV[1], "")
    print target ": " ARGV[1] included >depfile
    count = split(included, paths, " ")
    for (i = 1; i <= count; ++i)
        print paths[i] ":" >depfile
}
