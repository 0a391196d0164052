# Install rules (XGO_INSTALL, on at top level):
#   cmake --install build --prefix P
# puts the public headers in P/include/xgo, libxgo_core.a (and the hosted
# assert handler it links) in P/lib, the programs in P/bin, the Wireshark
# dissector in P/share/xgo/wireshark, a CMake package in P/lib/cmake/xgo
# (find_package(xgo) -> xgo::core) and P/lib/pkgconfig/xgo.pc.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(XGO_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/xgo)

# The portable core: the public headers only (src/core/*.h stay private).
set(xgo_core_targets xgo_core)
if(TARGET xgo_assert_hosted)
  list(APPEND xgo_core_targets xgo_assert_hosted)
endif()
install(TARGETS ${xgo_core_targets} EXPORT xgoTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/xgo DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.h")

# The programs that exist in this build.
foreach(program xgo-emu xgo-cli xgo-replay xgo-plot)
  if(TARGET ${program})
    install(TARGETS ${program} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  endif()
endforeach()
if(TARGET xgo-wireshark)
  install(FILES ${PROJECT_BINARY_DIR}/wireshark/xgo.lua ${PROJECT_BINARY_DIR}/wireshark/xgo_tables.lua
          DESTINATION ${CMAKE_INSTALL_DATADIR}/xgo/wireshark)
endif()

# CMake package: find_package(xgo) gives xgo::core.
install(EXPORT xgoTargets NAMESPACE xgo:: FILE xgoTargets.cmake DESTINATION ${XGO_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/xgoConfig.cmake.in
  ${PROJECT_BINARY_DIR}/xgoConfig.cmake INSTALL_DESTINATION ${XGO_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/xgoConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/xgoConfig.cmake ${PROJECT_BINARY_DIR}/xgoConfigVersion.cmake
        DESTINATION ${XGO_CMAKE_DIR})

# pkg-config: the same flags for builds without CMake.
set(XGO_PC_LIBS "-lxgo_core")
if(TARGET xgo_assert_hosted)
  string(APPEND XGO_PC_LIBS " -lxgo_assert_hosted")
endif()
set(XGO_PC_CFLAGS "")
if(XGO_ASSERTS)
  set(XGO_PC_CFLAGS "-DXGO_ASSERT_ENABLED=1")
endif()
# the prefix relative to the .pc file: it does not know the prefix until
# `cmake --install --prefix` picks one
file(RELATIVE_PATH XGO_PC_TO_PREFIX /p/${CMAKE_INSTALL_LIBDIR}/pkgconfig /p)
string(REGEX REPLACE "/$" "" XGO_PC_TO_PREFIX "${XGO_PC_TO_PREFIX}")
configure_file(${PROJECT_SOURCE_DIR}/cmake/xgo.pc.in ${PROJECT_BINARY_DIR}/xgo.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/xgo.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
