#!/usr/bin/env bash
# The docs are executable: runs every ```sh / ```bash block of README.md and docs/*.md in a scratch
# directory, as a new user would, and checks what the docs say about the results.
#
# * Each command (continuation lines joined) runs with `bash -c` in the scratch directory, where
#   build/skylight and build/skylight_bench are the built programs (and build/ is on PATH) and
#   data/ is the repository's;
#   every `/tmp/` in a command is replaced by the scratch directory's tmp/, so runs never collide.
# * A command must exit 0, or with N where it ends in the comment `# exit N`.
# * A comment line right after a command that quotes output (`# "key": 1.23..., "other": "x", ...`
#   for JSON, `# => turbidity        3.49..., sky pixels` for text) is checked fragment by fragment
#   (split at ", "; a trailing "..." means "starts with"; the "=> " is not part of the text): each
#   fragment must occur in that command's stdout.
# * A ```text block preceded by `<!-- doc-test: stdout of `COMMAND PART` -->` must equal, line for
#   line, the stdout of the first command run that contains COMMAND PART.
# * A block preceded by `<!-- doc-test: skip REASON -->` is not run (it installs, or it is the
#   main job or the test command itself); skipped blocks are counted and listed.
# Blocks with another language (```cpp, ```cmake: the library example, built by tests/consumer;
# ```text: outputs and synopses) are not commands.
#
# Usage: tests/docs/run_doc_blocks.sh SOURCE_DIR PATH/TO/skylight [PATH/TO/skylight_bench]
# Without skylight_bench (a build with SKYLIGHT_BUILD_BENCH=OFF) its commands are skipped and
# counted as such. SKYLIGHT_DOC_FILES (paths relative to SOURCE_DIR, space-separated) limits the
# run to those files, each optionally to the blocks that start in a line range (FILE:FROM-TO, TO
# may be empty: to the end); default README.md and docs/*.md. ctest runs one test per file
# (Docs.<file>; README.md in three ranges). A quoted output whose command lies in a block outside
# the range is left to the run of that range.
set -euo pipefail
src="${1:?usage: run_doc_blocks.sh SOURCE_DIR PATH/TO/skylight [PATH/TO/skylight_bench]}"
cli="${2:?usage: run_doc_blocks.sh SOURCE_DIR PATH/TO/skylight [PATH/TO/skylight_bench]}"
bench="${3:-}"
scratch="$(mktemp -d "${TMPDIR:-/tmp}/skylight_docs.XXXXXX")"
trap 'rm -rf "$scratch"' EXIT
mkdir -p "$scratch/build" "$scratch/tmp" "$scratch/parsed"
ln -s "$cli" "$scratch/build/skylight"
# The Python package built beside the CLI (SKYLIGHT_PYTHON), for `PYTHONPATH=build/python` blocks.
[ -d "$(dirname "$cli")/python" ] && ln -s "$(dirname "$cli")/python" "$scratch/build/python"
# The package's example scripts (python/examples), read-only like data/.
mkdir -p "$scratch/python" && ln -s "$src/python/examples" "$scratch/python/examples"
# The repository's data/ (committed weights files, tables), read-only for the commands, as in a
# checkout.
ln -s "$src/data" "$scratch/data"
[ -n "$bench" ] && [ -x "$bench" ] && ln -s "$bench" "$scratch/build/skylight_bench"

# Split each Markdown file into numbered records under parsed/:
#   NNNN.sh (a command block; first line "#file:line"), NNNN.skip (its reason),
#   NNNN.expect (an expected stdout) with NNNN.expect_cmd (the command part it belongs to).
n=0
shopt -s nullglob
if [ -n "${SKYLIGHT_DOC_FILES:-}" ]; then
  read -r -a doc_files <<<"$SKYLIGHT_DOC_FILES"
  doc_files=("${doc_files[@]/#/$src/}")
