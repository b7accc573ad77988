# Every committed figure is shown in the book. The book is made by Doxygen from book/*.md and
# each chapter's intro.md and results.md (book/CMakeLists.txt); a figure under figures/ that no
# page embeds, as ![caption](name.png) or \image html name.png, is read by no one. This script
# fails, listing each such figure. The figures' own .md files in figures/ and README.md are not
# pages of the book and do not count.
#
#   cmake -DSOURCE_DIR=<repository> -P tests/figures_shown.cmake
cmake_minimum_required(VERSION 3.20)
if(NOT SOURCE_DIR OR NOT IS_DIRECTORY "${SOURCE_DIR}")
  message(FATAL_ERROR "figures_shown.cmake: SOURCE_DIR: give -DSOURCE_DIR=<the repository>")
endif()

file(GLOB pages LIST_DIRECTORIES false
     "${SOURCE_DIR}/book/*.md" "${SOURCE_DIR}/chapters/*/intro.md" "${SOURCE_DIR}/chapters/*/results.md")
if(NOT pages)
  message(FATAL_ERROR "figures_shown.cmake: SOURCE_DIR: no book pages under ${SOURCE_DIR}")
endif()
set(book "")
foreach(page IN LISTS pages)
  file(READ "${page}" text)
  string(APPEND book "\n${text}")
endforeach()

file(GLOB_RECURSE figures LIST_DIRECTORIES false RELATIVE "${SOURCE_DIR}"
     "${SOURCE_DIR}/figures/*.png" "${SOURCE_DIR}/figures/*.svg" "${SOURCE_DIR}/figures/*.gif"
     "${SOURCE_DIR}/figures/*.jpg" "${SOURCE_DIR}/figures/*.jpeg")
if(NOT figures)
  message(FATAL_ERROR "figures_shown.cmake: SOURCE_DIR: no figures under ${SOURCE_DIR}/figures")
endif()

set(unshown "")
set(unshown_count 0)
list(LENGTH figures figure_count)
foreach(figure IN LISTS figures)
  get_filename_component(name "${figure}" NAME)
  # Doxygen finds an image by its bare name on IMAGE_PATH: the page must name exactly this file.
  string(REGEX REPLACE "([][.+*?^$()|\\\\])" "\\\\\\1" escaped "${name}")
  string(REGEX MATCH "\\]\\([ \t]*${escaped}[ \t]*\\)|[\\\\@]image[ \t]+html[ \t]+${escaped}" shown "${book}")
  if(shown STREQUAL "")
    string(APPEND unshown "  ${figure}\n")
    math(EXPR unshown_count "${unshown_count} + 1")
  endif()
endforeach()

if(unshown_count GREATER 0)
  message(FATAL_ERROR "figures_shown: ${unshown_count} of ${figure_count} figures are shown on no page of the book "
                      "(book/*.md, chapters/*/intro.md, chapters/*/results.md):\n${unshown}")
endif()
message(STATUS "figures_shown: all ${figure_count} figures are shown in the book")
