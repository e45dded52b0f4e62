# SPDX-License-Identifier: BSD-3-Clause
# What `cmake --install` (and `make install`) puts under the prefix: the
# CLI and its manual page, the static and the shared library, the FMU's binary, the public headers, flexbond.pc,
# the Python package (python/flexbond), and the examples and documents
# under share/doc/flexbond. Included from CMakeLists.txt.

install(TARGETS flexbond ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
if(TARGET flexbond_shared)
  install(TARGETS flexbond_shared LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
endif()
install(DIRECTORY ${CMAKE_SOURCE_DIR}/include/flexbond DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
# The FMU's binary and its sources, which flexbond fmu packages
# (fb_fmu_runtime_path looks for it there).
if(TARGET flexbond_fmu)
  install(TARGETS flexbond_fmu LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/flexbond)
  install(DIRECTORY $<TARGET_FILE_DIR:flexbond_fmu>/fmu-sources
          DESTINATION ${CMAKE_INSTALL_LIBDIR}/flexbond)
endif()
if(TARGET flexbond_cli)
  install(TARGETS flexbond_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  # The manual page, from the built command's --help texts (cmake/manpage.sh).
  find_program(BASH_EXECUTABLE bash REQUIRED)
  add_custom_command(OUTPUT ${CMAKE_BINARY_DIR}/flexbond.1
                     COMMAND ${BASH_EXECUTABLE} ${CMAKE_SOURCE_DIR}/cmake/manpage.sh
                             $<TARGET_FILE:flexbond_cli> ${CMAKE_BINARY_DIR}/flexbond.1
                     DEPENDS flexbond_cli ${CMAKE_SOURCE_DIR}/cmake/manpage.sh
                     COMMENT "Writing the manual page flexbond.1")
  add_custom_target(flexbond_manpage ALL DEPENDS ${CMAKE_BINARY_DIR}/flexbond.1)
  install(FILES ${CMAKE_BINARY_DIR}/flexbond.1 DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
endif()

# flexbond.pc: the prefix relative to the .pc file's directory, one ".."
# per component of the library directory and one for pkgconfig/; an
# absolute library or include directory is written as it is.
set(FLEXBOND_PC_LIBDIR "\${prefix}/${CMAKE_INSTALL_LIBDIR}")
set(FLEXBOND_PC_INCLUDEDIR "\${prefix}/${CMAKE_INSTALL_INCLUDEDIR}")
if(IS_ABSOLUTE "${CMAKE_INSTALL_INCLUDEDIR}")
  set(FLEXBOND_PC_INCLUDEDIR "${CMAKE_INSTALL_INCLUDEDIR}")
endif()
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(FLEXBOND_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
  set(FLEXBOND_PC_LIBDIR "${CMAKE_INSTALL_LIBDIR}")
else()
  set(FLEXBOND_PC_PREFIX "\${pcfiledir}/..")
  string(REPLACE "/" ";" libdir_parts "${CMAKE_INSTALL_LIBDIR}")
  foreach(part IN LISTS libdir_parts)
    string(APPEND FLEXBOND_PC_PREFIX "/..")
  endforeach()
endif()
configure_file(${CMAKE_SOURCE_DIR}/cmake/flexbond.pc.in ${CMAKE_BINARY_DIR}/flexbond.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/flexbond.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

install(DIRECTORY ${CMAKE_SOURCE_DIR}/examples/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/examples)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(FILES ${CMAKE_SOURCE_DIR}/README.md ${CMAKE_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR})

# The Python package (docs/python.md), for the system python3 (Debian's
# /usr/bin/python3 before any other on PATH: its python3-numpy is the one
# the package needs). It finds the shared library through library_path,
# written at install time with the library's installed path (without
# DESTDIR: where it will be, not where it is staged).
find_program(FLEXBOND_PYTHON3 python3 PATHS /usr/bin NO_DEFAULT_PATH)
find_program(FLEXBOND_PYTHON3 python3)
if(FLEXBOND_PYTHON3 AND TARGET flexbond_shared)
  execute_process(COMMAND ${FLEXBOND_PYTHON3} -c
                          "import sys; print('%d.%d' % sys.version_info[:2])"
                  OUTPUT_VARIABLE FLEXBOND_PYTHON3_VERSION OUTPUT_STRIP_TRAILING_WHITESPACE
                  RESULT_VARIABLE python_rc)
  if(python_rc EQUAL 0)
    set(FLEXBOND_PYTHON_DIR "lib/python${FLEXBOND_PYTHON3_VERSION}/dist-packages" CACHE STRING
        "Where the Python package goes, relative to the prefix (on python3's path for /usr/local)")
    install(FILES ${CMAKE_SOURCE_DIR}/python/flexbond/__init__.py
            DESTINATION ${FLEXBOND_PYTHON_DIR}/flexbond)
    # Either directory may be absolute, or relative to the prefix given at
    # install time (cmake --install --prefix).
    install(CODE "
      set(libdir \"${CMAKE_INSTALL_LIBDIR}\")
      set(pydir \"${FLEXBOND_PYTHON_DIR}\")
      if(NOT IS_ABSOLUTE \"\${libdir}\")
        set(libdir \"\${CMAKE_INSTALL_PREFIX}/\${libdir}\")
      endif()
      if(NOT IS_ABSOLUTE \"\${pydir}\")
        set(pydir \"\${CMAKE_INSTALL_PREFIX}/\${pydir}\")
      endif()
      set(txt \"\$ENV{DESTDIR}\${pydir}/flexbond/library_path\")
      message(STATUS \"Installing: \${txt}\")
      file(WRITE \"\${txt}\" \"\${libdir}/$<TARGET_SONAME_FILE_NAME:flexbond_shared>\")
      list(APPEND CMAKE_INSTALL_MANIFEST_FILES \"\${txt}\")
    ")
  endif()
endif()
