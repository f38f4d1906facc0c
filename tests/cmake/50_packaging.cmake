# SPDX-License-Identifier: MIT
# Packaging and ABI: header tests, struct layout, C99 and dlopen programs, ctypes, install consumers, exports, abidiff.

set(KAIROS_ABI_TESTS ${CMAKE_CURRENT_SOURCE_DIR}/abi)
set(KAIROS_PUBLIC_INCLUDE_FLAGS -I${PROJECT_SOURCE_DIR}/include -I${KAIROS_GENERATED_INCLUDE})
# Under ASan a library can only be loaded into a process that starts with the ASan runtime, so
# the Python interpreter cannot load it; those tests run in the plain builds only.
if(CMAKE_C_FLAGS MATCHES "-fsanitize" OR CMAKE_CXX_FLAGS MATCHES "-fsanitize")
    set(KAIROS_SANITIZED ON)
else()
    set(KAIROS_SANITIZED OFF)
endif()

# ---- The public header compiles alone, strictly, as C99 and as C++ ------------------------------
set(KAIROS_STRICT -Wall -Wextra -pedantic -Werror)
add_test(NAME abi_header_c99
    COMMAND ${CMAKE_C_COMPILER} -x c -std=c99 ${KAIROS_STRICT} -Wstrict-prototypes -Wundef
            -fsyntax-only ${KAIROS_PUBLIC_INCLUDE_FLAGS} ${KAIROS_ABI_TESTS}/header_alone.c)
foreach(std IN ITEMS 11 20)
    add_test(NAME abi_header_cxx${std}
        COMMAND ${CMAKE_CXX_COMPILER} -x c++ -std=c++${std} ${KAIROS_STRICT} -Wundef -Wold-style-cast
                -fsyntax-only ${KAIROS_PUBLIC_INCLUDE_FLAGS} ${KAIROS_ABI_TESTS}/header_alone.c)
endforeach()
set_tests_properties(abi_header_c99 abi_header_cxx11 abi_header_cxx20 PROPERTIES LABELS abi)

# ---- Struct sizes and offsets, pinned for x86-64 LP64 -------------------------------------------
if(CMAKE_SYSTEM_PROCESSOR MATCHES "^(x86_64|AMD64|amd64)$" AND CMAKE_SIZEOF_VOID_P EQUAL 8)
    add_test(NAME abi_layout
        COMMAND ${CMAKE_C_COMPILER} -std=c99 ${KAIROS_STRICT} -c ${KAIROS_PUBLIC_INCLUDE_FLAGS}
                ${KAIROS_ABI_TESTS}/layout.c -o ${CMAKE_CURRENT_BINARY_DIR}/abi_layout.o)
    set_tests_properties(abi_layout PROPERTIES LABELS abi)
endif()

# ---- A strict C99 program linked against the library --------------------------------------------
add_executable(kairos_abi_c99 ${KAIROS_ABI_TESTS}/c99_program.c)
set_target_properties(kairos_abi_c99 PROPERTIES C_STANDARD 99 C_STANDARD_REQUIRED ON C_EXTENSIONS OFF)
target_compile_options(kairos_abi_c99 PRIVATE ${KAIROS_STRICT})
target_link_libraries(kairos_abi_c99 PRIVATE kairos::kairos Threads::Threads m)
add_test(NAME abi_c99_program COMMAND kairos_abi_c99)
set_tests_properties(abi_c99_program PROPERTIES LABELS abi)

# ---- dlopen: only kairos_get_api, and dlclose really unloads ------------------------------------
# Not linked against kairos (that would load it at start-up); it only needs the header's types.
add_executable(kairos_abi_dlopen ${KAIROS_ABI_TESTS}/dlopen_test.c)
set_target_properties(kairos_abi_dlopen PROPERTIES C_STANDARD 99 C_STANDARD_REQUIRED ON C_EXTENSIONS OFF)
target_compile_options(kairos_abi_dlopen PRIVATE ${KAIROS_STRICT})
target_include_directories(kairos_abi_dlopen PRIVATE ${PROJECT_SOURCE_DIR}/include ${KAIROS_GENERATED_INCLUDE})
target_link_libraries(kairos_abi_dlopen PRIVATE ${CMAKE_DL_LIBS})
add_dependencies(kairos_abi_dlopen kairos)
add_test(NAME abi_dlopen COMMAND kairos_abi_dlopen $<TARGET_FILE:kairos>)
set_tests_properties(abi_dlopen PROPERTIES LABELS abi)

