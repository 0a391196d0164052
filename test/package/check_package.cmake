# check_package.cmake - xgo-board as a package a C project consumes; run by
# ctest (test/CMakeLists.txt) in one of two modes:
#
#   MODE=find_package   cmake --install BUILD --prefix WORK/prefix, check what
#                       is there (and that no private header is), then build
#                       and run examples/host-test with find_package(xgo), and
#                       once more with the flags of pkg-config's xgo.pc;
#   MODE=subdirectory   build and run examples/host-test with
#                       add_subdirectory(SOURCE): the consumer's build type
#                       stays unset and xgo's targets get no -Werror.
#
# Variables: MODE, SOURCE, BUILD, WORK, C_COMPILER, C_FLAGS (the build's
# sanitizer flags, which a consumer of its library needs too).
cmake_minimum_required(VERSION 3.16)

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${ARGN}\n${out}\n${err}")
  endif()
  message(STATUS "${what}: ok")
  set(run_output "${out}" PARENT_SCOPE)
endfunction()

# Configure, build and test the example in dir with the extra arguments.
function(consumer dir)
  file(REMOVE_RECURSE ${dir})
  run("configure ${dir}" ${CMAKE_COMMAND} -S ${SOURCE}/examples/host-test -B ${dir}
      -DCMAKE_C_COMPILER=${C_COMPILER} "-DCMAKE_C_FLAGS=${C_FLAGS}" ${ARGN})
  run("build ${dir}" ${CMAKE_COMMAND} --build ${dir} -j2)
  run("test ${dir}" ${CMAKE_CTEST_COMMAND} --test-dir ${dir} --output-on-failure)
endfunction()

if(MODE STREQUAL "find_package")
  set(prefix ${WORK}/prefix)
  file(REMOVE_RECURSE ${prefix})
  run("cmake --install" ${CMAKE_COMMAND} --install ${BUILD} --prefix ${prefix})
  foreach(f include/xgo/board.h include/xgo/protocol.h include/xgo/reg_units.h
            lib/libxgo_core.a lib/cmake/xgo/xgoConfig.cmake lib/cmake/xgo/xgoConfigVersion.cmake
            lib/pkgconfig/xgo.pc bin/xgo-emu bin/xgo-cli bin/xgo-replay
            share/xgo/wireshark/xgo.lua share/xgo/wireshark/xgo_tables.lua)
    if(NOT EXISTS ${prefix}/${f})
      message(FATAL_ERROR "not installed: ${f}")
    endif()
  endforeach()
  foreach(program xgo-emu xgo-cli xgo-replay)
    run("${program} --version (installed)" ${prefix}/bin/${program} --version)
  endforeach()
  # only the public headers: every installed one is in include/xgo of the source
  file(GLOB installed RELATIVE ${prefix}/include/xgo ${prefix}/include/xgo/*)
  foreach(h ${installed})
    if(NOT EXISTS ${SOURCE}/include/xgo/${h})
      message(FATAL_ERROR "installed but not public: include/xgo/${h}")
    endif()
  endforeach()
  foreach(private motion.h codec.h regfile.h gait.h)
    if(EXISTS ${prefix}/include/xgo/${private} OR EXISTS ${prefix}/include/${private})
      message(FATAL_ERROR "a private header was installed: ${private}")
    endif()
  endforeach()
  consumer(${WORK}/consumer-find-package -DCMAKE_PREFIX_PATH=${prefix})

  # pkg-config: the installed xgo.pc alone is enough to build the test
  find_program(PKG_CONFIG pkg-config)
  if(PKG_CONFIG)
    set(ENV{PKG_CONFIG_PATH} ${prefix}/lib/pkgconfig)
    run("pkg-config xgo" ${PKG_CONFIG} --cflags --libs xgo)
    string(STRIP "${run_output}" flags)
    separate_arguments(flags UNIX_COMMAND "${flags} ${C_FLAGS}")
    run("cc with pkg-config's flags" ${C_COMPILER} -std=c99 ${SOURCE}/examples/host-test/host_test.c
        ${flags} -o ${WORK}/host_test_pkg_config)
    run("host_test (pkg-config)" ${WORK}/host_test_pkg_config)
  else()
    message(STATUS "pkg-config not found: xgo.pc not exercised")
  endif()
elseif(MODE STREQUAL "subdirectory")
  set(dir ${WORK}/consumer-subdirectory)
  consumer(${dir} -DXGO_SOURCE_DIR=${SOURCE})
  file(STRINGS ${dir}/CMakeCache.txt build_type REGEX "^CMAKE_BUILD_TYPE:")
  if(NOT build_type STREQUAL "CMAKE_BUILD_TYPE:STRING=")
    message(FATAL_ERROR "xgo forced the consumer's build type: ${build_type}")
  endif()
  file(READ ${dir}/xgo-board/src/core/CMakeFiles/xgo_core.dir/flags.make core_flags)
  if(core_flags MATCHES "-Werror")
    message(FATAL_ERROR "xgo forced -Werror on a consumer:\n${core_flags}")
  endif()
  if(NOT core_flags MATCHES "-Wall")
    message(FATAL_ERROR "xgo_core's flags not where expected:\n${core_flags}")
  endif()
  message(STATUS "build type left unset, no -Werror in xgo's targets")
else()
  message(FATAL_ERROR "MODE must be find_package or subdirectory")
endif()
