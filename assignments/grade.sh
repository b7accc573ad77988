#!/usr/bin/env bash
# Grades a course assignment: runs the test cases that grade each function you wrote, and
# prints how many pass, the first failing check of each test case that fails, and a score.
#
#   assignments/grade.sh NN [--reference] [--build-dir DIR] [--check-stubs | --check-reference]
#
#   NN                 the assignment, e.g. 01 (the folder assignments/01_*)
#   --reference        grade the library's own code instead of your stubs (it scores 100 %)
#   --build-dir DIR    where the build is (default: build/release, the release preset)
#   --check-stubs      for CI: fail unless the stubs as handed out score below 100 % and every
#                      graded function fails at least one test case
#   --check-reference  for CI: fail unless the library's own code scores 100 %
#
# It only runs what is built: `./kerf.sh assignment NN` builds it first, then calls this.
# Which test cases grade which function is the assignment's grading.txt, one line each (lines
# that start with # are comments):
#   <function> | <test suite, a folder of tests/, or "assignment"> | <doctest test-case filter>
# The suite "assignment" is the assignment's own test cases, in its folder tests/. Each function
# is graded alone: its test cases run in an executable where it is the only function of the
# stubs that is yours, and every other stubbed function is the library's (isolate.sh), so a bug
# lowers the score of the function that has it and of no other.
# Exit status: 0 when the grading ran (whatever the score) or the check passed, 1 when a check
# failed, 2 when the grading could not run (a bad argument, a missing file or executable).
set -euo pipefail

fail() { echo "grade.sh: $*" >&2; exit 2; }

here=$(pwd)
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
number="" mode=stubs check="" build_dir=$root/build/release # a --build-dir is taken from where you are
while [ $# -gt 0 ]; do
  case $1 in
    --reference) mode=reference ;;
    --check-stubs) check=stubs ;;
    --check-reference) check=reference mode=reference ;;
    --build-dir)
      [ $# -ge 2 ] || fail "--build-dir needs a folder"
      build_dir=$2
      shift ;;
    -h | --help) sed -n '2,23p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) fail "unknown option $1 (try --help)" ;;
    *)
      [ -z "$number" ] || fail "one assignment at a time: got $number and $1"
      number=$1 ;;
  esac
  shift
done

