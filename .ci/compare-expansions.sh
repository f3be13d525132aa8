#!/usr/bin/env bash
# The generated code of every model of the workspace (its tests, examples,
# FMU examples and the crate of parts) at a commit and in the working
# tree, compared: a change to the pipeline that should not change what it
# generates shows here that it does not.
#
#   bash .ci/compare-expansions.sh BASE     # e.g. HEAD, or main~3
#
# Each side is built with DAEGEN_EXPANSIONS naming a folder, where every
# `#[dae_model]` expansion is written (codegen/src/recorded.rs); the files
# that expand models are touched first, so that cargo expands them again.
# BASE is checked out into target/expansions/base-tree and built in its
# own target directory, target/expansions/base-target (the first run
# builds everything once). Exits 1 when any expansion differs, printing
# the first lines of each difference.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
base=${1:?usage: bash .ci/compare-expansions.sh BASE}
work=$root/target/expansions
mkdir -p "$work"
rm -rf "$work/base" "$work/head"

# Expands every model of the workspace at $1 into folder $2, building in
# target directory $3.
expand() {
    local tree=$1 into=$2 target=$3
    (
        cd "$tree"
        grep -rl --include='*.rs' -e 'dae_model' -e 'component]' . \
            | grep -v -e '^./target/' -e '^./bench/' -e '^./fuzz/' | xargs touch
        DAEGEN_EXPANSIONS=$into CARGO_TARGET_DIR=$target \
            cargo build --quiet --workspace --all-features --tests --examples
    )
    # A file a model reads (a URDF) is named by its absolute path, and the
    # compiler breaks the tokens' lines by their lengths.
    find "$into" -type f -exec sed -i "s#$tree/#<tree>/#g" {} +
    find "$into" -type f -exec perl -0pi -e 's/\s+/ /g' {} +
}

git worktree remove --force "$work/base-tree" 2>/dev/null || true
git worktree add --quiet --force --detach "$work/base-tree" "$base"
expand "$work/base-tree" "$work/base" "$work/base-target"
git worktree remove --force "$work/base-tree"
expand "$root" "$work/head" "$root/target"

count=$(ls "$work/head" | wc -l)
if diff -rq "$work/base" "$work/head" >"$work/differences"; then
    echo "$count expansions, all as at $base"
    exit 0
fi
echo "$(wc -l <"$work/differences") of $count expansions differ from $base:"
while read -r line; do
    echo "$line"
done <"$work/differences"
exit 1
