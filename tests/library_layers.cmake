# The library's areas (common/include/kerf/<area>, common/src/<area>) build on one another in one
# direction: the enrichment and its models (xfem) come before the scene files that choose them
# (scene) and the time steppers that move them (dynamics), so nothing in xfem includes either.
# This script fails, naming file:line, on each include that goes the other way.
#
#   cmake -DSOURCE_DIR=<repository> -P tests/library_layers.cmake
#
# Not yet checked, because not yet true: mesh includes fem (check_tet_mesh.cpp: a Tet10's
# curved Jacobian), and app (input errors) and io are used by most areas and use some of them.
cmake_minimum_required(VERSION 3.20)
if(NOT SOURCE_DIR OR NOT IS_DIRECTORY "${SOURCE_DIR}")
  message(FATAL_ERROR "library_layers.cmake: SOURCE_DIR: give -DSOURCE_DIR=<the repository>")
endif()
# Each rule: an area, then the areas it must not include.
set(rules "xfem:scene,dynamics")
set(found "")
foreach(rule IN LISTS rules)
  string(REPLACE ":" ";" parts "${rule}")
  list(GET parts 0 area)
  list(GET parts 1 above)
  string(REPLACE "," ";" above "${above}")
  file(GLOB_RECURSE files LIST_DIRECTORIES false
       "${SOURCE_DIR}/common/include/kerf/${area}/*" "${SOURCE_DIR}/common/src/${area}/*")
  if(NOT files)
    message(FATAL_ERROR "library_layers.cmake: SOURCE_DIR: no files in the area ${area} under ${SOURCE_DIR}")
  endif()
  foreach(file IN LISTS files)
    file(STRINGS "${file}" lines)
    set(number 0)
    foreach(line IN LISTS lines)
      math(EXPR number "${number} + 1")
      foreach(other IN LISTS above)
        if(line MATCHES "#include \"kerf/${other}/")
          file(RELATIVE_PATH relative "${SOURCE_DIR}" "${file}")
          string(APPEND found "\n  ${relative}:${number}: ${area} includes ${other}: ${line}")
        endif()
      endforeach()
    endforeach()
  endforeach()
endforeach()
if(found)
  message(FATAL_ERROR "library_layers.cmake: includes against the library's layers:${found}")
endif()
message(STATUS "library_layers.cmake: no include goes against the layers checked")
