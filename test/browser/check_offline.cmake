# The view page loads nothing from elsewhere (issue 7: no third-party
# scripts, works with no network): no page file may contain "://" (no
# absolute URL of any scheme), and index.html loads only view.js and view.css.
#   cmake -DVIEW_DIR=src/host/view -P check_offline.cmake
cmake_minimum_required(VERSION 3.16)
file(GLOB files "${VIEW_DIR}/*")
if(NOT files)
  message(FATAL_ERROR "no page files in ${VIEW_DIR}")
endif()
foreach(f IN LISTS files)
  file(READ "${f}" text)
  string(FIND "${text}" "://" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "${f}: contains \"://\" at offset ${at}: the page must not load anything from elsewhere")
  endif()
endforeach()
file(READ "${VIEW_DIR}/index.html" html)
string(REGEX MATCHALL "(src|href)=\"[^\"]*\"" refs "${html}")
if(NOT refs STREQUAL "href=\"view.css\";src=\"view.js\"")
  message(FATAL_ERROR "index.html loads ${refs}; expected only view.css and view.js")
endif()
list(LENGTH files n)
message(STATUS "view page: ${n} files, no absolute URL, loads only view.css and view.js")