available() {
  local list="" d
  for d in "$root"/assignments/[0-9][0-9]_*/; do [ -d "$d" ] && list+=" $(basename "$d" | cut -c1-2)"; done
  echo "${list:- none}"
}
[ -n "$number" ] || fail "which assignment? usage: assignments/grade.sh NN [--reference]; there are:$(available)"
[[ $number =~ ^[0-9]{1,2}$ ]] || fail "\"$number\" is not an assignment number; there are:$(available)"
number=$(printf '%02d' "$((10#$number))")
folders=("$root"/assignments/"$number"_*/)
[ -d "${folders[0]}" ] || fail "there is no assignment $number (no folder assignments/${number}_*); there are:$(available)"
[ ${#folders[@]} -eq 1 ] || fail "assignment $number has ${#folders[@]} folders; keep one: ${folders[*]#"$root"/}"
folder=${folders[0]%/}
name=assignments/$(basename "$folder")
grading=$folder/grading.txt
[ -f "$grading" ] || fail "$name/grading.txt is missing: it names the test cases that grade each function"

case $build_dir in /*) ;; *) build_dir=$here/$build_dir ;; esac
[ -d "$build_dir" ] || fail "no build in $build_dir: run ./kerf.sh assignment $number, which builds it"

# The executable that grades function $2 on suite $1: the assignment's copy of the suite with
# your $2 alone in place of the library's, or, with --reference, the suite itself.
executable() {
  if [ "$mode" = reference ]; then
    if [ "$1" = assignment ]; then echo "$build_dir/assignments/assignment_${number}_assignment_reference"
    else echo "$build_dir/tests/test_$1"; fi
  else
    echo "$build_dir/assignments/assignment_${number}_$1_$(printf '%s' "$2" | sed 's/[^A-Za-z0-9_]/_/g')"
  fi
}

# The test cases of a suite whose names match a doctest filter, one per line.
list_test_cases() {
  "$1" --list-test-cases --no-version --no-colors "-tc=$2" |
    awk '/^====/ { inside = !inside; next } inside { print }'
}

# A test case's name as a doctest filter that matches it alone: a comma or a backslash in the
# name would otherwise split the filter or escape what follows.
exact_filter() { printf '%s' "$1" | sed 's/\\/\\\\/g; s/,/\\,/g'; }

# A test case that runs longer than this (in seconds) has failed: a loop that never ends must
# not stop the grading.
time_limit=${KERF_GRADE_TIMEOUT:-300}

# Runs one test case in one executable once; remembers whether it passed and, if not, the first
# failing check doctest printed (its location, what failed, the values).
declare -A passed first_failure
run_test_case() {
  local key="$1"$'\t'"$2" output status=0
  [ -n "${passed[$key]+set}" ] && return 0
  output=$(timeout "$time_limit" "$1" --no-version --no-colors "-tc=$(exact_filter "$2")" 2>&1) || status=$?
  if [ "$status" -eq 0 ]; then
    passed[$key]=1
  elif [ "$status" -eq 124 ]; then
    passed[$key]=0
    first_failure[$key]="(stopped after $time_limit s: an endless loop? KERF_GRADE_TIMEOUT sets the limit)"
  else
    passed[$key]=0
    # doctest's block for a failure starts at "<file>:<line>: ERROR:" (or FATAL ERROR, or a
    # crash) and ends at a blank line; paths are shown from the top of the repository (the
    # compiler may have seen them absolute, or relative to the build folder). An exception in a
    # SUBCASE first gets a block that only says it "will translate later": the next block has
    # the exception's message, so that one is shown.
    # (awk reads a here-string, not a pipe: it stops at the first block, and a writer into a
    # closed pipe would be killed by SIGPIPE, which pipefail turns into the script's death.)
    first_failure[$key]=$(awk '/: (ERROR|FATAL ERROR):/ && block == "" { block = $0; next }
           block != "" && /^$/ { if (block !~ /will translate later/) { print block; shown = 1; exit } block = ""; next }
           block != "" { block = block "\n" $0 }
           END { if (!shown && block != "" && block !~ /will translate later/) print block }' <<< "$output" |
      sed "s|$root/||g; s|^\(\.\./\)*||")
    [ -n "${first_failure[$key]}" ] || first_failure[$key]="(no failing check printed; the test program exited with status $status)"
  fi
}

trim() { local s=$1; s=${s#"${s%%[![:space:]]*}"}; printf '%s' "${s%"${s##*[![:space:]]}"}"; }

# grading.txt: "<function> | <suite> | <filter>" per line; a line that starts with # is a
# comment (a # elsewhere is part of the line: test-case names may have one).
functions=() suites=() filters=() line_number=0
while IFS= read -r line || [ -n "$line" ]; do
  line_number=$((line_number + 1))
  [[ $line =~ ^[[:space:]]*(#.*)?$ ]] && continue
  IFS='|' read -r function suite filter extra <<<"$line"
  function=$(trim "$function") suite=$(trim "${suite:-}") filter=$(trim "${filter:-}")
  if [ -z "$function" ] || [ -z "$suite" ] || [ -z "$filter" ] || [ -n "${extra:-}" ]; then
    fail "$name/grading.txt:$line_number: expected \"<function> | <suite> | <test-case filter>\", got \"$line\""
  fi
  if [ "$suite" = assignment ]; then
    [ -d "$folder/tests" ] || fail "$name/grading.txt:$line_number: the suite \"assignment\" is $name/tests, and there is none"
  else
    [ -d "$root/tests/$suite" ] || fail "$name/grading.txt:$line_number: there is no test suite tests/$suite"
  fi
  functions+=("$function") suites+=("$suite")
  filters+=("$(printf '%s' "$filter" | sed 's/[[:space:]]*,[[:space:]]*/,/g')")
done <"$grading"
[ ${#functions[@]} -gt 0 ] || fail "$name/grading.txt grades no function: write \"<function> | <suite> | <test-case filter>\" lines"

if [ "$mode" = reference ]; then
  echo "Grading assignment $number ($name) on the library's own code (--reference)"
else
  echo "Grading assignment $number ($name): your code in $name/stubs"
fi
echo

# The test cases that grade each function (a function may have lines for several suites), as
# "<suite><tab><test case>", in the order of grading.txt.
declare -A graded_by
order=()
for i in "${!functions[@]}"; do
  function=${functions[$i]} suite=${suites[$i]} filter=${filters[$i]}
  exe=$(executable "$suite" "$function")
  if [ ! -x "$exe" ]; then
    fail "${exe#"$root"/} is not built: run ./kerf.sh assignment $number$([ "$mode" = reference ] && echo " --reference"), or cmake --build ${build_dir#"$root"/} --target assignment_$number"
  fi
  mapfile -t cases < <(list_test_cases "$exe" "$filter")
  [ ${#cases[@]} -gt 0 ] || fail "$name/grading.txt: the filter of $function matches no test case of tests/$suite: \"$filter\""
  [ -n "${graded_by[$function]+set}" ] || order+=("$function")
  for test_case in "${cases[@]}"; do graded_by[$function]+="$suite"$'\t'"$test_case"$'\n'; done
done

# Where a suite's test cases are, as the report names it.
suite_folder() { if [ "$1" = assignment ]; then echo "$name/tests"; else echo "tests/$1"; fi; }

total=0 total_passed=0 functions_without_failure=()
for function in "${order[@]}"; do
  mapfile -t cases < <(printf '%s' "${graded_by[$function]}")
  count=0 where="" keys=()
  for entry in "${cases[@]}"; do
    suite=${entry%%$'\t'*}
    key=$(executable "$suite" "$function")$'\t'${entry#*$'\t'}
    keys+=("$key")
    run_test_case "${key%%$'\t'*}" "${key#*$'\t'}"
    [ "${passed[$key]}" = 1 ] && count=$((count + 1))
    [[ $where == *"$(suite_folder "$suite")"* ]] || where+="${where:+, }$(suite_folder "$suite")"
  done
  printf '%-28s %d/%d test cases pass  (%s)\n' "$function" "$count" "${#keys[@]}" "$where"
  for i in "${!keys[@]}"; do
    key=${keys[$i]} test_case=${keys[$i]#*$'\t'} suite_note=""
    [[ $where == *,* ]] && suite_note="  ($(suite_folder "${cases[$i]%%$'\t'*}"))"
    if [ "${passed[$key]}" = 1 ]; then
      echo "    passed  $test_case$suite_note"
    else
      echo "    FAILED  $test_case$suite_note"
      printf '%s\n' "${first_failure[$key]}" | sed 's/^/              /'
    fi
  done
  [ "$count" -lt "${#keys[@]}" ] || functions_without_failure+=("$function")
  total=$((total + ${#keys[@]})) total_passed=$((total_passed + count))
done

percent=$((100 * total_passed / total)) # rounded down: 100 % means everything passes
echo
echo "score: $total_passed/$total test cases ($percent %)"
if [ "$mode" != reference ] && [ "$percent" -lt 100 ]; then
  echo "(each function counts its own test cases, run with the library's version of every other function)"
fi

case $check in
  stubs)
    status=0
    if [ "$percent" -ge 100 ]; then
      echo "grade.sh: --check-stubs: the stubs as handed out score 100 %: they must fail the grading tests" >&2
      status=1
    fi
    for function in ${functions_without_failure[@]+"${functions_without_failure[@]}"}; do
      echo "grade.sh: --check-stubs: no test case of $function fails with the stubs: it grades nothing" >&2
      status=1
    done
    # Not an error by the design, but worth a look: a test case that passes with a function's
    # stub does not call that function (or runs a chapter's program, which links the library's
    # own code) and gives its points away.
    for key in "${!passed[@]}"; do
      [ "${passed[$key]}" = 1 ] &&
        echo "grade.sh: --check-stubs: note: \"${key#*$'\t'}\" passes in $(basename "${key%%$'\t'*}"), with that function's stub: it does not grade it" >&2
    done
    for function in "${order[@]}"; do
      grep -rqw -- "$function" "$folder/stubs" ||
        { echo "grade.sh: --check-stubs: $function is graded but no file of $name/stubs mentions it" >&2; status=1; }
    done
    exit $status ;;
  reference)
    if [ "$percent" -lt 100 ]; then
      echo "grade.sh: --check-reference: the library's own code scores $percent %, not 100 %: a grading test case fails without any stub" >&2
      exit 1
    fi ;;
esac
exit 0
