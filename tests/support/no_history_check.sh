#!/usr/bin/env bash
# no_history_check.sh REPO_ROOT
# The tree says what is; history (which session, which issue) belongs in commit messages.
# Fails, printing each offending line, when a tracked text file mentions a session or an
# issue by number (case-insensitive, as a word: "tissue 1000" is not a hit).
set -u
root=${1:?usage: no_history_check.sh REPO_ROOT}
cd "$root" || { echo "no_history_check: cannot enter $root"; exit 1; }
git rev-parse --is-inside-work-tree >/dev/null 2>&1 || { echo "no_history_check: $root is not a git work tree"; exit 1; }
# The pattern is built so that this file does not match itself.
pattern='\<(sessio[n]|issu[e]) [0-9]'
# -I skips binary files; ls-files -z keeps odd file names intact.
hits=$(git ls-files -z | xargs -0 grep -I -n -i -E "$pattern" -- 2>/dev/null)
if [ -n "$hits" ]; then
  echo "history markers in tracked files (say what is; move the history to the commit message):"
  echo "$hits"
  exit 1
fi
echo "no history markers in $(git ls-files | wc -l) tracked files"
