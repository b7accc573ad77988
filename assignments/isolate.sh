#!/usr/bin/env bash
# Makes the objects that grade ONE function of an assignment alone: the student's version of
# that function, and the library's own version of everything else the stubs replace, so that a
# bug in one function costs only that function's test cases.
#
#   assignments/isolate.sh <function> pair <student.o> <library.o> <student_out.o> <library_out.o> ...
#
# one pair per stub file: the stub's object and that of the library's own file it replaces.
#   - a stub that defines <function>: in its object every global symbol is made weak except
#     those of <function>, and in the library's object the symbols of <function> are made weak;
#   - a stub that does not: the library's object in its place (its symbols weak in the copy
#     that stands where the stub's was), the stub's code left out.
#
# Linked together (each stub's object before its library's), each symbol has one strong
# definition and the linker takes it: <function> from the student, the rest from the library (a
# weak definition only stands in where there is no strong one, e.g. a helper of the student's
# own). A function the compiler emits weak itself (an explicit instantiation of a template)
# is taken from the first object that defines it, the stub's: so a stub file must not hold two
# graded templates, or the second would be the student's in the first's grading too. Both
# objects must be compiled with -fPIC: GCC then treats every exported function as
# interposable, so a call from one function of a file to another goes through the symbol, and
# is neither inlined nor specialised in place (assignments/CMakeLists.txt compiles them so).
#
# <function> is matched against the demangled names without their namespaces' prefix (and
# template arguments): "NewmarkIntegrator::step" matches kerf::NewmarkIntegrator::step, and
# every overload and instantiation of the name counts. Exit status 2, with a one-line message,
# when no stub defines <function>: the library's version would then be graded in its place.
set -euo pipefail

fail() { echo "isolate.sh: $*" >&2; exit 2; }
[ $# -ge 1 ] || fail "usage: isolate.sh <function> student <in.o> <out.o> ... library <in.o> <out.o> ..."
function=$1
shift

# The global symbols an object defines, one "<binding><tab><mangled><tab><demangled>" a line
# (binding "strong" or "weak").
defined_symbols() {
  nm --defined-only --extern-only "$1" | awk '$2 ~ /^[TDBRGWV]$/ { print ($2 ~ /^[WV]$/ ? "weak" : "strong") "\t" $3 }' |
    while IFS=$'\t' read -r binding mangled; do
      printf '%s\t%s\t%s\n' "$binding" "$mangled" "$(printf '%s' "$mangled" | c++filt)"
    done
}

# Whether a demangled name is <function>: its qualified name (up to the parameter list, and
# without a template's arguments or return type) is the function's, or ends with "::<function>".
is_function() {
  local name=${1%%(*}
  name=${name%%<*}
  name=${name##* }
  [ "$name" = "$function" ] || [[ $name == *"::$function" ]]
}

# `objcopy` with every listed symbol made weak.
weakened_copy() {
  local input=$1 output=$2
  shift 2
  objcopy "${@/#/--weaken-symbol=}" "$input" "$output"
}

defined_by_student=0
while [ $# -gt 0 ]; do
  [ "$1" = pair ] && [ $# -ge 5 ] || fail "expected \"pair <student.o> <library.o> <student_out.o> <library_out.o>\", got \"$*\""
  student=$2 library=$3 student_out=$4 library_out=$5
  shift 5
  [ -f "$student" ] || fail "no object $student"
  [ -f "$library" ] || fail "no object $library"
  mine=() others=() all_library=() function_in_library=()
  while IFS=$'\t' read -r binding mangled demangled; do
    if is_function "$demangled"; then mine+=("$mangled"); elif [ "$binding" = strong ]; then others+=("$mangled"); fi
  done < <(defined_symbols "$student")
  while IFS=$'\t' read -r binding mangled demangled; do
    [ "$binding" = strong ] || continue
    all_library+=("$mangled")
    is_function "$demangled" && function_in_library+=("$mangled")
  done < <(defined_symbols "$library")
  if [ ${#mine[@]} -gt 0 ]; then
    defined_by_student=1
    weakened_copy "$student" "$student_out" ${others[@]+"${others[@]}"}
    weakened_copy "$library" "$library_out" ${function_in_library[@]+"${function_in_library[@]}"}
  else
    weakened_copy "$library" "$student_out" ${all_library[@]+"${all_library[@]}"}
    cp "$library" "$library_out"
  fi
done
[ "$defined_by_student" = 1 ] || fail "no stub file defines $function: its test cases would grade the library's own"
