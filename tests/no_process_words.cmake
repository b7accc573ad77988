# The repository states facts and cites the papers by their bibliography names; it does not
# refer to the work that produced it: tracker entries and their numbered points, the unpublished
# notes on the papers and their section numbers, a review's findings, or a paper by the number of
# its text file. This script reads every source and text file of the repository and fails,
# naming file:line, on each such reference.
#
#   cmake -DSOURCE_DIR=<repository> -P tests/no_process_words.cmake
#
# The words are put together from pieces below, so that this file does not match itself.
cmake_minimum_required(VERSION 3.20)
if(NOT SOURCE_DIR OR NOT IS_DIRECTORY "${SOURCE_DIR}")
  message(FATAL_ERROR "no_process_words.cmake: SOURCE_DIR: give -DSOURCE_DIR=<the repository>")
endif()

string(CONCAT tracker "is" "sue")
string(CONCAT point "it" "em")
string(CONCAT notes "no" "tes")
string(CONCAT paper "pa" "per")
string(CONCAT finding "re" "view")

# Matched against the lower-cased text, so case does not matter. A reference may be broken
# over two comment lines: `gap` lets whitespace and comment marks lie between its words.
set(gap "[ \t\r\n/*#]+")
set(patterns
    "[^a-z]${tracker}s?${gap}[0-9]"                       # "<tracker> 10"
    "[^a-z]${tracker}:"                                   # "<tracker>: chapter 7"
    "[^a-z]the ${tracker}[^a-z]"                          # "the <tracker> asks", "the <tracker>'s"
    "[^a-z]${point}s?${gap}[0-9]"                         # "<point> 7", "<point>s 1-3"
    "[^a-z]${notes}[ \t\r\n/*#,:;(]*([0-9]|section|question)"  # "<notes> 5.3", "<notes>, section 7.2"
    "[(]${notes}[^a-z]"                                   # "(<notes> ...)"
    "[^a-z]the ${notes}[^a-z]"                            # "the <notes>' resolution"
    "${notes}_ch"                                         # their file's name
    "[^a-z]${paper}${gap}00[0-9]"                         # a paper by its file number
    "[^a-z]the ${finding}'s"                              # "the <finding>'s F3"
    "[^a-z]${finding}${gap}f[0-9]")                       # "<finding> F10"
list(JOIN patterns "|" any_pattern)

file(GLOB_RECURSE files LIST_DIRECTORIES false RELATIVE "${SOURCE_DIR}"
     "${SOURCE_DIR}/common/*" "${SOURCE_DIR}/chapters/*" "${SOURCE_DIR}/tests/*" "${SOURCE_DIR}/examples/*"
     "${SOURCE_DIR}/figures/*" "${SOURCE_DIR}/book/*" "${SOURCE_DIR}/assignments/*" "${SOURCE_DIR}/bench/*"
     "${SOURCE_DIR}/cmake/*")
foreach(top README.md CMakeLists.txt CMakePresets.json kerf.sh)
  if(EXISTS "${SOURCE_DIR}/${top}")
    list(APPEND files ${top})
  endif()
endforeach()
list(FILTER files EXCLUDE REGEX "(^|/)(build|output|work)/")
list(FILTER files EXCLUDE REGEX "\\.(png|jpe?g|gif|pdf|apng|vtu|stl|gz|xz|zip|o|a|so)$")

set(hits "")
set(hit_count 0)
list(LENGTH files file_count)
foreach(file IN LISTS files)
  file(READ "${SOURCE_DIR}/${file}" text)
  string(TOLOWER "${text}" text)
  # Line 1 is preceded by a newline, so that a reference at the very start has a non-letter before it.
  set(rest "\n${text}")
  set(line 0)
  while(TRUE)
    string(REGEX MATCH "${any_pattern}" match "${rest}")
    if(match STREQUAL "")
      break()
    endif()
    string(FIND "${rest}" "${match}" at)
    string(SUBSTRING "${rest}" 0 ${at} before)
    # The match may begin with the character before the word (a newline counts there).
    string(SUBSTRING "${match}" 0 1 first)
    if(first STREQUAL "\n")
      string(APPEND before "\n")
    endif()
    string(REGEX MATCHALL "\n" newlines "${before}")
    list(LENGTH newlines n)
    math(EXPR hit_line "${line} + ${n}")
    string(REGEX REPLACE "[\r\n\t ]+" " " shown "${match}")
    string(STRIP "${shown}" shown)
    string(APPEND hits "  ${file}:${hit_line}: \"${shown}\"\n")
    math(EXPR hit_count "${hit_count} + 1")
    # Go on after the match, counting the lines it spans.
    string(LENGTH "${match}" length)
    math(EXPR after "${at} + ${length}")
    string(SUBSTRING "${rest}" 0 ${after} consumed)
    string(REGEX MATCHALL "\n" newlines "${consumed}")
    list(LENGTH newlines n)
    math(EXPR line "${line} + ${n}")
    string(SUBSTRING "${rest}" ${after} -1 rest)
  endwhile()
endforeach()

if(hit_count GREATER 0)
  message(FATAL_ERROR "${hit_count} reference(s) to the development process instead of a fact or a paper's "
                      "bibliography name (book/bibliography.md), in ${file_count} files read:\n${hits}")
endif()
message(STATUS "no_process_words: ${file_count} files read, no reference to the development process")
