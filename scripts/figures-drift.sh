#!/usr/bin/env bash
# Compares two outputs of scripts/figures.sh: every `instructions` figure present in both must lie
# within a tolerance (0.5 % unless given) of the old one. For checking that a change which adds
# a stage costs nothing where the stage is not used: run `scripts/figures.sh SCENES > new.tsv`
# on the change and compare with docs/figures.tsv (the figures of record before it).
#
# Usage: scripts/figures-drift.sh OLD.tsv NEW.tsv [PERCENT]
# Prints one line per compared figure (scene, renderer, old, new, change in %) and exits with 1
# if any moves by more than PERCENT; figures in only one file are listed as such, not failed.
set -euo pipefail

[ "$#" -ge 2 ] || {
    sed -n '/^# Usage/,/^# Prints/p' "$0" | sed 's/^# \{0,1\}//' >&2
    exit 2
}
old="$1"
new="$2"
tolerance="${3:-0.5}"

awk -F'\t' -v tol="$tolerance" '
    FNR == NR { if ($3 == "instructions") old[$1 "\t" $2] = $4; next }
    $3 == "instructions" {
        key = $1 "\t" $2
        if (!(key in old)) { printf "%s\tnew only\t%s\n", key, $4; next }
        seen[key] = 1
        change = ($4 - old[key]) * 100 / old[key]
        flag = (change > tol || change < -tol) ? "\tOVER" : ""
        printf "%s\t%s\t%s\t%+.3f %%%s\n", key, old[key], $4, change, flag
        if (flag != "") bad = 1
    }
    END { exit bad }
' "$old" "$new"
