#!/usr/bin/env bash
# Word check of every tracked text file: the project describes what it is, not the rounds of work
# that made it, and states its reasons instead of pointing at the tracker. Fails (exit 1, with the
# offending lines) on:
#   - the name of a round of work ("s-e-s-s-i-o-n", singular or plural, any case), except where it
#     names Slang's API objects (targets/slangc.mjs's variable of that name and its methods, and
#     prose that says "Slang ..." or "global ..." before the word);
#   - a reference to the tracker: the word for a tracker entry followed by a number (with or
#     without "#"), or that word after "the".
# Left out: materials/ (third-party example files, Apache-2.0), the generated tables and the
# fuzzer's binary corpus.
# Run by scripts/test.sh beside the format check, e.g. `scripts/check-words.sh`.
set -euo pipefail
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$repo_root"
excluded=(':!:materials/*' ':!:slang/generated/*' ':!:fuzz/corpus/*' ':!:package-lock.json')
word='sess''ions?'
# Lines that name Slang's own objects of that name: the variable of targets/slangc.mjs, its
# methods, and the prose that names them as Slang's.
slang_api="(Slang( global)? ${word}|global ${word}|\\b${word}\\.(loadModuleFromSource|createCompositeComponentType|delete)\\b|const ${word} = |'${word}')"
status=0
if matches=$(git grep -n -I -i -w -E "$word" -- "${excluded[@]}" | grep -v -E "$slang_api"); then
  echo "check-words: names of rounds of work in tracked text; say what the code does and why instead:" >&2
  echo "$matches" >&2
  status=1
fi
if matches=$(git grep -n -I -i -E "\\bissues? #?[0-9]+|\\bthe issue('s)?\\b" -- "${excluded[@]}"); then
  echo "check-words: references to the tracker in tracked text; state the target or the reason itself:" >&2
  echo "$matches" >&2
  status=1
fi
((status == 0)) && echo "check-words: $(git ls-files -- "${excluded[@]}" | wc -l) tracked files, no round names or tracker references"
exit "$status"