# ---- Python ctypes (standard library only; python3 from PATH at test time) ----------------------
if(NOT KAIROS_SANITIZED)
    add_test(NAME abi_python_ctypes
        COMMAND sh -c "command -v python3 >/dev/null || { echo 'python3 not found: skipped'; exit 77; }; exec python3 \"$@\""
                sh ${CMAKE_CURRENT_SOURCE_DIR}/python/test_ctypes.py $<TARGET_FILE:kairos>)
    set_tests_properties(abi_python_ctypes PROPERTIES LABELS abi SKIP_RETURN_CODE 77)
endif()

# ---- The Python package's pytest suite (python/tests) on the interpreter cmake/python.cmake chose ----
# Skipped (77) when that interpreter lacks numpy or pytest, except in CI (CI set), where a suite
# that cannot run is a failure.
if(NOT KAIROS_SANITIZED AND KAIROS_PYTHON3)
    add_test(NAME python_package
        COMMAND sh -c "\"$1\" -c 'import numpy, pytest' 2>/dev/null || { echo \"numpy or pytest missing for $1\"; [ -n \"$CI\" ] && exit 1; exit 77; }; exec \"$1\" -m pytest -q -p no:cacheprovider \"$2\""
                sh ${KAIROS_PYTHON3} ${PROJECT_SOURCE_DIR}/python/tests)
    set_tests_properties(python_package PROPERTIES LABELS python SKIP_RETURN_CODE 77 TIMEOUT 600
        ENVIRONMENT "KAIROS_LIBRARY=$<TARGET_FILE:kairos>;PYTHONPATH=${PROJECT_SOURCE_DIR}/python;PYTHONDONTWRITEBYTECODE=1")
endif()

# ---- Exports: only kairos_ functions, SONAME libkairos.so.0, node KAIROS_0 ----------------------
add_test(NAME abi_exports
    COMMAND bash ${KAIROS_ABI_TESTS}/check_exports.sh $<TARGET_FILE:kairos> ${PROJECT_SOURCE_DIR}/include/kairos/kairos.h)
set_tests_properties(abi_exports PROPERTIES LABELS abi
    ENVIRONMENT "NM=${CMAKE_NM};READELF=${CMAKE_READELF}")

# ---- Install into a scratch prefix; outside CMake and pkg-config consumers ----------------------
# The consumers are built with this build's C flags, so under ASan they start with its runtime.
set(KAIROS_CONSUMER_DIR ${CMAKE_BINARY_DIR}/consumer-test)
set(KAIROS_CONSUMER_ENV
    "CMAKE=${CMAKE_COMMAND}" "CC=${CMAKE_C_COMPILER}" "CFLAGS=${CMAKE_C_FLAGS}"
    "LDFLAGS=${CMAKE_EXE_LINKER_FLAGS}" "KAIROS_EXPECTED_VERSION=${PROJECT_VERSION}" "PYTHON3=${KAIROS_PYTHON3}")
set(KAIROS_CONSUMER_STEPS install cmake pkgconfig major)
if(NOT KAIROS_SANITIZED AND KAIROS_PYTHON3)
    list(APPEND KAIROS_CONSUMER_STEPS python)
