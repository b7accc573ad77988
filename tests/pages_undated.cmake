# The book's pages state current numbers and the commands that make them, not when a run was
# made: a date on a page is a measurement log, which belongs in the figures' own notes. This
# script fails, naming file:line, on a date ("1 December 2026", "2026-12-01") in a page of the
# book (book/*.md and each chapter's intro.md and results.md); a date inside a file's name
# (bench_corotation_2026-11-23_amd.md) is the file's, not the page's.
#
#   cmake -DSOURCE_DIR=<repository> -P tests/pages_undated.cmake
cmake_minimum_required(VERSION 3.20)
if(NOT SOURCE_DIR OR NOT IS_DIRECTORY "${SOURCE_DIR}")
  message(FATAL_ERROR "pages_undated.cmake: SOURCE_DIR: give -DSOURCE_DIR=<the repository>")
endif()
file(GLOB pages LIST_DIRECTORIES false RELATIVE "${SOURCE_DIR}"
     "${SOURCE_DIR}/book/*.md" "${SOURCE_DIR}/chapters/*/intro.md" "${SOURCE_DIR}/chapters/*/results.md")
if(NOT pages)
  message(FATAL_ERROR "pages_undated.cmake: SOURCE_DIR: no book pages under ${SOURCE_DIR}")
endif()
set(months "january|february|march|april|may|june|july|august|september|october|november|december")
set(written "[0-9]+ (${months}) 20[0-9][0-9]")
set(numeric "(^|[^_0-9a-z-])20[0-9][0-9]-[01][0-9]-[0-3][0-9]([^_0-9a-z]|$)")
set(found "")
foreach(page IN LISTS pages)
  file(STRINGS "${SOURCE_DIR}/${page}" lines)
  set(number 0)
  foreach(line IN LISTS lines)
    math(EXPR number "${number} + 1")
    string(TOLOWER "${line}" lower)
    if(lower MATCHES "${written}" OR lower MATCHES "${numeric}")
      string(APPEND found "\n  ${page}:${number}: ${line}")
    endif()
  endforeach()
endforeach()
if(found)
  message(FATAL_ERROR "pages_undated.cmake: dates of runs on the book's pages (move them to the figures' notes):${found}")
endif()
list(LENGTH pages count)
message(STATUS "pages_undated.cmake: no date on the book's ${count} pages")
