#!/bin/sh
# Developer helper for parallel work in git worktrees: run from a worktree
# whose branch is fully committed.  Rebases the branch onto main, checks
# that it builds warnings-clean and passes make test, and fast-forwards main (in the main
# checkout) to it.  Serialised by a lock so concurrent landings queue.
set -eu
main_dir=${PGSIM_MAIN:-/work/main}
br=$(git rev-parse --abbrev-ref HEAD)
[ -z "$(git status --porcelain --untracked-files=no)" ] ||
    { echo "land: commit your changes first" >&2; exit 1; }
exec 9>/tmp/pgsim-land.lock
flock 9
git rebase main || { echo "land: resolve the conflict, git rebase --continue, rerun" >&2; exit 1; }
out=$(make -s -j2 all 2>&1) || { echo "$out" | tail -20; echo "land: build fails" >&2; exit 1; }
if echo "$out" | grep -q 'warning:'; then echo "$out" | grep warning: | head; echo "land: warnings" >&2; exit 1; fi
# The rebased tree must pass the suite: another landing may have changed
# what this branch's tests (or goldens) expect.
log=/tmp/pgsim-land-test-$br.log # one per branch: landings queue, logs do not mix
make test > "$log" 2>&1 ||
    { tail -20 "$log"; echo "land: make test fails after the rebase" >&2; exit 1; }
# make test builds the test binaries: they are held to -Wall -Wextra too.
if grep -Eq '^[^ ]+\.[ch]:[0-9]+:[0-9]+: warning:' "$log"; then grep -E '^[^ ]+\.[ch]:[0-9]+:[0-9]+: warning:' "$log" | head; echo "land: warnings in the tests' build" >&2; exit 1; fi
cd "$main_dir"
git merge --ff-only -q "$br"
echo "land: main is now $(git rev-parse --short HEAD)"
