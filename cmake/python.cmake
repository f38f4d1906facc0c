# SPDX-License-Identifier: MIT
# The Python package (python/kairos: ctypes and numpy, nothing compiled), installed beside the
# library, and the interpreter its tests run with.
#
# Debian's python3-numpy and python3-pytest serve Debian's /usr/bin/python3; a machine may put
# another python3 first on PATH (pyenv, a virtualenv) without them, so /usr/bin/python3 is
# preferred. -DKAIROS_PYTHON3=... names another.
find_program(KAIROS_PYTHON3 NAMES python3 PATHS /usr/bin NO_DEFAULT_PATH
    DOC "The Python interpreter the package is installed and tested for")
if(NOT KAIROS_PYTHON3)
    find_program(KAIROS_PYTHON3 NAMES python3 DOC "The Python interpreter the package is installed and tested for")
endif()

# Where the package goes, relative to the install prefix: the directory Debian's python3 searches
# (/usr/local/lib/python3.X/dist-packages for the default prefix, /usr/lib/python3/dist-packages
# for /usr).
set(KAIROS_PYTHON_INSTALL_DIR "" CACHE STRING
    "Install directory of the Python package kairos, relative to the prefix (empty: chosen for the interpreter)")
set(KAIROS_PYTHON_VERSION "")
if(KAIROS_PYTHON3)
    execute_process(COMMAND ${KAIROS_PYTHON3} -c "import sys; print('%d.%d' % sys.version_info[:2])"
        OUTPUT_VARIABLE KAIROS_PYTHON_VERSION OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
endif()
set(KAIROS_PYTHON_DIR "${KAIROS_PYTHON_INSTALL_DIR}")
if(KAIROS_PYTHON_DIR STREQUAL "")
    if(CMAKE_INSTALL_PREFIX STREQUAL "/usr" OR KAIROS_PYTHON_VERSION STREQUAL "")
        set(KAIROS_PYTHON_DIR lib/python3/dist-packages)
    else()
        set(KAIROS_PYTHON_DIR lib/python${KAIROS_PYTHON_VERSION}/dist-packages)
    endif()
endif()

# The package finds the installed library through _location.py: the path from the package's
# directory to libkairos.so.0, relative, so an install moved with --prefix or DESTDIR still works.
file(RELATIVE_PATH KAIROS_LIBRARY_FROM_PACKAGE
    ${CMAKE_INSTALL_PREFIX}/${KAIROS_PYTHON_DIR}/kairos ${CMAKE_INSTALL_FULL_LIBDIR}/libkairos.so.0)
file(GENERATE OUTPUT ${CMAKE_CURRENT_BINARY_DIR}/python/_location.py CONTENT
"# Written by CMake at install: the library's path relative to this package's directory.
LIBRARY_FROM_PACKAGE = \"${KAIROS_LIBRARY_FROM_PACKAGE}\"
")
install(DIRECTORY python/kairos DESTINATION ${KAIROS_PYTHON_DIR}
    FILES_MATCHING PATTERN "*.py" PATTERN "py.typed" PATTERN "__pycache__" EXCLUDE)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/python/_location.py DESTINATION ${KAIROS_PYTHON_DIR}/kairos)
