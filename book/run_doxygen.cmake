# Runs Doxygen on the book and fails, showing the warnings, if it wrote any. Doxygen writes its
# warnings to a log in the build tree (so that the test can read them), which is why we print
# the log here: a failed build should say what failed.
#   cmake -DDOXYGEN=... -DDOXYFILE=... -DWARNINGS=... -DHTML=... -DMATHJAX=... -P run_doxygen.cmake
file(REMOVE ${WARNINGS})
execute_process(COMMAND ${DOXYGEN} ${DOXYFILE} RESULT_VARIABLE status)
set(log "")
if(EXISTS ${WARNINGS})
  file(READ ${WARNINGS} log)
endif()
if(NOT status EQUAL 0 OR NOT log STREQUAL "")
  message(FATAL_ERROR "Doxygen failed (exit status ${status}); the book must build without warnings:\n${log}")
endif()
# The pages load MathJax from html/mathjax: a link to the system's copy, not a copy of it.
file(REMOVE ${HTML}/mathjax)
file(CREATE_LINK ${MATHJAX} ${HTML}/mathjax SYMBOLIC)