endif()
foreach(step IN LISTS KAIROS_CONSUMER_STEPS)
    add_test(NAME consumer_${step}
        COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/consumer/run_consumer.sh ${step} ${CMAKE_BINARY_DIR} ${KAIROS_CONSUMER_DIR})
    set_tests_properties(consumer_${step} PROPERTIES LABELS consumer ENVIRONMENT "${KAIROS_CONSUMER_ENV}"
        SKIP_RETURN_CODE 77)
    if(step STREQUAL "install")
        set_tests_properties(consumer_${step} PROPERTIES FIXTURES_SETUP kairos_installed)
    else()
        set_tests_properties(consumer_${step} PROPERTIES FIXTURES_REQUIRED kairos_installed)
    endif()
endforeach()
# The consumers write into one directory: run them one after another.
list(TRANSFORM KAIROS_CONSUMER_STEPS PREPEND consumer_ OUTPUT_VARIABLE KAIROS_CONSUMER_TESTS)
set_tests_properties(${KAIROS_CONSUMER_TESTS} PROPERTIES RESOURCE_LOCK kairos_consumer_dir)

# ---- Embedded with add_subdirectory, with the test and benchmark packages hidden ---------------
# Configures and builds tests/embed (the library alone, from this source tree) in a scratch
# directory with find_package unable to see GoogleTest, Google Benchmark, the peers or
# pkg-config, then runs its program.
set(KAIROS_EMBED_DIR ${CMAKE_BINARY_DIR}/embed-test)
add_test(NAME embed_add_subdirectory
    COMMAND sh -c "rm -rf \"$1\" && \"$2\" -S \"$3\" -B \"$1\" -DKAIROS_SOURCE_DIR=\"$4\" \
        -DCMAKE_C_COMPILER=\"$5\" -DCMAKE_CXX_COMPILER=\"$6\" \"-DCMAKE_C_FLAGS=$7\" \"-DCMAKE_CXX_FLAGS=$8\" \
        \"-DCMAKE_EXE_LINKER_FLAGS=$9\" \
        -DCMAKE_DISABLE_FIND_PACKAGE_GTest=ON -DCMAKE_DISABLE_FIND_PACKAGE_benchmark=ON \
        -DCMAKE_DISABLE_FIND_PACKAGE_PkgConfig=ON -DCMAKE_DISABLE_FIND_PACKAGE_fcl=ON \
        -DCMAKE_DISABLE_FIND_PACKAGE_ccd=ON -DCMAKE_DISABLE_FIND_PACKAGE_Bullet=ON \
        && \"$2\" --build \"$1\" && \"$1/kairos_embedder\""
        sh ${KAIROS_EMBED_DIR} ${CMAKE_COMMAND} ${CMAKE_CURRENT_SOURCE_DIR}/embed ${PROJECT_SOURCE_DIR}
        ${CMAKE_C_COMPILER} ${CMAKE_CXX_COMPILER} "${CMAKE_C_FLAGS}" "${CMAKE_CXX_FLAGS}" "${CMAKE_EXE_LINKER_FLAGS}")
set_tests_properties(embed_add_subdirectory PROPERTIES LABELS consumer TIMEOUT 600)

# ---- ABI check against the committed baseline (abidw/abidiff, public headers only) --------------
if(KAIROS_ABI_CHECK)
    if(CMAKE_BUILD_TYPE MATCHES "^(RelWithDebInfo|Debug)$" OR CMAKE_C_FLAGS MATCHES "(^| )-g")
        add_test(NAME abi_abidiff
            COMMAND bash ${KAIROS_ABI_TESTS}/check_abi.sh check $<TARGET_FILE:kairos>
                    ${PROJECT_SOURCE_DIR}/abi/libkairos.abi ${CMAKE_BINARY_DIR}/abi-check
                    ${PROJECT_SOURCE_DIR}/include ${KAIROS_GENERATED_INCLUDE})
        # check_abi.sh exits 77 when abidw is missing outside CI; with CI set it fails instead.
        set_tests_properties(abi_abidiff PROPERTIES LABELS abi SKIP_RETURN_CODE 77)
    else()
        message(STATUS "KAIROS_ABI_CHECK: build type '${CMAKE_BUILD_TYPE}' has no debug info; the ABI check needs -g (use RelWithDebInfo)")
    endif()
endif()
