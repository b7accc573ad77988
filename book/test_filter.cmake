# The test `book_filter`: the literate filter on tricky input.
#   - every tests/book/NAME.cpp with a NAME.expected.md must filter to exactly that text, and
#     Doxygen must take the page without a warning;
#   - every tests/book/NAME.cpp with a NAME.expected-error must be rejected with a message
#     that contains that text (and names the file and line).
#   - every tests/book/NAME.page.md is an intro or results file with kernel lines, checked the same
#     way against NAME.page.expected.md or NAME.page.expected-error;
#   cmake -DFILTER=kerf_literate -DDOXYGEN=doxygen -DINPUTS=tests/book -DSOURCE=top -DWORK=dir -P test_filter.cmake
file(GLOB inputs ${INPUTS}/*.cpp)
if(NOT inputs)
  message(FATAL_ERROR "no test inputs in ${INPUTS}")
endif()
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(failures "")
set(pages "")
# One run of the filter on input LABEL: against EXPECTED (its whole output, which then also goes
# to Doxygen as page PAGE_ID titled TITLE) or, if that file is absent, against EXPECTED_ERROR (the
# message's one line, and the input's file name LOCATION with its line). Appends to `failures`
# and `pages`.
function(check_run label status output error expected expected_error location page_id title)
  if(EXISTS ${expected})
    file(READ ${expected} text)
    get_filename_component(expected_name ${expected} NAME)
    if(NOT status EQUAL 0)
      string(APPEND failures "${label}: the filter failed: ${error}\n")
    elseif(NOT output STREQUAL text)
      file(WRITE ${WORK}/${label}.actual.md "${output}")
      string(APPEND failures "${label}: output differs from ${expected_name}; see ${WORK}/${label}.actual.md\n")
    endif()
    file(WRITE ${WORK}/${page_id}.md "# ${title} ${label} {#${page_id}}\n\n${output}")
    list(APPEND pages ${WORK}/${page_id}.md)
  elseif(EXISTS ${expected_error})
    file(STRINGS ${expected_error} message LIMIT_COUNT 1)
    string(FIND "${error}" "${message}" found)
    string(FIND "${error}" "${location}:" located)
    if(status EQUAL 0)
      string(APPEND failures "${label}: the filter accepted input it must reject\n")
    elseif(found EQUAL -1 OR located EQUAL -1)
      string(APPEND failures "${label}: expected an error with '${message}' and the file and line, got: ${error}\n")
    endif()
  else()
    string(APPEND failures "${label}: has neither ${expected} nor ${expected_error}\n")
  endif()
  set(failures "${failures}" PARENT_SCOPE)
  set(pages "${pages}" PARENT_SCOPE)
endfunction()

foreach(input ${inputs})
  get_filename_component(name ${input} NAME_WE)
  execute_process(COMMAND ${FILTER} filter ${input} RESULT_VARIABLE status
                  OUTPUT_VARIABLE output ERROR_VARIABLE error)
  check_run(${name} "${status}" "${output}" "${error}" ${INPUTS}/${name}.expected.md ${INPUTS}/${name}.expected-error
            ${name}.cpp ${name} "Filter test")
endforeach()

# Pages with kernels: every NAME.page.md, run as a chapter's intro or results file is (the
# kernels' files relative to SOURCE), against NAME.page.expected.md or NAME.page.expected-error.
file(GLOB page_inputs ${INPUTS}/*.page.md)
foreach(input ${page_inputs})
  get_filename_component(file_name ${input} NAME)
  string(REGEX REPLACE "\\.page\\.md$" "" name ${file_name})
  file(RELATIVE_PATH relative ${SOURCE} ${input})
  execute_process(COMMAND ${FILTER} page ${SOURCE} ${relative} WORKING_DIRECTORY ${SOURCE} RESULT_VARIABLE status
                  OUTPUT_VARIABLE output ERROR_VARIABLE error)
  check_run(${name}.page "${status}" "${output}" "${error}" ${INPUTS}/${name}.page.expected.md
            ${INPUTS}/${name}.page.expected-error ${file_name} page_${name} "Page test")
endforeach()

# The header filter: every NAME.hpp with a NAME.expected.hpp.
file(GLOB headers ${INPUTS}/*.hpp)
set(header_inputs "")
foreach(header ${headers})
  get_filename_component(name ${header} NAME)
  if(name MATCHES "\\.expected\\.hpp$")
    continue()
  endif()
  string(REGEX REPLACE "\\.hpp$" ".expected.hpp" expected_file ${header})
  if(NOT EXISTS ${expected_file})
    string(APPEND failures "${name}: has no expected output ${expected_file}\n")
    continue()
  endif()
  execute_process(COMMAND ${FILTER} header ${header} RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE error)
  file(READ ${expected_file} expected)
  if(NOT status EQUAL 0)
    string(APPEND failures "${name}: the header filter failed: ${error}\n")
  elseif(NOT output STREQUAL expected)
    file(WRITE ${WORK}/${name}.actual "${output}")
    string(APPEND failures "${name}: header filter output differs from ${expected_file}; see ${WORK}/${name}.actual\n")
  endif()
  list(APPEND header_inputs ${header})
endforeach()

# What the filters made must go through Doxygen without a warning.
if(pages)
  list(JOIN pages " " input_list)
  foreach(header ${header_inputs})
    string(APPEND input_list " ${header}")
  endforeach()
  file(WRITE ${WORK}/Doxyfile "INPUT = ${input_list}\nOUTPUT_DIRECTORY = ${WORK}\nQUIET = YES\n"
       "HAVE_DOT = NO\nGENERATE_LATEX = NO\nUSE_MATHJAX = YES\nMATHJAX_RELPATH = mathjax\n"
       "WARN_LOGFILE = ${WORK}/warnings.log\nWARN_AS_ERROR = FAIL_ON_WARNINGS\n"
       "EXTRACT_ALL = YES\nFILTER_PATTERNS = \"*.hpp=${FILTER} header\"\n")
  # The tricky input refers to \ref chapter_99: give it a target.
  file(WRITE ${WORK}/chapter_99.md "# A chapter for references {#chapter_99}\n\nNothing here.\n")
  file(APPEND ${WORK}/Doxyfile "INPUT += ${WORK}/chapter_99.md\n")
  execute_process(COMMAND ${DOXYGEN} ${WORK}/Doxyfile RESULT_VARIABLE status WORKING_DIRECTORY ${WORK})
  set(log "")
  if(EXISTS ${WORK}/warnings.log)
    file(READ ${WORK}/warnings.log log)
  endif()
  if(NOT status EQUAL 0 OR NOT log STREQUAL "")
    string(APPEND failures "Doxygen on the filtered pages (exit status ${status}):\n${log}\n")
  endif()
endif()

if(NOT failures STREQUAL "")
  message(FATAL_ERROR "literate filter test failed:\n${failures}")
endif()
