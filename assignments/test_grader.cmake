# The test `assignment_grader`: grade.sh says what is wrong in one line, and exits 2, for each
# mistake a student or a teacher can make before anything is graded. It copies grade.sh into
# a small tree of its own, with an assignment folder for each mistake, and runs it there:
#   cmake -DGRADE_SH=<assignments/grade.sh> -DSUITE=<a test suite's executable> -DWORK=<folder> -P test_grader.cmake
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/assignments ${WORK}/tests/common ${WORK}/build/assignments)
file(COPY ${GRADE_SH} DESTINATION ${WORK}/assignments)
file(MAKE_DIRECTORY ${WORK}/assignments/97_no_grading/stubs)
file(WRITE ${WORK}/assignments/96_no_match/grading.txt "# a filter no test case matches\nf | common | no test case has this name*\n")
file(WRITE ${WORK}/assignments/95_bad_line/grading.txt "# a line without its filter\nf | common\n")
file(WRITE ${WORK}/assignments/94_no_suite/grading.txt "f | no_such_suite | *\n")
file(WRITE ${WORK}/assignments/93_not_built/grading.txt "f | common | *\n")
# The suite's own executable stands in for assignment 96's graded copy: only its test-case
# names matter here.
file(CREATE_LINK ${SUITE} ${WORK}/build/assignments/assignment_96_common_f SYMBOLIC)

function(expect_one_line_error expected)
  execute_process(COMMAND bash ${WORK}/assignments/grade.sh ${ARGN} --build-dir ${WORK}/build
                  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(REGEX MATCHALL "\n" newlines "${err}")
  list(LENGTH newlines lines)
  if(NOT status EQUAL 2 OR NOT lines EQUAL 1 OR NOT err MATCHES "^grade.sh: .*${expected}")
    message(FATAL_ERROR "grade.sh ${ARGN}: expected exit status 2 and one line on stderr saying "
                        "\"${expected}\", got status ${status} and:\n${err}")
  endif()
  message(STATUS "grade.sh ${ARGN}: ${err}")
endfunction()

expect_one_line_error("which assignment\\?")
expect_one_line_error("\"x1\" is not an assignment number" x1)
expect_one_line_error("there is no assignment 42 \\(no folder assignments/42_\\*\\)" 42)
expect_one_line_error("unknown option --fast" 96 --fast)
expect_one_line_error("assignments/97_no_grading/grading.txt is missing" 97)
expect_one_line_error("the filter of f matches no test case of tests/common" 96)
expect_one_line_error("grading.txt:2: expected" 95)
expect_one_line_error("there is no test suite tests/no_such_suite" 94)
expect_one_line_error("assignment_93_common_f is not built" 93)
