# The test `book`: builds the book and fails if Doxygen failed or wrote any warning.
#   cmake -DBINARY_DIR=... -DCONFIG=... -DWARNINGS=... -DHTML=... -P test_book.cmake
file(REMOVE ${WARNINGS} ${HTML}/index.html)
set(config_args "")
if(CONFIG)
  set(config_args --config ${CONFIG})
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BINARY_DIR} --target book ${config_args}
                RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "building the book failed (exit status ${status})")
endif()
# Belt and braces: the build step checks the log too, but a test must not trust what it tests.
if(NOT EXISTS ${WARNINGS})
  message(FATAL_ERROR "Doxygen wrote no warning log at ${WARNINGS}: did it run?")
endif()
file(READ ${WARNINGS} log)
if(NOT log STREQUAL "")
  message(FATAL_ERROR "Doxygen warnings:\n${log}")
endif()
if(NOT EXISTS ${HTML}/index.html)
  message(FATAL_ERROR "no ${HTML}/index.html after building the book")
endif()
message(STATUS "the book built without warnings: ${HTML}/index.html")