else
  doc_files=("$src/README.md" "$src"/docs/*.md)
fi
for entry in "${doc_files[@]}"; do
  md="$entry" from=1 to=""
  if [[ "$entry" =~ ^(.*):([0-9]+)-([0-9]*)$ ]]; then
    md="${BASH_REMATCH[1]}" from="${BASH_REMATCH[2]}" to="${BASH_REMATCH[3]}"
  fi
  [ -f "$md" ] || { echo "run_doc_blocks: no file $md" >&2; exit 2; }
  n=$(awk -v out="$scratch/parsed" -v start="$n" -v file="${md#"$src"/}" -v from="$from" \
    -v to="${to:-0}" '
    function flush_marker() { marker = "" }
    BEGIN { n = start; inb = 0; marker = "" }
    {
      if (!inb) {
        if ($0 ~ /^<!-- doc-test: /) { marker = $0; next }
        if ($0 ~ /^```/) {
          lang = substr($0, 4)
          inb = 1; n++
          base = sprintf("%s/%04d", out, n)
          if (lang == "sh" || lang == "bash") {
            kind = "sh"; print "#" file ":" NR > (base ".sh")
            if (NR < from || (to > 0 && NR > to)) print "" > (base ".outside")
            if (marker ~ /doc-test: skip /) {
              reason = marker; sub(/^<!-- doc-test: skip /, "", reason); sub(/ -->$/, "", reason)
              print reason > (base ".skip")
            }
          } else if (marker ~ /doc-test: stdout of `/) {
            kind = "expect"
            cmd = marker; sub(/^<!-- doc-test: stdout of `/, "", cmd); sub(/` -->$/, "", cmd)
            print cmd > (base ".expect_cmd")
            printf "" > (base ".expect")
          } else kind = "other"
          marker = ""
          next
        }
        if ($0 !~ /^[[:space:]]*$/) marker = ""
        next
      }
      if ($0 ~ /^```/) { inb = 0; next }
      if (kind == "sh") print > (base ".sh")
      else if (kind == "expect") print > (base ".expect")
    }
    END { print n }' "$md")
done

ran_blocks=0 skipped_blocks=0 ran_cmds=0 skipped_cmds=0 failures=0 quoted_lines=0 quoted_fragments=0
declare -a cmd_texts=()
fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}
# Runs one logical command; its stdout goes to cmd_K.out.
last_out=""
run_command() {
  local where="$1" text="$2" want=0
  if [[ "$text" =~ \#[[:space:]]*exit[[:space:]]+([0-9]+)[[:space:]]*$ ]]; then
    want="${BASH_REMATCH[1]}"
  fi
  if [[ "$text" == *skylight_bench* ]] && [ ! -e "$scratch/build/skylight_bench" ]; then
    echo "skip (skylight_bench not built): $text"
    skipped_cmds=$((skipped_cmds + 1))
    last_out=""
    return
  fi
  local k=${#cmd_texts[@]}
  cmd_texts+=("$text")
  local run="${text//\/tmp\//$scratch/tmp/}"
  local status=0
  (cd "$scratch" && PATH="$scratch/build:$PATH" bash -c "$run") \
    >"$scratch/cmd_$k.out" 2>"$scratch/cmd_$k.err" || status=$?
  ran_cmds=$((ran_cmds + 1))
  last_out="$scratch/cmd_$k.out"
  if [ "$status" != "$want" ]; then
    fail "$where: exit $status, the docs say $want: $text"
    sed 's/^/    stderr: /' "$scratch/cmd_$k.err" | head -5 >&2
  fi
}
# A comment after a command quoting its output: every fragment must be in that stdout.
check_quoted() {
  local where="$1" line="$2" body frag
  body="${line#\# }"
  body="${body#=> }"
  [ -n "$last_out" ] || return 0
  quoted_lines=$((quoted_lines + 1))
  local IFS=$'\x1f'
  # shellcheck disable=SC2086
  for frag in $(sed 's/, /\x1f/g' <<<"$body"); do
    frag="${frag%...}"
    [ -z "$frag" ] && continue
    quoted_fragments=$((quoted_fragments + 1))
    if ! grep -qF -- "$frag" "$last_out"; then fail "$where: output lacks $frag (quoted in the docs)"; fi
  done
}

# What a reader pastes must run, skipped blocks included: no synopsis (`[--json]`, `A|B`: those go in
# ```text blocks) and no output into the repository's own folders (a pasted command would
# overwrite tracked files).
check_pasteable() {
  local where="$1" file="$2" line
  while IFS= read -r line || [ -n "$line" ]; do
    [[ "$line" =~ ^[[:space:]]*(#.*)?$ ]] && continue
    line="${line%%  #*}"
    if [[ "$line" =~ \[-|\ [A-Z]+\|[A-Z]+ ]]; then
      fail "$where: a synopsis in a runnable block (put it in a \`\`\`text block): $line"
    fi
    if [[ "$line" =~ (-o|--output|--log|--preview|--false-colour|\>)[[:space:]]+\'?(docs|data|src|tests|scripts|cmake|bench)/ ]]; then
      fail "$where: writes into the repository's ${BASH_REMATCH[2]}/ (write into the working directory): $line"
    fi
  done < <(tail -n +2 "$file")
}
in_git=0
git -C "$src" rev-parse --is-inside-work-tree >/dev/null 2>&1 && in_git=1
[ "$in_git" = 1 ] && tree_before="$(git -C "$src" status --porcelain --untracked-files=all)"
quoted_output_re='^#[[:space:]]("|=> )'
for f in "$scratch"/parsed/*.sh; do
  [ -e "$f" ] || continue
  base="${f%.sh}"
  where="$(head -1 "$f")"
  where="${where#\#}"
  [ -e "$base.outside" ] && continue
  check_pasteable "$where" "$f"
  if [ -e "$base.skip" ]; then
    echo "skip block $where: $(cat "$base.skip")"
    skipped_blocks=$((skipped_blocks + 1))
    continue
  fi
  ran_blocks=$((ran_blocks + 1))
  block_start=$(date +%s.%N)
  cmd=""
  last_out=""
  while IFS= read -r line || [ -n "$line" ]; do
    if [ -n "$cmd" ]; then
      cmd+=$'\n'"$line"
    elif [[ "$line" =~ $quoted_output_re ]]; then
      check_quoted "$where" "$line"
      continue
    elif [[ "$line" =~ ^[[:space:]]*(#.*)?$ ]]; then
      continue
    else
      cmd="$line"
    fi
    [[ "$line" == *\\ ]] && continue
    run_command "$where" "$cmd"
    cmd=""
  done < <(tail -n +2 "$f")
  [ -z "$cmd" ] || run_command "$where" "$cmd"
  echo "ran block $where ($(awk -v a="$block_start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }') s)"
done

# Every Markdown table is whole: a row after a blank line (outside code blocks) that does not start
# a new table (no |---| line under it) is a table split by a blank line, which renders as raw text.
for entry in "${doc_files[@]}"; do
  md="${entry%%:[0-9]*-*}"
  while IFS= read -r where; do
    fail "$where: a table row after a blank line (the table is split; remove the blank line)"
  done < <(awk -v file="${md#"$src"/}" '
    /^```/ { code = !code; prev = $0; next }
    !code && prev ~ /^[[:space:]]*$/ && $0 ~ /^\|/ { pending = NR; next_is_sep = 1; prev = $0; next }
    pending { if ($0 !~ /^\|[ :-]*-/) print file ":" pending; pending = 0 }
    { prev = $0 }
    END { if (pending) print file ":" pending }' "$md")
done

# Nothing the commands ran may have written into the source tree (through data/ or a path).
if [ "$in_git" = 1 ]; then
  tree_after="$(git -C "$src" status --porcelain --untracked-files=all)"
  if [ "$tree_after" != "$tree_before" ]; then
    fail "the commands changed the source tree: $(diff <(echo "$tree_before") <(echo "$tree_after") | grep '^[<>]' | head -5 | tr '\n' ' ')"
  fi
fi

checked_outputs=0
for e in "$scratch"/parsed/*.expect; do
  [ -e "$e" ] || continue
  part="$(cat "${e%.expect}.expect_cmd")"
  found=""
  for k in "${!cmd_texts[@]}"; do
    if [[ "${cmd_texts[$k]}" == *"$part"* ]]; then
      found="$k"
      break
    fi
  done
  if [ -z "$found" ]; then
    outside=""
    for o in "$scratch"/parsed/*.outside; do
      if grep -qF -- "$part" "${o%.outside}.sh"; then outside=1; fi
    done
    [ -n "$outside" ] && continue  # checked by the run of that block's range
    fail "quoted output of '$part': no command of the docs contains it"
    continue
  fi
  checked_outputs=$((checked_outputs + 1))
  if ! diff -u "$e" "$scratch/cmd_$found.out" >"$scratch/diff.txt"; then
    fail "the output quoted for '$part' differs from what it prints:"
    cat "$scratch/diff.txt" >&2
  fi
done

echo "doc blocks: $ran_blocks run ($ran_cmds commands), $skipped_blocks skipped;" \
  "$skipped_cmds commands skipped; $checked_outputs quoted outputs compared; $quoted_lines quoted lines ($quoted_fragments fragments) checked; $failures failures"
[ "$failures" -eq 0 ] && [ "$ran_blocks" -gt 0 ]
